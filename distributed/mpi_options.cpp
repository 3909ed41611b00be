// mpi_options.cpp — frontsteal-mpi's options (mpi_options.hpp), through report::CommandLine (CLI11).
#include "distributed/mpi_options.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>

#include "core/id_range.hpp"
#include "distributed/synthetic_cost.hpp"
#include "reporting/command_line.hpp"

namespace frontsteal::mpi {
namespace {

// Every scheduler frontsteal-mpi runs, for --schedulers and --reference.
const std::vector<std::string> kSchedulerNames{"rma",    "rma-seeded",   "request", "central",
                                               "static", "static-space", "hier",    "hier-seeded"};

constexpr const char* kDescription = R"(usage: mpirun -np P frontsteal-mpi [options]

Runs the frame loop across MPI ranks under each scheduler (rma, request, central, static, static-space), audits every frame
(each item executed exactly once, triangle count equal to a serial loop's) and prints a table per scheduler:
frames/s, per-rank busy time, items, steals, mean steal latency, bytes moved, owner overhead per item; then
medians with 95 % bootstrap confidence intervals and the noise monitor's verdict.
As root, Open MPI needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 in the environment; with more
ranks than cores add --oversubscribe --mca mpi_yield_when_idle 1.)";
constexpr const char* kFooter = R"(
Exit status: 0 all audits passed; 1 an audit failed; 2 bad command line; 3 --die; 86 watchdog.)";

std::vector<std::string> split(std::string_view s, char sep) {
  std::vector<std::string> out;
  while (true) {
    const auto p = s.find(sep);
    out.emplace_back(s.substr(0, p));
    if (p == std::string_view::npos) break;
    s.remove_prefix(p + 1);
  }
  return out;
}

// "A:B:C" of `parts` non-negative integers, each at most the matching bound.
CLI::Validator integers_validator(std::vector<int> bounds, std::string shape) {
  return CLI::Validator(
      [bounds, shape](std::string& text) -> std::string {
        const auto p = split(text, ':');
        if (p.size() != bounds.size()) return "expects " + shape + ", got '" + text + "'";
        for (std::size_t k = 0; k < p.size(); ++k) {
          int v = -1;
          const auto [end, ec] = std::from_chars(p[k].data(), p[k].data() + p[k].size(), v);
          if (ec != std::errc{} || end != p[k].data() + p[k].size() || v < 0 || v > bounds[k]) {
            return "expects " + shape + " (non-negative integers, at most " + std::to_string(bounds[k]) + " in place " +
                   std::to_string(k + 1) + "), got '" + text + "'";
          }
        }
        return {};
      },
      shape);
}

CLI::Validator scene_validator() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        if (v.empty()) return "needs a non-empty value";
        const SyntheticScene s = parse_synthetic_scene(v);
        if (!s.synthetic) return {};
        if (s.items < 1 || s.items > 50000000) {
          return s.prefix + ":N needs N between 1 and 50000000, got '" + v + "'";
        }
        return {};
      },
      "");
}

// A file the run will write at its end: its folder must exist and the path must not name a folder, so that a
// typing mistake is refused before MPI starts, not found after the last frame.
CLI::Validator output_file_validator() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        if (v.empty()) return "needs a file name";
        const std::filesystem::path p(v);
        std::error_code ec;
        if (std::filesystem::is_directory(p, ec)) return "'" + v + "' is a folder, not a file";
        const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
        if (!std::filesystem::is_directory(folder, ec)) return "the folder of '" + v + "' does not exist";
        return {};
      },
      "FILE");
}

// off, microseconds between 0 and 1e6, and (with_auto) auto.
CLI::Validator interval_validator(bool with_auto) {
  return CLI::Validator(
      [with_auto](std::string& v) -> std::string {
        if (v == "off" || (with_auto && v == "auto")) return {};
        double us = -1;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), us);
        if (ec != std::errc{} || end != v.data() + v.size() || us < 0 || us > 1e6) {
          return std::string("expects ") + (with_auto ? "auto, " : "") +
                 "off or microseconds between 0 and 1000000, got '" + v + "'";
        }
        return {};
      },
      with_auto ? "auto|off|US" : "off|US");
}

}  // namespace

int launcher_rank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    if (const char* s = std::getenv(v)) return std::atoi(s);
  }
  return 0;
}

Options parse_options(int argc, char** argv) {
  Options o;
  report::CommandLine cli(std::string(kProgram), kDescription, kFooter);
  cli.set_speaks(launcher_rank() == 0);  // every rank parses; rank 0 alone prints
  cli.option("--scene", o.scene,
             "synthetic:N (a moving heavy fifth) | cascade:N (cost concentrated in space, synthetic_cost.hpp) | "
             "teapot | teacup | teaspoon | plant:N[:seed] | model file")
      ->check(scene_validator());
  cli.option("--frames", o.frames, "frames along the camera path")->check(CLI::Range(1, 100000));
  cli.app()
      .add_option(
          "--schedulers", o.schedulers,
          "comma list of rma,rma-seeded (lists from the last frame's measured costs),request,central,"
          "static (round robin),static-space (contiguous blocks of ids: regions of space),hier (ranks x "
          "--threads: stealing among a rank's threads, then across ranks),hier-seeded (hier, lists from the last "
          "frame's measured costs)")
      ->delimiter(',')
      ->check(CLI::IsMember(kSchedulerNames));
  cli.option("--work-ns", o.work_ns, "synthetic: cost of a light item (cascade: of the mean item) in ~ns of busy work")
      ->check(CLI::Range(0u, 100000000u));
  cli.option("--skew", o.skew, "synthetic: the heavy fifth of the ids (a window that moves each frame) costs K x")
      ->check(CLI::Range(1u, 10000u));
  cli.option("--tolerance", o.tolerance, "tessellation pixel tolerance")->check(CLI::PositiveNumber);
  cli.option("--json", o.json, "also write the results (or, with --calibrate, the latencies) as JSON to this file")
      ->check(output_file_validator());
  cli.option("--markdown", o.markdown, "also write the medians with 95 % CIs and the noise verdict as markdown")
      ->check(output_file_validator());
  cli.option("--plots", o.plots,
             "also write plots to this directory: frame time per scheduler, busy and idle time "
             "per rank (PNG through gnuplot, with their data and script)");
  cli.option("--watchdog-s", o.watchdog_s, "a rank that makes no progress for S s exits 86 (0 = off)")
      ->check(CLI::Range(0.0, 86400.0));
  std::string stall, die, slow;
  cli.option("--stall", stall, "R:F:MS: rank R sleeps MS ms after its first item of frame F (fault test)")
      ->check(integers_validator({1 << 20, 100000, 3600000}, "RANK:FRAME:MS"));
  cli.option("--slow", slow,
             "R:F:MS: rank R is slowed 10x by the OS for MS ms from its first item of frame F: a helper process "
             "stops it (SIGSTOP) 9 ms of every 10 and lets it run (SIGCONT) 1 ms (fault test)")
      ->check(integers_validator({1 << 20, 100000, 3600000}, "RANK:FRAME:MS"));
  cli.option("--die", die, "R:F: rank R exits abruptly (status 3) after its first item of frame F (fault test)")
      ->check(integers_validator({1 << 20, 100000}, "RANK:FRAME"));
  cli.option("--plant-defect", o.defect,
             "negative controls: none | skip-reread (rma thief skips T4/T5) | stale-view (rma thief's one-Get view "
             "of a victim outlives its stores and answers T5: Front as it was at T1) | "
             "request-keeps-share (request owner sends a share and keeps it) | read-before-flush (one-sided results "
             "read before MPI_Win_flush: the start-up window self-test must fail over osc/pt2pt) | "
             "lifeline-drops-notice (hier: a rank that learns the frame is over tells no other rank: the ranks "
             "waiting on their lifelines never learn it, and the watchdog must end the job)")
      ->check(CLI::IsMember(
          {"none", "skip-reread", "stale-view", "request-keeps-share", "read-before-flush", "lifeline-drops-notice"}));
  cli.flag("--force-overlap", o.force_overlap,
           "rma thieves wait, before T3, until the victim has claimed into the planned share");
  cli.option("--owner-fence", o.owner_fence,
             "the rma owner's F1: cpu (a seq_cst fence, no MPI call on the owner path) | "
             "win-sync (MPI_Win_sync + the fence: the standard's barrier, but a progress call per claim)")
      ->check(CLI::IsMember({"cpu", "win-sync"}));
  cli.option("--owner-progress", o.owner_progress,
             "the busy rma owner calls MPI_Iprobe at most every US microseconds "
             "(0: every item) so one-sided operations aimed at it complete on transports without asynchronous "
             "progress (TCP); the request owner's poll and rank 0 in central chunks use the same interval; "
             "auto: off under Open MPI with every rank on one node (osc/sm), else 50")
      ->check(interval_validator(true));
  cli.option("--progress-thread", o.progress_thread,
             "each rank runs a thread that calls MPI_Iprobe, sleeping US microseconds between calls (0: yielding), "
             "so one-sided operations aimed at the rank complete whatever its workers do; needs "
             "MPI_THREAD_MULTIPLE, which Open MPI 4.1's osc/pt2pt refuses (over TCP use --mca osc ucx)")
      ->check(interval_validator(false));
  cli.flag("--require-steals", o.require_steals,
           "exit 1 unless rma, request and hier each made at least one steal (hier: "
           "across ranks; tests: stealing was exercised)");
  cli.flag("--calibrate", o.calibrate,
           "measure get/put/CAS/fetch-and-op/flush latency and the owner's per-item "
           "costs, then exit");
  cli.option("--calibrate-op-s", o.calibrate_op_s, "--calibrate: at most this many seconds per operation")
      ->check(CLI::Range(0.01, 600.0));
  cli.option("--rounds", o.rounds,
             "paired rounds: each round runs every scheduler, its A/A twin and a planted slowdown of --reference "
             "for --frames frames, in a random order; each is then compared with --reference (0: one pass each)")
      ->check(CLI::Range(0, 100000));
  cli.option("--reference", o.reference, "--rounds: the scheduler every other arm is compared with")
      ->check(CLI::IsMember(kSchedulerNames));
  cli.option("--margin-pct", o.margin_pct, "--rounds: equivalence margin of the verdicts, % of time")
      ->check(CLI::Range(0.1, 50.0));
  cli.option("--planted-pct", o.planted_pct,
             "--rounds: the planted arm is --reference slowed by this % of its frame time (rank 0 spins after "
             "each frame, inside the timed region)")
      ->check(CLI::Range(0.1, 500.0));
  cli.option("--seed", o.seed, "--rounds: seed of the round orders");
  cli.option("--threads", o.threads,
             "hier: worker threads per rank (core's protocol among them; only the rank's main thread calls MPI)")
      ->check(CLI::Range(1, 256));
  cli.option("--chunk-us", o.chunk_us,
             "hier: a worker takes from its rank's list a chunk of about this much work (us, by the last frame's "
             "measured item times; an item without one priced by the worker's last item, their number capped; at "
             "most 256 items)")
      ->check(CLI::Range(0.001, 1e6));
  std::string lifelines = "on";
  cli.option("--lifelines", lifelines,
             "hier: on = a rank that found nothing in a round of 8 random victims registers at its lifelines "
             "((r + 2^k) mod P), reads the count and waits to be invited, and the frame's end travels a tree of "
             "notices (lifelines.hpp); off = rounds of random victims with back-off, each after a read of the count")
      ->check(CLI::IsMember({"on", "off"}));
  std::string batch_claims = "on";
  cli.option("--batch-claims", batch_claims,
             "hier: on = a refill claims each run of consecutive ids of its chunk from the rank list in one owner "
             "handshake (core's Owner::try_claim_up_to); off = one handshake per item (Owner::try_claim)")
      ->check(CLI::IsMember({"on", "off"}));
  std::string thief_reads = "view";
  cli.option("--thief-reads", thief_reads,
             "rma, hier: view = a thief reads a victim's Front, End and list in one MPI_Get (rma_backend.hpp V1); "
             "words = one operation per word, for comparison")
      ->check(CLI::IsMember({"view", "words"}));
  cli.option("--ledger", o.ledger,
             "each rank records its frame and the items it ran in DIR/rank-R.ledger (a mapped file that outlives "
             "the rank): after a job a dead rank ended, --post-mortem DIR says what was lost");
  cli.option("--post-mortem", o.post_mortem,
             "read the ledgers a --ledger run left in DIR, report which rank died and which items of its last "
             "frame were lost, and exit (run without mpirun)");
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  o.lifelines = lifelines == "on";
  o.batch_claims = batch_claims == "on";
  o.thief_views = thief_reads == "view";
  const auto is_hier = [](const std::string& s) { return s == "hier" || s == "hier-seeded"; };
  const bool hier =
      std::any_of(o.schedulers.begin(), o.schedulers.end(), is_hier) || (o.rounds > 0 && is_hier(o.reference));
  if (hier && !stall.empty()) {
    cli.usage_error(
        "--stall sleeps the rank's main thread until a thief lowers its End, and under hier its other threads keep "
        "emptying the rank list: use --slow (the whole rank slowed by the OS) or --die with hier");
  }
  if (o.defect == "lifeline-drops-notice" && (!hier || !o.lifelines)) {
    cli.usage_error(
        "--plant-defect lifeline-drops-notice plants its defect in hier's lifelines: run it with "
        "--schedulers hier (or hier-seeded) and --lifelines on");
  }
  if (hier && o.owner_fence == "win-sync") {
    cli.usage_error(
        "--owner-fence win-sync calls MPI on every claim, and under hier any worker thread claims: "
        "use --owner-fence cpu with hier");
  }
  if (o.rounds > 0 && o.planted_pct <= o.margin_pct) {
    cli.usage_error("--planted-pct (" + std::to_string(o.planted_pct) + ") must exceed --margin-pct (" +
                    std::to_string(o.margin_pct) + "): the planted arm must be found slower, beyond the margin");
  }
  if (!stall.empty()) {
    const auto p = split(stall, ':');
    o.stall_rank = std::stoi(p[0]), o.stall_frame = std::stoi(p[1]), o.stall_ms = std::stoi(p[2]);
  }
  if (!slow.empty()) {
    const auto p = split(slow, ':');
    o.slow_rank = std::stoi(p[0]), o.slow_frame = std::stoi(p[1]), o.slow_ms = std::stoi(p[2]);
  }
  if (!die.empty()) {
    const auto p = split(die, ':');
    o.die_rank = std::stoi(p[0]), o.die_frame = std::stoi(p[1]);
  }
  return o;
}

}  // namespace frontsteal::mpi
