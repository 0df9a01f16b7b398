#include "ldm_impls/fixed_arrays/ppfla.h"

#include <algorithm>

#include "harness/gl/bindings.h"

namespace ldm {

Ppfla::Ppfla(StructureParams& params) : requested_k_(read_fixed_array_k(params)) {}

void Ppfla::prepare(const BuildInputs& in) {
  layout_ = plan_fixed_arrays("ppfla", requested_k_, in);
  census_fragments_ = in.census.total_fragments;
  defines_ = fixed_array_defines(layout_, in);
  entries_ = GlBuffer("entries", layout_.entry_bytes());
  counts_ = GlBuffer("counts", layout_.pixels * sizeof(uint32_t));
  dropped_ = GlBuffer("dropped", sizeof(uint32_t));
  build_program_ = in.fragments.build_program("ldm/fixed_arrays/ppfla_build.frag", defines_);
  ShaderDefines sort_defines = binding_defines();
  sort_defines.values.insert(sort_defines.values.end(), defines_.values.begin(),
                             defines_.values.end());
  sort_program_ =
      build_program({{GL_COMPUTE_SHADER, "ldm/fixed_arrays/ppfla_sort.comp", {}}}, sort_defines);
}

void Ppfla::bind_storage() const {
  entries_.bind_storage(kStructureBinding0);
  counts_.bind_storage(kStructureBinding0 + 1);
}

void Ppfla::sort_every_pixel() const {
  sort_program_.use();
  bind_storage();
  // One invocation per pixel in groups of 64, split over x and y (x alone caps at 65535).
  const uint64_t groups = (layout_.pixels + 63) / 64;
  const uint64_t gx = std::min<uint64_t>(groups, 32768), gy = (groups + gx - 1) / gx;
  glDispatchCompute(GLuint(gx), GLuint(gy), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void Ppfla::build(const BuildInputs& in, GpuTimer* timer) {
  {
    // Entries need no clearing: a pixel's count says how many of them this build wrote.
    ScopedSubpass timed(timer, "clear");
    counts_.clear_to_zero();
    dropped_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    bind_storage();
    dropped_.bind_atomic_counter(kStructureCounterBinding);
    in.fragments.run(build_program_);
  }
  {
    ScopedSubpass timed(timer, "sort");
    sort_every_pixel();
  }
}

BuildStats Ppfla::stats() const {
  BuildStats s = fixed_array_stats(dropped_, census_fragments_);
  return s;
}

std::vector<std::string> Ppfla::query_sources() const {
  return {"ldm/fixed_arrays/ppfla_query.glsl"};
}
ShaderDefines Ppfla::query_defines() const { return defines_; }
void Ppfla::bind_for_query() const { bind_storage(); }

std::vector<BufferMemory> Ppfla::memory() const {
  const uint64_t stored = stats().fragments_stored;
  return {{"entries", entries_.bytes(), stored * sizeof(uint32_t)},
          {"counts", counts_.bytes(), counts_.bytes()},
          {"dropped_counter", dropped_.bytes(), dropped_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> Ppfla::sizing() const {
  return fixed_array_sizing(layout_);
}

}  // namespace ldm
