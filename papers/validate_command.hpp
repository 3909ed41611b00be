// validate_command.hpp — `frontsteal-paper validate`: the simulator's held-out validation (validation.hpp)
// against a folder of main-job results, written to validation.{md,json,csv}.
#pragma once

namespace frontsteal::papers {

// argv[0] is "validate"; parses its own options (report::CommandLine: usage errors exit 2 naming the flag).
// Returns the exit status: 0 written, 1 a file could not be read or written.
int run_validate_command(int argc, char** argv);

}  // namespace frontsteal::papers
