// json.hpp — frontsteal.json (nlohmann, schema in docs/results-schema.md): the set-up, the round-robin
// spread, the noise, the serial loop, and per scheduler and P the data table's row with the structured values
// added (comparisons, noise, per worker, per pass, per round, per frame).
#pragma once

#include "reporting/json.hpp"
#include "reporting/table.hpp"
#include "schedulers/main_job/analysis.hpp"

namespace frontsteal::main_job {

// `data`: the data table (tables.hpp); its rows become results[] (row 0, the serial loop, is "serial").
report::Json results_json(const Measured& m, const Analysis& a, const report::Table& data);

// frontsteal-calibration.json (--calibrate): each calibration arm against its base, planted and realized.
report::Json calibration_json(const Measured& m, const Analysis& a);

}  // namespace frontsteal::main_job
