// source_location.hpp — where a labelled access was written: the location every backend receives with each
// access (labelled_access.hpp), so a chaos trace or a failed check names the protocol's line.
//
// std::source_location where the compiler provides it (GCC 11+, Clang 15+). Clang 14 on libstdc++ 12 (the
// clang-tidy-14 of Debian 12, tests/scripts/check_tidy_test.sh) has no __builtin_source_location, so the
// standard header is empty there; the stand-in below keeps the protocol compiling, with every location "?":0.
#pragma once

#include <version>

#if defined(__cpp_lib_source_location)
#include <source_location>
#endif

namespace frontsteal {

#if defined(__cpp_lib_source_location)
using SourceLocation = std::source_location;
#else
struct SourceLocation {
  static constexpr SourceLocation current() noexcept { return {}; }
  constexpr const char* file_name() const noexcept { return "?"; }
  constexpr const char* function_name() const noexcept { return "?"; }
  constexpr unsigned line() const noexcept { return 0; }
  constexpr unsigned column() const noexcept { return 0; }
};
#endif

}  // namespace frontsteal
