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

std::vector<ColumnSpec> ao_pass_columns(bool ldm, const std::vector<ColumnSpec>& own, bool range) {
  std::vector<ColumnSpec> columns = ao_setting_columns(ldm);
  columns.insert(columns.end(), own.begin(), own.end());
  if (range)
    for (auto& c : ao_range_columns()) columns.push_back(c);
  return columns;
}

std::vector<std::pair<std::string, RecordValue>> ao_setting_values(const AoSettings& ao, bool ldm) {
  std::vector<std::pair<std::string, RecordValue>> values = {
      {"visibility", std::string(ao.attenuated ? "attenuated" : "unattenuated")},
      {"d_max", double(ao.d_max)},
      {"falloff_exponent", double(ao.falloff_exponent)}};
  if (ldm) {
    values.emplace_back("normal_offset_pixels", double(ao.normal_offset_pixels));
    values.emplace_back("trace", ao_trace_name(ao.trace));
    values.emplace_back("ao_estimator", ao_estimator_name(ao.estimator));
  }
  return values;
}

}  // namespace ldm
