// stress_modes.hpp — frontsteal-stress's two modes: the bounded suite (every target × P under chaos, the model
// checker's scenarios on real threads, the faults) and --rates (duplicate rates of Paper, the exactly-once
// policies and every one-step weakening of Fenced and Minimal, on this machine's memory model, no chaos).
#pragma once

#include <chrono>

#include "stress/stress_options.hpp"
#include "stress/stress_report.hpp"

namespace frontsteal::stress {

// The bounded suite; progress lines on stderr are timed from `started`.
StressReport run_suite(const Options& o, std::chrono::steady_clock::time_point started);

// --rates: the handshake raced head-on, then the frame-level duplicate rate per million items.
StressReport run_rates(const Options& o);

}  // namespace frontsteal::stress
