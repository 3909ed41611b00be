// progress.hpp — the main job's progress lines on stderr: "[done/total elapsed, ~left] what".
//
// Why its own header: the measurement steps it, the main reads the elapsed time for the closing line.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace frontsteal::main_job {

class Progress {
 public:
  Progress(bool quiet, std::size_t total) : quiet_(quiet), total_(total), start_(std::chrono::steady_clock::now()) {}
  void set_total(std::size_t total) { total_ = total; }
  void step(const std::string& what) {
    ++done_;
    if (quiet_) return;
    const double elapsed = seconds();
    const double eta = done_ ? elapsed / done_ * (total_ - done_) : 0;
    std::fprintf(stderr, "[%3zu/%zu %5.0fs, ~%.0fs left] %s\n", done_, total_, elapsed, eta, what.c_str());
  }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  bool quiet_;
  std::size_t total_, done_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace frontsteal::main_job
