// subcommands.hpp — `frontsteal <subcommand>`, git-style: one command in front of every frontsteal program.
//
// `frontsteal` alone, or `frontsteal run`, is the main job (this executable). Every other subcommand names a
// program of its own — the Relacy checkers, the TSan stress binary, MPI and OpenGL programs stay separate
// executables because they are built differently — and `frontsteal X ARGS` replaces this process with that
// program and ARGS, as `git X` runs `git-X`. A few subcommands add leading arguments (`calibrate` is
// `run --calibrate`, `simulate` is `frontsteal-paper simulate`).
//
// Where a program is found, in order: beside this executable (an installed bin/ directory); in its folder of
// the build tree, a sibling of this executable's folder (build/<preset>/papers/frontsteal-paper beside
// build/<preset>/schedulers/frontsteal); then on PATH.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace frontsteal::main_job {

struct Subcommand {
  std::string_view name;                  // what the user types after `frontsteal`
  std::string_view program;               // the executable it runs ("" = the main job in this process)
  std::string_view build_dir;             // the program's folder in the build tree
  std::vector<std::string_view> leading;  // arguments put before the user's
  std::string_view summary;               // one line for `frontsteal --help`
};

const std::vector<Subcommand>& subcommands();
const Subcommand* find_subcommand(std::string_view name);

// The lines `frontsteal --help` opens with: every subcommand and its summary.
std::string subcommand_help();

// Where `program` would run from when this executable is `self` (see above); nullopt when it is nowhere.
std::optional<std::string> locate_program(std::string_view program, std::string_view build_dir,
                                          const std::string& self);

// What main does first. argv[1] a subcommand of another program: replaces this process with it (returns
// only when that fails: message on stderr, exit status 2 returned in `exit_status`). `run` (or `calibrate`):
// removes it from argv (adding --calibrate) and returns so that the main job parses the rest. Anything else
// (options, or nothing): returns untouched; an argument that is neither an option nor a subcommand is a
// usage error (message, exit status 2).
struct Dispatch {
  std::vector<std::string> args;   // the main job's arguments, argv[0] first
  std::optional<int> exit_status;  // set: main returns it at once
};
Dispatch dispatch(int argc, char** argv);

}  // namespace frontsteal::main_job
