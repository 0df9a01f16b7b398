#include "ldm_impls/common/build_verifier.h"

#include "harness/util/error.h"

namespace ldm {

const char* verify_mode_name(VerifyMode mode) {
  return mode == VerifyMode::Every ? "every" : "sampled";
}

VerifyMode parse_verify_mode(const std::string& text, const std::string& what) {
  if (text == "every") return VerifyMode::Every;
  if (text == "sampled") return VerifyMode::Sampled;
  throw UserError(what + " '" + text + "': expected every or sampled");
}

BuildVerifier::BuildVerifier(const LdmStructure& structure, const LdmInspector& inspector,
                             BuildHealth& health, VerifyMode mode, uint32_t stride)
    : structure_(structure), inspector_(inspector), health_(health), mode_(mode),
      stride_(stride ? stride : 1) {}

void BuildVerifier::verify(bool storage_changed) {
  const bool full = mode_ == VerifyMode::Every || counts_.full == 0 || storage_changed;
  if (!full) {
    const SampledIntegrity sample = inspector_.check_sample(block_hashes_, next_phase_, stride_);
    next_phase_ = (next_phase_ + 1) % stride_;
    health_.observe_sample(sample);
    ++counts_.sampled;
    counts_.sampled_pixels += sample.pixels;
    return;
  }
  last_stats_ = structure_.stats();
  if (mode_ == VerifyMode::Every) {
    health_.observe(last_stats_, inspector_.check());
  } else {
    // A new reference for the samples that follow (the storage may have been reallocated).
    if (block_hashes_.bytes() != inspector_.block_hash_bytes())
      block_hashes_ = GlBuffer("inspect_block_hashes", inspector_.block_hash_bytes());
    health_.observe(last_stats_, inspector_.check(block_hashes_));
  }
  ++counts_.full;
}

}  // namespace ldm
