#include "harness/image/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
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

// The image encoded in memory (through an IOProxy, where the format's writer takes one) and
// written as one block through write_file_atomically (util/files.h): every byte reaches the
// file through one checked write, so a full disk is an IoError with its errno, and no
// library's buffered writes can fail unseen (a 0-byte PNG once landed under its name).
void write_with_oiio(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                     const void* data) {
  auto out = OIIO::ImageOutput::create(path);  // format from the final name's extension
  if (!out) throw UserError("cannot write image '" + path + "': " + OIIO::geterror());
  if (out->supports("ioproxy")) {
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    if (!out->set_ioproxy(&memory) || !out->open(path, spec) || !out->write_image(type, data) || !out->close())
      throw UserError("cannot encode image '" + path + "': " + out->geterror());
    write_bytes_atomically(path, bytes.data(), bytes.size());
    return;
  }
  // A format without IOProxy support: written by the library into the temporary.
  write_file_atomically(path, [&](const std::string& temporary) {
    errno = 0;
    if (!out->open(temporary, spec) || !out->write_image(type, data) || !out->close() || out->has_error()) {
      const int error = errno ? errno : EIO;
      throw IoError("cannot write image '" + path + "': " + out->geterror() + ": " + errno_text(error), error);
    }
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
