// rank_ledger.hpp — a flight recorder per rank, so that a job a dead rank ended can say what was lost.
//
// WHY. When a rank dies, Open MPI's mpirun ends every other rank (SIGTERM, then SIGKILL); nothing runs afterwards
// that could say which items of the frame never ran, and the dead rank cannot say anything at all. With
// --ledger DIR every rank keeps DIR/rank-R.ledger, a file mapped into its memory (MAP_SHARED): the frame and
// scheduler in progress, and one byte per item set when this rank ran it in this frame. Writes to a shared file
// mapping outlive the process that made them, so after the job is gone `frontsteal-mpi --post-mortem DIR` reads
// every rank's ledger and reports: which rank ended without a recorded exit (it died), where each rank was, and
// which items of the last frame no surviving rank ran (lost), and which only the dead rank ran (their results
// died with it).
//
// RECORDED EXITS. A clean end, the watchdog's exit (86), and a SIGTERM (what mpirun sends the survivors) are
// recorded in the header; a rank that crashed, was killed (SIGKILL) or exited abruptly (--die) records nothing,
// which is how the post-mortem tells it from the others.
//
// COST. Per item one byte store and one relaxed fetch-add to this rank's own mapping; per frame a memset of one
// byte per item. Nothing when --ledger is not given.
//
// LIMITS. One node: DIR must be node-local memory or disk on each host (collect the files before the
// post-mortem); a host that dies takes its ledger files with it unless DIR is on shared storage.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::mpi {

enum class LedgerState : std::int32_t {
  kRunning = 0,     // no exit recorded: the rank is running, or died without a word
  kFinished = 1,    // the run ended normally
  kWatchdog = 2,    // the watchdog ended it (no progress)
  kTerminated = 3,  // SIGTERM (mpirun ending the job after another rank failed)
};
const char* to_string(LedgerState s) noexcept;

// Opens (creates) DIR/rank-R.ledger for n items and installs the SIGTERM recorder. Throws naming the file on
// failure. No-op for an empty dir.
void open_ledger(const std::string& dir, int rank, int ranks, ItemId n);
void ledger_begin_frame(int frame, std::string_view scheduler) noexcept;
void ledger_mark(ItemId id) noexcept;  // this rank ran `id` in the current frame (any thread)
void ledger_frame_done() noexcept;     // past the frame's done barrier
void ledger_exit(LedgerState state) noexcept;

// What one rank's ledger says.
struct LedgerRecord {
  int rank = 0, ranks = 0, pid = 0, frame = -1;
  bool frame_done = false;
  LedgerState state = LedgerState::kRunning;
  std::string scheduler;
  std::uint64_t ran = 0;         // items this rank ran in its current frame
  std::vector<std::uint8_t> by;  // per item: 1 = this rank ran it in its current frame
};

struct PostMortem {
  std::vector<LedgerRecord> ranks;  // by rank
  int frame = -1;                   // the last frame any rank was in
  std::string scheduler;
  std::uint32_t items = 0;
  std::vector<int> died;    // ranks with no recorded exit, the others having recorded one
  RangeList never_ran;      // items of `frame` no rank ran
  RangeList only_dead_ran;  // items of `frame` only died ranks ran (their results died too)
  std::uint64_t never_ran_count = 0, only_dead_ran_count = 0;
  bool clean = false;  // every rank finished normally
};

// Reads every rank-*.ledger in dir. Throws naming the directory or the file on a missing or malformed ledger.
PostMortem read_ledgers(const std::string& dir);
// The report, the answer first.
std::string describe(const PostMortem& pm);

}  // namespace frontsteal::mpi
