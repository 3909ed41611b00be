// papers/paper_options.hpp: frontsteal-paper's command line. Every option is the parent's, so it means the same
// before and after the subcommand; the subcommands come from the caller's table. Usage errors (exit 2) are
// ctests of the binary; here the values a valid command line yields.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "papers/paper_options.hpp"

namespace fp = frontsteal::papers;

namespace {

const std::vector<fp::SubcommandSummary> kCommands{{"table1", "Table 1"}, {"fig8", "Fig. 8"}, {"table2", "Table 2"}};

fp::Options parse(std::vector<std::string> args) {
  args.insert(args.begin(), "frontsteal-paper");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return fp::parse_options(static_cast<int>(argv.size()), argv.data(), kCommands);
}

}  // namespace

TEST_CASE("an option means the same before and after the subcommand", "[papers][options]") {
  const fp::Options before = parse({"--frames", "2", "--max-p", "8", "fig8"});
  const fp::Options after = parse({"fig8", "--frames", "2", "--max-p", "8"});
  for (const fp::Options& o : {before, after}) {
    CHECK(o.command == "fig8");
    CHECK(o.frames == 2);
    CHECK(o.max_p == 8);
    CHECK(o.repeats == 3);  // untouched: the default
  }
}

TEST_CASE("the defaults, and the flags that turn them off", "[papers][options]") {
  const fp::Options plain = parse({"table1"});
  CHECK(plain.out == "results/papers");
  CHECK(plain.plot);
  CHECK(plain.cost_multiplier == 0);  // auto
  CHECK(plain.scenes.empty());
  const fp::Options changed = parse({"table2", "--no-plot", "--cost-multiplier", "off", "--scenes", "teapot,plant:100",
                                     "--null-renderer", "--seed", "9", "--validation", "v.json"});
  CHECK(changed.command == "table2");
  CHECK_FALSE(changed.plot);
  CHECK(changed.cost_multiplier == -1);
  CHECK(changed.scenes == std::vector<std::string>{"teapot", "plant:100"});
  CHECK(changed.null_renderer);
  CHECK(changed.seed == 9);
  CHECK(changed.validation == "v.json");
  CHECK(parse({"table2", "--cost-multiplier", "12"}).cost_multiplier == 12);
}
