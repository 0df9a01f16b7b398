#pragma once
// The point cloud of thesis §3.4.5 (Fig. 17) for `ldmbench view`: every depth the built
// structure stores for one LDM view (or all of them), read through the structure's GLSL
// query API on the GPU (shaders/viewer/point_cloud.comp), reconstructed to a point in the
// scene's frame and drawn from the viewer's camera, coloured by layer index or by view.
// Holes (pixels where a view stores nothing) and surfaces a direction misses show as gaps.
// Nothing of the structure is copied to the CPU; only two counters are read back.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct PointCloudCounts {
  uint64_t stored = 0;  // depths the query API returned for the pixels shown
  uint64_t shown = 0;   // of them drawn (the first `layers` of each pixel)
  uint32_t layers = 0;  // layers per pixel drawn
};

class PointCloud {
 public:
  // `max_points`: the largest buffer (pixels x layers) the cloud may allocate.
  explicit PointCloud(uint64_t max_points = uint64_t(1) << 23);

  // Reads the structure's current build for view `view` (all views when `view` is
  // views.size()) with up to `max_layers` layers per pixel (fewer when the buffer would
  // exceed max_points).
  PointCloudCounts extract(const LdmStructure& structure, const GpuViewSet& views,
                           uint32_t view, uint32_t max_layers);
  // Draws the last extract() with `view_projection` (scene frame -> clip) into the bound
  // framebuffer and viewport, depth-tested.
  void draw(const glm::mat4& view_projection, bool colour_by_view, float point_size) const;

 private:
  uint64_t max_points_;
  // What extract_program_ was compiled from (query sources, defines): a new structure may
  // live at the address of the last one, so the structure's address cannot be the key.
  std::string compiled_from_;
  GlProgram extract_program_, draw_program_;
  GlBuffer points_;
  GlVertexArray vao_;
  uint64_t slots_ = 0;
};

}  // namespace ldm
