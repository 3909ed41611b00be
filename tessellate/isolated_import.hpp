// isolated_import.hpp — a foreign CAD file read in a child process, so that a reader that crashes, loops or
// eats the machine's memory costs the user one clear error instead of the program.
//
// Why: Open CASCADE's readers are not hardened against hostile input. A STEP file with a dangling or self
// reference made them crash (SIGSEGV); a truncated BREP, a BREP claiming 2·10⁹ curves or a STEP with NaN
// points made them run forever. Such faults cannot be caught in-process.
//
// How: fork(); the child runs import_cad_file (occt_import.hpp) and sends its report and the imported surfaces
// (in the native format, full precision) through a pipe, then _exits. The parent reads the pipe while it
// watches the child: past `time_limit_s` of wall time, or past `memory_limit_mb` of resident memory (read from
// /proc/<pid>/statm every 20 ms, which works under sanitizers, unlike RLIMIT_AS), it kills the child with
// SIGKILL. A child killed by a signal, a time-out, a memory kill, or a reader error all throw ImportFailure
// naming the file and the cause; `out` is then unchanged (nothing partial is kept). What the child sent is
// parsed by the strict native parser before any of it is appended.
#pragma once

#include <stdexcept>
#include <string>

#include "tessellate/model.hpp"
#include "tessellate/occt_import.hpp"

namespace frontsteal::tess {

struct IsolationLimits {
  double time_limit_s = 30.0;
  double memory_limit_mb = 4096.0;
};

class ImportFailure : public std::runtime_error {
 public:
  enum class Cause { reader_error, crashed, timed_out, out_of_memory, protocol };
  ImportFailure(Cause cause, const std::string& message) : std::runtime_error(message), cause_(cause) {}
  Cause cause() const noexcept { return cause_; }

 private:
  Cause cause_;
};

// As import_cad_file, in a child process under `limits`. Throws ImportFailure (out unchanged) on any failure;
// std::invalid_argument for bad options. Call from one thread at a time (it forks).
ImportReport import_cad_file_isolated(const std::string& path, Model& out, const ImportOptions& options = {},
                                      const IsolationLimits& limits = {});

}  // namespace frontsteal::tess
