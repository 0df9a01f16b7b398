#include "ldm_impls/fixed_arrays/psppfla.h"

#include "harness/gl/bindings.h"

namespace ldm {

namespace {
// The empty entry: above every ordered depth (shaders/ldm/fixed_arrays/ordered_depth.glsl),
// so that atomicMin stores into it and a pixel's entries end at the first one left empty.
constexpr uint32_t kEmptyEntry = 0xFFFFFFFFu;
}  // namespace

Psppfla::Psppfla(StructureParams& params) : requested_k_(read_fixed_array_k(params)) {}

void Psppfla::prepare(const BuildInputs& in) {
  layout_ = plan_fixed_arrays("psppfla", requested_k_, in);
  census_fragments_ = in.census.total_fragments;
  defines_ = fixed_array_defines(layout_, in);
  entries_ = GlBuffer("entries", layout_.entry_bytes());
  dropped_ = GlBuffer("dropped", sizeof(uint32_t));
  build_program_ = in.fragments.build_program("ldm/fixed_arrays/psppfla_build.frag", defines_);
}

void Psppfla::build(const BuildInputs& in, GpuTimer* timer) {
  {
    ScopedSubpass timed(timer, "clear");
    entries_.clear_to_uint(kEmptyEntry);
    dropped_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    entries_.bind_storage(kStructureBinding0);
    dropped_.bind_atomic_counter(kStructureCounterBinding);
    in.fragments.run(build_program_);
  }
}

BuildStats Psppfla::stats() const {
  BuildStats s = fixed_array_stats(dropped_, census_fragments_);
  return s;
}

std::vector<std::string> Psppfla::query_sources() const {
  return {"ldm/fixed_arrays/psppfla_query.glsl"};
}
ShaderDefines Psppfla::query_defines() const { return defines_; }
void Psppfla::bind_for_query() const { entries_.bind_storage(kStructureBinding0); }

std::vector<BufferMemory> Psppfla::memory() const {
  const uint64_t stored = stats().fragments_stored;
  return {{"entries", entries_.bytes(), stored * sizeof(uint32_t)},
          {"dropped_counter", dropped_.bytes(), dropped_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> Psppfla::sizing() const {
  return fixed_array_sizing(layout_);
}

}  // namespace ldm
