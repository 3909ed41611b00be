// litmus_certificate.hpp — a policy's one-step weakenings against the stealing protocol's litmus paths: for every
// site of the policy that one step can weaken (models_check/table_policy.hpp's lattice), the paths that contain
// the site, and the models under which the weakened policy reaches a path's bad outcome (a duplicate or an
// early quit). A policy is certified on these paths when its own verdicts are all "forbidden" and every
// weakening at a site the paths contain is killed under C++ with load buffering (RC11 without no-thin-air, the
// weakest C++ model here). Weakenings at sites no path contains (the frame loop's E-sites, installs, the lock
// probe, the thief's first reads) are listed as not reached: Relacy's certificate covers them.
#pragma once

#include <string>
#include <vector>

#include "models_check/axiomatic/checker.hpp"
#include "models_check/axiomatic/protocol_litmus.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::axiomatic {

struct LitmusPath {
  std::string name;  // "handshake", "re-read", "termination", "lock"
  LitmusTest test;
};

// The stealing protocol's paths under the policy that model::current_table() holds.
inline std::vector<LitmusPath> stealing_paths_of_current_table() {
  using P = model::TablePolicy;
  return {{"handshake", handshake_litmus<P>().test},
          {"re-read", reread_litmus<P>().test},
          {"termination", termination_litmus<P>().test},
          {"lock", lock_litmus<P>().test}};
}

inline bool contains_site(const LitmusTest& t, Site s) {
  for (const auto& thread : t.threads) {
    for (const Instruction& i : thread) {
      if (i.label == info(s).label) return true;
    }
  }
  return false;
}

// The four model columns of the reports, in order.
inline std::vector<std::string> certificate_models() {
  return {"RC11", "RC11 without no-thin-air", "ARMv8 (LDAR)", "ARMv8.3 (LDAPR)"};
}

// Which of the four models reach the path's bad outcome.
inline std::vector<bool> reached_under(const LitmusTest& t) {
  return {check(t, Model::rc11).allowed, check(t, Model::rc11_without_nta).allowed,
          check(compile_to_armv8(t), Model::armv8).allowed,
          check(compile_to_armv8(t, true, true), Model::armv8).allowed};
}

struct WeakeningRow {
  std::string site, from, to;
  std::vector<std::string> paths;  // the paths that contain the site (empty: not reached here)
  std::vector<std::string> kills;  // "path: model" for every path and model that reaches its bad outcome
  bool killed_under_cpp = false;   // some path reaches its bad outcome under RC11 without no-thin-air
};

struct LitmusCertificate {
  std::string policy;
  std::vector<std::string> base_failures;  // "path: model" where the policy itself reaches a bad outcome
  std::vector<WeakeningRow> rows;

  // Sound on every path and model, and every weakening the paths reach is killed under C++.
  bool certified() const {
    if (!base_failures.empty()) return false;
    for (const WeakeningRow& r : rows) {
      if (!r.paths.empty() && !r.killed_under_cpp) return false;
    }
    return true;
  }
};

inline LitmusCertificate certify_on_stealing_paths(const model::PolicyTable& base) {
  const std::vector<std::string> models = certificate_models();
  LitmusCertificate out;
  out.policy = base.name;
  const auto failures = [&](const std::vector<LitmusPath>& paths, std::vector<std::string>* kills, bool* cpp) {
    for (const LitmusPath& p : paths) {
      const std::vector<bool> reached = reached_under(p.test);
      for (std::size_t m = 0; m < models.size(); ++m) {
        if (!reached[m]) continue;
        kills->push_back(p.name + ": " + models[m]);
        if (m == 1 && cpp) *cpp = true;
      }
    }
  };
  const model::PolicyTable saved = model::current_table();
  model::current_table() = base;
  const std::vector<LitmusPath> base_paths = stealing_paths_of_current_table();
  failures(base_paths, &out.base_failures, nullptr);
  for (const model::Mutant& m : model::one_step_mutants(base)) {
    model::current_table() = m.table;
    const std::vector<LitmusPath> paths = stealing_paths_of_current_table();
    WeakeningRow row{std::string(info(m.site).label), m.from, m.to, {}, {}, false};
    std::vector<LitmusPath> containing;
    // Which paths hold the site is read off the base policy's programs: a fence weakened to none is gone from
    // the weakened one.
    for (std::size_t k = 0; k < paths.size(); ++k) {
      if (!contains_site(base_paths[k].test, m.site)) continue;
      row.paths.push_back(paths[k].name);
      containing.push_back(paths[k]);
    }
    failures(containing, &row.kills, &row.killed_under_cpp);
    out.rows.push_back(std::move(row));
  }
  model::current_table() = saved;
  return out;
}

}  // namespace frontsteal::axiomatic
