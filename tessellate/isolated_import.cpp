// isolated_import.cpp — see isolated_import.hpp.
#include "tessellate/isolated_import.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <poll.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tessellate/model_format.hpp"

namespace frontsteal::tess {
namespace {

// The child's message: "report" line, "skip"/"warn" lines, then "model" and the native-format text; or one
// "error" line. Reasons are single lines (newlines replaced).
std::string one_line(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

[[noreturn]] void run_child(int fd, const std::string& path, const ImportOptions& options) {
  // A reader's crash must end the child by its signal, whatever handlers the program installed (a sanitizer's
  // handler would print a report and exit(1) instead): the parent names the signal.
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
  std::ostringstream msg;
  int status = 0;
  try {
    Model model;
    const ImportReport r = import_cad_file(path, model, options);
    msg << "report " << r.faces << ' ' << r.faces_imported << ' ' << r.patches << ' ' << r.surfaces << ' '
        << r.trim_loops << ' ' << r.loops_reoriented << ' ' << r.corner_loops_cut << ' ' << std::hexfloat
        << r.max_patch_error << std::defaultfloat << '\n';
    for (const ImportSkip& s : r.skipped) msg << "skip " << s.face << ' ' << one_line(s.reason) << '\n';
    for (const std::string& w : r.warnings) msg << "warn " << one_line(w) << '\n';
    msg << "model\n";
    write_model(msg, model);
  } catch (const std::bad_alloc&) {
    msg.str("");
    msg << "error out of memory\n";
    status = 1;
  } catch (const std::exception& e) {
    msg.str("");
    msg << "error " << one_line(e.what()) << '\n';
    status = 1;
  }
  const std::string text = msg.str();
  for (std::size_t sent = 0; sent < text.size();) {
    const ssize_t n = ::write(fd, text.data() + sent, text.size() - sent);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(3);
    sent += static_cast<std::size_t>(n);
  }
  ::close(fd);
  _exit(status);
}

double resident_mb(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  long pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0;
  return static_cast<double>(pages_resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

std::string reader_name(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".step" || ext == ".stp") return "the STEP reader";
  if (ext == ".iges" || ext == ".igs") return "the IGES reader";
  if (ext == ".brep") return "the BREP reader";
  return "the reader";
}

}  // namespace

ImportReport import_cad_file_isolated(const std::string& path, Model& out, const ImportOptions& options,
                                      const IsolationLimits& limits) {
  if (options.samples_per_span < 1) throw std::invalid_argument("ImportOptions::samples_per_span must be >= 1");
  if (!(limits.time_limit_s > 0) || !(limits.memory_limit_mb > 0)) {
    throw std::invalid_argument("IsolationLimits: time and memory limits must be > 0");
  }
  int fds[2];
  if (::pipe(fds) != 0)
    throw ImportFailure(ImportFailure::Cause::protocol, path + ": cannot create a pipe: " + std::strerror(errno));
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw ImportFailure(ImportFailure::Cause::protocol,
                        path + ": cannot start the reader process: " + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    run_child(fds[1], path, options);
  }
  ::close(fds[1]);

  // Read while watching: the pipe must be drained or a large model would block the child forever.
  std::string text;
  const auto start = std::chrono::steady_clock::now();
  bool open = true, killed_time = false, killed_memory = false;
  double peak_mb = 0;
  char buffer[1 << 16];
  while (open) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, 20);
    if (ready > 0) {
      const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
      if (n > 0) text.append(buffer, static_cast<std::size_t>(n));
      if (n == 0) open = false;
      if (n < 0 && errno != EINTR) open = false;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    peak_mb = std::max(peak_mb, resident_mb(child));
    if (open && elapsed > limits.time_limit_s) killed_time = true;
    if (open && peak_mb > limits.memory_limit_mb) killed_memory = true;
    if (killed_time || killed_memory) {
      ::kill(child, SIGKILL);
      break;
    }
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  const std::string reader = reader_name(path);
  std::ostringstream limit;
  if (killed_time) {
    limit << path << ": " << reader << " did not finish in " << limits.time_limit_s
          << " s (stopped; the limit is set with --time-limit)";
    throw ImportFailure(ImportFailure::Cause::timed_out, limit.str());
  }
  if (killed_memory) {
    limit << path << ": " << reader << " used more than " << limits.memory_limit_mb
          << " MiB of memory (stopped; the limit is set with --memory-limit)";
    throw ImportFailure(ImportFailure::Cause::out_of_memory, limit.str());
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    throw ImportFailure(ImportFailure::Cause::crashed, path + ": " + reader + " crashed (signal " +
                                                           std::to_string(sig) + ", SIG" + sigabbrev_np(sig) +
                                                           ") reading this file");
  }
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) {  // it exited without a word: as much a crash as a signal
    throw ImportFailure(ImportFailure::Cause::crashed, path + ": " + reader + " crashed (exit status " +
                                                           std::to_string(WEXITSTATUS(status)) +
                                                           ", no result) reading this file");
  }
  if (line.starts_with("error ")) {
    const std::string why = line.substr(6);
    throw ImportFailure(
        why == "out of memory" ? ImportFailure::Cause::out_of_memory : ImportFailure::Cause::reader_error,
        why == "out of memory" ? path + ": " + reader + " ran out of memory" : why);
  }
  ImportReport report;
  report.file = path;
  {
    std::istringstream r(line);
    std::string word, error;  // the error as a hexadecimal float (exact), which operator>> does not read
    char* end = nullptr;
    if (!(r >> word >> report.faces >> report.faces_imported >> report.patches >> report.surfaces >>
          report.trim_loops >> report.loops_reoriented >> report.corner_loops_cut >> error) ||
        word != "report" ||
        (report.max_patch_error = std::strtod(error.c_str(), &end), end != error.c_str() + error.size())) {
      throw ImportFailure(ImportFailure::Cause::protocol, path + ": garbled result from the reader process");
    }
  }
  while (std::getline(in, line) && line != "model") {
    if (line.starts_with("skip ")) {
      std::istringstream r(line.substr(5));
      ImportSkip s{};
      r >> s.face;
      std::getline(r >> std::ws, s.reason);
      report.skipped.push_back(s);
    } else if (line.starts_with("warn ")) {
      report.warnings.push_back(line.substr(5));
    }
  }
  Model imported;
  try {
    imported = parse_model(in, path + " (imported)");
  } catch (const ModelError& e) {
    throw ImportFailure(ImportFailure::Cause::protocol,
                        std::string("the imported surfaces failed the native checks: ") + e.what());
  }
  if (out.name.empty()) out.name = imported.name;
  for (Surface& s : imported.surfaces) out.surfaces.push_back(std::move(s));
  return report;
}

}  // namespace frontsteal::tess
