#pragma once
// An image of the viewer (the pass's, the reference, the error map) as an 8-bit RGBA
// texture, drawn pixel for pixel by shaders/viewer/display.*. It holds the bytes that
// `ldmbench run` writes into its PNGs (png_bytes), so a screenshot compares with them.
#include <vector>

#include "harness/gl/gl_objects.h"

namespace ldm::viewer {

struct DisplayImage {
  GlTexture2D texture;
  int width = 0, height = 0;
  bool valid = false;

  // `bytes`: png_bytes() of an image with `channels` channels, rows top first.
  void upload(const std::vector<unsigned char>& bytes, int w, int h, int channels);
};

}  // namespace ldm::viewer
