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
  bool operator==(const LdmIntegrity&) const = default;
};

class LdmInspector {
 public:
  // `max_list_length`: a list longer than this is overlong (the census's maximum depth
  // complexity in measurements; 0: the structure's own LDM_MAX_LIST_LENGTH). Programs are
  // recompiled when the structure's storage (and so its query defines) changed.
  LdmInspector(const LdmStructure& structure, const BuildInputs& in, uint32_t max_list_length = 0);
  LdmIntegrity check() const;
  // Depth lists, nearest first, of every pixel of one view (index y * R + x).
  std::vector<std::vector<float>> read_back(uint32_t view) const;

 private:
  void dispatch(const GlProgram& program, uint64_t first, uint64_t count,
                bool store_lengths) const;
  void compile_if_stale() const;
  const LdmStructure& structure_;
  const GpuViewSet& views_;
  uint32_t max_list_length_;
  mutable uint64_t generation_ = 0;
  mutable GlProgram check_program_, dump_program_;
};

}  // namespace ldm
