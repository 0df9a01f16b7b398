#include "ldm_impls/common/build_health.h"

#include <algorithm>
#include <stdexcept>

namespace ldm {

const char* build_status_name(BuildStatus status) {
  switch (status) {
    case BuildStatus::Ok: return "ok";
    case BuildStatus::Lossy: return "lossy";
    case BuildStatus::Invalid: return "invalid";
  }
  return "invalid";
}

BuildHealth::BuildHealth(const FragmentCensus& census) : census_(census) {
  if (census.total_fragments == 0)
    report_problem("no fragment in any LDM view (the geometry is edge-on to every view or too "
                   "thin to cover a pixel centre): nothing was measured");
}

void BuildHealth::observe(const BuildStats& stats, const LdmIntegrity& integrity) {
  ++builds_;
  max_lost_ = std::max(max_lost_, stats.fragments_lost);
  max_tied_ = std::max(max_tied_, integrity.tied_depths);
  overflow_ = overflow_ || stats.overflow;
  if (stats.fragments_rasterized != census_.total_fragments)
    report_problem("the build rasterised " + std::to_string(stats.fragments_rasterized) +
                   " fragments where the census counted " +
                   std::to_string(census_.total_fragments));
  if (integrity.fragments != stats.fragments_stored)
    report_problem(std::to_string(stats.fragments_stored) + " fragments stored but " +
                   std::to_string(integrity.fragments) +
                   " reachable through the query API (dropped or corrupted entries)");
  if (integrity.unsorted_pixels > 0)
    report_problem(std::to_string(integrity.unsorted_pixels) + " pixels with unsorted depths");
  if (integrity.overlong_pixels > 0)
    report_problem(std::to_string(integrity.overlong_pixels) +
                   " pixels longer than the census's maximum depth complexity");
  if (builds_ == 1) {
    first_checksum_ = integrity.checksum;
  } else if (integrity.checksum != first_checksum_) {
    ++checksum_changes_;
    // A lossy build may legitimately keep a different subset (first come, first stored).
    if (stats.fragments_lost == 0)
      report_problem("the stored lists changed between identical builds (nodes dropped or reordered)");
  }
}

void BuildHealth::observe_sample(const SampledIntegrity& sample) {
  if (builds_ == 0) throw std::logic_error("BuildHealth: a sampled check before any full check");
  ++sampled_builds_;
  if (sample.unsorted_pixels > 0)
    report_problem(std::to_string(sample.unsorted_pixels) + " pixels with unsorted depths");
  if (sample.overlong_pixels > 0)
    report_problem(std::to_string(sample.overlong_pixels) +
                   " pixels longer than the census's maximum depth complexity");
  if (sample.changed_blocks == 0) return;
  ++checksum_changes_;
  if (max_lost_ == 0)
    report_problem("the stored lists changed between identical builds (nodes dropped or "
                   "reordered): " + std::to_string(sample.changed_blocks) + " of " +
                   std::to_string(sample.blocks) + " sampled 64-pixel blocks differ");
}

void BuildHealth::report_problem(const std::string& p) {
  if (std::find(problems_.begin(), problems_.end(), p) == problems_.end()) problems_.push_back(p);
}

BuildStatus BuildHealth::status() const {
  if (!problems_.empty()) return BuildStatus::Invalid;
  return max_lost_ > 0 ? BuildStatus::Lossy : BuildStatus::Ok;
}

std::string BuildHealth::detail() const {
  std::string out;
  for (const auto& p : problems_) out += (out.empty() ? "" : "; ") + p;
  if (out.empty() && max_lost_ > 0)
    out = std::to_string(max_lost_) + " fragments lost per build (configured capacity)";
  return out;
}

}  // namespace ldm
