#include "ldm_impls/common/list_node_pool.h"
#include "ldm_impls/common/structure_counters.h"
#include "ldm_impls/common/sizing_strategy.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "harness/util/error.h"

namespace ldm {

ListNodePool::ListNodePool(const std::string& structure, StructureParams& params)
    : structure_(structure) {
  if (params.values().count("pool"))
    throw UserError("--param " + structure_ +
                    ":pool is replaced by the sizing policy: --sizing oracle (was pool=counted), "
                    "--sizing previous_frame (was pool=grow), --sizing budget or " + structure_ +
                    ":capacity=<nodes> (was pool=fixed)");
  fixed_capacity_ = params.has("capacity") ? params.get_uint("capacity") : 0;
}

AxisSpec ListNodePool::capacity_parameter() {
  AxisSpec p = numeric_parameter(
      "capacity", AxisKind::UInt, 1, double((uint64_t(1) << 31) - 1), "", "nodes",
      "fixes the node pool (all views), overriding the sizing policy; what does not fit is dropped and counted");
  p.default_note = "sized by the sizing policy";
  return p;
}

WorkCounter ListNodePool::nodes_visited_counter() {
  return {"", "nodes_visited", WorkShape::Distribution, "nodes",
          "PSPPSLL, PPSLL or DF-buffer: nodes (DF-buffer: depth-array entries) one query (an "
          "ldm_begin or ldm_next) moved the cursor onto: 1, or 0 at the end of the list"};
}

std::vector<WorkCounter> ListNodePool::query_work_counters() {
  // A query is one ldm_begin or ldm_next; the lists are sorted whatever the order their
  // fragments arrived in, so every count is deterministic.
  return {
      nodes_visited_counter(),
      bytes_loaded("", "heads", "PSPPSLL or PPSLL: list heads its queries read (4 bytes per ldm_begin)"),
      bytes_loaded("", "nodes",
          "PSPPSLL or PPSLL: node bytes its queries read (a next index per ldm_next, a depth per "
          "ldm_depth; 4 bytes each)"),
  };
}

void ListNodePool::prepare(const BuildInputs& in, const std::string& build_shader,
                           ShaderDefines extra_defines) {
  heads_ = in.views.views().total_pixels();
  plan_ = in.sizing;
  build_shader_ = build_shader;
  defines_ = common_structure_defines(in);
  defines_.values.insert(defines_.values.end(), extra_defines.values.begin(),
                         extra_defines.values.end());
  counters_ = GlBuffer("counters", 2 * sizeof(uint32_t));
  fragments_ = &in.fragments;
  if (fixed_capacity_ > 0) {
    allocate(fixed_capacity_);
  } else if (plan_.strategy().fixed_by_budget()) {
    const uint64_t fixed = heads_ * sizeof(uint32_t) + counters_.bytes();
    allocate(budget_after(structure_, plan_, fixed) / (kWordsPerNode * sizeof(uint32_t)));
  } else {
    allocate(plan_.initial.fragments);
  }
}

SizingNeeds ListNodePool::needed() const {
  const uint64_t wanted = read_counters()[0];
  return {wanted, 0, wanted > capacity_};
}

bool ListNodePool::fits(const SizingNeeds& needs) const {
  return size_is_fixed() || needs.fragments <= capacity_;
}

void ListNodePool::resize(const SizingNeeds& needs) {
  if (!fits(needs)) allocate(needs.fragments);
}

void ListNodePool::allocate(uint64_t capacity) {
  capacity_ = std::max<uint64_t>(1, capacity);
  const uint64_t words = heads_ + kWordsPerNode * capacity_;
  if (words >= (uint64_t(1) << 32))
    throw UserError(structure_ + ": " + std::to_string(capacity_) +
                    " nodes exceed what 32-bit node indices address");
  data_ = GlBuffer("data", checked_storage_block(structure_, "data", words * sizeof(uint32_t)));
  data_.clear_to_zero();
  ShaderDefines defines = defines_;
  defines.set("LDM_NODE_CAPACITY", std::to_string(capacity_) + "u");
  build_program_ = fragments_->build_program(build_shader_, defines);
}

void ListNodePool::bind() const {
  data_.bind_storage(kStructureBinding0);
  counters_.bind_atomic_counter(kStructureCounterBinding);
}

void ListNodePool::build(const BuildInputs& in, GpuTimer* timer) {
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
  return {{"pool_size_source", size_source(plan_, fixed_capacity_ > 0)},
          {"pool_capacity_nodes", std::to_string(capacity_)},
          {"node_bytes", std::to_string(kWordsPerNode * sizeof(uint32_t))}};
}

}  // namespace ldm
