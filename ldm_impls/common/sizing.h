#pragma once
// The sizing policy: how a structure learns how much storage a frame needs (issue 7 §2).
// Sizing is part of what a structure costs, so it is an explicit, recorded choice:
//   oracle          the untimed fragment census taken before the run sizes every structure
//                   exactly (a free pre-pass a real renderer does not have; labelled as such)
//   census          a census pass runs every frame, timed and charged to the build
//                   ("census"; growing storage from it is timed as "reallocate"). The
//                   DF-buffer's own count pass + scan is a census: it reads its scan total
//                   back instead ("readback") and grows its depth array from it
//   previous_frame  sizes from the last frame's own GPU counters (what the thesis's code
//                   does); the first frame starts from a stated guess, a build that overflows
//                   is resized from its counters and rebuilt ("rebuild", counted)
//   budget          a fixed memory budget: the structure sizes itself within it and counts
//                   what does not fit (status lossy)
// A structure sees only a SizingPlan (never the census): the census is verification.
#include <cstdint>
#include <string>
#include <vector>

namespace ldm {

class SizingStrategy;

enum class SizingPolicy { Oracle, Census, PreviousFrame, Budget };

const char* sizing_policy_name(SizingPolicy policy);
std::vector<std::string> sizing_policy_names();
// The policy's part of a configuration id: oracle, census, prevframe, budget.
std::string sizing_id_name(SizingPolicy policy);
// Throws UserError naming the known policies.
SizingPolicy parse_sizing_policy(const std::string& name);

// What a build needs, in the two quantities every structure sizes from. 0 means "not known".
struct SizingNeeds {
  uint64_t fragments = 0;             // all views together (pools, tables, arrays)
  uint32_t max_depth_complexity = 0;  // deepest pixel (fixed arrays' k, sort arrays)
  // Set by LdmStructure::needed(): the build these needs come from lost fragments (it
  // overflowed), so previous_frame rebuilds it.
  bool lost = false;
};

struct SizingPlan {
  SizingPolicy policy = SizingPolicy::Oracle;
  // What prepare() sizes from: oracle: the census's needs; census and previous_frame: the
  // stated first guess (the census policy's first frame grows it before building); budget:
  // unused.
  SizingNeeds initial;
  uint64_t budget_bytes = 0;  // budget: the structure's whole allocation
  // Where `initial` came from, for records: "census (untimed oracle)", "guess: ...".
  std::string initial_source;
  // The policy's behaviour (ldm_impls/common/sizing_strategy.h): what a structure asks when it
  // plans its storage (fixed_by_budget(), sized_by_oracle(), ...).
  const SizingStrategy& strategy() const;
};

// What a run asks for (--sizing, --sizing-budget-mib, --sizing-initial-per-pixel).
struct SizingSettings {
  SizingPolicy policy = SizingPolicy::Oracle;
  uint64_t budget_bytes = 0;        // budget
  uint32_t initial_per_pixel = 1;   // previous_frame's first guess, fragments per LDM pixel
};

// The plan for `settings` without the census (census, previous_frame, budget): the census
// policy starts from nothing (its first frame's census sizes the storage), previous_frame
// from `initial_per_pixel` fragments in every LDM pixel. The oracle's plan is made where
// the census is (harness/measuring/ldm_setup.cpp), the one place a census reaches a plan.
SizingPlan plan_without_census(const SizingSettings& settings, uint64_t ldm_pixels);

}  // namespace ldm
