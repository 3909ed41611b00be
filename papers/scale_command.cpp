// scale_command.cpp — the body of `frontsteal-paper scale` (scale_command.hpp).
//
// Steps: read every <study>/<set>/frontsteal.json (schema 4: with the loss account); take the simulator's
// constants from the microbenchmarks (calibrate()) or --calibration, and the account's from the calibration set
// (scale.hpp); record one cost trace per path and one of the large scene (kept in --traces and reused); predict
// every held-out row's account term by term; sweep P = 1 ... --max-p on both traces; write the report.
#include "papers/scale_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "measure/machine_info.hpp"
#include "papers/scale.hpp"
#include "papers/workload.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/json.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"

namespace frontsteal::papers {
namespace {

constexpr const char* kProgram = "frontsteal-paper scale";
constexpr const char* kDescription =
    "The loss account, SIMULATED: its constants from one measured main-job run (the calibration set of --study: "
    "per-item claim and checks, each worker's wake-up, the join, the work's inflation at each P), every term of "
    "every other set's rows predicted and compared with what the main job measured (error per term), then the "
    "account of stealing/Fenced, queue-mutex and chase-lev at P = 1, 2, 4 ... --max-p on the main job's scene and "
    "on --large-scene, with the P at which each falls below 90 % of the machine's limit and the term that grows "
    "first.";
constexpr const char* kFooter =
    "Writes scale.md, scale.json and scale.png (the sweep's losses against P) into --out. Every number is labelled "
    "measured or simulated.\nExit status: 0 written, 1 a file could not be read or written, 2 usage.";

struct Options {
  std::string study, calibrate_on = "orbit-then-zoom-none", traces, calibration, out = "results/papers";
  std::string large_scene = "plant:63624", inflation, wake_us;
  int passes = 3;
  unsigned max_p = 256;
  std::uint64_t seed = 1;
  bool quiet = false;
};

std::string pct(double share, int digits = 1) { return report::fixed_text(100 * share, digits); }

// "16:1.19,32:1.25" → {16: 1.19, 32: 1.25}; throws std::invalid_argument on a malformed entry.
std::map<WorkerId, double> parse_pairs(const std::string& text, const char* flag) {
  std::map<WorkerId, double> out;
  std::istringstream in(text);
  std::string entry;
  while (std::getline(in, entry, ',')) {
    const auto colon = entry.find(':');
    if (colon == std::string::npos) throw std::invalid_argument(std::string(flag) + ": '" + entry + "' is not K:VALUE");
    const unsigned long p = std::stoul(entry.substr(0, colon));
    const double f = std::stod(entry.substr(colon + 1));
    if (!(f > 0)) throw std::invalid_argument(std::string(flag) + ": '" + entry + "' needs a VALUE > 0");
    out[static_cast<WorkerId>(p)] = f;
  }
  return out;
}

CostTrace trace_of(const std::string& scene, const std::string& path, const std::filesystem::path& dir, int passes,
                   const std::function<void(const std::string&)>& say) {
  std::string key = scene + "-" + path;
  std::replace(key.begin(), key.end(), ':', '-');
  const auto file = dir / ("trace-" + key + ".txt");
  if (std::filesystem::exists(file)) return read_cost_trace(file);
  say("recording the trace of " + scene + " along " + path + " (" + std::to_string(passes) + " serial passes)");
  PathWorkload wl(WorkloadOptions{.scene = scene, .path = path, .data_dir = FRONTSTEAL_DATA_DIR});
  CostTrace t = record_cost_trace(wl, passes, machine_description(), FRONTSTEAL_GIT_COMMIT, true);
  write_cost_trace(t, file);
  return t;
}

}  // namespace

int run_scale_command(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--study", o.study, "folder of main-job result folders, each with a frontsteal.json of schema 4")
      ->required()
      ->type_name("DIR");
  cli.option("--calibrate-on", o.calibrate_on, "the set (folder name) the account's constants come from")
      ->type_name("SET");
  cli.option("--traces", o.traces, "folder of the cost traces (recorded when missing; default OUT/traces)")
      ->type_name("DIR");
  cli.option("--calibration", o.calibration, "the microbenchmarks' constants to use instead of measuring them")
      ->type_name("FILE");
  cli.option("--passes", o.passes, "serial passes per trace (per surface the median)")->check(CLI::Range(1, 100));
  cli.option("--large-scene", o.large_scene, "the second scene of the sweep, large enough for many workers")
      ->type_name("S");
  cli.option("--max-p", o.max_p, "the sweep's largest P (powers of two from 1)")->check(CLI::Range(1u, 4096u));
  cli.option("--wake-us", o.wake_us,
             "the wake-up of worker W (us) instead of the calibration set's, as W:US,... (0-based; the last one given "
             "stands for every further worker), e.g. from a larger machine's measurement")
      ->type_name("LIST");
  cli.option("--inflation", o.inflation,
             "the work's inflation at P beyond the measured ones, as P:FACTOR,... (default: the largest measured "
             "P's); e.g. 16:1.19")
      ->type_name("LIST");
  cli.seed(o.seed);
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  auto say = [&](const std::string& s) {
    if (!o.quiet) std::cerr << "scale: " << s << '\n';
  };
  try {
    std::map<WorkerId, double> extra_inflation, wake_override;
    try {
      extra_inflation = parse_pairs(o.inflation, "--inflation");
      wake_override = parse_pairs(o.wake_us, "--wake-us");
      if (extra_inflation.count(0)) throw std::invalid_argument("--inflation: P starts at 1");
    } catch (const std::exception& e) {
      cli.usage_error(e.what());
    }
    // ---- the measured sets and the constants ------------------------------------------------------------
    const std::vector<MeasuredSet> sets = read_study(o.study);
    const auto cal =
        std::find_if(sets.begin(), sets.end(), [&](const MeasuredSet& s) { return s.name == o.calibrate_on; });
    if (cal == sets.end()) cli.usage_error("--calibrate-on: no set '" + o.calibrate_on + "' under " + o.study);
    const Overheads base = o.calibration.empty() ? calibrate(machine_description(), FRONTSTEAL_GIT_COMMIT, say)
                                                 : read_overheads(o.calibration);
    AccountConstants constants = account_constants(*cal, base);
    for (const auto& [p, f] : extra_inflation) constants.inflation[p] = f;
    if (!wake_override.empty()) {
      std::vector<double>& wake = constants.overheads.wake_by_worker_ns;
      wake.resize(std::max<std::size_t>(wake.size(), wake_override.rbegin()->first + 1),
                  wake.empty() ? 0 : wake.back());
      for (const auto& [w, us] : wake_override) wake[w] = 1000 * us;
      wake.resize(wake_override.rbegin()->first + 1);  // the last given stands for every further worker
    }
    say("calibration set " + cal->name + "; " + std::to_string(sets.size()) + " sets");

    // ---- traces ---------------------------------------------------------------------------------------------
    const std::filesystem::path trace_dir =
        o.traces.empty() ? std::filesystem::path(o.out) / "traces" : std::filesystem::path(o.traces);
    std::filesystem::create_directories(trace_dir);
    std::map<std::string, CostTrace> traces;  // by set
    for (const MeasuredSet& s : sets) traces[s.name] = trace_of(s.scene, s.path, trace_dir, o.passes, say);
    const double trace_scale = cal->serial_ms / (traces.at(cal->name).path_cost_ns() / 1e6);

    // ---- term by term, every row of every set -----------------------------------------------------------------
    std::vector<TermComparison> rows;
    for (const MeasuredSet& s : sets) {
      for (const MeasuredCell& c : s.cells) {
        if (!c.account || !model_of(c.scheduler) || c.workers > hardware_cores()) {
          continue;
        }
        TermComparison r{s.name, c.scheduler, c.workers, comparable_shares(*c.account), {}, {}};
        r.predicted = predict_account(traces.at(s.name), trace_scale, constants, c.scheduler, c.workers, o.seed).shares;
        std::vector<std::pair<double, std::string>> by_size;
        for (const auto& [term, share] : r.measured) by_size.emplace_back(share, term);
        std::sort(by_size.rbegin(), by_size.rend());
        for (std::size_t i = 0; i < std::min<std::size_t>(2, by_size.size()); ++i)
          r.largest.push_back(by_size[i].second);
        rows.push_back(std::move(r));
      }
    }
    if (rows.empty()) throw std::runtime_error("no row with a loss account and a simulator model under " + o.study);

    // ---- the sweep beyond the machine -----------------------------------------------------------------------------
    const std::vector<std::string> swept{"stealing/Fenced", "queue-mutex", "chase-lev"};
    const CostTrace& main_trace = traces.at(cal->name);
    const CostTrace large = trace_of(o.large_scene, cal->path, trace_dir, o.passes, say);
    say("sweeping P = 1 ... " + std::to_string(o.max_p));
    std::vector<ScalePoint> points = sweep(main_trace, cal->scene, trace_scale, constants, swept, o.max_p, o.seed);
    const std::vector<ScalePoint> large_points =
        sweep(large, o.large_scene, trace_scale, constants, swept, o.max_p, o.seed);
    points.insert(points.end(), large_points.begin(), large_points.end());

    // ---- the report -----------------------------------------------------------------------------------------------
    report::Json js = report::document(kProgram, 1, "simulated", FRONTSTEAL_GIT_COMMIT);
    js["machine"] = machine_description();
    js["calibration_set"] = cal->name;
    js["trace_scale"] = trace_scale;
    js["constants"] = {{"checks_per_item_ns", constants.overheads.checks_ns},
                       {"claim_per_item_ns",
                        {{"static", constants.overheads.static_list.item_ns},
                         {"queue", constants.overheads.queue.item_ns},
                         {"stealing", constants.overheads.stealing.item_ns},
                         {"chase_lev", constants.overheads.chase_lev.item_ns}}},
                       {"wake_by_worker_ns", constants.overheads.wake_by_worker_ns},
                       {"further_worker_wake_ns", constants.overheads.extra_worker_ns()},
                       {"join_ns", constants.overheads.join_ns}};
    report::Json infl = report::Json::object();
    for (const auto& [p, f] : constants.inflation) infl[std::to_string(p)] = f;
    js["constants"]["inflation_by_p"] = infl;

    std::ostringstream md;
    md << "# The loss account, simulated: validated term by term, then predicted beyond the machine\n\n"
       << "Machine: " << machine_description() << ". Commit " << FRONTSTEAL_GIT_COMMIT
       << ". Measured sets: the folders of `" << std::filesystem::path(o.study).filename().string()
       << "` (the main job's frontsteal.json, schema 4). **Calibration set: " << cal->name
       << "**: the only measured accounts the model sees. Every other set is held out. Everything below marked "
          "SIMULATED is the simulator's; MEASURED is the main job's.\n\n"
       << "Constants (from the calibration set's account unless marked): checks "
       << report::fixed_text(constants.overheads.checks_ns, 1) << " ns per item; claim per item: static "
       << report::fixed_text(constants.overheads.static_list.item_ns, 1) << ", queue "
       << report::fixed_text(constants.overheads.queue.item_ns, 1) << ", stealing "
       << report::fixed_text(constants.overheads.stealing.item_ns, 1) << ", chase-lev "
       << report::fixed_text(constants.overheads.chase_lev.item_ns, 1) << " ns; wake-up by worker:";
    for (std::size_t w = 0; w < constants.overheads.wake_by_worker_ns.size(); ++w) {
      md << (w ? "," : "") << " w" << w << " " << report::fixed_text(constants.overheads.wake_by_worker_ns[w] / 1000, 1)
         << " us";
    }
    md << (wake_override.empty() ? "" : " (given by --wake-us)") << ", then "
       << report::fixed_text(constants.overheads.extra_worker_ns() / 1000, 2)
       << " us more per further worker (ASSUMED: the kernel's wake of one more thread); join "
       << report::fixed_text(constants.overheads.join_ns / 1000, 1) << " us; the work's inflation by P:";
    for (const auto& [p, f] : constants.inflation) {
      md << " P=" << p << " " << report::fixed_text(f, 3)
         << (extra_inflation.count(p) ? " (given by --inflation)" : "");
    }
    md << " (beyond: the largest P's). Trace scale " << report::fixed_text(trace_scale, 4)
       << " (the calibration set's serial loop over the trace's sum).\n\n";

    // Per term: the held-out rows' errors.
    md << "## Term by term (held out, P <= cores)\n\nError = 100 x (SIMULATED - MEASURED) / MEASURED share of P x T "
          "(measured with off-CPU time put back and the T4 wait in steal); '-' where the measured share is below "
          "0.2 %.\n\n";
    std::vector<report::Column> cols{{"set", "set", false}, {"scheduler", "scheduler", false}, {"workers", "P"}};
    for (const char* t : kSimulatedTerms) {
      cols.push_back({std::string(t) + "_measured", std::string(t) + " meas (%)"});
      cols.push_back({std::string(t) + "_simulated", std::string(t) + " sim (%)"});
    }
    cols.push_back({"two_largest_error_pct", "error of the two largest (%)", false});
    report::Table table(cols);
    std::map<std::string, std::vector<double>> held_out_errors;
    std::vector<double> two_largest_errors;
    report::Json js_rows = report::Json::array();
    for (const TermComparison& r : rows) {
      const bool held_out = r.set != cal->name;
      std::vector<report::Cell> cells{r.set + (held_out ? "" : " (calibration)"), r.scheduler, r.workers};
      report::Json jr{{"set", r.set}, {"held_out", held_out}, {"scheduler", r.scheduler}, {"workers", r.workers}};
      for (const char* t : kSimulatedTerms) {
        cells.emplace_back(pct(r.measured.at(t), 2));
        cells.emplace_back(pct(r.predicted.at(t), 2));
        const double e = r.error_pct(t);
        jr[t] = {{"measured", r.measured.at(t)},
                 {"simulated", r.predicted.at(t)},
                 {"error_pct", std::isnan(e) ? report::Json(nullptr) : report::Json(e)}};
        if (held_out && !std::isnan(e)) held_out_errors[t].push_back(std::fabs(e));
      }
      std::string largest;
      for (const std::string& t : r.largest) {
        const double e = r.error_pct(t);
        largest += (largest.empty() ? "" : ", ") + t + " " + (std::isnan(e) ? "-" : report::fixed_text(e, 1));
        if (held_out && !std::isnan(e)) two_largest_errors.push_back(std::fabs(e));
      }
      cells.emplace_back(largest);
      jr["two_largest"] = r.largest;
      table.add_row(std::move(cells));
      js_rows.push_back(std::move(jr));
    }
    md << table.markdown() << "\n";
    report::Table summary({{"term", "term", false},
                           {"rows", "held-out rows"},
                           {"median", "median |error| (%)"},
                           {"worst", "worst |error| (%)"}});
    report::Json js_summary = report::Json::object();
    for (const char* t : kSimulatedTerms) {
      std::vector<double> e = held_out_errors[t];
      std::sort(e.begin(), e.end());
      const double med = e.empty() ? 0 : e[e.size() / 2], worst = e.empty() ? 0 : e.back();
      summary.add_row({t, static_cast<std::uint64_t>(e.size()), e.empty() ? "-" : report::fixed_text(med, 1),
                       e.empty() ? "-" : report::fixed_text(worst, 1)});
      js_summary[t] = {{"rows", e.size()}, {"median_abs_pct", med}, {"worst_abs_pct", worst}};
    }
    const double worst_two =
        two_largest_errors.empty() ? 0 : *std::max_element(two_largest_errors.begin(), two_largest_errors.end());
    // The two largest terms over the held-out rows (mean measured share), and their errors.
    std::vector<std::pair<double, std::string>> mean_share;
    for (const char* t : kSimulatedTerms) {
      double sum = 0;
      std::size_t n = 0;
      for (const TermComparison& r : rows) {
        if (r.set == cal->name) continue;
        sum += r.measured.at(t);
        ++n;
      }
      mean_share.emplace_back(n ? sum / static_cast<double>(n) : 0, t);
    }
    std::sort(mean_share.rbegin(), mean_share.rend());
    md << summary.markdown() << "\n";
    report::Json js_largest = report::Json::array();
    bool medians_met = true;
    for (std::size_t i = 0; i < 2 && i < mean_share.size(); ++i) {
      const std::string& t = mean_share[i].second;
      const report::Json& sj = js_summary[t];
      const double med = sj["median_abs_pct"].get<double>(), worst = sj["worst_abs_pct"].get<double>();
      medians_met = medians_met && med <= 10;
      md << "- The " << (i == 0 ? "largest" : "second largest") << " term over the held-out rows, **" << t << "** ("
         << pct(mean_share[i].first) << " % of P x T on average): median |error| " << report::fixed_text(med, 1)
         << " %, worst " << report::fixed_text(worst, 1) << " %.\n";
      js_largest.push_back(
          {{"term", t}, {"mean_share", mean_share[i].first}, {"median_abs_pct", med}, {"worst_abs_pct", worst}});
    }
    md << "\n**Goal (the two largest terms within 10 %): median " << (medians_met ? "met" : "NOT met")
       << "; row by row (each held-out row's own two largest terms) the worst |error| is "
       << report::fixed_text(worst_two, 1) << " %: " << (worst_two <= 10 ? "met" : "NOT met") << ".**\n\n";
    js["rows"] = js_rows;
    js["held_out_summary"] = js_summary;
    js["two_largest_terms"] = js_largest;
    js["two_largest_median_goal_met"] = medians_met;
    js["row_two_largest_worst_abs_pct"] = worst_two;

    // The sweep, per trace and scheduler: limit-efficiency and the largest loss at each P.
    md << "## Beyond the machine (SIMULATED)\n\nThe machine's limit is P copies of the same work at the same "
          "inflation, so the limit-efficiency is the work's share of P x T. The largest-item bound (from the trace "
          "alone, no model): per frame the work over P cannot end before the frame's costliest surface does; it caps "
          "every scheduler of whole items, and termination grows as P approaches it.\n\n";
    report::Json js_sweep = report::Json::array();
    for (const std::string& trace_name : {cal->scene, o.large_scene}) {
      md << "### " << trace_name << " along " << cal->path << "\n\n";
      std::vector<report::Column> sc{{"scheduler", "scheduler", false},
                                     {"workers", "P"},
                                     {"frames_per_s", "frames/s"},
                                     {"limit_efficiency", "limit-eff (%)"},
                                     {"critical_path_bound", "largest-item bound (%)"}};
      for (const char* t : kSimulatedTerms) {
        if (std::string(t) != "work") sc.push_back({t, std::string(t) + " (%)"});
      }
      sc.push_back({"largest_loss", "largest loss", false});
      report::Table st(sc);
      for (const ScalePoint& pt : points) {
        if (pt.trace != trace_name) continue;
        const double fps = pt.path_ns > 0 ? 1e9 * static_cast<double>(main_trace.frames()) / pt.path_ns : 0;
        std::vector<report::Cell> cells{pt.scheduler, pt.workers, report::fixed_text(fps, 1), pct(pt.limit_efficiency),
                                        pct(pt.critical_path_bound)};
        report::Json jp{{"trace", pt.trace},
                        {"scheduler", pt.scheduler},
                        {"workers", pt.workers},
                        {"path_ns", pt.path_ns},
                        {"limit_efficiency", pt.limit_efficiency},
                        {"critical_path_bound", pt.critical_path_bound},
                        {"largest_loss", pt.largest_loss}};
        for (const char* t : kSimulatedTerms) {
          jp[t] = pt.shares.at(t);
          if (std::string(t) != "work") cells.emplace_back(pct(pt.shares.at(t)));
        }
        cells.emplace_back(pt.largest_loss);
        st.add_row(std::move(cells));
        js_sweep.push_back(std::move(jp));
      }
      md << st.markdown() << "\n";
      for (const std::string& s : swept) {
        const ScalePoint* below = nullptr;
        for (const ScalePoint& pt : points) {
          if (pt.trace == trace_name && pt.scheduler == s && pt.limit_efficiency < 0.9) {
            below = &pt;
            break;
          }
        }
        md << "- " << s << ": "
           << (below ? "falls below 90 % of the limit at P = " + std::to_string(below->workers) + " (" +
                           pct(below->limit_efficiency) + " %), where its largest loss is " + below->largest_loss
                     : "stays above 90 % of the limit up to P = " + std::to_string(o.max_p))
           << ".\n";
      }
      md << "\n";
    }
    js["sweep"] = js_sweep;
    const report::ResultsDir dir(kProgram, o.out);
    dir.write("scale.md", md.str());
    dir.write_json("scale.json", js);
    // The losses against P on the main scene, one panel per scheduler.
    std::ostringstream dat;
    for (const std::string& s : swept) {
      dat << "\"" << s << "\"\n";
      for (const ScalePoint& pt : points) {
        if (pt.trace != cal->scene || pt.scheduler != s) continue;
        dat << pt.workers;
        for (const char* t : kSimulatedTerms) {
          if (std::string(t) != "work") dat << ' ' << 100 * pt.shares.at(t);
        }
        dat << '\n';
      }
      dat << "\n\n";
    }
    dir.write("scale.dat", dat.str());
    std::ostringstream gp;
    gp << "set output 'scale.png'\nset multiplot layout 1," << swept.size()
       << " title \"Where the time goes beyond the work, SIMULATED (% of P x T), " << report::gnuplot_text(cal->scene)
       << "; constants from the MEASURED account of " << report::gnuplot_text(cal->name) << "\"\n"
       << "set logscale x 2\nset xlabel 'P'\nset ylabel '% of P x T'\nset key top left font ',8'\nset yrange [0:*]\n";
    for (std::size_t i = 0; i < swept.size(); ++i) {
      gp << "set title '" << report::gnuplot_text(swept[i]) << "'\nplot ";
      int col = 2;
      for (const char* t : kSimulatedTerms) {
        if (std::string(t) == "work") continue;
        gp << (col > 2 ? ", " : "") << "'scale.dat' index " << i << " using 1:" << col << " with linespoints title '"
           << t << "'";
        ++col;
      }
      gp << "\n";
    }
    gp << "unset multiplot\n";
    dir.write_gnuplot("scale.gp", {1500, 520}, gp.str());
    dir.plot("scale.gp");
    if (!o.quiet) std::cout << md.str();
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace frontsteal::papers
