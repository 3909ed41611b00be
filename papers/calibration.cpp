// calibration.cpp — microbenchmarks behind the simulator's costs (calibration.hpp).
#include "papers/calibration.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <map>
#include <random>
#include <time.h>
#include <type_traits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "papers/workload.hpp"
#include "schedulers/registry.hpp"

namespace frontsteal::papers {
namespace {

using Clock = std::chrono::steady_clock;

double ns_since(Clock::time_point t0) { return std::chrono::duration<double, std::nano>(Clock::now() - t0).count(); }

// Median frame time (ns) of `frames` frames of `items` items on the registry scheduler `name`; an item spins
// for `item_spin_ns` (0: a no-op).
double frame_time(const std::string& name, WorkerId workers, ItemId items, int frames, double item_spin_ns) {
  const sched::SchedulerInfo* info = sched::find_scheduler(name);
  if (!info) throw std::logic_error("calibration: no scheduler " + name);
  auto s = info->make({.workers = workers, .items = items, .seed = 1}, {});
  std::vector<std::uint64_t> sink(workers * 8, 0);
  const auto spin = std::chrono::nanoseconds(static_cast<std::int64_t>(item_spin_ns));
  auto item = [&](ItemId id, WorkerId w) {
    if (item_spin_ns > 0) {
      const auto until = Clock::now() + spin;
      while (Clock::now() < until) {
      }
    }
    sink[w * 8] += id;
  };
  std::vector<double> v;
  for (int f = 0; f < frames + 3; ++f) {
    const FrameStats& st = s->run_frame(item);
    if (f >= 3) v.push_back(static_cast<double>(st.wall_ns));
  }
  return median(v);
}

// The serial loop's time for the same spinning items: what a frame would take with no scheduler at all.
double serial_spin_time(ItemId items, double item_spin_ns, int frames) {
  const auto spin = std::chrono::nanoseconds(static_cast<std::int64_t>(item_spin_ns));
  std::vector<double> v;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = Clock::now();
    for (ItemId i = 0; i < items; ++i) {
      const auto until = Clock::now() + spin;
      while (Clock::now() < until) {
      }
    }
    v.push_back(ns_since(t0));
  }
  return median(v);
}

// Per-item cost from no-op items at P = 1; per-frame cost from frames of about a millisecond (so that the
// caller sleeps in the kernel while the workers run, as on real frames): wall − serial / P − items × item / P.
ModelCosts model_costs(const std::string& name, bool two_cores) {
  ModelCosts c;
  constexpr ItemId kItems = 200000;
  const double f1_empty = frame_time(name, 1, 1, 41, 0);
  const double full = frame_time(name, 1, kItems, 9, 0);
  c.item_ns = std::max(0.0, (full - f1_empty) / kItems);
  constexpr ItemId kSpinItems = 1000;
  constexpr double kSpinNs = 1000;
  const double serial = serial_spin_time(kSpinItems, kSpinNs, 21);
  auto frame_cost = [&](WorkerId p) {
    const double wall = frame_time(name, p, kSpinItems, 41, kSpinNs);
    return std::max(0.0, wall - (serial + kSpinItems * c.item_ns) / p);
  };
  std::vector<double> f1, f2;  // interleaved, so drifts of a noisy machine hit both
  for (int r = 0; r < 3; ++r) {
    f1.push_back(frame_cost(1));
    if (two_cores) f2.push_back(frame_cost(2));
  }
  c.frame_fixed_ns = median(f1);
  c.second_worker_ns = two_cores ? std::max(0.0, median(f2) - c.frame_fixed_ns) : 0;
  return c;
}

double ping_pong_ns() {
  constexpr int kRounds = 200000;
  std::atomic<int> ball{0};
  std::thread other([&] {
    for (int i = 0; i < kRounds; ++i) {
      while (ball.load(std::memory_order::acquire) != 2 * i + 1) {
      }
      ball.store(2 * i + 2, std::memory_order::release);
    }
  });
  const auto t0 = Clock::now();
  for (int i = 0; i < kRounds; ++i) {
    ball.store(2 * i + 1, std::memory_order::release);
    while (ball.load(std::memory_order::acquire) != 2 * i + 2) {
    }
  }
  const double ns = ns_since(t0);
  other.join();
  return ns / (2.0 * kRounds);
}

double lock_ns(int threads) {
  constexpr int kPerThread = 200000;
  std::mutex m;
  std::uint64_t cursor = 0;
  auto body = [&] {
    for (int i = 0; i < kPerThread; ++i) {
      m.lock();
      ++cursor;
      m.unlock();
    }
  };
  const auto t0 = Clock::now();
  std::vector<std::thread> others;
  for (int t = 1; t < threads; ++t) others.emplace_back(body);
  body();
  for (auto& t : others) t.join();
  const double ns = ns_since(t0);
  if (cursor != static_cast<std::uint64_t>(threads) * kPerThread) throw std::logic_error("calibration: lost update");
  return ns / (static_cast<double>(threads) * kPerThread);
}

// A waiter's hand-off latency: the holder keeps the lock long enough (1 ms) for the waiter to fall asleep in
// the futex, stamps the time and unlocks; the waiter stamps the time it holds the lock. Median of `rounds`.
double lock_wake_latency_ns(int rounds) {
  std::mutex m;
  std::atomic<int> round{-1};
  std::atomic<std::int64_t> unlocked_at{0};
  std::vector<double> latency;
  std::thread waiter([&] {
    for (int r = 0; r < rounds; ++r) {
      while (round.load(std::memory_order::acquire) != r) {
      }
      m.lock();
      const auto now = Clock::now().time_since_epoch().count();
      latency.push_back(static_cast<double>(now - unlocked_at.load(std::memory_order::acquire)));
      m.unlock();
      round.store(-1 - r - 1, std::memory_order::release);  // "round r done"
    }
  });
  for (int r = 0; r < rounds; ++r) {
    m.lock();
    round.store(r, std::memory_order::release);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    unlocked_at.store(Clock::now().time_since_epoch().count(), std::memory_order::release);
    m.unlock();
    while (round.load(std::memory_order::acquire) != -1 - r - 1) {
    }
  }
  waiter.join();
  static_assert(std::is_same_v<Clock::duration, std::chrono::nanoseconds>);
  return median(latency);
}

// The per-frame wake-up as worker_team.hpp does it: P threads asleep in atomic wait on a frame counter, the
// caller bumps it and calls notify_all; each thread stamps when it runs. Returns the median over frames of
// (latest stamp − earliest stamp) / (P − 1): how much later each further worker starts its frame.
double wake_skew_ns(unsigned workers, int frames) {
  std::atomic<std::uint64_t> started{0};
  std::atomic<std::uint64_t> arrived{0};
  std::vector<std::int64_t> stamp(workers * 8, 0);
  std::vector<std::thread> team;
  for (unsigned w = 0; w < workers; ++w) {
    team.emplace_back([&, w] {
      for (std::uint64_t k = 1; k <= static_cast<std::uint64_t>(frames); ++k) {
        std::uint64_t s = started.load(std::memory_order::acquire);
        while (s < k) {
          started.wait(s, std::memory_order::acquire);
          s = started.load(std::memory_order::acquire);
        }
        stamp[w * 8] = Clock::now().time_since_epoch().count();
        if (arrived.fetch_add(1, std::memory_order::acq_rel) + 1 == k * workers) arrived.notify_all();
      }
    });
  }
  std::vector<double> skew;
  for (int f = 1; f <= frames; ++f) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // every worker asleep in the futex
    started.store(static_cast<std::uint64_t>(f), std::memory_order::release);
    started.notify_all();
    // The caller sleeps too (as worker_team's does): a spinning caller would hold one of two cores.
    for (std::uint64_t a = arrived.load(std::memory_order::acquire); a < static_cast<std::uint64_t>(f) * workers;
         a = arrived.load(std::memory_order::acquire)) {
      arrived.wait(a, std::memory_order::acquire);
    }
    std::int64_t lo = stamp[0], hi = stamp[0];
    for (unsigned w = 1; w < workers; ++w) {
      lo = std::min(lo, stamp[w * 8]);
      hi = std::max(hi, stamp[w * 8]);
    }
    skew.push_back(static_cast<double>(hi - lo) / (workers - 1));
  }
  for (auto& t : team) t.join();
  return median(skew);
}

double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e9 * static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec);
}

double fence_cost_ns() {
  constexpr int kFences = 2000000;
  const auto t0 = Clock::now();
  for (int i = 0; i < kFences; ++i) std::atomic_thread_fence(std::memory_order::seq_cst);
  return ns_since(t0) / kFences;
}

}  // namespace

Overheads calibrate(const std::string& machine, const std::string& commit,
                    const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  Overheads o;
  o.machine = machine;
  o.commit = commit;
  const bool two = std::thread::hardware_concurrency() >= 2;
  say("calibration: per-item and per-frame costs of the real schedulers (no-op items)");
  o.static_list = model_costs("round-robin", two);
  o.queue = model_costs("queue-mutex", two);
  o.stealing = model_costs("stealing/Fenced", two);
  o.chase_lev = model_costs("chase-lev", two);
  say("calibration: lock, fence and cache-line transfer microbenchmarks");
  std::vector<double> lu, lh, pp, fe;
  for (int r = 0; r < 5; ++r) {
    lu.push_back(lock_ns(1));
    fe.push_back(fence_cost_ns());
    if (two) {
      lh.push_back(lock_ns(2));
      pp.push_back(ping_pong_ns());
    }
  }
  if (two) {
    say("calibration: lock hand-off to a sleeping waiter, per-frame wake-up skew of two sleeping workers");
    std::vector<double> lw, ws;
    for (int r = 0; r < 3; ++r) {
      lw.push_back(lock_wake_latency_ns(100));
      ws.push_back(wake_skew_ns(2, 100));
    }
    o.lock_wake_ns = median(lw);
    o.wake_skew_ns = median(ws);
  }
  o.lock_uncontended_ns = median(lu);
  o.fence_ns = median(fe);
  if (two) {
    o.lock_handoff_ns = median(lh);
    o.line_transfer_ns = median(pp);
  }
  o.assumed = !two;
  return o;
}

AffinityMeasurement measure_affinity(PathWorkload& wl, int repeats, std::uint64_t seed,
                                     const std::function<void(const std::string&)>& progress) {
  constexpr WorkerId kWorkers = 2;
  const ItemId n = wl.surfaces();
  wl.prepare_workers(kWorkers);
  std::mt19937_64 rng(seed);
  std::vector<WorkerId> last(n, 0);  // the worker that ran each item last
  std::uint64_t moved_runs = 0, counted_runs = 0;
  // One run of the path at P = 2; returns Σ thread CPU time in items over frames 1..F−1 (frame 0 reshuffles
  // after the previous run and is not counted).
  auto run_path = [&](bool shuffled) {
    double busy = 0;
    std::vector<std::vector<ItemId>> lists(kWorkers);
    for (int f = 0; f < wl.frames(); ++f) {
      for (auto& l : lists) l.clear();
      for (ItemId id = 0; id < n; ++id) {
        const WorkerId w = shuffled ? static_cast<WorkerId>(rng() & 1U) : (id < n / 2 ? 0 : 1);
        lists[w].push_back(id);
        if (f > 0 && shuffled) {
          ++counted_runs;
          if (w != last[id]) ++moved_runs;
        }
        last[id] = w;
      }
      double cpu[kWorkers] = {0, 0};
      auto body = [&](WorkerId w) {
        const double t0 = thread_cpu_ns();
        for (ItemId id : lists[w]) wl.tessellate(f, id, w);
        cpu[w] = thread_cpu_ns() - t0;
      };
      std::thread other(body, 1);
      body(0);
      other.join();
      if (f > 0) busy += cpu[0] + cpu[1];
    }
    return busy;
  };
  AffinityMeasurement a;
  run_path(false);  // warm-up
  for (int r = 0; r < repeats; ++r) {
    double kept = 0, shuffled = 0;
    if (r % 2 == 0) {
      kept = run_path(false);
      shuffled = run_path(true);
    } else {
      shuffled = run_path(true);
      kept = run_path(false);
    }
    a.kept_busy_ms.push_back(kept / 1e6);
    a.shuffled_busy_ms.push_back(shuffled / 1e6);
    if (progress) {
      progress("affinity: repeat " + std::to_string(r + 1) + ": kept " + std::to_string(kept / 1e6) + " ms, shuffled " +
               std::to_string(shuffled / 1e6) + " ms of CPU in items");
    }
  }
  a.moved_fraction = counted_runs ? static_cast<double>(moved_runs) / static_cast<double>(counted_runs) : 0;
  const double runs_per_path = static_cast<double>(n) * (wl.frames() - 1);
  std::vector<double> per_item;
  for (int r = 0; r < repeats; ++r) {
    const double moved_cost = a.kept_busy_ms[r] * a.moved_fraction;  // a random half: the kept mean cost
    a.penalty_per_repeat.push_back((a.shuffled_busy_ms[r] - a.kept_busy_ms[r]) / moved_cost);
    per_item.push_back(1e6 * (a.shuffled_busy_ms[r] - a.kept_busy_ms[r]) / (runs_per_path * a.moved_fraction));
  }
  a.moved_cost_ms = median(a.kept_busy_ms) * a.moved_fraction;
  a.penalty = median(a.penalty_per_repeat);
  a.penalty_ns_per_moved_item = median(per_item);
  return a;
}

void write_overheads(const Overheads& o, const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  out << "frontsteal-calibration 1\nmachine " << o.machine << "\ncommit " << o.commit << "\nassumed " << o.assumed
      << '\n';
  auto model = [&](const char* name, const ModelCosts& c) {
    out << name << ".item_ns " << c.item_ns << '\n'
        << name << ".frame_fixed_ns " << c.frame_fixed_ns << '\n'
        << name << ".second_worker_ns " << c.second_worker_ns << '\n';
  };
  model("static", o.static_list);
  model("queue", o.queue);
  model("stealing", o.stealing);
  model("chase_lev", o.chase_lev);
  out << "line_transfer_ns " << o.line_transfer_ns << "\nlock_uncontended_ns " << o.lock_uncontended_ns
      << "\nlock_handoff_ns " << o.lock_handoff_ns << "\nfence_ns " << o.fence_ns << "\nidle_round_ns "
      << o.idle_round_ns << "\nlock_wake_ns " << o.lock_wake_ns << "\nwake_skew_ns " << o.wake_skew_ns
      << "\naffinity_penalty " << o.affinity_penalty << "\naffinity_measured " << o.affinity_measured << '\n';
}

Overheads read_overheads(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot open calibration " + file.string());
  Overheads o;
  std::map<std::string, double*> numbers = {{"static.item_ns", &o.static_list.item_ns},
                                            {"static.frame_fixed_ns", &o.static_list.frame_fixed_ns},
                                            {"static.second_worker_ns", &o.static_list.second_worker_ns},
                                            {"queue.item_ns", &o.queue.item_ns},
                                            {"queue.frame_fixed_ns", &o.queue.frame_fixed_ns},
                                            {"queue.second_worker_ns", &o.queue.second_worker_ns},
                                            {"stealing.item_ns", &o.stealing.item_ns},
                                            {"stealing.frame_fixed_ns", &o.stealing.frame_fixed_ns},
                                            {"stealing.second_worker_ns", &o.stealing.second_worker_ns},
                                            {"chase_lev.item_ns", &o.chase_lev.item_ns},
                                            {"chase_lev.frame_fixed_ns", &o.chase_lev.frame_fixed_ns},
                                            {"chase_lev.second_worker_ns", &o.chase_lev.second_worker_ns},
                                            {"line_transfer_ns", &o.line_transfer_ns},
                                            {"lock_uncontended_ns", &o.lock_uncontended_ns},
                                            {"lock_handoff_ns", &o.lock_handoff_ns},
                                            {"fence_ns", &o.fence_ns},
                                            {"idle_round_ns", &o.idle_round_ns},
                                            {"lock_wake_ns", &o.lock_wake_ns},
                                            {"wake_skew_ns", &o.wake_skew_ns},
                                            {"affinity_penalty", &o.affinity_penalty}};
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream s(line);
    std::string key;
    s >> key;
    auto where = [&] { return file.string() + ":" + std::to_string(line_no) + ": "; };
    if (line_no == 1) {
      if (key != "frontsteal-calibration") throw std::runtime_error(where() + "not a frontsteal calibration file");
      continue;
    }
    if (key.empty()) continue;
    std::string rest;
    std::getline(s >> std::ws, rest);
    if (key == "machine")
      o.machine = rest;
    else if (key == "commit")
      o.commit = rest;
    else if (key == "assumed")
      o.assumed = rest == "1";
    else if (key == "affinity_measured")
      o.affinity_measured = rest == "1";
    else if (auto it = numbers.find(key); it != numbers.end()) {
      std::istringstream v(rest);
      if (!(v >> *it->second) || *it->second < 0) throw std::runtime_error(where() + "bad value for " + key);
    } else {
      throw std::runtime_error(where() + "unknown key '" + key + "'");
    }
  }
  if (line_no == 0) throw std::runtime_error(file.string() + ": empty calibration file");
  return o;
}

std::string describe(const Overheads& o) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "| model | item (ns) | frame at P = 1 (µs) | second worker adds (µs) |\n|---|---:|---:|---:|\n";
  auto row = [&](const char* name, const ModelCosts& c) {
    s << "| " << name << " | " << c.item_ns << " | " << c.frame_fixed_ns / 1e3 << " | " << c.second_worker_ns / 1e3
      << " |\n";
  };
  row("static (round-robin)", o.static_list);
  row("queue (queue-mutex)", o.queue);
  row("stealing (stealing/Fenced)", o.stealing);
  row("chase-lev", o.chase_lev);
  s << "\n| cost | ns |\n|---|---:|\n| line transfer | " << o.line_transfer_ns << " |\n| lock, uncontended | "
    << o.lock_uncontended_ns << " |\n| lock, contended (per acquisition) | " << o.lock_handoff_ns
    << " |\n| seq_cst fence | " << o.fence_ns << " |\n| steal (4 transfers + fence, derived) | " << o.steal_ns()
    << " |\n| idle round pause (assumed) | " << o.idle_round_ns
    << " |\n| each worker beyond 2, per frame (assumed: "
       "1 µs + 2 transfers) | "
    << o.extra_worker_ns() << " |\n| lock hand-off to a sleeping waiter | " << o.lock_wake_ns
    << " |\n| wake-up skew per further worker, per frame | " << o.wake_skew_ns
    << " |\n\nCache affinity: an item that changed worker since the previous frame costs " << o.affinity_penalty * 100
    << " % more"
    << (o.affinity_measured ? " (measured: lists kept vs shuffled at P = 2).\n"
                            : " (ASSUMED: not measured in this calibration).\n");
  if (o.assumed) s << "\nTwo-thread costs are ASSUMED defaults (one hardware thread: not measurable).\n";
  return s.str();
}

}  // namespace frontsteal::papers
