#pragma once
// What the screen-space AO kernels (HbaoKernel, GtaoKernel) share, written once: an R32F AO
// target of the image's size, its framebuffer, and a full-screen fragment program drawn over
// the G-buffer (positions at texture unit 0, normals at 1). Each kernel builds its own
// program's defines and sets its own uniforms.
#include "harness/gl/gl_objects.h"
#include "harness/gl/shader_program.h"

namespace ldm {

// Draws the full-screen triangle (shaders/passes/fullscreen.vert) with `program` into
// `framebuffer`, width x height, depth test off.
void draw_fullscreen(GLuint framebuffer, int width, int height, const GlProgram& program,
                     const GlVertexArray& vao);

class FullscreenAoKernel {
 public:
  // Writes AO into target(), width x height, 0 on background.
  void run(const GlTexture2D& positions, const GlTexture2D& normals) const;
  GlTexture2D& target() { return output_; }
  const GlTexture2D& target() const { return output_; }

 protected:
  // `label`: the kernel's name in GL errors ("HBAO"); `fragment`: its shader under shaders/
  // ("passes/hbao.frag"), built with `defines`.
  FullscreenAoKernel(const char* label, const char* fragment, const ShaderDefines& defines,
                     int width, int height);

  GlProgram program_;

 private:
  int width_, height_;
  GlTexture2D output_;
  GlFramebuffer framebuffer_;
  GlVertexArray empty_vao_;
};

}  // namespace ldm
