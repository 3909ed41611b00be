// checker_report.cpp — CheckerReport: the opening and closing every Relacy checker's report shares.
#include "models_check/checker_report.hpp"
#include "reporting/build_stamp.hpp"

#include <filesystem>
#include <utility>

namespace frontsteal::model {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

CheckerReport::CheckerReport(std::string program, std::string out, bool histories)
    : json(report::document(program, 2, "model-checked (bounded search)", FRONTSTEAL_GIT_COMMIT)),
      program_(std::move(program)),
      out_(std::move(out)),
      dir_(program_, out_),
      histories_(histories) {
  if (histories) std::filesystem::create_directories(dir_.file("histories"));
  started_ = std::chrono::steady_clock::now();
}

void CheckerReport::write(std::string_view stem) const {
  dir_.write(std::string(stem) + ".md", markdown);
  dir_.write_json(std::string(stem) + ".json", json);
}

int CheckerReport::close(std::string_view stem, bool all_as_expected, bool quiet) {
  const double run_seconds = seconds();
  json["all_as_expected"] = all_as_expected;
  json["seconds"] = run_seconds;
  markdown += "\n" +
              std::string(all_as_expected ? "Every verdict as expected." : "**Some verdicts were not as expected.**") +
              " Run time " + std::to_string(static_cast<int>(run_seconds)) + " s." +
              (histories_ ? " Failing executions' histories: histories/." : "") + "\n";
  write(stem);
  std::cout << markdown;
  if (!quiet) std::cerr << program_ << ": wrote " << out_ << "/" << stem << ".{md,json}\n";
  return all_as_expected ? 0 : 1;
}

}  // namespace frontsteal::model
