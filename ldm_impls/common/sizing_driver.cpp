#include "ldm_impls/common/sizing_driver.h"

#include <cstdio>

namespace ldm {

namespace {

// A structure as the sizing strategy sees it: its build, its own counters, and (unless its
// build counts its own fragments, as the DF-buffer's does) the census pass.
class StructureWork final : public SizedWork {
 public:
  StructureWork(LdmStructure& structure, const BuildInputs& in, CensusPass* census)
      : structure_(structure), in_(in), census_(census) {}
  bool fits(const SizingNeeds& needs) const override { return structure_.fits(needs); }
  void resize(const SizingNeeds& needs) override { structure_.resize(needs); }
  void run(GpuTimer* timer) override { structure_.build(in_, timer); }
  SizingNeeds needed() override { return structure_.needed(); }
  bool has_census() const override { return census_ != nullptr; }
  SizingNeeds census() override { return census_->run(); }

 private:
  LdmStructure& structure_;
  const BuildInputs& in_;
  CensusPass* census_;
};

}  // namespace

SizingDriver::SizingDriver(LdmStructure& structure, const BuildInputs& in)
    : structure_(structure), in_(in), strategy_(in.sizing.strategy()) {
  if (strategy_.counts_every_frame() && !structure.counts_own_fragments())
    census_ = std::make_unique<CensusPass>(in.fragments, in.views.views().total_pixels());
}

SizingDriver::~SizingDriver() = default;

void SizingDriver::build(GpuTimer* timer) {
  StructureWork work(structure_, in_, census_.get());
  strategy_.frame(work, timer, "", state_, counts_);
}

std::vector<std::pair<std::string, std::string>> SizingDriver::describe() const {
  const SizingPlan& plan = in_.sizing;
  std::vector<std::pair<std::string, std::string>> d = {{"policy", strategy_.name()}};
  if (strategy_.sized_by_oracle())
    d.emplace_back("note", "sized from the untimed census before the run (not a real renderer's cost)");
  if (strategy_.fixed_by_budget()) {
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
