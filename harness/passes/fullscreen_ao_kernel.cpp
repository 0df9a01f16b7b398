#include "harness/passes/fullscreen_ao_kernel.h"

#include <string>

namespace ldm {

void draw_fullscreen(GLuint framebuffer, int width, int height, const GlProgram& program,
                     const GlVertexArray& vao) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  program.use();
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

FullscreenAoKernel::FullscreenAoKernel(const char* label, const char* fragment,
                                       const ShaderDefines& defines, int width, int height)
    : width_(width), height_(height), output_(GL_R32F, width, height) {
  framebuffer_.attach_color(0, output_);
  framebuffer_.check_complete((std::string(label) + " output").c_str());
  program_ = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                            {GL_FRAGMENT_SHADER, fragment, {}}},
                           defines);
}

void FullscreenAoKernel::run(const GlTexture2D& positions, const GlTexture2D& normals) const {
  glBindTextureUnit(0, positions.id());
  glBindTextureUnit(1, normals.id());
  draw_fullscreen(framebuffer_.id(), width_, height_, program_, empty_vao_);
}

}  // namespace ldm
