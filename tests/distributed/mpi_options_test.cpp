// distributed/mpi_options.hpp: frontsteal-mpi's command line as every rank parses it before MPI_Init. Usage
// errors (exit 2, rank 0 alone printing) are ctests of the binary (distributed.mpi.bad_flag.*); here the
// values a valid command line yields, and the launcher's rank read from the environment.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/rank_stats.hpp"

namespace mpi = frontsteal::mpi;

namespace {

mpi::Options parse(std::vector<std::string> args) {
  args.insert(args.begin(), "frontsteal-mpi");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return mpi::parse_options(static_cast<int>(argv.size()), argv.data());
}

// Sets an environment variable for one scope and restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      ::setenv(name_, old_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST_CASE("no flags: the defaults the docs promise", "[distributed][options]") {
  const mpi::Options o = parse({});
  CHECK(o.scene == "synthetic:20000");
  CHECK(o.frames == 30);
  CHECK(o.schedulers == std::vector<std::string>{"rma", "request", "central", "static", "static-space"});
  CHECK(o.owner_progress == "auto");
  CHECK(o.owner_fence == "cpu");
  CHECK(o.defect == "none");
  CHECK(o.stall_rank == -1);
  CHECK(o.die_rank == -1);
  CHECK_FALSE(o.calibrate);
}

TEST_CASE("every value of a full command line arrives", "[distributed][options]") {
  const mpi::Options o = parse({"--scene",
                                "synthetic:500",
                                "--frames",
                                "4",
                                "--schedulers",
                                "rma,static",
                                "--work-ns",
                                "10",
                                "--skew",
                                "3",
                                "--stall",
                                "1:2:30",
                                "--die",
                                "2:3",
                                "--plant-defect",
                                "skip-reread",
                                "--owner-progress",
                                "10",
                                "--owner-fence",
                                "win-sync",
                                "--require-steals",
                                "--quiet",
                                "--json",
                                "out.json",
                                "--plots",
                                "plots"});
  CHECK(o.scene == "synthetic:500");
  CHECK(o.frames == 4);
  CHECK(o.schedulers == std::vector<std::string>{"rma", "static"});
  CHECK(o.work_ns == 10);
  CHECK(o.skew == 3);
  CHECK(o.stall_rank == 1);
  CHECK(o.stall_frame == 2);
  CHECK(o.stall_ms == 30);
  CHECK(o.die_rank == 2);
  CHECK(o.die_frame == 3);
  CHECK(o.defect == "skip-reread");
  CHECK(o.owner_progress == "10");
  CHECK(o.owner_fence == "win-sync");
  CHECK(o.require_steals);
  CHECK(o.quiet);
  CHECK(o.json == "out.json");
  CHECK(o.plots == "plots");
}

TEST_CASE("the launcher's rank is read before MPI_Init, from any of the three launchers", "[distributed][options]") {
  const ScopedEnv ompi("OMPI_COMM_WORLD_RANK", nullptr), pmi("PMI_RANK", nullptr), pmix("PMIX_RANK", nullptr);
  CHECK(mpi::launcher_rank() == 0);  // not launched: rank 0 speaks
  {
    const ScopedEnv hydra("PMI_RANK", "3");
    CHECK(mpi::launcher_rank() == 3);
  }
  {
    const ScopedEnv pmix_rank("PMIX_RANK", "5");
    CHECK(mpi::launcher_rank() == 5);
    const ScopedEnv open_mpi("OMPI_COMM_WORLD_RANK", "1");  // Open MPI's own variable wins
    CHECK(mpi::launcher_rank() == 1);
  }
}

TEST_CASE("a rank's statistics travel as a flat array of doubles", "[distributed][rank_stats]") {
  // MPI_Gather sends kRankStatFields MPI_DOUBLEs: a field of another type would be cut or misread.
  CHECK(mpi::kRankStatFields * sizeof(double) == sizeof(mpi::RankStats));
  mpi::RankStats s;
  s.busy_s = 1.5;
  s.steal_operations = 7;  // the last field
  const double* flat = reinterpret_cast<const double*>(&s);
  CHECK(flat[0] == 1.5);
  CHECK(flat[mpi::kRankStatFields - 1] == 7);
}
