#pragma once
// Every axis ldmbench knows, in one list: the harness's (harness/settings/harness_axes.h), then
// each structure's and each pass's declared parameters, qualified OWNER:KEY (the AO settings
// passes read through a harness axis are listed once, as that axis). `ldmbench axes` prints
// it; the report reads its JSON.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/axes/axis.h"

namespace ldm {

std::vector<AxisSpec> registered_axes();

// {"axes": [...]}: axis_spec_json of each, in registry order.
nlohmann::json axes_json();
// One row per axis: name, kind, range or choices, default, unit, identity, description.
std::string axes_markdown();
std::string axes_text();

}  // namespace ldm
