#include "harness/scene/ao_axes.h"

#include "harness/scene/ao_variants.h"

namespace ldm {

// Each declared in one designated initializer (the fields in AxisSpec's order); the fields
// left out keep their defaults, which GCC 12's -Wextra would name one by one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
AxisSpec ao_axis(AoAxis which) {
  switch (which) {
    case AoAxis::DMax:
      // Compared as the 32-bit float the GPU uses; 1e30 keeps d_max^2 finite.
      return {.key = "d_max", .label = "d_max", .flags = "--d-max", .kind = AxisKind::Real, .min = 1e-30,
              .max = 1e30, .default_note = "the scene's", .unit = "scene units",
              .description = "AO attenuation distance d_max (thesis §4.1.2)", .column = "d_max",
              .pass_parameter = "d_max"};
    case AoAxis::Visibility:
      return {.key = "visibility", .flags = "--visibility", .kind = AxisKind::Choice,
              .choices = {"scene", "attenuated", "unattenuated"}, .default_value = "scene",
              .description = "AO visibility: attenuated (min(d/d_max,1)^falloff), unattenuated, or the scene's own choice",
              .column = "visibility", .pass_parameter = "visibility"};
    case AoAxis::NormalOffset:
      return {.key = "normal_offset", .label = "normal offset", .flags = "--normal-offset", .kind = AxisKind::Real,
              .min = 0, .max = 1000, .default_note = "the scene's (0.5 for the built-in scenes; 0 = off)",
              .list = false, .ldm_only = true, .unit = "LDM pixels",
              .description = "normal offset of thesis §4.4.2 at the traced point", .column = "normal_offset_pixels",
              .pass_parameter = "normal_offset_pixels"};
    case AoAxis::Trace:
      return {.key = "trace", .label = "trace variant", .flags = "--trace", .kind = AxisKind::Choice,
              .dynamic_choices = ao_trace_names, .default_value = ao_trace_name(kDefaultAoTrace), .ldm_only = true,
              .description = "LDM trace: listing5 (thesis Listing 5), interval (split at x's depth; needs an offset >= ~0.7), plane (skip x's own plane)",
              .column = "trace", .pass_parameter = "trace"};
    case AoAxis::Estimator:
      return {.key = "ao_estimator", .label = "AO estimator", .flags = "--ao-estimator", .kind = AxisKind::Choice,
              .dynamic_choices = ao_estimator_names, .default_value = ao_estimator_name(AoEstimatorChoice::Eq13),
              .ldm_only = true,
              .description = "eq13 (thesis Eq. 13, 2/N sum V|cos|, may exceed 1) or normalized (sum V|cos| / sum |cos|)",
              .column = "ao_estimator", .pass_parameter = "ao_estimator"};
  }
  return {};
}
#pragma GCC diagnostic pop

AxisSpec ao_pass_parameter(AoAxis which) {
  AxisSpec p = ao_axis(which);
  p.key = p.pass_parameter;
  p.flags.clear();
  return p;
}

}  // namespace ldm
