// child_options.cpp — frontsteal-llvm-openmp's command line (child_options.hpp).
#include "schedulers/llvm_openmp/child_options.hpp"

#include <charconv>
#include <tuple>

#include "reporting/command_line.hpp"

namespace frontsteal::llvm_openmp {

namespace {

namespace report = frontsteal::report;

constexpr const char* kDescription =
    R"(The tessellation workload under LLVM libomp's static_steal, for the main job (frontsteal), which starts it
as a child process and talks to it over stdin/stdout (protocol in schedulers/llvm_openmp/static_steal_child.cpp).
Commands on stdin: "path" (run the camera path once, report every frame), "frames A B" (frames A .. B-1 only), "quit".)";

// --fault drop:K | dup:K → (kind, K); false when malformed.
bool parse_fault(const std::string& v, Options::Fault& kind, int& item) {
  const auto colon = v.find(':');
  if (colon == std::string::npos) return false;
  const std::string k = v.substr(0, colon);
  if (k != "drop" && k != "dup") return false;
  const char* first = v.data() + colon + 1;
  const char* last = v.data() + v.size();
  int k_item = 0;
  const auto [end, ec] = std::from_chars(first, last, k_item);
  if (ec != std::errc{} || end != last || first == last || k_item < 0 || k_item > (1 << 30)) return false;
  kind = k == "drop" ? Options::Fault::drop : Options::Fault::dup;
  item = k_item;
  return true;
}

}  // namespace

Options parse_options(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription);
  cli.option("--workers", o.workers, "OpenMP threads")->type_name("P")->required()->check(CLI::Range(1, 1024));
  cli.option("--scene", o.scene, "as frontsteal's --scene")->type_name("S");
  cli.option("--frames", o.frames, "frames along the path")->type_name("F")->check(CLI::Range(1, 100000));
  std::string path = ts::name(o.path);
  cli.option("--path", path, "camera path")
      ->type_name("NAME")
      ->check(CLI::IsMember({"orbit-then-zoom", "orbit", "zoom", "walkthrough", "dense-zoom"}));
  cli.option("--tolerance", o.tolerance, "screen-space tolerance in pixels")
      ->type_name("PX")
      ->check(CLI::Range(0.01, 1000.0));
  std::string size = "1280x720";
  cli.option("--size", size, "image size")->type_name("WxH")->check(report::size_validator());
  cli.option("--grain", o.grain, "items per chunk")->type_name("G")->check(CLI::Range(1, 1 << 30));
  std::string defect;
  cli.option("--plant-defect", defect, "frontsteal's tessellation negative control")
      ->type_name("D")
      ->check(CLI::IsMember({"wave1-bridge", "drop-ear"}));
  cli.flag("--pin", o.pin, "pin thread t to the t-th allowed CPU");
  cli.flag("--reuse", o.reuse, "frame-to-frame reuse of unchanged surfaces, as frontsteal --reuse");
  cli.option("--schedule", o.schedule,
             "static-steal, or the probe's negative controls monotonic-dynamic and static, which must make it fail")
      ->type_name("S")
      ->check(CLI::IsMember({"static-steal", "monotonic-dynamic", "static"}));
  std::string fault;
  cli.option("--fault", fault,
             "drop:K | dup:K: skip item K, or run it twice, in every frame (the audit's negative "
             "control)")
      ->type_name("F")
      ->check(CLI::Validator(
          [](std::string& v) {
            Options::Fault kind;
            int item = 0;
            return parse_fault(v, kind, item) ? std::string() : "expects drop:K or dup:K, got '" + v + "'";
          },
          ""));
  cli.parse(argc, argv);

  o.path = *ts::camera_path_named(path);
  std::tie(o.width, o.height) = report::parse_size(size);
  if (!defect.empty()) o.defect = *ts::planted_defect_named(defect);
  if (!fault.empty()) parse_fault(fault, o.fault, o.fault_item);
  return o;
}

}  // namespace frontsteal::llvm_openmp
