#include "ldm_impls/common/list_node_pool.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"

namespace ldm {

ListNodePool::ListNodePool(const std::string& structure, StructureParams& params)
    : structure_(structure) {
  const std::string pool = params.get_choice("pool", "counted", {"counted", "grow", "fixed"});
  policy_ = pool == "grow" ? Policy::Grow : pool == "fixed" ? Policy::Fixed : Policy::Counted;
  fixed_capacity_ = params.get_uint("capacity", 0, 1, (uint64_t(1) << 31) - 1);
  if ((policy_ == Policy::Fixed) != (fixed_capacity_ > 0))
    throw UserError(structure_ + ": capacity=<nodes> goes with pool=fixed, and pool=fixed needs it");
}

void ListNodePool::prepare(const BuildInputs& in, const std::string& build_shader,
                           ShaderDefines extra_defines) {
  heads_ = in.views.views().total_pixels();
  build_shader_ = build_shader;
  defines_ = common_structure_defines(in);
  defines_.values.insert(defines_.values.end(), extra_defines.values.begin(),
                         extra_defines.values.end());
  counters_ = GlBuffer("counters", 2 * sizeof(uint32_t));
  rebuilds_ = 0;
  switch (policy_) {
    case Policy::Counted: allocate(in, in.census.total_fragments); break;
    case Policy::Grow: allocate(in, heads_); break;
    case Policy::Fixed: allocate(in, fixed_capacity_); break;
  }
}

void ListNodePool::allocate(const BuildInputs& in, uint64_t capacity) {
  capacity_ = std::max<uint64_t>(1, capacity);
  const uint64_t words = heads_ + kWordsPerNode * capacity_;
  if (words >= (uint64_t(1) << 32))
    throw UserError(structure_ + ": " + std::to_string(capacity_) +
                    " nodes exceed what 32-bit node indices address");
  data_ = GlBuffer("data", checked_storage_block(structure_, "data", words * sizeof(uint32_t)));
  data_.clear_to_zero();
  ShaderDefines defines = defines_;
  defines.set("LDM_NODE_CAPACITY", std::to_string(capacity_) + "u");
  build_program_ = in.fragments.build_program(build_shader_, defines);
}

void ListNodePool::bind() const {
  data_.bind_storage(kStructureBinding0);
  counters_.bind_atomic_counter(kStructureCounterBinding);
}

void ListNodePool::construct(const BuildInputs& in, GpuTimer* timer) {
  {
    ScopedSubpass timed(timer, "clear");
    const uint32_t zero = 0;  // only the heads: nodes are written before they are linked
    glClearNamedBufferSubData(data_.id(), GL_R32UI, 0, GLsizeiptr(heads_ * sizeof(uint32_t)),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    counters_.clear_to_zero();
  }
  ScopedSubpass timed(timer, "construct");
  bind();
  in.fragments.run(build_program_);
}

void ListNodePool::build(const BuildInputs& in, GpuTimer* timer) {
  construct(in, timer);
  if (policy_ != Policy::Grow) return;
  // The counter tells how many nodes this construction wanted.
  for (uint64_t wanted = read_counters()[0]; wanted > capacity_; wanted = read_counters()[0]) {
    uint64_t capacity = capacity_;
    while (capacity < wanted) capacity *= 2;
    allocate(in, capacity);
    ++rebuilds_;
    construct(in, timer);
  }
}

std::array<uint32_t, 2> ListNodePool::read_counters() const {
  std::array<uint32_t, 2> c{};
  counters_.download(c.data(), sizeof c);
  return c;
}

BuildStats ListNodePool::stats(const std::array<uint32_t, 2>& counters, uint64_t unlinked) const {
  BuildStats s;
  s.fragments_rasterized = counters[0];
  s.overflow = counters[0] > capacity_;
  const uint64_t written = std::min<uint64_t>(counters[0], capacity_);
  s.fragments_stored = written - std::min(written, unlinked);
  s.fragments_lost = s.fragments_rasterized - s.fragments_stored;
  s.counters = {{"pool_rebuilds", double(rebuilds_)}};
  return s;
}

std::vector<BufferMemory> ListNodePool::memory(uint64_t stored_nodes) const {
  const uint64_t head_bytes = heads_ * sizeof(uint32_t);
  const uint64_t node_bytes = kWordsPerNode * sizeof(uint32_t);
  return {{"heads", head_bytes, head_bytes},
          {"nodes", capacity_ * node_bytes, stored_nodes * node_bytes},
          {"counters", counters_.bytes(), counters_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> ListNodePool::sizing() const {
  static const char* const names[] = {"counted", "grow", "fixed"};
  return {{"pool_policy", names[int(policy_)]},
          {"pool_capacity_nodes", std::to_string(capacity_)},
          {"node_bytes", std::to_string(kWordsPerNode * sizeof(uint32_t))}};
}

}  // namespace ldm
