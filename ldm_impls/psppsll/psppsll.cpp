#include "ldm_impls/psppsll/psppsll.h"

#include "harness/gl/bindings.h"
#include "harness/util/error.h"

namespace ldm {

namespace {
constexpr uint64_t kWordsPerNode = 2;  // next index, depth
}

Psppsll::Psppsll(StructureParams& params) {
  const std::string pool = params.get_choice("pool", "counted", {"counted", "grow", "fixed"});
  pool_ = pool == "grow" ? Pool::Grow : pool == "fixed" ? Pool::Fixed : Pool::Counted;
  fixed_capacity_ = params.get_uint("capacity", 0, 1, (uint64_t(1) << 31) - 1);
  if ((pool_ == Pool::Fixed) != (fixed_capacity_ > 0))
    throw UserError("psppsll: capacity=<nodes> goes with pool=fixed, and pool=fixed needs it");
  atomic_reads_ = params.get_bool("atomic_reads", false);
}

void Psppsll::allocate(const BuildInputs& in, uint64_t capacity) {
  capacity_ = std::max<uint64_t>(1, capacity);
  const uint64_t words = heads_ + kWordsPerNode * capacity_;
  if (words >= (uint64_t(1) << 32))
    throw UserError("psppsll: " + std::to_string(capacity_) +
                    " nodes exceed what 32-bit node indices address");
  const uint64_t bytes = checked_storage_block("psppsll", "data", words * sizeof(uint32_t));
  data_ = GlBuffer("data", bytes);
  data_.clear_to_zero();

  ShaderDefines defines = common_structure_defines(in);
  defines.set("LDM_NODE_CAPACITY", std::to_string(capacity_) + "u");
  // Each step passes one node or retries after a concurrent insert: at most 2 x the list.
  defines.set("LDM_MAX_INSERT_STEPS",
              std::to_string(4ull * in.census.max_depth_complexity + 64) + "u");
  defines.set("LDM_ATOMIC_READS", atomic_reads_ ? 1 : 0);
  build_program_ = build_ldm_raster_program("ldm/psppsll/build.frag", defines);
}

void Psppsll::prepare(const BuildInputs& in) {
  heads_ = in.views.views().total_pixels();
  query_defines_ = common_structure_defines(in);
  counters_ = GlBuffer("counters", 2 * sizeof(uint32_t));
  rasterizer_ = std::make_unique<LdmRasterizer>(in.views.views().resolution);
  rebuilds_ = 0;
  switch (pool_) {
    case Pool::Counted: allocate(in, in.census.total_fragments); break;
    case Pool::Grow: allocate(in, heads_); break;
    case Pool::Fixed: allocate(in, fixed_capacity_); break;
  }
}

void Psppsll::construct(const BuildInputs& in, GpuTimer* timer) {
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

void Psppsll::build(const BuildInputs& in, GpuTimer* timer) {
  construct(in, timer);
  if (pool_ != Pool::Grow) return;
  // Grow-and-rebuild: the counter tells how many nodes this build wanted.
  for (uint64_t wanted = read_node_counter(); wanted > capacity_; wanted = read_node_counter()) {
    uint64_t capacity = capacity_;
    while (capacity < wanted) capacity *= 2;
    allocate(in, capacity);
    ++rebuilds_;
    construct(in, timer);
  }
}

uint64_t Psppsll::read_node_counter() const {
  uint32_t count = 0;
  counters_.download(&count, sizeof count);
  return count;
}

BuildStats Psppsll::stats() {
  uint32_t c[2] = {0, 0};
  counters_.download(c, sizeof c);
  BuildStats s;
  s.fragments_rasterized = c[0];
  s.overflow = c[0] > capacity_;
  const uint64_t written = std::min<uint64_t>(c[0], capacity_);
  s.fragments_stored = written - std::min<uint64_t>(written, c[1]);
  s.fragments_lost = s.fragments_rasterized - s.fragments_stored;
  s.counters = {{"aborted_insertions", double(c[1])}, {"pool_rebuilds", double(rebuilds_)}};
  stored_ = s.fragments_stored;
  return s;
}

std::vector<std::string> Psppsll::query_sources() const { return {"ldm/psppsll/query.glsl"}; }
ShaderDefines Psppsll::query_defines() const { return query_defines_; }
void Psppsll::bind_for_query() const { data_.bind_storage(kStructureBinding0); }

std::vector<BufferMemory> Psppsll::memory() const {
  const uint64_t head_bytes = heads_ * sizeof(uint32_t);
  const uint64_t node_bytes = kWordsPerNode * sizeof(uint32_t);
  return {{"heads", head_bytes, head_bytes},
          {"nodes", capacity_ * node_bytes, stored_ * node_bytes},
          {"counters", counters_.bytes(), counters_.bytes()}};
}

std::vector<std::pair<std::string, std::string>> Psppsll::sizing() const {
  static const char* const names[] = {"counted", "grow", "fixed"};
  return {{"pool_policy", names[int(pool_)]},
          {"pool_capacity_nodes", std::to_string(capacity_)},
          {"node_bytes", std::to_string(kWordsPerNode * sizeof(uint32_t))},
          {"atomic_reads", atomic_reads_ ? "1" : "0"}};
}

}  // namespace ldm
