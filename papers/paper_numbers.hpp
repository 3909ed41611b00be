// paper_numbers.hpp — the numbers Kumar, Chang & Manocha report in SC'96 §6, as printed, for side-by-side tables.
//
// Table 1 (Pixel-Planes 5, 25 Graphics Processors = Intel i860 at 40 MHz, tessellating): round-robin vs graph
// partitioning. Table 2 (SGI Onyx, Reality Engine II, 4 host CPUs): greedy rendering. Fig. 8 (Onyx, and a
// Challenge for more processors) is a plot; its text gives only ratios, which are kept here as the claims.
// Model names are the paper's (parts of a submarine storage and handling system, a dragon, two cars); our runs
// use procedural stand-ins with the same surface counts (tessellate/scene_generator.hpp), not those models.
#pragma once

#include <array>
#include <string_view>

namespace frontsteal::papers {

struct PaperTable1Row {
  std::string_view model;
  int surfaces;
  double round_robin_fps, round_robin_utilization_pct;
  double partition_fps, partition_utilization_pct;
};
inline constexpr int kPaperTable1Processors = 25;  // "a configuration of 25 GPs"
inline constexpr std::array<PaperTable1Row, 3> kPaperTable1 = {{
    {"Torpedo", 1201, 10.80, 72.6, 11.74, 80.1},
    {"Pivot", 4101, 15.41, 61.9, 15.95, 81.0},
    {"Ship", 3392, 19.05, 65.3, 19.86, 78.0},
}};

struct PaperTable2Row {
  std::string_view model;
  int surfaces;
  double tessellations_per_s, updates_per_s, average_lag;
};
inline constexpr std::array<PaperTable2Row, 3> kPaperTable2 = {{
    {"Dragon", 5354, 4.20, 19.96, 15.76},
    {"Car 1", 5053, 4.84, 19.97, 15.13},
    {"Car 2", 8693, 2.20, 8.55, 6.35},
}};

// Fig. 8: three models, tessellation rate against processors, static vs global queue vs load stealing.
inline constexpr std::array<int, 3> kPaperFig8Surfaces = {5302, 10604, 15906};
// "the global queue scheme provides 5% to 10% improvement over the static scheme, while the load stealing
// scheme provides another 10% to 20% improvement over the global queue scheme ... The speedup is close to linear."
inline constexpr double kPaperQueueOverStaticMin = 1.05, kPaperQueueOverStaticMax = 1.10;
inline constexpr double kPaperStealingOverQueueMin = 1.10, kPaperStealingOverQueueMax = 1.20;
inline constexpr int kPaperFig8MaxProcessors = 4;  // the Onyx; the Challenge's counts are not given in the text

}  // namespace frontsteal::papers
