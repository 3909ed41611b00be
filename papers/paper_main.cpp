// frontsteal-paper — regenerates the paper's Table 1, Fig. 8 and Table 2 beside its numbers, and replays cost
// traces through the scheduler models (simulator.hpp) for more processors than this machine has.
//
// One subcommand per artifact; each writes <name>.md, <name>.csv, <name>.json and <name>.png (gnuplot) into
// --out (default results/papers), stamped with the machine, the commit and the date. Measured figures come
// from the real schedulers on this machine; simulated ones from the models; every table and plot says which.
//
// This file only parses (papers/paper_options.hpp), picks the subcommand and hands over a PaperRun
// (papers/paper_run.hpp); each artifact is its own file in papers/. A new subcommand is one line in
// kSubcommands below and one function `int (PaperRun&)`.
#include <algorithm>
#include <exception>
#include <iterator>
#include <iostream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "papers/fig8_curves.hpp"
#include "papers/paper_options.hpp"
#include "papers/paper_run.hpp"
#include "papers/table1_report.hpp"
#include "papers/table2_report.hpp"
#include "papers/scale_command.hpp"
#include "papers/validate_command.hpp"
#include "render/headless_gl.hpp"
#include "reporting/build_stamp.hpp"
#include "tessellate/model_format.hpp"

namespace fp = frontsteal::papers;

namespace {

struct Subcommand {
  const char* name;
  const char* summary;                              // its paragraph in --help
  int (*run)(fp::PaperRun&);                        // runs with the shared options, or
  int (*run_own)(int argc, char** argv) = nullptr;  // parses its own (must come first: `frontsteal-paper NAME ...`)
};

int run_all(fp::PaperRun& run);

// The registration table: --help lists the subcommands in this order.
constexpr Subcommand kSubcommands[] = {
    {"table1",
     "round robin vs spatial partition (paper Table 1): frames/s and utilization on stand-ins of 1,201 / "
     "4,101 / 3,392 surfaces; measured at P = cores, simulated at P = cores and P = 25 (the paper's 25 "
     "Graphics Processors) (~1.5 min on 2 cores)",
     fp::run_table1},
    {"fig8",
     "static vs global queue vs stealing (paper Fig. 8, + Chase-Lev): tessellation rate against P on 5,302 / "
     "10,604 / 15,906 surfaces; measured at P = 1 ... cores, simulated at P = 1 ... 64, with the simulator's "
     "error at the measured P (~3 min on 2 cores)",
     fp::run_fig8},
    {"table2",
     "greedy rendering (paper Table 2): tessellations/s, updates/s, average lag on stand-ins of 5,354 / "
     "5,053 / 8,693 surfaces (headless OpenGL; --null-renderer without); two rows per stand-in: natural, "
     "and tessellation-bound (--cost-multiplier) (~1 min)",
     fp::run_table2},
    {"calibrate", "the microbenchmarks behind the simulator's costs (~10 s)", fp::run_calibrate},
    {"trace", "record a cost trace of --scene into --trace FILE", fp::run_trace},
    {"simulate", "replay --trace FILE through every model for P = 1 ... --max-p", fp::run_simulate},
    {"all", "calibrate, table1, fig8, table2", run_all},
    {"validate",
     "the simulator's held-out validation against main-job runs (--study DIR); takes its own options, "
     "see `frontsteal-paper validate --help`",
     nullptr, fp::run_validate_command},
    {"scale",
     "the loss account simulated: validated term by term against main-job runs with accounts (--study DIR), "
     "then predicted for P up to 256 with the first bottleneck named; takes its own options, see "
     "`frontsteal-paper scale --help`",
     nullptr, fp::run_scale_command},
};

int run_all(fp::PaperRun& run) {
  for (auto step : {fp::run_table1, fp::run_fig8, fp::run_table2}) {
    if (const int rc = step(run)) return rc;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (const Subcommand& s : kSubcommands) {
    if (s.run_own && argc > 1 && std::string_view(argv[1]) == s.name) return s.run_own(argc - 1, argv + 1);
  }
  std::vector<fp::SubcommandSummary> summaries;
  for (const Subcommand& s : kSubcommands) summaries.push_back({s.name, s.summary});
  fp::PaperRun run(fp::parse_options(argc, argv, summaries), FRONTSTEAL_GIT_COMMIT, FRONTSTEAL_DATA_DIR);
  const auto* chosen = std::find_if(std::begin(kSubcommands), std::end(kSubcommands),
                                    [&](const Subcommand& s) { return run.options().command == s.name; });
  if (!chosen->run) {
    std::cerr << fp::kPaperProgram << ": " << chosen->name
              << " takes its own options; put it first: " << fp::kPaperProgram << ' ' << chosen->name << " --help\n";
    return 2;
  }
  try {
    return chosen->run(run);
  } catch (const frontsteal::render::GraphicsError& e) {
    std::cerr << fp::kPaperProgram << ": no OpenGL: " << e.what()
              << "\n(install libegl-mesa0 libgl1-mesa-dri, or run table2 with --null-renderer)\n";
    return 3;
  } catch (const frontsteal::tess::ModelError& e) {
    std::cerr << fp::kPaperProgram << ": bad scene: " << e.what() << '\n';
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << fp::kPaperProgram << ": " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << fp::kPaperProgram << ": " << e.what() << '\n';
    return 1;
  }
}
