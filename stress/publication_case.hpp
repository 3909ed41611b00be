// publication_case.hpp — one case of frontsteal-stress-publication: greedy rendering's publication and reclamation
// (core/component_publication.hpp) on real threads under chaos. A pusher thread draws every component as fast as it
// can, P tessellators (the stealing scheduler, Fenced) write every surface every frame, the caller drives frames.
//
// What is checked, per pusher update and component:
//   torn        the surfaces of the slot it read carry different frames (invariant I1);
//   reuse       a tessellator was writing the slot while the pusher read it: each slot counts its writers in
//               flight, and the pusher reads every surface's stamp twice around its "draw" (invariant I2);
//   backwards   a component showed an older frame than in an earlier update (I3);
// plus, under ThreadSanitizer, races on the triangle cells themselves (the sound policy's cells are plain memory;
// the planted defects' cells are relaxed atomics so that the audit, not TSan's halt, reports them).
// Outcome histogram: how many frames behind the newest finished frame each drawn component was (the lag).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/component_publication.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "stress/watchdog.hpp"
#include "stress/chaos_backend.hpp"

namespace frontsteal::stress::publication_stress {

// What one run does (parsed in publication_stress.cpp; --help gives each option's meaning and default).
struct Options {
  double seconds = 2;
  double control_seconds = 60;
  std::vector<WorkerId> threads{2, 4};
  std::vector<SlotIndex> slots{2, 3};
  std::uint32_t components = 24;
  std::uint32_t chaos = 20000;
  std::uint64_t seed = 1;
  std::string out = "out/stress-publication";
  bool quiet = false;
};

struct CaseResult {
  std::string policy;
  WorkerId threads = 0;
  SlotIndex slots = 0;
  bool negative_control = false;
  std::uint64_t frames = 0, updates = 0, driver_waits = 0;
  std::uint64_t torn = 0, reuse = 0, backwards = 0;
  double seconds = 0;                          // for a negative control: until the first catch
  std::map<std::uint64_t, std::uint64_t> lag;  // frames behind the newest finished frame -> component draws
  bool passed() const { return negative_control ? (torn + reuse + backwards) > 0 : (torn + reuse + backwards) == 0; }
};

// One triangle cell per (component, slot, surface): the frame that wrote it. Plain memory for the sound policy
// (ThreadSanitizer checks it), relaxed atomics for the planted defects (the audit reports them, TSan does not halt).
template <bool kPlain>
struct TriangleCell {
  std::uint64_t frame = 0;
  std::uint64_t read() const { return frame; }
  void write(std::uint64_t f) { frame = f; }
};
template <>
struct TriangleCell<false> {
  std::atomic<std::uint64_t> frame{0};
  std::uint64_t read() const { return frame.load(std::memory_order::relaxed); }
  void write(std::uint64_t f) { frame.store(f, std::memory_order::relaxed); }
};

// One case: Policy with `threads` tessellators and `slots` slots per component, for o.seconds (a negative
// control: until the pusher catches it, at most o.control_seconds).
template <class Policy>
CaseResult run_case(const Options& o, WorkerId threads, SlotIndex slots, bool negative_control) {
  constexpr bool kPlain =
      !has(Policy::defects(), Defect::kReuseWithoutGrace) && !has(Policy::defects(), Defect::kPublishEachSurface);
  CaseResult r;
  r.policy = std::string(Policy::kName);
  r.threads = threads;
  r.slots = slots;
  r.negative_control = negative_control;
  std::mt19937_64 rng(o.seed);
  std::vector<std::uint32_t> sizes(o.components);
  std::vector<ComponentId> owner;       // surface -> component
  std::vector<std::uint32_t> position;  // surface -> index inside its component
  for (ComponentId c = 0; c < o.components; ++c) {
    sizes[c] = 1 + static_cast<std::uint32_t>(rng() % 4);
    for (std::uint32_t i = 0; i < sizes[c]; ++i) {
      owner.push_back(c);
      position.push_back(i);
    }
  }
  const auto surfaces = static_cast<ItemId>(owner.size());
  ComponentPublication<ChaosBackend, Policy> publication(sizes, slots);
  std::vector<TriangleCell<kPlain>> cells(static_cast<std::size_t>(o.components) * slots * 4);
  std::vector<std::atomic<std::uint32_t>> writing(static_cast<std::size_t>(o.components) * slots);
  const auto cell = [&](ComponentId c, SlotIndex s, std::uint32_t i) -> TriangleCell<kPlain>& {
    return cells[(static_cast<std::size_t>(c) * slots + s) * 4 + i];
  };
  std::atomic<std::uint64_t> newest_frame{0};
  std::atomic<bool> stop{false};
  std::atomic<bool> caught{false};       // the pusher saw a violation: a negative control can end its case
  chaos_settings() = {o.chaos, o.seed};  // before any thread of the case starts; reset after all have joined

  // The pusher reads every component's slot first and checks it again after "drawing" them all, so it holds
  // each slot for a whole update, as the renderer does.
  std::thread pusher([&] {
    std::vector<std::uint64_t> last(o.components, 0), first(o.components, 0);
    std::vector<SlotIndex> held(o.components);
    std::vector<char> torn(o.components);
    while (!stop.load(std::memory_order::relaxed)) {
      publication.begin_update();
      const std::uint64_t newest = newest_frame.load(std::memory_order::relaxed);
      for (ComponentId c = 0; c < o.components; ++c) {
        held[c] = publication.read(c);
        if (held[c] == decltype(publication)::kNothing) continue;
        first[c] = cell(c, held[c], 0).read();
        torn[c] = false;
        for (std::uint32_t i = 1; i < sizes[c]; ++i) torn[c] = torn[c] || cell(c, held[c], i).read() != first[c];
        r.reuse += writing[static_cast<std::size_t>(c) * slots + held[c]].load(std::memory_order::relaxed) != 0;
      }
      // "Drawing": the window a premature reuse would hit. A sleep, not a yield, so that tessellators get a core
      // even when other processes load every core (a yield alone left the defect uncaught under CI load).
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      for (ComponentId c = 0; c < o.components; ++c) {
        if (held[c] == decltype(publication)::kNothing) continue;
        bool reused = writing[static_cast<std::size_t>(c) * slots + held[c]].load(std::memory_order::relaxed) != 0;
        for (std::uint32_t i = 0; i < sizes[c]; ++i)
          reused = reused || (!torn[c] && cell(c, held[c], i).read() != first[c]);
        r.torn += torn[c];
        r.reuse += reused;
        r.backwards += first[c] < last[c];
        last[c] = std::max(last[c], first[c]);
        ++r.lag[newest >= first[c] ? newest - first[c] : 0];
      }
      publication.end_update();
      ++r.updates;
      if (r.torn + r.reuse + r.backwards > 0) caught.store(true, std::memory_order::relaxed);
    }
  });

  {
    StealingScheduler<Fenced, ChaosBackend> scheduler({.workers = threads, .items = surfaces, .seed = o.seed});
    // A frame that stops moving ends the run with every worker's state (stress/watchdog.hpp), not a ctest timeout.
    const Watchdog dog =
        watch_workers(scheduler, "frontsteal-stress-publication: " + r.policy + ", P=" + std::to_string(threads) +
                                     ", slots=" + std::to_string(slots));
    const auto start = std::chrono::steady_clock::now();
    const auto deadline = start + std::chrono::duration<double>(negative_control ? o.control_seconds : o.seconds);
    while (std::chrono::steady_clock::now() < deadline &&
           !(negative_control && caught.load(std::memory_order::relaxed))) {
      r.driver_waits += publication.prepare_frame();
      const std::uint64_t frame = ++r.frames;
      scheduler.run_frame([&](ItemId id, WorkerId) {
        const ComponentId c = owner[id];
        const SlotIndex s = publication.back_slot(c);
        std::atomic<std::uint32_t>& w = writing[static_cast<std::size_t>(c) * slots + s];
        w.fetch_add(1, std::memory_order::relaxed);
        cell(c, s, position[id]).write(frame);
        w.fetch_sub(1, std::memory_order::release);
        publication.finish_surface(c);
      });
      newest_frame.store(frame, std::memory_order::relaxed);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  stop.store(true, std::memory_order::relaxed);
  pusher.join();
  chaos_settings() = {0, o.seed};
  return r;
}

}  // namespace frontsteal::stress::publication_stress
