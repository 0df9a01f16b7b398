#pragma once
// Rasterises the scene from the user's camera into positions (in the scene's frame,
// Scene::frame_origin: centred for LdmSetup's scene) and camera-facing
// normals, one sample per pixel centre (the points the AO pass and the reference shade).
// With `albedo`, also each point's diffuse albedo (lighting passes; the scene must be uploaded
// with materials), and from any pinhole view (the indirect pass's light G-buffer). With
// `triangle_ids`, also which triangle each pixel shows (its index in the scene's mesh + 1, 0 on
// background: gl_PrimitiveID of the one draw), for a pass that needs the triangle itself (the
// GPU ray tracer offsets its rays along the triangle's plane, as the reference does).
#include "harness/gl/gl_objects.h"
#include "harness/image/image.h"
#include "harness/measure/gpu_timer.h"
#include "harness/measure/work_counters.h"
#include "harness/scene/gpu_scene.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

// The work gbuffer.vert and gbuffer.frag count in the counting replay (harness/measure/
// work_counters.h) under `subpass` (the name render_view() is timed under: "gbuffer", the
// indirect pass's "light_gbuffer"): vertex shader invocations and fragments shaded. Every
// pass that draws a G-buffer declares them for each sub-pass it draws one in.
std::vector<WorkCounter> gbuffer_work_counters(const std::string& subpass);
// The work_counters() of a pass that draws the G-buffer first (as "gbuffer"): its counters,
// then `own`, then `after` (a smoothing's).
std::vector<WorkCounter> with_gbuffer_counters(const std::vector<WorkCounter>& own,
                                               const std::vector<WorkCounter>& after = {});

class GBufferPass {
 public:
  GBufferPass(int width, int height, bool albedo = false, bool triangle_ids = false);
  void render(const GpuScene& scene, const Scene& description, GpuTimer* timer);
  // From `eye` through `view_projection` (normals face `eye`), timed as `subpass`.
  void render_view(const GpuScene& scene, const glm::mat4& view_projection, glm::vec3 eye,
                   GpuTimer* timer, const char* subpass);
  const GlTexture2D& albedo() const { return albedo_; }  // empty without `albedo`
  const GlTexture2D& positions() const { return positions_; }
  const GlTexture2D& normals() const { return normals_; }
  const GlTexture2D& triangle_ids() const { return triangle_ids_; }  // empty without them
  int width() const { return width_; }
  int height() const { return height_; }
  // Its targets (positions, normals, depth, and albedo or triangle ids where drawn), for a
  // pass's memory columns.
  std::vector<BufferMemory> memory() const;
  // Top-row-first copies (xyzw), for tests and the reference renderer's cross-checks.
  Image read_positions() const;
  Image read_normals() const;
  Image read_albedo() const;  // rgba
  std::vector<uint32_t> read_triangle_ids() const;  // GL rows (bottom first)

 private:
  int width_, height_;
  GlTexture2D positions_, normals_, albedo_, triangle_ids_, depth_;
  bool with_albedo_ = false, with_triangle_ids_ = false;
  GlFramebuffer framebuffer_;
  GlProgram program_;
};

}  // namespace ldm
