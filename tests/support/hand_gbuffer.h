#pragma once
// A hand-made G-buffer for the screen-space AO kernels' tests (HBAO, GTAO): `width` x
// `height` texels of (position, covered) and normals, uploaded as the RGBA32F textures the
// G-buffer pass would write.
#include <vector>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"

namespace ldm::test {

struct HandGBuffer {
  int width, height;
  std::vector<glm::vec4> positions, normals;
  HandGBuffer(int w, int h) : width(w), height(h), positions(w * h), normals(w * h) {}
  void set(int x, int y, glm::vec3 p, glm::vec3 n = {0.0f, 0.0f, 1.0f}) {
    positions[y * width + x] = glm::vec4(p, 1.0f);
    normals[y * width + x] = glm::vec4(n, 0.0f);
  }
  GlTexture2D upload(const std::vector<glm::vec4>& texels) const {
    GlTexture2D texture(GL_RGBA32F, width, height);
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels.data());
    return texture;
  }
};

}  // namespace ldm::test
