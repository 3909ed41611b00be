// progress_thread.cpp — the rank's progress thread (progress_thread.hpp).
#include "distributed/progress_thread.hpp"

#include <chrono>

#include "distributed/owner_progress.hpp"

namespace frontsteal::mpi {

ProgressThread::ProgressThread(MPI_Comm comm, double sleep_us) {
  const auto pause =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double, std::micro>(sleep_us));
  thread_ = std::thread([this, comm, pause] {
    while (!stop_.load(std::memory_order_acquire)) {
      int flag = 0;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagProgressProbe, comm, &flag, MPI_STATUS_IGNORE);
      calls_.fetch_add(1, std::memory_order_relaxed);
      if (pause.count() > 0) {
        std::this_thread::sleep_for(pause);
      } else {
        std::this_thread::yield();
      }
    }
  });
}

ProgressThread::~ProgressThread() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

}  // namespace frontsteal::mpi
