#include "harness/passes/ao_parameters.h"

#include "ldm_impls/ldm_structure.h"

namespace ldm {

AoOverrides read_ao_overrides(StructureParams& params) {
  AoOverrides overrides;
  if (params.has("d_max")) overrides.d_max = float(params.get_double("d_max"));
  const std::string visibility = params.get_choice("visibility");
  if (visibility != "scene") overrides.attenuated = visibility == "attenuated";
  return overrides;
}

std::vector<ColumnSpec> ao_setting_columns(bool ldm) {
  std::vector<ColumnSpec> columns = {
      {"pass", "visibility", "", "AO visibility: attenuated or unattenuated (after --visibility)"},
      {"pass", "d_max", "scene units", "AO attenuation distance (after --d-max)"},
      {"pass", "falloff_exponent", "", "AO falloff exponent of min(d/d_max, 1)^e"},
  };
  if (ldm) {
    std::vector<ColumnSpec> trace = {
        {"pass", "normal_offset_pixels", "LDM pixels", "normal offset of thesis §4.4.2 (after --normal-offset)"},
        {"pass", "trace", "", "AO trace variant: listing5, interval or plane (after --trace)"},
        {"pass", "ao_estimator", "", "AO estimator: eq13 (thesis Eq. 13, 2/N sum of V cos) or normalized (divided by the sum of cos instead)"},
    };
    columns.insert(columns.end(), trace.begin(), trace.end());
  }
  return columns;
}

std::vector<ColumnSpec> ao_range_columns() {
  return {
      {"pass", "ao_max", "", "largest AO value over the covered pixels (Eq. 13 may exceed 1)"},
      {"pass", "ao_fraction_above_1", "", "share of covered pixels whose AO is above 1"},
  };
}

}  // namespace ldm
