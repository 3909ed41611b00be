// command_line.hpp — every frontsteal executable's options, through CLI11 (Debian libcli11-dev).
//
// One spelling for the flags programs share (--out, --seed, --threads, --quiet, --help), defaults shown in
// --help, and one behaviour for mistakes: the message names the flag, points at --help, and the exit
// status is 2 (usage), the convention of every frontsteal program and of the tests that check them.
// --help prints to stdout and exits 0.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace frontsteal::report {

class CommandLine {
 public:
  // `description`: what the program does (first paragraph of --help); `footer`: printed after the options
  // (outputs, exit statuses, notes).
  CommandLine(std::string program, std::string description, std::string footer = {});

  CLI::App& app() noexcept { return app_; }
  const std::string& program() const noexcept { return program_; }

  // An option with a value; its current value is the default shown in --help.
  template <class T>
  CLI::Option* option(const std::string& names, T& value, const std::string& help) {
    return app_.add_option(names, value, help)->capture_default_str();
  }
  CLI::Option* flag(const std::string& names, bool& value, const std::string& help) {
    return app_.add_flag(names, value, help);
  }

  // The shared flags.
  CLI::Option* out(std::string& dir, const std::string& help = "results directory");
  CLI::Option* seed(std::uint64_t& seed, const std::string& help = "seed of every random choice");
  CLI::Option* threads(std::vector<unsigned>& counts, const std::string& help = "worker counts P, comma-separated");
  CLI::Option* quiet(bool& quiet, const std::string& help = "no progress lines");

  // Parses argv; --help: usage on stdout, exit 0; a mistake: message on stderr, exit 2.
  void parse(int argc, char** argv);
  // Whether this process prints help and mistakes (it exits with the same status either way): under mpirun
  // every rank parses the same command line and only rank 0 speaks.
  void set_speaks(bool speaks) noexcept { speaks_ = speaks; }

  // A mistake found after parsing (two options that do not go together ...): message, exit 2.
  [[noreturn]] void usage_error(const std::string& message) const;

 private:
  std::string program_;
  CLI::App app_;
  bool speaks_ = true;
};

// "WxH" → (W, H), each within [16, 16384]; throws CLI::ValidationError otherwise (for --size options).
std::pair<int, int> parse_size(const std::string& text);
// The validator of a --size option: parse_size's check, for ->check().
CLI::Validator size_validator();

}  // namespace frontsteal::report
