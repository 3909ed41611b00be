// brepmesh_report.hpp — brepmesh_comparison's report: the stamp (machine, commit, date, load average), the
// markdown table on stdout and in brepmesh.md, brepmesh.csv and brepmesh.json in --out.
#pragma once

#include <string>
#include <vector>

#include "tessellate/benchmarks/brepmesh_measure.hpp"

namespace frontsteal::brepmesh {

// `missing`: files that were not there (skipped); `load_before`, `load_after`: the 1-minute load average.
void write_report(const Options& o, const std::vector<Row>& rows, const std::vector<std::string>& missing,
                  const std::string& load_before, const std::string& load_after);

}  // namespace frontsteal::brepmesh
