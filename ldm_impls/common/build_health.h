#pragma once
// The integrity policy every consumer applies to a structure's builds (`ldmbench run`,
// `ldmbench_gbench`, the tests): one verdict from the build statistics and the inspector's
// read-back, so no two binaries can disagree on whether a build is sound.
//
//   invalid  a build disagreed with the census, stored fragments that the query API cannot
//            reach, returned unsorted or overlong lists, or changed its lists between
//            identical builds without losing fragments; or the pass's image was not finite
//   lossy    the structure's configured capacity dropped fragments, counted exactly
//   ok       otherwise
#include <cstdint>
#include <string>
#include <vector>

#include "ldm_impls/common/fragment_census.h"
#include "ldm_impls/common/ldm_inspector.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

enum class BuildStatus { Ok, Lossy, Invalid };
const char* build_status_name(BuildStatus status);  // "ok", "lossy", "invalid"

// Watches every build of one configuration (warm-up builds included: a fault is a fault).
class BuildHealth {
 public:
  // A census of 0 fragments is a problem from the start: every check of a build would pass
  // vacuously and the pass would have nothing to read.
  explicit BuildHealth(const FragmentCensus& census);

  void observe(const BuildStats& stats, const LdmIntegrity& integrity);
  // A build checked on a sample of its pixels only (ldm_impls/common/build_verifier.h),
  // after at least one full observe(): its lists against the full check's, block by block.
  void observe_sample(const SampledIntegrity& sample);
  // A fault found outside the build (e.g. a NaN in the pass's image): the result is invalid.
  void report_problem(const std::string& problem);

  BuildStatus status() const;
  // The problems, "; "-separated, or for a lossy build how many fragments it lost.
  std::string detail() const;
  uint64_t builds() const { return builds_; }  // fully checked builds
  uint64_t sampled_builds() const { return sampled_builds_; }
  uint64_t checksum_changes() const { return checksum_changes_; }
  uint64_t tied_depths() const { return max_tied_; }  // the most of any checked build
  uint64_t first_checksum() const { return first_checksum_; }
  bool overflow() const { return overflow_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  const FragmentCensus& census_;
  uint64_t builds_ = 0, sampled_builds_ = 0, max_lost_ = 0, checksum_changes_ = 0, first_checksum_ = 0;
  uint64_t max_tied_ = 0;
  bool overflow_ = false;
  std::vector<std::string> problems_;
};

}  // namespace ldm
