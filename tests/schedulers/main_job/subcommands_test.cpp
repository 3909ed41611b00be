// `frontsteal <subcommand>` (schedulers/main_job/subcommands.hpp):
//   - every subcommand has a unique name and a summary, and --help's list names every one;
//   - a program is found beside the executable first, then in its folder of the build tree, then on PATH, and
//     not at all when it is in none of them (a file that is not executable does not count);
//   - `run` and bare options stay in this process; an unknown word is a usage error (exit status 2).
#include "schedulers/main_job/subcommands.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace mj = frontsteal::main_job;
namespace fsys = std::filesystem;

namespace {

void make_program(const fsys::path& p, bool runnable = true) {
  fsys::create_directories(p.parent_path());
  std::ofstream(p) << "#!/bin/sh\n";
  ::chmod(p.c_str(), runnable ? 0755 : 0644);
}

struct TempTree {
  fsys::path root = fsys::temp_directory_path() / ("frontsteal_subcommands_" + std::to_string(::getpid()));
  TempTree() { fsys::remove_all(root); }
  ~TempTree() { fsys::remove_all(root); }
};

}  // namespace

TEST_CASE("subcommands: unique names, each summarised, all listed by --help") {
  std::set<std::string_view> names;
  const std::string help = mj::subcommand_help();
  for (const mj::Subcommand& s : mj::subcommands()) {
    REQUIRE(names.insert(s.name).second);
    REQUIRE(!s.summary.empty());
    REQUIRE(mj::find_subcommand(s.name) == &s);
    REQUIRE(help.find("  " + std::string(s.name) + " ") != std::string::npos);
  }
  for (const char* expected : {"run", "paper", "simulate", "tessellate", "import", "render", "view", "modelcheck",
                               "stress", "mpi", "calibrate"}) {
    REQUIRE(mj::find_subcommand(expected) != nullptr);
  }
  REQUIRE(mj::find_subcommand("nosuch") == nullptr);
}

TEST_CASE("subcommands: beside the executable, then the build tree's folder, then PATH") {
  TempTree t;
  const fsys::path self = t.root / "build" / "schedulers" / "frontsteal";
  make_program(self);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", (t.root / "bin").c_str(), 1);

  REQUIRE_FALSE(mj::locate_program("frontsteal-paper", "papers", self.string()));
  make_program(t.root / "bin" / "frontsteal-paper");
  REQUIRE(mj::locate_program("frontsteal-paper", "papers", self.string()) ==
          (t.root / "bin" / "frontsteal-paper").string());
  make_program(t.root / "build" / "papers" / "frontsteal-paper");
  REQUIRE(mj::locate_program("frontsteal-paper", "papers", self.string()) ==
          (t.root / "build" / "papers" / "frontsteal-paper").string());
  make_program(t.root / "build" / "schedulers" / "frontsteal-paper");
  REQUIRE(mj::locate_program("frontsteal-paper", "papers", self.string()) ==
          (t.root / "build" / "schedulers" / "frontsteal-paper").string());
  // Not executable: not a program.
  make_program(t.root / "build" / "render" / "frontsteal-view", false);
  REQUIRE_FALSE(mj::locate_program("frontsteal-view", "render", self.string()));

  ::setenv("PATH", old_path.c_str(), 1);
}

TEST_CASE("subcommands: run and options stay here, an unknown word is a usage error") {
  std::string prog = "frontsteal", run = "run", cal = "calibrate", opt = "--quiet", bad = "nosuch";
  {
    char* argv[] = {prog.data(), opt.data()};
    const mj::Dispatch d = mj::dispatch(2, argv);
    REQUIRE_FALSE(d.exit_status);
    REQUIRE(d.args == std::vector<std::string>{"frontsteal", "--quiet"});
  }
  {
    char* argv[] = {prog.data(), run.data(), opt.data()};
    const mj::Dispatch d = mj::dispatch(3, argv);
    REQUIRE_FALSE(d.exit_status);
    REQUIRE(d.args == std::vector<std::string>{"frontsteal", "--quiet"});
  }
  {
    char* argv[] = {prog.data(), cal.data(), opt.data()};
    const mj::Dispatch d = mj::dispatch(3, argv);
    REQUIRE_FALSE(d.exit_status);
    REQUIRE(d.args == std::vector<std::string>{"frontsteal", "--calibrate", "--quiet"});
  }
  {
    char* argv[] = {prog.data(), bad.data()};
    const mj::Dispatch d = mj::dispatch(2, argv);
    REQUIRE(d.exit_status == 2);
  }
}
