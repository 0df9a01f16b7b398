#include "harness/image/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "harness/util/error.h"
#include "harness/util/files.h"

namespace ldm {

Image image_from_gl_rows(const std::vector<float>& gl_rows, int width, int height, int channels) {
  Image image(width, height, channels);
  const size_t row = size_t(width) * size_t(channels);
  for (int y = 0; y < height; ++y)
    std::copy_n(gl_rows.begin() + std::ptrdiff_t(size_t(height - 1 - y) * row), row,
                image.pixels.begin() + std::ptrdiff_t(size_t(y) * row));
  return image;
}

namespace {

void write_with_oiio(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                     const void* data) {
  write_file_atomically(path, [&](const std::string& temporary) {
    auto out = OIIO::ImageOutput::create(path);  // format from the final name's extension
    if (!out) throw UserError("cannot write image '" + path + "': " + OIIO::geterror());
    if (!out->open(temporary, spec))
      throw UserError("cannot open '" + temporary + "' for writing: " + out->geterror());
    if (!out->write_image(type, data))
      throw UserError("cannot write image '" + path + "': " + out->geterror());
    out->close();
  });
}

float srgb_encode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void write_exr(const std::string& path, const Image& image) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  if (image.channels == 1) spec.channelnames = {"Y"};
  spec.attribute("compression", "zip");
  write_with_oiio(path, spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

std::vector<unsigned char> png_bytes(const Image& image, float exposure) {
  std::vector<unsigned char> bytes(image.pixels.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    const float v = std::clamp(image.pixels[i] * exposure, 0.0f, 1.0f);
    bytes[i] = static_cast<unsigned char>(std::lround(srgb_encode(std::isfinite(v) ? v : 0.0f) * 255.0f));
  }
  return bytes;
}

void write_png(const std::string& path, const Image& image, float exposure) {
  write_png_bytes(path, image.width, image.height, image.channels, png_bytes(image, exposure));
}

void write_png_bytes(const std::string& path, int width, int height, int channels,
                     const std::vector<unsigned char>& bytes) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  write_with_oiio(path, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

Image read_image(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw UserError("image '" + path + "' does not exist");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw UserError("cannot read image '" + path + "': " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image image(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw UserError("cannot read image '" + path + "': " + in->geterror());
  const bool encoded = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                       spec.format.basetype == OIIO::TypeDesc::UINT16;
  if (encoded) {
    for (float& v : image.pixels)
      v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  in->close();
  return image;
}

}  // namespace ldm
