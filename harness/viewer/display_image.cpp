#include "harness/viewer/display_image.h"

#include <algorithm>

namespace ldm::viewer {

void DisplayImage::upload(const std::vector<unsigned char>& bytes, int w, int h, int channels) {
  std::vector<unsigned char> rgba(size_t(w) * h * 4, 255);
  for (size_t p = 0; p < size_t(w) * h; ++p)
    for (int c = 0; c < 3; ++c) rgba[p * 4 + c] = bytes[p * channels + std::min(c, channels - 1)];
  if (!valid || w != width || h != height) {
    texture = GlTexture2D(GL_RGBA8, w, h);
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    width = w;
    height = h;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture.id(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  valid = true;
}

}  // namespace ldm::viewer
