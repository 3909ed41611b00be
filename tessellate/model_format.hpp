// model_format.hpp — frontsteal's native model file: a strict, line-oriented text format.
//
//   # comments run to the end of a line; blank lines are ignored
//   frontsteal-model 1                  first line: format and version
//   model <name>                        optional, once, before the first surface
//   surface [<name>]                    one block per surface
//     component <k>                     optional: connected-component id (>= 0)
//     solid                             optional: part of a closed solid whose normals S_u × S_v point
//                                       outwards (back faces may be culled)
//     patch <degree_u> <degree_v>       degrees 1..25
//     cp <x> <y> <z> [<w>]              (degree_u+1)(degree_v+1) control points, i along u outer, j along v
//                                       inner; w > 0 (default 1)
//     loop                              zero or more trim loops; the first is the outer one (CCW), the
//       curve <degree>                  rest holes (CW); a loop is a closed chain of segments:
//       pt <u> <v>                      a Bézier curve in (u, v): degree+1 points
//       polyline <count>                or a polyline: count >= 2 points
//       pt <u> <v>
//     endloop
//   endsurface
//
// The parser is strict: the first problem stops it with a ModelError naming file:line and the reason —
// a byte-order mark, CR-only line ends, a NUL byte, an unknown keyword, a wrong count, a number that is not
// finite or out of range (|coordinate| <= 1e12, weights 1e-12..1e12), a degree out of range, a trim point
// outside [0,1]², an open loop, a loop of the wrong orientation, loops that cross, touch, retrace an edge or
// nest (loop_validation.hpp), a component id not below the number of surfaces — and nothing is half-loaded
// (the model is returned only when the whole file is valid).
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>

#include "tessellate/model.hpp"

namespace frontsteal::tess {

// Limits of the numbers a model may hold. Step sizes and culling square lengths and multiply weights: beyond
// these, intermediate values overflow to inf/NaN (a 1e155 coordinate made a NaN step count), and no 1 px
// tolerance is representable next to such magnitudes anyway.
inline constexpr double kMaxCoordinate = 1e12;
inline constexpr double kMinWeight = 1e-12;
inline constexpr double kMaxWeight = 1e12;

class ModelError : public std::runtime_error {
 public:
  ModelError(std::string file, int line, const std::string& reason)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + reason), file_(std::move(file)), line_(line) {}
  const std::string& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }

 private:
  std::string file_;
  int line_;
};

// Parses a whole model; `file_name` is used in error messages only.
Model parse_model(std::istream& in, const std::string& file_name);
// Opens and parses `path`; a file that cannot be opened (missing, a directory, unreadable) is a ModelError at
// line 0 that says which.
Model load_model(const std::string& path);
// Writes `model` in the native format (full precision: parse_model(write_model(m)) reproduces m). Throws
// std::invalid_argument, writing nothing, for a model with numbers the parser would refuse.
void write_model(std::ostream& out, const Model& model);

}  // namespace frontsteal::tess
