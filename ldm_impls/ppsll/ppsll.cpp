#include "ldm_impls/ppsll/ppsll.h"

#include "harness/gl/bindings.h"
#include "harness/util/error.h"
#include "ldm_impls/common/compute_grid.h"
#include "ldm_impls/common/post_sort.h"

namespace ldm {

namespace {
constexpr uint64_t kWordsPerNode = 2;    // next index, depth (shaders/ldm/ppsll/nodes.glsl)
constexpr uint64_t kSortGroupSize = 64;  // local_size_x of sort.comp
}  // namespace

Ppsll::Ppsll(StructureParams& params) {
  const std::string pool = params.get_choice("pool", "counted", {"counted", "grow", "fixed"});
  pool_ = pool == "grow" ? Pool::Grow : pool == "fixed" ? Pool::Fixed : Pool::Counted;
  fixed_capacity_ = params.get_uint("capacity", 0, 1, (uint64_t(1) << 31) - 1);
  if ((pool_ == Pool::Fixed) != (fixed_capacity_ > 0))
    throw UserError("ppsll: capacity=<nodes> goes with pool=fixed, and pool=fixed needs it");
  requested_local_ = read_sort_local_param(params);
}

void Ppsll::allocate(const BuildInputs& in, uint64_t capacity) {
  capacity_ = std::max<uint64_t>(1, capacity);
  const uint64_t words = heads_ + kWordsPerNode * capacity_;
  if (words >= (uint64_t(1) << 32))
    throw UserError("ppsll: " + std::to_string(capacity_) +
                    " nodes exceed what 32-bit node indices address");
  const uint64_t bytes = checked_storage_block("ppsll", "data", words * sizeof(uint32_t));
  data_ = GlBuffer("data", bytes);
  data_.clear_to_zero();

  ShaderDefines defines = common_structure_defines(in);
  defines.set("LDM_NODE_CAPACITY", std::to_string(capacity_) + "u");
  build_program_ = build_ldm_raster_program("ldm/ppsll/build.frag", defines);
}

void Ppsll::prepare(const BuildInputs& in) {
  heads_ = in.views.views().total_pixels();
  local_ = sort_local_size(requested_local_, in.census);
  query_defines_ = common_structure_defines(in);
  counters_ = GlBuffer("counters", 2 * sizeof(uint32_t));
  rasterizer_ = std::make_unique<LdmRasterizer>(in.views.views().resolution);
  rebuilds_ = 0;

  ShaderDefines sort_defines = common_structure_defines(in);
  sort_defines.set("LDM_SORT_LOCAL", std::to_string(local_) + "u");
  sort_program_ = build_compute_program("ldm/ppsll/sort.comp", sort_defines);

  switch (pool_) {
    case Pool::Counted: allocate(in, in.census.total_fragments); break;
    case Pool::Grow: allocate(in, heads_); break;
    case Pool::Fixed: allocate(in, fixed_capacity_); break;
  }
}

void Ppsll::construct(const BuildInputs& in, GpuTimer* timer) {
  {
    ScopedSubpass timed(timer, "clear");
    const uint32_t zero = 0;
    glClearNamedBufferSubData(data_.id(), GL_R32UI, 0, GLsizeiptr(heads_ * sizeof(uint32_t)),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    counters_.clear_to_zero();
  }
  {
    ScopedSubpass timed(timer, "construct");
    data_.bind_storage(kStructureBinding0);
    counters_.bind_atomic_counter(kStructureCounterBinding);
    rasterizer_->rasterize(in.scene, in.views, build_program_);
  }
}

void Ppsll::sort(GpuTimer* timer) {
  ScopedSubpass timed(timer, "sort");
  data_.bind_storage(kStructureBinding0);
  counters_.bind_atomic_counter(kStructureCounterBinding);
  sort_program_.use();
  dispatch_linear_groups(groups_for(heads_, kSortGroupSize));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);
}

void Ppsll::build(const BuildInputs& in, GpuTimer* timer) {
  construct(in, timer);
  if (pool_ == Pool::Grow) {
    // Grow-and-rebuild, as PSPPSLL: the counter tells how many nodes this build wanted.
    for (uint64_t wanted = read_node_counter(); wanted > capacity_;
         wanted = read_node_counter()) {
      uint64_t capacity = capacity_;
      while (capacity < wanted) capacity *= 2;
      allocate(in, capacity);
      ++rebuilds_;
      construct(in, timer);
    }
  }
  sort(timer);
}

uint64_t Ppsll::read_node_counter() const {
  uint32_t count = 0;
  counters_.download(&count, sizeof count);
  return count;
}

BuildStats Ppsll::stats() {
  uint32_t c[2] = {0, 0};
  counters_.download(c, sizeof c);
  BuildStats s;
  s.fragments_rasterized = c[0];
  s.overflow = c[0] > capacity_;
  s.fragments_stored = std::min<uint64_t>(c[0], capacity_);
  s.fragments_lost = s.fragments_rasterized - s.fragments_stored;
  s.counters = {{"lists_sorted_in_place", double(c[1])}, {"pool_rebuilds", double(rebuilds_)}};
  stored_ = s.fragments_stored;
  return s;
}

// The same layout as PSPPSLL, sorted after construction: its list query reads both.
std::vector<std::string> Ppsll::query_sources() const { return {"ldm/psppsll/query.glsl"}; }
ShaderDefines Ppsll::query_defines() const { return query_defines_; }
void Ppsll::bind_for_query() const { data_.bind_storage(kStructureBinding0); }

std::vector<BufferMemory> Ppsll::memory() const {
  const uint64_t head_bytes = heads_ * sizeof(uint32_t);
  const uint64_t node_bytes = kWordsPerNode * sizeof(uint32_t);
  return {{"heads", head_bytes, head_bytes},
          {"nodes", capacity_ * node_bytes, stored_ * node_bytes},
          {"counters", counters_.bytes(), counters_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> Ppsll::sizing() const {
  static const char* const pool_names[] = {"counted", "grow", "fixed"};
  return {{"pool_policy", pool_names[int(pool_)]},
          {"pool_capacity_nodes", std::to_string(capacity_)},
          {"node_bytes", std::to_string(kWordsPerNode * sizeof(uint32_t))},
          {"sort_local", std::to_string(local_)},
          {"sort_local_policy", sort_local_policy(requested_local_)}};
}

}  // namespace ldm
