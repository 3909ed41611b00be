// workers_snapshot.hpp — a plain copy of every worker's thief-visible state, for diagnostics only.
//
// StealingWorkers::debug_state() fills it with relaxed atomic reads (Access::peek) from a thread outside the
// protocol — the watchdog's (stress/watchdog.hpp). The copy is racy by design: each field is some value its
// variable held recently, and the fields are not one consistent cut (a claim or a steal may land between two
// reads). That is enough to tell a hang from progress and to say where each worker stands; it is never used
// to decide anything in the protocol. Every read is atomic, so ThreadSanitizer reports nothing.
//
// OWNERSHIP: a value type; whoever called debug_state() owns the copy.
#pragma once

#include <cstdint>
#include <cstdio>
#include <vector>

namespace frontsteal {

struct WorkerSnapshot {
  std::uint32_t front = 0;      // Front[w]
  std::uint32_t end = 0;        // End of ActivityList[w]
  std::uint32_t transient = 0;  // ListTransient[w]: 1 while a claim is in flight (or stuck in flight)
  bool lock_held = false;       // LockList[w] taken (by a thief of w, or by w installing a list)
};

struct WorkersSnapshot {
  std::vector<WorkerSnapshot> workers;
  std::uint32_t active = 0;    // ActiveWorkers count (termination, A1-A3)
  std::uint32_t started = 0;   // frames released by the caller (E1)
  std::uint32_t done = 0;      // frames completed (E5)
  std::uint64_t arrivals = 0;  // worker arrivals over all frames (E3)

  // A frame is in flight: released and not yet completed. Only then can a worker be stuck inside it; between
  // frames the caller may take as long as it likes.
  bool frame_in_flight() const noexcept { return started > done; }
  // Workers that have arrived at the end of the frame in flight (frame done + 1).
  std::uint64_t arrived_in_current_frame() const noexcept {
    const std::uint64_t before = std::uint64_t{done} * workers.size();
    return arrivals >= before ? arrivals - before : 0;
  }

  // Changes whenever the protocol moves: a watchdog calls two equal fingerprints "no progress". A claim moves
  // Front, a steal End (and the active count), a frame boundary the counters. LockList is left out on purpose:
  // idle thieves probing an empty victim take and drop its lock endlessly without moving anything, and a
  // frame stuck that way is a hang.
  std::uint64_t fingerprint() const noexcept {
    std::uint64_t h = 0xcbf29ce484222325ull;
    auto mix = [&h](std::uint64_t v) { h = (h ^ v) * 0x100000001b3ull; };
    mix(active);
    mix(started);
    mix(done);
    mix(arrivals);
    for (const WorkerSnapshot& w : workers) {
      mix(w.front);
      mix(w.end);
      mix(w.transient);
    }
    return h;
  }

  // The report a watchdog prints: one line for the frame counters, one per worker. stdio, not iostreams: it
  // runs just before the process exits, possibly while other threads are stuck holding a stream's lock.
  void print(std::FILE* out) const {
    std::fprintf(out, "  frames: released %u, done %u, %s; active workers %u (of %zu)\n", started, done,
                 frame_in_flight() ? "frame in flight" : "no frame in flight", active, workers.size());
    if (frame_in_flight()) {
      std::fprintf(out, "  frame %u: %llu of %zu workers have arrived at its end\n", done + 1,
                   static_cast<unsigned long long>(arrived_in_current_frame()), workers.size());
    }
    for (std::size_t w = 0; w < workers.size(); ++w) {
      const WorkerSnapshot& s = workers[w];
      std::fprintf(out, "  worker %zu: Front %u  End %u  ListTransient %u  LockList %s  unclaimed %u\n", w, s.front,
                   s.end, s.transient, s.lock_held ? "held" : "free", s.end > s.front ? s.end - s.front : 0u);
    }
  }
};

}  // namespace frontsteal
