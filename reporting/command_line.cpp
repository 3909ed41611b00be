// command_line.cpp — CommandLine: CLI11 with frontsteal's conventions (exit 2 on a mistake, the flag named).
#include "reporting/command_line.hpp"

#include <charconv>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>

namespace frontsteal::report {

namespace {

// CLI11 2.1's help prints each description on one line however long, and a validator's text ("INT:INT in
// [1 - 100000]") after every option name. This one wraps descriptions at 78 columns and shows
// "--flag VALUE" with the default and the accepted range or set at the end of the description instead.
class WrappingFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* opt) const override {
    std::string type = opt->get_type_name();
    if (type.empty()) return {};  // a flag
    type = type.substr(0, type.find(':'));
    return " " + (type.empty() ? std::string("VALUE") : type);
  }
  std::string make_option_desc(const CLI::Option* opt) const override {
    std::string text = opt->get_description();
    const std::string full_type = opt->get_type_name();
    if (const auto colon = full_type.find(':'); colon != std::string::npos)
      text += " (" + full_type.substr(colon + 1) + ")";
    if (!full_type.empty() && !opt->get_default_str().empty() && opt->get_default_str() != "[]")
      text += " [default " + opt->get_default_str() + "]";
    return wrap(text, 78 - get_column_width());
  }
  // Subcommands' summaries wrapped like option descriptions (frontsteal-paper's are a paragraph each).
  std::string make_subcommand(const CLI::App* sub) const override {
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true), wrap(sub->get_description(), 78 - get_column_width()),
                             get_column_width());
    return out.str();
  }

 private:
  static std::string wrap(const std::string& text, std::size_t width) {
    std::string out, word;
    std::size_t line = 0;
    auto flush = [&] {
      if (word.empty()) return;
      if (line > 0 && line + 1 + word.size() > width) {
        out += '\n';
        line = 0;
      } else if (line > 0) {
        out += ' ';
        ++line;
      }
      out += word;
      line += word.size();
      word.clear();
    };
    for (char c : text) {
      if (c == ' ' || c == '\n') {
        flush();
        if (c == '\n') out += '\n', line = 0;
      } else {
        word += c;
      }
    }
    flush();
    return out;
  }
};

}  // namespace

CommandLine::CommandLine(std::string program, std::string description, std::string footer)
    : program_(std::move(program)), app_(std::move(description), program_) {
  app_.description(app_.get_description() + "\n");
  if (!footer.empty()) app_.footer(footer + (footer.back() == '\n' ? "" : "\n"));
  auto formatter = std::make_shared<WrappingFormatter>();
  formatter->column_width(30);
  app_.formatter(formatter);
  app_.option_defaults()->always_capture_default();
}

CLI::Option* CommandLine::out(std::string& dir, const std::string& help) { return option("--out", dir, help); }
CLI::Option* CommandLine::seed(std::uint64_t& seed, const std::string& help) {
  // CLI11 2.1 takes "-1" (and values past 2^64 - 1) for an unsigned without a word; from_chars does not.
  return option("--seed", seed, help)
      ->check(CLI::Validator(
          [](std::string& v) {
            std::uint64_t parsed = 0;
            const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
            return ec == std::errc{} && end == v.data() + v.size()
                       ? std::string()
                       : "expects an integer in [0, 2^64 - 1], got '" + v + "'";
          },
          ""));
}
CLI::Option* CommandLine::threads(std::vector<unsigned>& counts, const std::string& help) {
  return app_.add_option("--threads", counts, help)->delimiter(',')->check(CLI::Range(1u, 1024u));
}
CLI::Option* CommandLine::quiet(bool& quiet, const std::string& help) { return flag("--quiet", quiet, help); }

void CommandLine::parse(int argc, char** argv) {
  try {
    app_.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    if (speaks_) std::cout << app_.help();
    std::exit(0);
  } catch (const CLI::CallForAllHelp&) {
    if (speaks_) std::cout << app_.help("", CLI::AppFormatMode::All);
    std::exit(0);
  } catch (const CLI::ParseError& e) {
    usage_error(e.what());
  }
}

void CommandLine::usage_error(const std::string& message) const {
  if (speaks_) std::cerr << program_ << ": " << message << "\n(run " << program_ << " --help for the options)\n";
  std::exit(2);
}

std::pair<int, int> parse_size(const std::string& text) {
  auto number = [&](std::string_view s) {
    int v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size() || v < 16 || v > 16384) {
      throw CLI::ValidationError("expects WxH with W, H in [16, 16384], e.g. 1280x720, got '" + text + "'");
    }
    return v;
  };
  const auto x = text.find('x');
  if (x == std::string::npos) {
    throw CLI::ValidationError("expects WxH, e.g. 1280x720, got '" + text + "'");
  }
  return {number(std::string_view(text).substr(0, x)), number(std::string_view(text).substr(x + 1))};
}

}  // namespace frontsteal::report

namespace frontsteal::report {

CLI::Validator size_validator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_size(text);
          return std::string();
        } catch (const CLI::ValidationError& e) {
          return std::string(e.what());
        }
      },
      "WxH");
}

}  // namespace frontsteal::report
