#include "harness/viewer/point_cloud.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "ldm_impls/common/compute_grid.h"

namespace ldm {
namespace {

constexpr uint64_t kHeaderBytes = 4 * sizeof(uint32_t);  // stored, shown, 2 pad
constexpr uint64_t kPointBytes = 4 * sizeof(float);

}  // namespace

PointCloud::PointCloud(uint64_t max_points) : max_points_(max_points) {
  draw_program_ = build_program({{GL_VERTEX_SHADER, "viewer/point_cloud.vert", {}},
                                 {GL_FRAGMENT_SHADER, "viewer/point_cloud.frag", {}}},
                                binding_defines());
}

PointCloudCounts PointCloud::extract(const LdmStructure& structure, const GpuViewSet& views,
                                     uint32_t view, uint32_t max_layers) {
  const ViewSet& set = views.views();
  const bool all = view >= set.size();
  const uint64_t pixels = all ? set.total_pixels() : set.pixels_per_view();
  const uint64_t first = all ? 0 : uint64_t(view) * set.pixels_per_view();
  const uint32_t layers =
      uint32_t(std::clamp<uint64_t>(std::min<uint64_t>(max_layers, max_points_ / std::max<uint64_t>(pixels, 1)), 1, 1u << 16));
  // The query defines change with the structure and its storage; the layer count is a define
  // too. Compiled again whenever what it is compiled from differs.
  ShaderDefines defines = binding_defines();
  for (const auto& define : structure.query_defines().values) defines.values.push_back(define);
  defines.set("POINT_LAYERS", std::to_string(layers) + "u");
  std::string inputs = defines.text();
  for (const std::string& source : structure.query_sources()) inputs += source + "\n";
  if (inputs != compiled_from_) {
    extract_program_ = build_program(
        {{GL_COMPUTE_SHADER, "viewer/point_cloud.comp", structure.query_sources()}}, defines);
    compiled_from_ = inputs;
  }
  slots_ = pixels * layers;
  const uint64_t bytes = kHeaderBytes + slots_ * kPointBytes;
  if (points_.bytes() < bytes) points_ = GlBuffer("point_cloud", bytes);
  points_.clear_to_zero();
  points_.bind_storage(kValidationBinding);
  extract_program_.use();
  extract_program_.set("cloud_first_pixel", unsigned(first));
  extract_program_.set("cloud_pixel_count", unsigned(pixels));
  structure.bind_for_query();
  views.bind();
  dispatch_linear_groups(groups_for(pixels, 64));
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t header[4] = {};
  points_.download(header, sizeof header);
  return {header[0], header[1], layers};
}

void PointCloud::draw(const glm::mat4& view_projection, bool colour_by_view,
                      float point_size) const {
  if (!slots_) return;
  draw_program_.use();
  draw_program_.set_mat4("camera_view_projection", &view_projection[0][0]);
  draw_program_.set("colour_by_view", unsigned(colour_by_view));
  draw_program_.set("point_size", point_size);
  glVertexArrayVertexBuffer(vao_.id(), 0, points_.id(), GLintptr(kHeaderBytes), GLsizei(kPointBytes));
  glEnableVertexArrayAttrib(vao_.id(), 0);
  glVertexArrayAttribFormat(vao_.id(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao_.id(), 0, 0);
  glBindVertexArray(vao_.id());
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDrawArrays(GL_POINTS, 0, GLsizei(slots_));
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
}

}  // namespace ldm
