#pragma once
// Reads a built structure back through its GLSL query API, exactly as passes see it: an
// integrity check after every measured build (nodes reachable, sortedness, a checksum that
// must not change between identical builds), and per-pixel depth lists for tests.
#include <cstdint>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct LdmIntegrity {
  uint64_t fragments = 0;        // fragments reachable through the query API
  uint64_t unsorted_pixels = 0;  // pixels whose depths are not ascending
  uint64_t overlong_pixels = 0;  // pixels longer than the bound (corrupt lists)
  uint64_t checksum = 0;         // of every pixel's depth sequence; equal builds, equal sums
  // Fragments stored at exactly their predecessor's depth in a list: coincident surfaces,
  // or, where the structure quantises depths (depth_quantum() > 0: the HA-buffer's 24-bit
  // keys), distinct depths that collided on one key and whose order is lost.
  uint64_t tied_depths = 0;
  bool operator==(const LdmIntegrity&) const = default;
};

// A check of some of the pixels only (LdmInspector::check_sample): the integrity of the
// lists it visited, and which of its 64-pixel blocks changed since the full check that
// wrote the reference block hashes.
struct SampledIntegrity {
  uint64_t pixels = 0;          // pixels visited
  uint64_t fragments = 0;       // fragments reachable from them
  uint64_t unsorted_pixels = 0;
  uint64_t overlong_pixels = 0;
  uint64_t blocks = 0;          // 64-pixel blocks visited
  uint64_t changed_blocks = 0;  // of those, blocks whose lists differ from the reference's
};

// Pixels are checked in blocks of one workgroup each.
inline constexpr uint32_t kInspectBlockPixels = 64;

// inspect.comp's inspect_block_* uniforms: 0 none, 1 write, 2 compare one block in stride.
struct InspectBlockMode {
  uint32_t mode = 0, stride = 1, phase = 0;
};

class LdmInspector {
 public:
  // `max_list_length`: a list longer than this is overlong (the census's maximum depth
  // complexity in measurements; 0: the structure's own LDM_MAX_LIST_LENGTH). Programs are
  // recompiled when the structure's storage (and so its query defines) changed.
  LdmInspector(const LdmStructure& structure, const BuildInputs& in, uint32_t max_list_length = 0);
  LdmIntegrity check() const;
  // The same full check, which also writes every 64-pixel block's hash into
  // `block_hashes` (block_hash_bytes() long): the reference for check_sample().
  LdmIntegrity check(const GlBuffer& block_hashes) const;
  uint64_t block_hash_bytes() const;
  // Visits one block in `stride` (at `phase`, rotated from block to block, so that
  // phases 0 .. stride-1 cover every block once) and compares each with `block_hashes`.
  SampledIntegrity check_sample(const GlBuffer& block_hashes, uint32_t phase, uint32_t stride) const;
  // Depth lists, nearest first, of every pixel of one view (index y * R + x).
  std::vector<std::vector<float>> read_back(uint32_t view) const;

 private:
  void dispatch(const GlProgram& program, uint64_t first, uint64_t count, bool store_lengths,
                uint64_t groups, InspectBlockMode blocks = InspectBlockMode()) const;
  std::vector<uint32_t> run_check(const GlBuffer* block_hashes, InspectBlockMode blocks, uint64_t groups) const;
  void compile_if_stale() const;
  const LdmStructure& structure_;
  const GpuViewSet& views_;
  uint32_t max_list_length_;
  mutable uint64_t generation_ = 0;
  mutable GlProgram check_program_, dump_program_;
};

}  // namespace ldm
