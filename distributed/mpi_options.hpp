// mpi_options.hpp — frontsteal-mpi's command line: what a run measures and which faults it plants.
//
// Every rank parses the same argv before MPI_Init (a bad flag costs no MPI start-up); only the rank the
// launcher calls 0 prints, and every rank exits 2 (report::CommandLine's usage contract).
#pragma once

#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include <cstdint>

namespace frontsteal::mpi {

inline constexpr std::string_view kProgram = "frontsteal-mpi";
inline constexpr int kWatchdogExitCode = 86;  // as stress/watchdog.hpp: distinct from a failed audit (1) and usage (2)

struct Options {
  std::string scene = "synthetic:20000";
  int frames = 30;
  std::vector<std::string> schedulers{"rma", "request", "central", "static", "static-space"};
  std::uint32_t work_ns = 2000;
  std::uint32_t skew = 20;
  double tolerance = 1.0;
  std::string json;
  std::string markdown;
  std::string plots;  // directory for the plots (mpi_plots.hpp); "" = none
  double watchdog_s = 60;
  int stall_rank = -1, stall_frame = -1, stall_ms = 0;
  int die_rank = -1, die_frame = -1;
  int slow_rank = -1, slow_frame = -1, slow_ms = 0;  // --slow: SIGSTOP/SIGCONT duty cycle, 10x (os_slowdown.hpp)
  std::string defect = "none";
  bool force_overlap = false;
  bool calibrate = false;
  double calibrate_op_s = 2.0;  // each calibrated operation runs for at most this long
  bool require_steals = false;
  std::string owner_fence = "cpu";
  std::string owner_progress = "auto";  // auto | off | U (µs between the busy owner's progress calls; 0: every item)
  std::string progress_thread = "off";  // off | U (µs the rank's progress thread sleeps between calls; 0: yields)
  double progress_thread_us() const {
    return progress_thread == "off" ? -1 : std::strtod(progress_thread.c_str(), nullptr);
  }
  bool quiet = false;
  // Paired rounds (paired_rounds.hpp): 0 = one pass of --frames per scheduler; R > 0 = R rounds, each running
  // every arm for --frames frames in a fresh random order, then each arm compared with --reference.
  int rounds = 0;
  std::string reference = "static-space";
  double margin_pct = 5;    // equivalence margin of the verdicts, % of time
  double planted_pct = 10;  // the planted arm: the reference slowed by this % of its frame time
  std::uint64_t seed = 1;   // the round orders
  // hier (hierarchical_rank.hpp): worker threads per rank, and the work (us) of one chunk taken from the rank list.
  int threads = 2;
  double chunk_us = 50;
  bool lifelines = true;     // hier: dry ranks wait on a lifeline graph (lifelines.hpp) instead of polling
  bool batch_claims = true;  // hier: a refill claims a run of the rank list per owner handshake, not one item
  bool thief_views = true;   // rma, hier: a thief reads a victim in one MPI_Get (rma_backend.hpp V1), not word by word
  std::string ledger;        // rank_ledger.hpp: each rank's flight recorder in this directory ("" = none)
  std::string post_mortem;   // read the ledgers in this directory, report, exit (no MPI)
};

// The rank the launcher assigned (Open MPI, MPICH/hydra, PMIx), readable before MPI_Init; 0 when unknown.
int launcher_rank();

// Parses argv; on a usage error prints (rank 0 only) and exits 2, on --help prints and exits 0.
Options parse_options(int argc, char** argv);

}  // namespace frontsteal::mpi
