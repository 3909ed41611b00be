// report_text.hpp — the text the Relacy checkers' reports and progress lines share: the one-cell summary of a
// search, a site's name, a policy's expected verdict (JSON goes through reporting/, nlohmann-json). Free of Relacy
// (the mains include it; only the suites include Relacy).
#pragma once

#include <cstddef>
#include <initializer_list>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "core/site.hpp"
#include "models_check/search.hpp"
#include "reporting/table.hpp"

namespace frontsteal::model {

// "100000 it" for a random search; "N done + M discarded" for a tree search (with "capped" if it hit the cap,
// and where it stopped if it found a failure).
inline std::string search_summary(const SearchResult& r) {
  if (r.spin_bound == 0) return std::to_string(r.iterations) + " it" + (r.capped ? " (capped)" : "");
  std::string out = std::to_string(r.completed) + " done + " + std::to_string(r.discarded) + " discarded";
  if (r.capped) out += " (capped)";
  if (r.verdict != Verdict::kPass) out += " (stopped at execution " + std::to_string(r.iterations) + ")";
  return out;
}

// "O1 owner.announce": a labelled site as the reports name it (label, then dotted name).
inline std::string site_text(Site s) { return std::string(info(s).label) + " " + std::string(info(s).name); }

// The "expected" cell of a judged policy: the sound one must pass, a planted defect must fail somewhere.
inline report::Cell expectation_cell(bool must_pass) {
  return report::Cell::shown_as(must_pass ? "pass" : "fail (negative control)", must_pass);
}

// A kill matrix's columns: the site, its order and the order it was weakened to, then `rest`.
inline std::vector<report::Column> weakening_columns(std::initializer_list<report::Column> rest) {
  std::vector<report::Column> columns{{"site", "site", false}, {"from", "order", false}, {"to", "weakened to", false}};
  columns.insert(columns.end(), rest.begin(), rest.end());
  return columns;
}

// A progress line on stderr, "program: what", unless quiet.
inline void progress(std::string_view program, bool quiet, const std::string& what) {
  if (!quiet) std::cerr << program << ": " << what << "\n";
}

// "program: mutant 3/17 Name[K3:acq_rel]": the k-th (from 0) of `total` mutants starts.
inline void mutant_progress(std::string_view program, bool quiet, std::size_t k, std::size_t total,
                            const std::string& mutant) {
  progress(program, quiet, "mutant " + std::to_string(k + 1) + "/" + std::to_string(total) + " " + mutant);
}

}  // namespace frontsteal::model
