// membarrier.hpp — the heavy half of an asymmetric fence: Linux membarrier(MEMBARRIER_CMD_PRIVATE_EXPEDITED).
//
// One call makes every CPU that currently runs a thread of this process execute a full memory barrier, so
// the owner's compiler-only barrier (the light half) is as strong as a seq_cst fence whenever a thief needs
// it. The process registers once (MEMBARRIER_CMD_REGISTER_PRIVATE_EXPEDITED); without registration the
// command fails with EPERM. Kernels before 4.14 lack it. Measured on the development machines: ~0.76 µs.
#pragma once

#include <linux/membarrier.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace frontsteal {

struct MembarrierStatus {
  bool available = false;
  std::string detail;  // why not, or which command is used
};

// Registers the process for private expedited membarrier once; later calls return the first answer.
inline const MembarrierStatus& membarrier_status() {
  static const MembarrierStatus status = [] {
    MembarrierStatus s;
    const long supported = ::syscall(SYS_membarrier, MEMBARRIER_CMD_QUERY, 0, 0);
    if (supported < 0) {
      s.detail = std::string("membarrier(QUERY) failed: ") + std::strerror(errno);
      return s;
    }
    if ((supported & MEMBARRIER_CMD_PRIVATE_EXPEDITED) == 0) {
      s.detail = "kernel lacks MEMBARRIER_CMD_PRIVATE_EXPEDITED (needs Linux >= 4.14)";
      return s;
    }
    if (::syscall(SYS_membarrier, MEMBARRIER_CMD_REGISTER_PRIVATE_EXPEDITED, 0, 0) != 0) {
      s.detail = std::string("membarrier(REGISTER_PRIVATE_EXPEDITED) failed: ") + std::strerror(errno);
      return s;
    }
    s.available = true;
    s.detail = "membarrier(PRIVATE_EXPEDITED) registered";
    return s;
  }();
  return status;
}

// The heavy fence. Only called after membarrier_status().available was checked (the scheduler refuses to
// start an Asymmetric policy otherwise), so a failure here means the kernel changed its mind: abort rather
// than continue without the fence the exactly-once argument rests on.
inline void membarrier_heavy_fence() noexcept {
  if (::syscall(SYS_membarrier, MEMBARRIER_CMD_PRIVATE_EXPEDITED, 0, 0) != 0) {
    std::fprintf(stderr, "frontsteal: membarrier(PRIVATE_EXPEDITED) failed: %s\n", std::strerror(errno));
    std::abort();
  }
}

}  // namespace frontsteal
