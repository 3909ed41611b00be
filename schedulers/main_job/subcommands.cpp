// subcommands.cpp — the subcommand table, where each program is found, and the hand-over (subcommands.hpp).
#include "schedulers/main_job/subcommands.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace frontsteal::main_job {

namespace fsys = std::filesystem;

const std::vector<Subcommand>& subcommands() {
  static const std::vector<Subcommand> table = {
      {"run",
       "",
       "schedulers",
       {},
       "the main job (also bare `frontsteal`): every scheduler on tessellation, "
       "in rounds, with verdicts"},
      {"calibrate",
       "",
       "schedulers",
       {"--calibrate"},
       "the main job with its A/A twin and planted slowdowns "
       "(run --calibrate)"},
      {"compare", "frontsteal-compare", "schedulers", {}, "any two arms of a frontsteal.json, round by round"},
      {"calibration-summary",
       "frontsteal-calibration-summary",
       "schedulers",
       {},
       "A/A and planted-effect rates over many calibrate runs"},
      {"paper",
       "frontsteal-paper",
       "papers",
       {},
       "the paper's Table 1, Fig. 8, Table 2, and the simulator's "
       "validation"},
      {"simulate",
       "frontsteal-paper",
       "papers",
       {"simulate"},
       "replays a cost trace through the schedulers' "
       "models for P = 1 ... 64 (paper simulate)"},
      {"tessellate",
       "frontsteal-tessellate",
       "tessellate",
       {},
       "tessellates a scene along the path and audits "
       "every surface; exports a frame"},
      {"import",
       "frontsteal-import",
       "tessellate",
       {},
       "STEP / IGES / BREP files into a frontsteal model "
       "(Open CASCADE)"},
      {"render", "frontsteal-render", "render", {}, "greedy rendering along the path, headless (EGL)"},
      {"view", "frontsteal-view", "render", {}, "greedy rendering live in a window"},
      {"gpu-tessellate",
       "frontsteal-gpu-tessellate",
       "render",
       {},
       "untrimmed patches on the GPU (compute shader) against the CPU, audited"},
      {"modelcheck",
       "frontsteal-modelcheck",
       "models_check",
       {},
       "Relacy: the protocol under every policy, "
       "mutation kill matrix, certificate"},
      {"modelcheck-publication",
       "frontsteal-modelcheck-publication",
       "models_check",
       {},
       "Relacy: greedy rendering's publication and reclamation"},
      {"modelcheck-chaselev",
       "frontsteal-modelcheck-chaselev",
       "models_check",
       {},
       "Relacy: the Chase-Lev deque baseline"},
      {"litmus",
       "frontsteal-litmus",
       "models_check/axiomatic",
       {},
       "axiomatic checker (RC11, C++ with load buffering, ARMv8) validated on published litmus verdicts; the "
       "handshake per policy"},
      {"stress",
       "frontsteal-stress",
       "stress",
       {},
       "the protocol on real threads, every item audited "
       "(TSan build: the stress preset)"},
      {"stress-publication",
       "frontsteal-stress-publication",
       "stress",
       {},
       "greedy rendering's publication on real threads with chaos"},
      {"mpi", "frontsteal-mpi", "distributed", {}, "the frame loop across MPI ranks (start with mpirun)"},
      {"mpi-simulate",
       "frontsteal-mpi-simulate",
       "distributed",
       {},
       "the MPI schedulers' efficiency, "
       "simulated from measured latencies"},
  };
  return table;
}

const Subcommand* find_subcommand(std::string_view name) {
  for (const Subcommand& s : subcommands()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string subcommand_help() {
  std::ostringstream out;
  out << "frontsteal [SUBCOMMAND] [OPTIONS] — subcommands (`frontsteal SUBCOMMAND --help` for each):\n";
  for (const Subcommand& s : subcommands()) {
    out << "  " << s.name << std::string(s.name.size() < 24 ? 24 - s.name.size() : 1, ' ') << s.summary << '\n';
  }
  out << "\nWithout a subcommand, or with `run`, the main job:\n";
  return out.str();
}

namespace {

bool executable(const fsys::path& p) {
  std::error_code ec;
  return fsys::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

}  // namespace

std::optional<std::string> locate_program(std::string_view program, std::string_view build_dir,
                                          const std::string& self) {
  const fsys::path here = fsys::path(self).parent_path();
  for (const fsys::path& candidate : {here / program, here.parent_path() / build_dir / program}) {
    if (executable(candidate)) return candidate.string();
  }
  if (const char* path = std::getenv("PATH")) {
    std::string_view rest(path);
    while (!rest.empty()) {
      const std::size_t colon = rest.find(':');
      const std::string_view dir = rest.substr(0, colon);
      if (!dir.empty() && executable(fsys::path(dir) / program)) return (fsys::path(dir) / program).string();
      if (colon == std::string_view::npos) break;
      rest.remove_prefix(colon + 1);
    }
  }
  return std::nullopt;
}

Dispatch dispatch(int argc, char** argv) {
  Dispatch d;
  d.args.assign(argv, argv + argc);
  if (argc < 2 || argv[1][0] == '-') return d;
  const std::string word = argv[1];
  const Subcommand* s = find_subcommand(word);
  if (!s) {
    std::cerr << "frontsteal: '" << word << "' is not a subcommand (see frontsteal --help)\n";
    d.exit_status = 2;
    return d;
  }
  if (s->program.empty()) {  // the main job, in this process
    d.args.erase(d.args.begin() + 1);
    d.args.insert(d.args.begin() + 1, s->leading.begin(), s->leading.end());
    return d;
  }
  std::error_code ec;
  const fsys::path self = fsys::read_symlink("/proc/self/exe", ec);
  const auto where = locate_program(s->program, s->build_dir, ec ? std::string(argv[0]) : self.string());
  if (!where) {
    std::cerr << "frontsteal " << word << ": " << s->program << " is not built here (looked beside "
              << (ec ? std::string(argv[0]) : self.string()) << ", in ../" << s->build_dir
              << "/ of the build tree and on PATH)\n";
    d.exit_status = 2;
    return d;
  }
  std::vector<std::string> args{*where};
  args.insert(args.end(), s->leading.begin(), s->leading.end());
  args.insert(args.end(), argv + 2, argv + argc);
  std::vector<char*> raw;
  for (std::string& a : args) raw.push_back(a.data());
  raw.push_back(nullptr);
  ::execv(where->c_str(), raw.data());
  std::cerr << "frontsteal " << word << ": cannot run " << *where << ": " << std::strerror(errno) << '\n';
  d.exit_status = 2;
  return d;
}

}  // namespace frontsteal::main_job
