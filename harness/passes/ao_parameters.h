#pragma once
// The ambient-occlusion settings several passes read (d_max, visibility, the normal offset,
// the LDM trace variant and the AO estimator), declared once here. The harness offers each
// as an axis of every configuration (--d-max, --visibility, --normal-offset, --trace,
// --ao-estimator: harness/settings/harness_axes.cpp) and hands its value to the pass as the
// parameter named in `pass_parameter`; a pass that reads one lists ao_pass_parameter(...) of
// it among its own parameters(). Neither is set as --param PASS:KEY: one name per setting.
#include <string>
#include <utility>
#include <vector>

#include "harness/axes/axis.h"
#include "harness/scene/ao_axes.h"
#include "harness/scene/scene.h"
#include "harness/records/columns.h"
#include "harness/records/record.h"

namespace ldm {

class StructureParams;

// The overrides of the scene's d_max and visibility that a pass's parameters
// ao_pass_parameter(AoAxis::DMax) and ao_pass_parameter(AoAxis::Visibility) carry: an absent
// d_max and visibility=scene keep the scene's value, as for the LDM AO.
AoOverrides read_ao_overrides(StructureParams& params);

// The record columns of the effective AO settings a pass writes in describe() (visibility,
// d_max, falloff_exponent; with `ldm` the LDM trace's too: normal offset, trace, estimator),
// and of the AO image's range (ao_max, ao_fraction_above_1).
std::vector<ColumnSpec> ao_setting_columns(bool ldm);
std::vector<ColumnSpec> ao_range_columns();
// An AO pass's columns(): ao_setting_columns(ldm), then `own`, then (with `range`)
// ao_range_columns().
std::vector<ColumnSpec> ao_pass_columns(bool ldm, const std::vector<ColumnSpec>& own, bool range);
// An AO pass's describe(): the values of ao_setting_columns(ldm) for the effective settings
// `ao` (its own parameters' columns are pass_parameter_values()').
std::vector<std::pair<std::string, RecordValue>> ao_setting_values(const AoSettings& ao, bool ldm);

}  // namespace ldm
