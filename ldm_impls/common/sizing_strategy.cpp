#include "ldm_impls/common/sizing_strategy.h"

namespace ldm {
namespace {

// One rebuild at most per frame: every work counts exactly what its overflowing run needed
// (attempts past the end, not just what it stored), so the rebuild is sized from the need
// itself and does not overflow again on a static scene. If it did (needs that grow between
// two identical runs), the frame stays lossy, is recorded so, and the next frame grows from
// the rebuild's own counts ("reallocate"); the first frame never repeats its build twice.
constexpr int kMaxRebuildsPerFrame = 1;

void grow(SizedWork& work, const SizingNeeds& needs, GpuTimer* timer, const std::string& subpass,
          SizingCounts& counts) {
  if (work.fits(needs)) return;
  ScopedSubpass timed(timer, subpass.c_str());
  work.resize(needs);
  ++counts.reallocations;
}

class OracleSizing final : public SizingStrategy {
 public:
  SizingPolicy policy() const override { return SizingPolicy::Oracle; }
  bool sized_by_oracle() const override { return true; }
  void frame(SizedWork& work, GpuTimer* timer, const std::string&, SizingState&,
             SizingCounts&) const override {
    // Sized before the first frame, untimed: a free pre-pass a real renderer does not have.
    if (!work.sized()) work.resize(work.census());
    work.run(timer);
  }
};

class CensusSizing final : public SizingStrategy {
 public:
  SizingPolicy policy() const override { return SizingPolicy::Census; }
  bool counts_every_frame() const override { return true; }
  void frame(SizedWork& work, GpuTimer* timer, const std::string& prefix, SizingState&,
             SizingCounts& counts) const override {
    if (work.has_census()) {
      SizingNeeds needs;
      {
        ScopedSubpass timed(timer, (prefix + "census").c_str());
        needs = work.census();
      }
      grow(work, needs, timer, prefix + "reallocate", counts);
    }
    work.run(timer);
  }
};

class PreviousFrameSizing final : public SizingStrategy {
 public:
  SizingPolicy policy() const override { return SizingPolicy::PreviousFrame; }
  bool grows_from_counters() const override { return true; }
  void frame(SizedWork& work, GpuTimer* timer, const std::string& prefix, SizingState& state,
             SizingCounts& counts) const override {
    if (state.have_last) grow(work, state.last, timer, prefix + "reallocate", counts);
    work.run(timer);
    {
      ScopedSubpass timed(timer, (prefix + "readback").c_str());
      state.last = work.needed();
      state.have_last = true;
    }
    for (int i = 0; i < kMaxRebuildsPerFrame && state.last.lost && !work.fits(state.last); ++i) {
      // The run overflowed: grow to what its own counters asked for and run again.
      ScopedSubpass timed(timer, (prefix + "rebuild").c_str());
      work.resize(state.last);
      ++counts.reallocations;
      ++counts.rebuilds;
      work.run(nullptr);
      state.last = work.needed();
    }
  }
};

class BudgetSizing final : public SizingStrategy {
 public:
  SizingPolicy policy() const override { return SizingPolicy::Budget; }
  bool fixed_by_budget() const override { return true; }
  void frame(SizedWork& work, GpuTimer* timer, const std::string&, SizingState&,
             SizingCounts&) const override {
    work.run(timer);
  }
};

}  // namespace

const SizingStrategy& sizing_strategy(SizingPolicy policy) {
  static const OracleSizing oracle;
  static const CensusSizing census;
  static const PreviousFrameSizing previous_frame;
  static const BudgetSizing budget;
  switch (policy) {
    case SizingPolicy::Census: return census;
    case SizingPolicy::PreviousFrame: return previous_frame;
    case SizingPolicy::Budget: return budget;
    default: return oracle;
  }
}

}  // namespace ldm
