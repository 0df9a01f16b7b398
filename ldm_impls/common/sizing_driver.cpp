#include "ldm_impls/common/sizing_driver.h"

#include <cstdio>

namespace ldm {

namespace {
// A static scene needs one rebuild at most; more would mean needs that keep growing between
// two identical builds, so the loop stops and the build stays lossy (and is recorded so).
constexpr int kMaxRebuildsPerFrame = 4;
}  // namespace

SizingDriver::SizingDriver(LdmStructure& structure, const BuildInputs& in)
    : structure_(structure), in_(in) {
  if (in.sizing.policy == SizingPolicy::Census && !structure.counts_own_fragments())
    census_ = std::make_unique<CensusPass>(in.fragments, in.views.views().total_pixels());
}

SizingDriver::~SizingDriver() = default;

void SizingDriver::grow(const SizingNeeds& needs, GpuTimer* timer, const char* subpass) {
  if (structure_.fits(needs)) return;
  ScopedSubpass timed(timer, subpass);
  structure_.resize(needs);
  ++reallocations_;
}

void SizingDriver::build(GpuTimer* timer) {
  switch (in_.sizing.policy) {
    case SizingPolicy::Oracle:
    case SizingPolicy::Budget:
      structure_.build(in_, timer);
      return;
    case SizingPolicy::Census:
      if (census_) {
        SizingNeeds needs;
        {
          ScopedSubpass timed(timer, "census");
          needs = census_->run();
        }
        grow(needs, timer, "reallocate");
      }
      structure_.build(in_, timer);
      return;
    case SizingPolicy::PreviousFrame:
      if (have_last_needs_) grow(last_needs_, timer, "reallocate");
      structure_.build(in_, timer);
      {
        ScopedSubpass timed(timer, "readback");
        last_needs_ = structure_.needed();
        have_last_needs_ = true;
      }
      for (int i = 0; i < kMaxRebuildsPerFrame && last_needs_.lost && !structure_.fits(last_needs_);
           ++i) {
        // The build overflowed: resize from its own counters and build again.
        ScopedSubpass timed(timer, "rebuild");
        structure_.resize(last_needs_);
        ++reallocations_;
        ++rebuilds_;
        structure_.build(in_, nullptr);
        last_needs_ = structure_.needed();
      }
      return;
  }
}

std::vector<std::pair<std::string, std::string>> SizingDriver::describe() const {
  const SizingPlan& plan = in_.sizing;
  std::vector<std::pair<std::string, std::string>> d = {{"policy", sizing_policy_name(plan.policy)}};
  if (plan.policy == SizingPolicy::Oracle)
    d.emplace_back("note", "sized from the untimed census before the run (not a real renderer's cost)");
  if (plan.policy == SizingPolicy::Budget) {
    char mib[32];
    std::snprintf(mib, sizeof mib, "%.6g", double(plan.budget_bytes) / double(1u << 20));
    d.emplace_back("budget_mib", mib);
  }
  if (!plan.initial_source.empty()) d.emplace_back("initial", plan.initial_source);
  return d;
}

std::vector<BufferMemory> SizingDriver::memory() const {
  if (!census_) return {};
  return {{"census_counts", census_->counts_bytes(), census_->counts_bytes()}};
}

}  // namespace ldm
