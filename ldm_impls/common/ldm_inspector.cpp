#include "ldm_impls/common/ldm_inspector.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"

namespace ldm {
namespace {

GlProgram inspect_program(const LdmStructure& structure, bool dump, uint32_t max_list_length) {
  ShaderDefines defines = binding_defines();
  const ShaderDefines query = structure.query_defines();
  for (const auto& define : query.values)
    if (!(max_list_length && define.first == "LDM_MAX_LIST_LENGTH")) defines.values.push_back(define);
  if (max_list_length) defines.set("LDM_MAX_LIST_LENGTH", std::to_string(max_list_length) + "u");
  defines.set("LDM_INSPECT_DUMP", dump ? 1 : 0);
  return build_program({{GL_COMPUTE_SHADER, "ldm/inspect.comp", structure.query_sources()}},
                       defines);
}

}  // namespace

LdmInspector::LdmInspector(const LdmStructure& structure, const BuildInputs& in,
                           uint32_t max_list_length)
    : structure_(structure),
      views_(in.views),
      max_list_length_(max_list_length),
      generation_(structure.storage_generation()),
      check_program_(inspect_program(structure, false, max_list_length)) {}

void LdmInspector::compile_if_stale() const {
  if (structure_.storage_generation() == generation_) return;
  generation_ = structure_.storage_generation();
  check_program_ = inspect_program(structure_, false, max_list_length_);
  dump_program_ = GlProgram();
}

void LdmInspector::dispatch(const GlProgram& program, uint64_t first, uint64_t count,
                            bool store_lengths, uint64_t groups, InspectBlockMode blocks) const {
  program.use();
  program.set("inspect_store_lengths", unsigned(store_lengths));
  program.set("inspect_first_pixel", unsigned(first));
  program.set("inspect_pixel_count", unsigned(count));
  program.set("inspect_block_mode", unsigned(blocks.mode));
  program.set("inspect_block_stride", unsigned(blocks.stride));
  program.set("inspect_block_phase", unsigned(blocks.phase));
  structure_.bind_for_query();
  views_.bind();
  dispatch_linear_groups(groups);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

uint64_t LdmInspector::block_hash_bytes() const {
  return std::max<uint64_t>(1, groups_for(views_.views().total_pixels(), kInspectBlockPixels)) *
         sizeof(uint32_t);
}

std::vector<uint32_t> LdmInspector::run_check(const GlBuffer* block_hashes, InspectBlockMode blocks,
                                              uint64_t groups) const {
  compile_if_stale();
  GlBuffer totals("inspect", 8 * sizeof(uint32_t));
  totals.clear_to_zero();
  totals.bind_storage(kValidationBinding);
  // The shader declares the block hashes in every mode; a tiny buffer when none is kept.
  GlBuffer unused;
  if (!block_hashes) {
    unused = GlBuffer("inspect_blocks_unused", sizeof(uint32_t));
    block_hashes = &unused;
  } else if (block_hashes->bytes() < block_hash_bytes()) {
    throw std::logic_error("LdmInspector: block hash buffer too small for the views");
  }
  block_hashes->bind_storage(kInspectBlocksBinding);
  dispatch(check_program_, 0, views_.views().total_pixels(), false, groups, blocks);
  std::vector<uint32_t> out(8);
  totals.download(out.data(), out.size() * sizeof(uint32_t));
  return out;
}

namespace {
LdmIntegrity integrity_from(const std::vector<uint32_t>& totals) {
  LdmIntegrity r;
  r.fragments = totals[0];
  r.unsorted_pixels = totals[1];
  r.overlong_pixels = totals[2];
  r.checksum = (uint64_t(totals[4]) << 32) | totals[3];
  r.tied_depths = totals[7];
  return r;
}
}  // namespace

LdmIntegrity LdmInspector::check() const {
  const uint64_t pixels = views_.views().total_pixels();
  return integrity_from(run_check(nullptr, {}, groups_for(pixels, kInspectBlockPixels)));
}

LdmIntegrity LdmInspector::check(const GlBuffer& block_hashes) const {
  const uint64_t pixels = views_.views().total_pixels();
  return integrity_from(run_check(&block_hashes, {1, 1, 0}, groups_for(pixels, kInspectBlockPixels)));
}

SampledIntegrity LdmInspector::check_sample(const GlBuffer& block_hashes, uint32_t phase,
                                            uint32_t stride) const {
  if (stride == 0) throw std::logic_error("LdmInspector::check_sample: stride 0");
  const uint64_t blocks = groups_for(views_.views().total_pixels(), kInspectBlockPixels);
  // Workgroup w visits block w * stride + (phase + w) mod stride (inspect.comp).
  const uint64_t groups = groups_for(blocks, stride);
  const std::vector<uint32_t> totals = run_check(&block_hashes, {2, stride, phase % stride}, groups);
  SampledIntegrity s;
  s.fragments = totals[0];
  s.unsorted_pixels = totals[1];
  s.overlong_pixels = totals[2];
  s.changed_blocks = totals[5];
  s.pixels = totals[6];
  for (uint64_t w = 0; w < groups; ++w)
    if (w * stride + (phase + w) % stride < blocks) ++s.blocks;
  return s;
}

std::vector<std::vector<float>> LdmInspector::read_back(uint32_t view) const {
  compile_if_stale();
  const uint64_t count = views_.views().pixels_per_view();
  const uint64_t first = uint64_t(view) * count;
  // Pass 1: lengths.
  GlBuffer lengths("inspect_lengths", (8 + count) * sizeof(uint32_t));
  lengths.clear_to_zero();
  lengths.bind_storage(kValidationBinding);
  dispatch(check_program_, first, count, true, groups_for(count, kInspectBlockPixels));
  std::vector<uint32_t> length(count);
  lengths.download(length.data(), count * sizeof(uint32_t), 8 * sizeof(uint32_t));
  // Pass 2: depths at prefix-summed offsets.
  std::vector<uint32_t> offsets(count);
  std::exclusive_scan(length.begin(), length.end(), offsets.begin(), 0u);
  const uint64_t total = count ? uint64_t(offsets.back()) + length.back() : 0;
  GlBuffer dump("inspect_dump", (8 + count + total) * sizeof(uint32_t));
  dump.clear_to_zero();
  dump.upload(offsets.data(), count * sizeof(uint32_t), 8 * sizeof(uint32_t));
  dump.bind_storage(kValidationBinding);
  // Built at the first read-back: most inspectors only check (the counting replay's, the
  // verifier's), and a compile costs llvmpipe more than a check of a small structure.
  if (!dump_program_) dump_program_ = inspect_program(structure_, true, max_list_length_);
  dispatch(dump_program_, first, count, false, groups_for(count, kInspectBlockPixels));
  std::vector<float> depths(total);
  dump.download(depths.data(), total * sizeof(float), (8 + count) * sizeof(uint32_t));
  std::vector<std::vector<float>> lists(count);
  for (uint64_t p = 0; p < count; ++p)
    lists[p].assign(depths.begin() + offsets[p], depths.begin() + offsets[p] + length[p]);
  return lists;
}

}  // namespace ldm
