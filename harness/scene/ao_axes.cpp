#include "harness/scene/ao_axes.h"

#include "harness/scene/ao_variants.h"

namespace ldm {

AxisSpec ao_axis(AoAxis which) {
  AxisSpec a;
  switch (which) {
    case AoAxis::DMax:
      a.key = a.column = a.pass_parameter = "d_max";
      a.label = "d_max";
      a.flags = "--d-max";
      a.kind = AxisKind::Real;
      // Compared as the 32-bit float the GPU uses; 1e30 keeps d_max^2 finite.
      a.min = 1e-30;
      a.max = 1e30;
      a.default_note = "the scene's";
      a.unit = "scene units";
      a.description = "AO attenuation distance d_max (thesis §4.1.2)";
      break;
    case AoAxis::Visibility:
      a.key = a.column = a.pass_parameter = "visibility";
      a.flags = "--visibility";
      a.kind = AxisKind::Choice;
      a.choices = {"scene", "attenuated", "unattenuated"};
      a.default_value = "scene";
      a.description = "AO visibility: attenuated (min(d/d_max,1)^falloff), unattenuated, or the scene's own choice";
      break;
    case AoAxis::NormalOffset:
      a.key = "normal_offset";
      a.column = a.pass_parameter = "normal_offset_pixels";
      a.label = "normal offset";
      a.flags = "--normal-offset";
      a.kind = AxisKind::Real;
      a.min = 0;
      a.max = 1000;
      a.list = false;
      a.ldm_only = true;
      a.default_note = "the scene's (0.5 for the built-in scenes; 0 = off)";
      a.unit = "LDM pixels";
      a.description = "normal offset of thesis §4.4.2 at the traced point";
      break;
    case AoAxis::Trace:
      a.key = a.column = a.pass_parameter = "trace";
      a.label = "trace variant";
      a.flags = "--trace";
      a.kind = AxisKind::Choice;
      a.dynamic_choices = ao_trace_names;
      a.default_value = ao_trace_name(kDefaultAoTrace);
      a.ldm_only = true;
      a.description = "LDM trace: listing5 (thesis Listing 5), interval (split at x's depth; needs an offset >= ~0.7), plane (skip x's own plane)";
      break;
    case AoAxis::Estimator:
      a.key = a.column = a.pass_parameter = "ao_estimator";
      a.label = "AO estimator";
      a.flags = "--ao-estimator";
      a.kind = AxisKind::Choice;
      a.dynamic_choices = ao_estimator_names;
      a.default_value = ao_estimator_name(AoEstimatorChoice::Eq13);
      a.ldm_only = true;
      a.description = "eq13 (thesis Eq. 13, 2/N sum V|cos|, may exceed 1) or normalized (sum V|cos| / sum |cos|)";
      break;
  }
  return a;
}

AxisSpec ao_pass_parameter(AoAxis which) {
  AxisSpec p = ao_axis(which);
  p.key = p.pass_parameter;
  p.flags.clear();
  return p;
}

}  // namespace ldm
