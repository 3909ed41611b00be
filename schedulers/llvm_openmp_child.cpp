// llvm_openmp_child.cpp — the parent's side of openmp-static-steal (llvm_openmp_child.hpp): spawn, protocol,
// audit, reaping.
#include "schedulers/llvm_openmp_child.hpp"

#include "measure/proc_file.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#ifndef FRONTSTEAL_LLVM_OPENMP_CHILD
#define FRONTSTEAL_LLVM_OPENMP_CHILD ""
#endif
#ifndef FRONTSTEAL_LLVM_OPENMP_REASON
#define FRONTSTEAL_LLVM_OPENMP_REASON "not configured"
#endif

namespace frontsteal::sched {

std::string llvm_openmp_child_path() {
  if (const char* env = std::getenv("FRONTSTEAL_LLVM_OPENMP"); env && *env) return env;
  return FRONTSTEAL_LLVM_OPENMP_CHILD;
}

std::string llvm_openmp_unavailable_reason() {
  const std::string configured = FRONTSTEAL_LLVM_OPENMP_REASON;
  const std::string path = llvm_openmp_child_path();
  if (!configured.empty() && !std::getenv("FRONTSTEAL_LLVM_OPENMP")) return configured;
  if (path.empty() || ::access(path.c_str(), X_OK) != 0) {
    return "the child executable " + (path.empty() ? std::string("(none)") : path) +
           " is missing (build the frontsteal target, which builds frontsteal-llvm-openmp with clang++-14)";
  }
  return "";
}

ExecutionAudit audit_runs(const std::vector<std::uint32_t>& runs) {
  ExecutionAudit a;
  a.items = runs.size();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::uint32_t r = runs[i];
    if (r == 0) {
      ++a.lost;
      if (a.first_lost.size() < 8) a.first_lost.push_back(static_cast<ItemId>(i));
    } else if (r > 1) {
      ++a.duplicated;
      a.extra_runs += r - 1;
      if (a.first_duplicated.size() < 8) a.first_duplicated.push_back(static_cast<ItemId>(i));
    }
  }
  return a;
}

namespace {

template <class T>
bool parse_int(std::string_view s, T& out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc{} && end == s.data() + s.size();
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> out;
  while (true) {
    const auto p = s.find(sep);
    out.push_back(s.substr(0, p));
    if (p == std::string_view::npos) return out;
    s.remove_prefix(p + 1);
  }
}

}  // namespace

bool decode_runs(std::string_view text, ItemId items, std::vector<std::uint32_t>& out) {
  out.clear();
  out.reserve(items);
  if (text == "-") return items == 0;
  for (std::string_view run : split(text, ',')) {
    const auto star = run.find('*');
    std::uint32_t value = 0;
    std::uint64_t length = 0;
    if (star == std::string_view::npos || !parse_int(run.substr(0, star), value) ||
        !parse_int(run.substr(star + 1), length) || length == 0 || out.size() + length > items) {
      return false;
    }
    out.insert(out.end(), length, value);
  }
  return out.size() == items;
}

LlvmOpenMpChild::LlvmOpenMpChild(WorkerId workers, ItemId items, const ChildWorkload& w, double reply_timeout_s,
                                 std::string executable)
    : workers_(workers), items_(items), frames_(w.frames), timeout_s_(reply_timeout_s) {
  if (executable.empty() || ::access(executable.c_str(), X_OK) != 0) {
    throw std::runtime_error("the child executable " + executable + " is missing");
  }
  // Everything the child needs is built before fork: between fork and exec only async-signal-safe calls.
  std::vector<std::string> args = {executable, "--workers", std::to_string(workers),  "--scene",
                                   w.scene,    "--frames",  std::to_string(w.frames), "--path",
                                   w.path};
  std::ostringstream tol;
  tol.precision(17);
  tol << w.tolerance;
  args.insert(args.end(),
              {"--tolerance", tol.str(), "--size", std::to_string(w.width) + "x" + std::to_string(w.height)});
  if (w.grain) args.insert(args.end(), {"--grain", std::to_string(w.grain)});
  if (!w.plant_defect.empty()) args.insert(args.end(), {"--plant-defect", w.plant_defect});
  if (w.pin) args.push_back("--pin");
  args.insert(args.end(), w.extra_args.begin(), w.extra_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    throw std::runtime_error(std::string("socketpair: ") + std::strerror(errno));
  }
  const pid_t parent = ::getpid();
  // vfork, not fork: fork marks every writable page of this (large) process copy-on-write, and after the child's
  // exec each page this process writes next takes a fault; the arm whose memory nobody else writes (the limit
  // arm's copies) paid all of its own, 10-30 % of its frame time in the pass after each restart. vfork shares the
  // memory until exec and leaves the page tables alone; the child only makes system calls before exec.
  pid_ = ::vfork();
  if (pid_ < 0) {
    const int e = errno;
    ::close(sv[0]);
    ::close(sv[1]);
    throw std::runtime_error(std::string("vfork: ") + std::strerror(e));
  }
  if (pid_ == 0) {
    // Child: die with the parent (and if it is already gone, go now); stdin and stdout are the socket.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(126);
    ::dup2(sv[1], 0);
    ::dup2(sv[1], 1);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(sv[1]);
  fd_ = sv[0];
  try {
    const std::string line = read_line();
    if (line.rfind("ready ", 0) != 0) {
      throw std::runtime_error(line.rfind("error ", 0) == 0 ? line.substr(6) : "unexpected first line '" + line + "'");
    }
    const std::string want = "items=" + std::to_string(items) + " ";
    if (line.find(want) == std::string::npos) {
      throw std::runtime_error("the child prepared another scene: '" + line + "', expected " + want);
    }
    ready_ = line;
  } catch (...) {
    reap();
    throw;
  }
}

LlvmOpenMpChild::~LlvmOpenMpChild() { reap(); }

void LlvmOpenMpChild::reap() {
  if (fd_ >= 0) {
    if (pid_ > 0) ::send(fd_, "quit\n", 5, MSG_NOSIGNAL);  // may fail: the child may be gone already
    ::close(fd_);                                          // end of input: the child exits even if it missed "quit"
    fd_ = -1;
  }
  if (pid_ <= 0) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  int status = 0;
  while (true) {
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_ || (r < 0 && errno != EINTR)) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid_, SIGKILL);
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  pid_ = -1;
}

void LlvmOpenMpChild::send(std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::send(fd_, text.data(), text.size(), MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("the child is gone (write: ") + std::strerror(errno) + ")");
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

std::string LlvmOpenMpChild::read_line() {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s_);
  while (true) {
    if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
      std::string line = buffer_.substr(0, nl);
      buffer_.erase(0, nl + 1);
      return line;
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw std::runtime_error("the child did not answer within " + std::to_string(static_cast<int>(timeout_s_)) +
                               " s");
    }
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (r < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    if (r <= 0) continue;
    char chunk[65536];
    const ssize_t n = ::read(fd_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != ECONNRESET) throw std::runtime_error(std::string("read: ") + std::strerror(errno));
    if (n <= 0) {
      // End of output, or the socket reset by a child that died with our "path" unread: it exited. Say how.
      int status = 0;
      std::string how = "the child closed its output";
      if (::waitpid(pid_, &status, 0) == pid_) {
        pid_ = -1;
        if (WIFEXITED(status)) {
          how = "the child exited with status " + std::to_string(WEXITSTATUS(status)) +
                (WEXITSTATUS(status) == 127 ? " (could not execute it)" : "");
        } else if (WIFSIGNALED(status)) {
          how = "the child was killed by signal " + std::to_string(WTERMSIG(status));
        }
      }
      throw std::runtime_error(how + (buffer_.empty() ? "" : "; last output: " + buffer_));
    }
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

std::vector<ChildFrame> LlvmOpenMpChild::run_path() { return run_frames(0, frames_); }

std::vector<ChildFrame> LlvmOpenMpChild::run_frames(int first, int last) {
  send("frames " + std::to_string(first) + " " + std::to_string(last) + "\n");
  std::vector<ChildFrame> frames;
  frames.reserve(static_cast<std::size_t>(last - first));
  std::vector<std::uint32_t> runs;
  auto bad = [](const std::string& line, const std::string& why) {
    return std::runtime_error("protocol: " + why + " in '" + line.substr(0, 200) + "'");
  };
  while (true) {
    const std::string line = read_line();
    if (line == "end") break;
    if (line.rfind("error ", 0) == 0) throw std::runtime_error(line.substr(6));
    const auto t = split(line, ' ');
    // frame f wall triangles inconsistent P {9 per worker} runs
    constexpr std::uint32_t kPerWorker = 9;
    std::uint32_t p = 0;
    if (t.size() < 7 || t[0] != "frame" || !parse_int(t[5], p) || p != workers_ || t.size() != 7 + kPerWorker * p) {
      throw bad(line, "malformed frame line");
    }
    ChildFrame cf;
    int f = -1;
    if (!parse_int(t[1], f) || f != first + static_cast<int>(frames.size()) || !parse_int(t[2], cf.stats.wall_ns) ||
        !parse_int(t[3], cf.triangles) || !parse_int(t[4], cf.inconsistent)) {
      throw bad(line, "malformed frame header");
    }
    cf.stats.frame = static_cast<std::uint32_t>(++frame_counter_);
    cf.stats.workers.resize(p);
    for (std::uint32_t w = 0; w < p; ++w) {
      std::int64_t v[kPerWorker];
      for (std::uint32_t k = 0; k < kPerWorker; ++k) {
        if (!parse_int(t[6 + kPerWorker * w + k], v[k])) throw bad(line, "malformed worker field");
      }
      WorkerFrameStats& ws = cf.stats.workers[w];
      ws.items_processed = static_cast<std::uint64_t>(v[0]);
      ws.claims = static_cast<std::uint64_t>(v[1]);
      ws.busy_ns = v[2];
      ws.idle_ns = cf.stats.wall_ns - v[2];
      ws.active_ns = v[3];
      ws.cpu_ns = v[4];
      // Steals: chunks this thread ran that libomp's static ranges gave another. Failed attempts are not
      // observable from outside libomp: attempts = successes.
      ws.steals_succeeded = ws.steal_attempts = static_cast<std::uint64_t>(v[5]);
      ws.items_stolen = static_cast<std::uint64_t>(v[6]);
      ws.wake_ns = v[7];
      ws.termination_ns = v[8];
    }
    if (!decode_runs(t.back(), items_, runs))
      throw bad(line, "per-item counts do not cover the " + std::to_string(items_) + " items");
    cf.audit = audit_runs(runs);
    frames.push_back(std::move(cf));
  }
  if (static_cast<int>(frames.size()) != last - first) {
    throw std::runtime_error("the child ran " + std::to_string(frames.size()) + " frames, expected " +
                             std::to_string(last - first));
  }
  return frames;
}

std::uint64_t LlvmOpenMpChild::cpu_ticks() const {
  if (pid_ <= 0) return 0;
  const std::string text = noise::read_proc_file("/proc/" + std::to_string(pid_) + "/stat");
  // "pid (comm) state ppid ...": comm may hold spaces, so fields are counted after the last ')'; utime and
  // stime are fields 14 and 15, i.e. the 12th and 13th after it.
  const auto close = text.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(text.substr(close + 1));
  std::string skip;
  for (int i = 0; i < 11; ++i) fields >> skip;
  std::uint64_t utime = 0, stime = 0;
  fields >> utime >> stime;
  return utime + stime;
}

}  // namespace frontsteal::sched
