#include "harness/scene/ao_variants.h"

#include "harness/util/error.h"
#include "harness/util/text.h"

namespace ldm {

std::string ao_trace_name(AoTrace t) {
  switch (t) {
    case AoTrace::Interval: return "interval";
    case AoTrace::Plane: return "plane";
    default: return "listing5";
  }
}

std::string ao_estimator_name(AoEstimatorChoice e) {
  return e == AoEstimatorChoice::Normalized ? "normalized" : "eq13";
}

std::vector<std::string> ao_trace_names() { return {"listing5", "interval", "plane"}; }
std::vector<std::string> ao_estimator_names() { return {"eq13", "normalized"}; }

AoTrace parse_ao_trace(const std::string& name) {
  for (AoTrace t : {AoTrace::Listing5, AoTrace::Interval, AoTrace::Plane})
    if (ao_trace_name(t) == name) return t;
  throw UserError("--trace: unknown trace '" + name + "' (known: " + joined(ao_trace_names()) + ")");
}

AoEstimatorChoice parse_ao_estimator(const std::string& name) {
  for (AoEstimatorChoice e : {AoEstimatorChoice::Eq13, AoEstimatorChoice::Normalized})
    if (ao_estimator_name(e) == name) return e;
  throw UserError("--ao-estimator: unknown estimator '" + name +
                  "' (known: " + joined(ao_estimator_names()) + ")");
}

}  // namespace ldm
