#include "harness/passes/gbuffer_pass.h"

#include "harness/gl/bindings.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {

// Colour attachments: 0 positions, 1 normals, 2 albedo, 3 triangle ids (the fragment shader's
// output locations).
constexpr int kTriangleIdAttachment = 3;

std::vector<WorkCounter> gbuffer_work_counters(const std::string& subpass) {
  return draw_work_counters(subpass,
                            "vertex shader invocations of the G-buffer draw (one indexed draw of "
                            "the scene; the post-transform cache may shade a shared vertex once)",
                            "fragments the G-buffer draw shaded (every rasterised fragment in the "
                            "image: with the counting variant's side effects no early depth test "
                            "culls any; helpers left out): the camera's depth complexity summed "
                            "over its pixels");
}

std::vector<WorkCounter> with_gbuffer_counters(const std::vector<WorkCounter>& own,
                                               const std::vector<WorkCounter>& after) {
  std::vector<WorkCounter> counters = gbuffer_work_counters("gbuffer");
  counters.insert(counters.end(), own.begin(), own.end());
  counters.insert(counters.end(), after.begin(), after.end());
  return counters;
}

GBufferPass::GBufferPass(int width, int height, bool albedo, bool triangle_ids)
    : width_(width),
      height_(height),
      positions_(GL_RGBA32F, width, height),
      normals_(GL_RGBA32F, width, height),
      depth_(GL_DEPTH_COMPONENT32F, width, height),
      with_albedo_(albedo),
      with_triangle_ids_(triangle_ids) {
  framebuffer_.attach_color(0, positions_);
  framebuffer_.attach_color(1, normals_);
  if (albedo) {
    albedo_ = GlTexture2D(GL_RGBA32F, width, height);
    framebuffer_.attach_color(2, albedo_);
  }
  if (triangle_ids) {
    triangle_ids_ = GlTexture2D(GL_R32UI, width, height);
    framebuffer_.attach_color(kTriangleIdAttachment, triangle_ids_);
  }
  framebuffer_.attach_depth(depth_);
  const GLenum targets[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                            albedo ? GLenum(GL_COLOR_ATTACHMENT2) : GLenum(GL_NONE),
                            GL_COLOR_ATTACHMENT3};
  glNamedFramebufferDrawBuffers(framebuffer_.id(), triangle_ids ? 4 : albedo ? 3 : 2, targets);
  framebuffer_.check_complete("G-buffer");
  ShaderDefines defines = binding_defines();
  defines.set("GBUFFER_ALBEDO", albedo ? 1 : 0);
  defines.set("GBUFFER_TRIANGLE_ID", triangle_ids ? 1 : 0);
  defines.set("INDIRECT_MATERIALS_BINDING", kMaterialsBinding);
  defines.set("INDIRECT_ALBEDO_BINDING", kMaterialAlbedoBinding);
  program_ = build_program({{GL_VERTEX_SHADER, "passes/gbuffer.vert", {}},
                            {GL_FRAGMENT_SHADER, "passes/gbuffer.frag", {}}},
                           defines);
}

std::vector<BufferMemory> GBufferPass::memory() const {
  std::vector<BufferMemory> out = {{"gbuffer_positions", positions_.bytes(), positions_.bytes()},
                                   {"gbuffer_normals", normals_.bytes(), normals_.bytes()},
                                   {"gbuffer_depth", depth_.bytes(), depth_.bytes()}};
  if (with_albedo_) out.push_back({"gbuffer_albedo", albedo_.bytes(), albedo_.bytes()});
  if (with_triangle_ids_)
    out.push_back({"gbuffer_triangle_ids", triangle_ids_.bytes(), triangle_ids_.bytes()});
  return out;
}

void GBufferPass::render(const GpuScene& scene, const Scene& description, GpuTimer* timer) {
  if (!scene.attributes().normals) throw GpuError("G-buffer pass needs scene normals uploaded");
  // A world-frame camera over centred geometry would render a plausible but wrong image.
  if (scene.frame_origin() != description.frame_origin)
    throw GpuError("G-buffer pass: the camera's scene and the uploaded geometry are in "
                   "different frames (pass LdmSetup::scene, not the scene as loaded)");
  const glm::mat4 vp = camera_view_projection(description.camera, width_, height_,
                                              description.bounding_sphere());
  render_view(scene, vp, description.camera.eye, timer, "gbuffer");
}

void GBufferPass::render_view(const GpuScene& scene, const glm::mat4& vp, glm::vec3 eye,
                              GpuTimer* timer, const char* subpass) {
  if (with_albedo_ && !scene.attributes().materials)
    throw GpuError("G-buffer pass with albedo needs the scene's materials uploaded");
  ScopedSubpass timed(timer, subpass);
  if (with_albedo_) scene.bind_materials(kMaterialsBinding, kMaterialAlbedoBinding);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width_, height_);
  const float zero[4] = {0, 0, 0, 0};
  const float far_depth = 1.0f;
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 1, zero);
  if (with_albedo_) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 2, zero);
  const GLuint no_triangle = 0;
  if (with_triangle_ids_)
    glClearNamedFramebufferuiv(framebuffer_.id(), GL_COLOR, kTriangleIdAttachment, &no_triangle);
  glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &far_depth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  program_.use();
  program_.set_mat4("camera_view_projection", &vp[0][0]);
  program_.set("camera_eye", eye.x, eye.y, eye.z);
  scene.draw();
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Image GBufferPass::read_positions() const {
  return image_from_gl_rows(positions_.read_floats(4), width_, height_, 4);
}

Image GBufferPass::read_albedo() const {
  return image_from_gl_rows(albedo_.read_floats(4), width_, height_, 4);
}

std::vector<uint32_t> GBufferPass::read_triangle_ids() const {
  std::vector<uint32_t> ids(size_t(width_) * size_t(height_));
  glGetTextureImage(triangle_ids_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    GLsizei(ids.size() * sizeof(uint32_t)), ids.data());
  check_gl("reading the G-buffer's triangle ids");
  return ids;
}

Image GBufferPass::read_normals() const {
  return image_from_gl_rows(normals_.read_floats(4), width_, height_, 4);
}

}  // namespace ldm
