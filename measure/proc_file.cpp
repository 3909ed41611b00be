// proc_file.cpp — open/read a /proc file (proc_file.hpp).
#include "measure/proc_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

namespace frontsteal::noise {

std::string read_open_file(int fd) noexcept {
  try {
    std::string text;
    char buf[4096];
    for (;;) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return {};  // ESRCH: the process ended after open(); any other error: nothing to report
      if (n == 0) return text;
      text.append(buf, static_cast<std::size_t>(n));
    }
  } catch (...) {  // std::bad_alloc: nothing read
    return {};
  }
}

std::string read_proc_file(const std::string& path) noexcept {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  std::string text = read_open_file(fd);
  ::close(fd);
  return text;
}

}  // namespace frontsteal::noise
