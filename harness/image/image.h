#pragma once
// A linear float image, rows top to bottom, channels interleaved.
#include <cstdint>
#include <string>
#include <vector>

namespace ldm {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), pixels(size_t(w) * size_t(h) * size_t(c), fill) {}
  float& at(int x, int y, int c = 0) { return pixels[(size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c = 0) const { return pixels[(size_t(y) * width + x) * channels + c]; }
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  bool same_shape(const Image& o) const {
    return width == o.width && height == o.height && channels == o.channels;
  }
};

// GL returns rows bottom to top; images here are top to bottom.
Image image_from_gl_rows(const std::vector<float>& gl_rows, int width, int height, int channels);

// Linear data, full float precision. Throws UserError naming the path on failure. The file is
// written to a temporary name and renamed, so a failure leaves no partial file.
void write_exr(const std::string& path, const Image& image);
// For viewing: value * exposure, clamped to [0, 1], sRGB-encoded, 8 bits.
void write_png(const std::string& path, const Image& image, float exposure = 1.0f);
// The bytes write_png writes (interleaved, rows top first), e.g. to show them on screen.
std::vector<unsigned char> png_bytes(const Image& image, float exposure = 1.0f);
// 8-bit data as they are (rows top first), e.g. a screenshot.
void write_png_bytes(const std::string& path, int width, int height, int channels,
                     const std::vector<unsigned char>& bytes);
// Reads OpenEXR or PNG (told by their signatures), as linear float (8-bit files are decoded
// from sRGB). Throws UserError naming the path.
Image read_image(const std::string& path);

}  // namespace ldm
