#include "ldm_impls/common/ldm_inspector.h"

#include <numeric>

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
      check_program_(inspect_program(structure, false, max_list_length)),
      dump_program_(inspect_program(structure, true, max_list_length)) {}

void LdmInspector::compile_if_stale() const {
  if (structure_.storage_generation() == generation_) return;
  generation_ = structure_.storage_generation();
  check_program_ = inspect_program(structure_, false, max_list_length_);
  dump_program_ = inspect_program(structure_, true, max_list_length_);
}

void LdmInspector::dispatch(const GlProgram& program, uint64_t first, uint64_t count,
                            bool store_lengths) const {
  program.use();
  program.set("inspect_store_lengths", unsigned(store_lengths));
  program.set("inspect_first_pixel", unsigned(first));
  program.set("inspect_pixel_count", unsigned(count));
  structure_.bind_for_query();
  views_.bind();
  dispatch_linear_groups(groups_for(count, 64));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

LdmIntegrity LdmInspector::check() const {
  compile_if_stale();
  const uint64_t pixels = views_.views().total_pixels();
  GlBuffer buffer("inspect", 8 * sizeof(uint32_t));
  buffer.clear_to_zero();
  buffer.bind_storage(kValidationBinding);
  dispatch(check_program_, 0, pixels, false);
  uint32_t totals[8];
  buffer.download(totals, sizeof totals);
  LdmIntegrity r;
  r.fragments = totals[0];
  r.unsorted_pixels = totals[1];
  r.overlong_pixels = totals[2];
  r.checksum = (uint64_t(totals[4]) << 32) | totals[3];
  return r;
}

std::vector<std::vector<float>> LdmInspector::read_back(uint32_t view) const {
  compile_if_stale();
  const uint64_t count = views_.views().pixels_per_view();
  const uint64_t first = uint64_t(view) * count;
  // Pass 1: lengths.
  GlBuffer lengths("inspect_lengths", (8 + count) * sizeof(uint32_t));
  lengths.clear_to_zero();
  lengths.bind_storage(kValidationBinding);
  dispatch(check_program_, first, count, true);
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
  dispatch(dump_program_, first, count, false);
  std::vector<float> depths(total);
  dump.download(depths.data(), total * sizeof(float), (8 + count) * sizeof(uint32_t));
  std::vector<std::vector<float>> lists(count);
  for (uint64_t p = 0; p < count; ++p)
    lists[p].assign(depths.begin() + offsets[p], depths.begin() + offsets[p] + length[p]);
  return lists;
}

}  // namespace ldm
