// scale_command.hpp — `frontsteal-paper scale`: the loss account simulated (scale.hpp), validated term by term on
// held-out main-job runs and predicted beyond the machine, written to scale.{md,json,png}.
#pragma once

namespace frontsteal::papers {

// argv[0] is "scale"; parses its own options (report::CommandLine: usage errors exit 2 naming the flag).
// Returns the exit status: 0 written, 1 a file could not be read or written.
int run_scale_command(int argc, char** argv);

}  // namespace frontsteal::papers
