// static_steal_frames.cpp — the child's frames under schedule(runtime) (static_steal_frames.hpp).
#include "schedulers/llvm_openmp/static_steal_frames.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "core/thread_cpu_time.hpp"
#include "reporting/build_stamp.hpp"
#include "schedulers/llvm_openmp/static_steal_probe.hpp"

namespace frontsteal::llvm_openmp {

namespace {

using Clock = std::chrono::steady_clock;
std::int64_t ns_since(Clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t).count();
}

}  // namespace

StaticStealFrames::StaticStealFrames(const Options& o) : o_(o) {
  ts::PathSceneOptions so{.scene = o.scene,
                          .data_dir = FRONTSTEAL_DATA_DIR,
                          .path = o.path,
                          .frames = o.frames,
                          .width = o.width,
                          .height = o.height,
                          .settings = {}};
  so.settings.pixel_tolerance = o.tolerance;
  so.settings.planted_defect = o.defect;
  try {
    scene_ = ts::make_path_scene(so);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot load scene '" + o.scene + "': " + e.what());
  }
  n_ = static_cast<long long>(scene_.surfaces());
  grain_ = o.grain;
  chunks_ = (n_ + grain_ - 1) / grain_;
  frames_.emplace(scene_, static_cast<frontsteal::WorkerId>(o.workers));
  frames_->set_reuse(o.reuse);
  runs_.assign(static_cast<std::size_t>(n_), 0);
  runner_.assign(static_cast<std::size_t>(n_), -1);
  workers_.resize(static_cast<std::size_t>(o.workers));
  for (Worker& w : workers_) w.ran.reserve(static_cast<std::size_t>(n_));
}

// The exactly-once audit's record is a plain store into the thread's own log: a locked increment per item would
// wait for the item's stores to drain (~30 ns here), a cost OpenMP programs do not pay (core/execution_log.hpp).
void StaticStealFrames::run_item(int f, long long id, int t) {
  frames_->run(f, static_cast<frontsteal::ItemId>(id), static_cast<frontsteal::WorkerId>(t));
  workers_[t].ran.push_back(static_cast<std::int32_t>(id));
  ++workers_[t].items;
}

// Each chunk index c covers items [c * grain, min((c + 1) * grain, N)), so static_steal's chunk 1 over chunk
// indices is its chunk `grain` over items, timed once per claim.
std::int64_t StaticStealFrames::run_frame(int f) {
  const int P = o_.workers;
  const int chunks32 = static_cast<int>(chunks_);  // the caller checked that it fits
  for (auto& w : workers_) {
    w.items = w.claims = w.busy_ns = w.active_ns = w.cpu_ns = w.chunks_stolen = w.items_stolen = 0;
    w.wake_ns = w.termination_ns = 0;
    w.ran.clear();
  }
  std::vector<Clock::time_point> first_claim(static_cast<std::size_t>(P)), last_done(static_cast<std::size_t>(P));
  const Clock::time_point start = Clock::now();
#pragma omp parallel num_threads(P)
  {
    const int t = omp_get_thread_num();
    if (o_.pin) pinning_.pin_this_thread(static_cast<unsigned>(t));
    const Clock::time_point span = Clock::now();
    const std::int64_t cpu = frontsteal::thread_cpu_ns();
    bool claimed = false;
    // A 32-bit induction variable: libomp's lock-free static_steal (one 64-bit CAS on a thread's (count,
    // limit) pair); 64-bit ones take a per-thread lock for every chunk (kmp_dispatch.cpp, type_size > 4).
#pragma omp for schedule(runtime) nowait
    for (int ci = 0; ci < chunks32; ++ci) {
      if (!claimed) {
        first_claim[static_cast<std::size_t>(t)] = Clock::now();
        claimed = true;
      }
      const long long c = ci;
      for (long long id = c * grain_; id < std::min((c + 1) * grain_, n_); ++id) {
        if (id == o_.fault_item && o_.fault == Options::Fault::drop) continue;
        run_item(f, id, t);
        if (id == o_.fault_item && o_.fault == Options::Fault::dup) run_item(f, id, t);
      }
    }
    if (claimed) {
      last_done[static_cast<std::size_t>(t)] = Clock::now();
      workers_[t].claims = 1;
      workers_[t].busy_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                last_done[static_cast<std::size_t>(t)] - first_claim[static_cast<std::size_t>(t)])
                                .count();
    }
    workers_[t].active_ns = ns_since(span);
    workers_[t].cpu_ns = frontsteal::thread_cpu_ns() - cpu;
  }
  const Clock::time_point end = Clock::now();
  const std::int64_t wall = std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count();
  for (int t = 0; t < P; ++t) {
    Worker& w = workers_[static_cast<std::size_t>(t)];
    if (w.claims == 0) continue;
    w.wake_ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(first_claim[static_cast<std::size_t>(t)] - start).count();
    w.termination_ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(end - last_done[static_cast<std::size_t>(t)]).count();
  }
  for (int t = 0; t < P; ++t) {
    for (const std::int32_t id : workers_[static_cast<std::size_t>(t)].ran) {
      ++runs_[static_cast<std::size_t>(id)];
      runner_[static_cast<std::size_t>(id)] = t;
    }
  }
  const bool static_ranges = P > 1 && chunks_ >= P;  // libomp's own condition for static_steal's ranges
  if (static_ranges) {
    for (long long c = 0; c < chunks_; ++c) {
      const int t = runner_[c * grain_];
      if (t >= 0 && t != owner_of(c, chunks_, P)) {
        ++workers_[t].chunks_stolen;
        workers_[t].items_stolen += std::min((c + 1) * grain_, n_) - c * grain_;
      }
    }
  }
  return wall;
}

void StaticStealFrames::warm_up() {
  for (int f = 0; f < o_.frames; ++f) run_frame(f);
  std::fill(runs_.begin(), runs_.end(), 0u);
}

std::string StaticStealFrames::encoded_runs() {
  std::string out;
  for (long long i = 0; i < n_;) {
    const std::uint32_t v = runs_[i];
    long long j = i;
    while (j < n_ && runs_[j] == v) runs_[j++] = 0;
    out += (i ? "," : "") + std::to_string(v) + '*' + std::to_string(j - i);
    i = j;
  }
  if (n_ == 0) out += "-";
  return out;
}

std::string StaticStealFrames::frame_line(int f) {
  std::fill(runner_.begin(), runner_.end(), -1);
  const std::int64_t wall = run_frame(f);
  const std::uint64_t tri = frames_->frame_triangles(), bad = frames_->count_inconsistent();
  std::string out = "frame " + std::to_string(f) + ' ' + std::to_string(wall) + ' ' + std::to_string(tri) + ' ' +
                    std::to_string(bad) + ' ' + std::to_string(o_.workers);
  for (const Worker& w : workers_) {
    for (std::int64_t v : {w.items, w.claims, w.busy_ns, w.active_ns, w.cpu_ns, w.chunks_stolen, w.items_stolen,
                           w.wake_ns, w.termination_ns}) {
      out += ' ' + std::to_string(v);
    }
  }
  return out + ' ' + encoded_runs();
}

}  // namespace frontsteal::llvm_openmp
