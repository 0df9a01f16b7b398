#pragma once
// How `ldmbench run` asks for the references its records are scored against: shared by
// every pass (each renders its own kind of reference, harness/passes/pass.h).
#include <cstdint>
#include <string>

namespace ldm {

struct ReferenceSettings {
  bool enabled = true;
  uint32_t spp_per_half = 0;         // 0: automatic (doubling until the noise target is met)
  double target_noise_mse = 1e-5;
  uint32_t max_spp_per_half = 4096;
  uint64_t seed = 1;
  std::string cache_dir;             // default: results/cache/references
};

}  // namespace ldm
