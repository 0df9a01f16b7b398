#pragma once
// How much of each build is checked (docs/reference/structures.md, "Verification"):
//   every    the full check after every build: the structure's stats() against the census
//            and the inspector's walk of every list (LdmInspector::check)
//   sampled  the full check after the first build and after every build that follows a
//            rebuild or reallocation by the sizing policy (new storage); after every other
//            build, the inspector walks one 64-pixel block in `stride`, rotating from build
//            to build, and compares each block's lists with the last full check's. A fault
//            that touches k blocks of an unchanged build goes unseen by one build's sample
//            with probability about (1 - 1/stride)^k.
// The default is sampled: on a software rasteriser a full walk costs a fifth of a frame
// (docs/measured/verification/), and a build is identical to the one fully checked unless
// its storage changed.
#include <cstdint>
#include <string>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/common/build_health.h"
#include "ldm_impls/common/ldm_inspector.h"

namespace ldm {

enum class VerifyMode { Every, Sampled };
const char* verify_mode_name(VerifyMode mode);
// "every" or "sampled"; throws UserError naming `what` otherwise.
VerifyMode parse_verify_mode(const std::string& text, const std::string& what = "--verify");

inline constexpr uint32_t kDefaultVerifyStride = 32;

struct VerifyCounts {
  uint64_t full = 0;            // builds checked in full
  uint64_t sampled = 0;         // builds checked on a sample
  uint64_t sampled_pixels = 0;  // pixels those samples visited
};

class BuildVerifier {
 public:
  // All four outlive the verifier.
  BuildVerifier(const LdmStructure& structure, const LdmInspector& inspector, BuildHealth& health,
                VerifyMode mode, uint32_t stride = kDefaultVerifyStride);

  // After each build; `storage_changed`: the sizing policy rebuilt or reallocated during it.
  void verify(bool storage_changed);
  // stats() of the last fully checked build (a sampled build is the same build).
  const BuildStats& last_stats() const { return last_stats_; }
  const VerifyCounts& counts() const { return counts_; }
  VerifyMode mode() const { return mode_; }
  uint32_t stride() const { return stride_; }

 private:
  const LdmStructure& structure_;
  const LdmInspector& inspector_;
  BuildHealth& health_;
  VerifyMode mode_;
  uint32_t stride_;
  GlBuffer block_hashes_;  // the last full check's, per 64-pixel block
  BuildStats last_stats_;
  VerifyCounts counts_;
  uint32_t next_phase_ = 0;
};

}  // namespace ldm
