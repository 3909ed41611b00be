// json.hpp — the JSON type of every frontsteal results file: nlohmann-json (Debian nlohmann-json3-dev) with
// keys kept in insertion order, so a file reads in the order its program wrote it and diffs stay small.
//
// Every results file is a `Json` object that starts with `schema_version` (an integer, raised when a key
// changes meaning or disappears; adding keys does not raise it), `program`, `kind` ("measured",
// "simulated", "model-checked" ...) and `commit`. The schemas are listed in docs/results-schema.md.
#pragma once

#include <nlohmann/json.hpp>

namespace frontsteal::report {

using Json = nlohmann::ordered_json;

}  // namespace frontsteal::report
