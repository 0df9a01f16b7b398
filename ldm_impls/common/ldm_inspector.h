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
  uint64_t overlong_pixels = 0;  // pixels longer than the census maximum (corrupt lists)
  uint64_t checksum = 0;         // of every pixel's depth sequence; equal builds, equal sums
  bool operator==(const LdmIntegrity&) const = default;
};

class LdmInspector {
 public:
  LdmInspector(const LdmStructure& structure, const BuildInputs& in);
  LdmIntegrity check() const;
  // Depth lists, nearest first, of every pixel of one view (index y * R + x).
  std::vector<std::vector<float>> read_back(uint32_t view) const;

 private:
  void dispatch(const GlProgram& program, uint64_t first, uint64_t count,
                bool store_lengths) const;
  const LdmStructure& structure_;
  const GpuViewSet& views_;
  GlProgram check_program_, dump_program_;
};

}  // namespace ldm
