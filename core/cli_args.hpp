// cli_args.hpp — the small command-line helpers every frontsteal executable shares: a usage error that names
// the program and points at --help, strict number parsing with a range, comma-separated lists.
#pragma once

#include <charconv>
#include <cstdlib>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

namespace frontsteal::cli {

// Bad input: say what was wrong and how to get help; exit status 2 (usage).
[[noreturn]] inline void usage_error(std::string_view program, const std::string& message) {
  std::cerr << program << ": " << message << "\n(run " << program << " --help for the options)\n";
  std::exit(2);
}

// Parses all of `text` as a number within [min_value, max_value], or exits with a usage error naming `flag`.
template <class T>
T parse_number(std::string_view program, std::string_view flag, std::string_view text, T min_value, T max_value) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size()) {
    usage_error(program, std::string(flag) + " expects a number, got '" + std::string(text) + "'");
  }
  if (value < min_value || value > max_value) {
    usage_error(program, std::string(flag) + " must be between " + std::to_string(min_value) + " and " +
                             std::to_string(max_value) + ", got " + std::string(text));
  }
  return value;
}

// Walks argv flag by flag; answers --help / -h itself (prints the usage text, exits 0) and turns a flag
// whose value is missing into a usage error.
class ArgReader {
 public:
  ArgReader(int argc, char** argv, std::string_view program, std::string_view usage)
      : argc_(argc), argv_(argv), program_(program), usage_(usage) {}

  // Moves to the next flag; false when none is left.
  bool next() {
    if (++i_ >= argc_) return false;
    flag_ = argv_[i_];
    if (flag_ == "--help" || flag_ == "-h") {
      std::cout << usage_;
      std::exit(0);
    }
    return true;
  }
  std::string_view flag() const noexcept { return flag_; }
  // The argument after the current flag.
  std::string_view value() {
    if (i_ + 1 >= argc_) usage_error(program_, std::string(flag_) + " needs a value");
    return argv_[++i_];
  }

 private:
  int argc_;
  char** argv_;
  std::string_view program_;
  std::string_view usage_;
  int i_ = 0;
  std::string_view flag_;
};

// "WxH" with both sides within [min_side, max_side] (image and window sizes), or a usage error naming `flag`.
struct Size {
  int width = 0, height = 0;
};
inline Size parse_size(std::string_view program, std::string_view flag, std::string_view text, int min_side, int max_side) {
  const auto x = text.find('x');
  if (x == std::string_view::npos) {
    usage_error(program, std::string(flag) + " expects WxH, e.g. 640x360, got '" + std::string(text) + "'");
  }
  return {parse_number<int>(program, flag, text.substr(0, x), min_side, max_side),
          parse_number<int>(program, flag, text.substr(x + 1), min_side, max_side)};
}

inline std::vector<std::string> split_list(std::string_view s) {
  std::vector<std::string> out;
  while (!s.empty()) {
    const auto comma = s.find(',');
    out.emplace_back(s.substr(0, comma));
    if (comma == std::string_view::npos) break;
    s.remove_prefix(comma + 1);
  }
  return out;
}

}  // namespace frontsteal::cli
