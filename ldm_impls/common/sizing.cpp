#include "ldm_impls/common/sizing.h"

#include <stdexcept>

#include "harness/util/error.h"
#include "ldm_impls/common/sizing_strategy.h"

namespace ldm {

const char* sizing_policy_name(SizingPolicy policy) {
  switch (policy) {
    case SizingPolicy::Census: return "census";
    case SizingPolicy::PreviousFrame: return "previous_frame";
    case SizingPolicy::Budget: return "budget";
    default: return "oracle";
  }
}

std::vector<std::string> sizing_policy_names() { return {"oracle", "census", "previous_frame", "budget"}; }

std::string sizing_id_name(SizingPolicy policy) {
  return policy == SizingPolicy::PreviousFrame ? "prevframe" : sizing_policy_name(policy);
}

SizingPolicy parse_sizing_policy(const std::string& name) {
  for (SizingPolicy p : {SizingPolicy::Oracle, SizingPolicy::Census, SizingPolicy::PreviousFrame,
                         SizingPolicy::Budget})
    if (name == sizing_policy_name(p)) return p;
  throw UserError("--sizing: unknown policy '" + name +
                  "' (known: oracle, census, previous_frame, budget)");
}

const SizingStrategy& SizingPlan::strategy() const { return sizing_strategy(policy); }

SizingPlan plan_without_census(const SizingSettings& settings, uint64_t ldm_pixels) {
  SizingPlan plan;
  plan.policy = settings.policy;
  plan.budget_bytes = settings.budget_bytes;
  switch (settings.policy) {
    case SizingPolicy::Census:
      plan.initial_source = "nothing: the first frame's census sizes the storage";
      break;
    case SizingPolicy::PreviousFrame:
      // Only a total: per-pixel depth is unknown, so fixed arrays start at this many per pixel.
      plan.initial = {ldm_pixels * settings.initial_per_pixel, 0};
      plan.initial_source = "guess: " + std::to_string(settings.initial_per_pixel) +
                            " fragment(s) per LDM pixel";
      break;
    case SizingPolicy::Budget:
      plan.initial_source = "budget";
      break;
    case SizingPolicy::Oracle:
      throw std::logic_error("the oracle plan comes from the census");
  }
  return plan;
}

}  // namespace ldm
