#include "harness/image/image.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

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

// Images are encoded in memory and written as one block through write_bytes_atomically
// (util/files.h): every byte reaches the file through one checked write, so a full disk is
// an IoError with its errno, and no library's buffered writes can fail unseen (a 0-byte PNG
// once landed under its name). OpenEXR and libpng directly, not OpenImageIO: OpenImageIO's
// Debian build links every image and video codec (about 400 MB of shared libraries), which a
// bundle for GPU nodes (scripts/bundle.sh) cannot carry.

// The name ends in the extension its writer's format has (a `--diff-map out.jpg` must not
// silently get PNG bytes).
void require_extension(const std::string& path, const std::string& extension, const char* format) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != extension)
    throw UserError("cannot write image '" + path + "': " + format + " images are written to " +
                    extension + " files only");
}

// Channel names as OpenImageIO wrote them: Y for one channel, else R, G, B, A.
std::vector<std::string> exr_channel_names(int channels) {
  if (channels == 1) return {"Y"};
  static const char* rgba[] = {"R", "G", "B", "A"};
  std::vector<std::string> names;
  for (int c = 0; c < channels; ++c) names.push_back(c < 4 ? rgba[c] : "channel" + std::to_string(c));
  return names;
}

std::string encode_exr(const Image& image) {
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  const std::vector<std::string> names = exr_channel_names(image.channels);
  Imf::FrameBuffer frame;
  const size_t pixel_stride = sizeof(float) * size_t(image.channels);
  for (int c = 0; c < image.channels; ++c) {
    header.channels().insert(names[size_t(c)], Imf::Channel(Imf::FLOAT));
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.pixels.data() + c));
    frame.insert(names[size_t(c)], Imf::Slice(Imf::FLOAT, base, pixel_stride, pixel_stride * size_t(image.width)));
  }
  Imf::StdOSStream memory;
  Imf::OutputFile out(memory, header, 0);  // in the calling thread: the callers have their own
  out.setFrameBuffer(frame);
  out.writePixels(image.height);
  return memory.str();
}

// The file's channels in the order OpenImageIO gave them: R, G, B, A first, then the rest
// by name (OpenEXR lists channels by name).
std::vector<std::string> exr_channel_order(const Imf::ChannelList& list) {
  std::vector<std::string> names;
  for (const char* n : {"R", "G", "B", "A"})
    if (list.findChannel(n)) names.push_back(n);
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string n = it.name();
    if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  }
  return names;
}

Image read_exr(const std::string& path) {
  Imf::InputFile in(path.c_str(), 0);  // in the calling thread
  const Imath::Box2i window = in.header().dataWindow();
  const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
  const std::vector<std::string> names = exr_channel_order(in.header().channels());
  if (names.empty() || width <= 0 || height <= 0)
    throw UserError("cannot read image '" + path + "': no pixels or no channels");
  Image image(width, height, int(names.size()));
  const size_t pixel_stride = sizeof(float) * names.size(), row_stride = pixel_stride * size_t(width);
  // Slices are addressed by absolute pixel coordinates: the base points at pixel (0, 0),
  // which lies outside the buffer when the data window does not start there.
  char* origin = reinterpret_cast<char*>(image.pixels.data()) - std::ptrdiff_t(window.min.x) * std::ptrdiff_t(pixel_stride) -
                 std::ptrdiff_t(window.min.y) * std::ptrdiff_t(row_stride);
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < names.size(); ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), pixel_stride, row_stride));
  in.setFrameBuffer(frame);
  in.readPixels(window.min.y, window.max.y);
  return image;
}

// 1 to 4 channels (PNG_FORMAT_GRAY is 0, so validity is the caller's check).
uint32_t png_format_of(int channels) {
  static const uint32_t formats[] = {PNG_FORMAT_GRAY, PNG_FORMAT_GA, PNG_FORMAT_RGB, PNG_FORMAT_RGBA};
  return formats[channels - 1];
}

std::vector<unsigned char> encode_png(const std::string& path, int width, int height, int channels,
                                      const std::vector<unsigned char>& bytes) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(width);
  png.height = png_uint_32(height);
  if (channels < 1 || channels > 4)
    throw UserError("cannot write image '" + path + "': PNG holds 1 to 4 channels, not " + std::to_string(channels));
  png.format = png_format_of(channels);
  if (bytes.size() != size_t(width) * size_t(height) * size_t(channels))
    throw UserError("cannot write image '" + path + "': " + std::to_string(bytes.size()) + " bytes for " +
                    std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels));
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, bytes.data(), 0, nullptr))
    throw UserError("cannot encode image '" + path + "': " + png.message);
  std::vector<unsigned char> encoded(size);
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, bytes.data(), 0, nullptr))
    throw UserError("cannot encode image '" + path + "': " + png.message);
  encoded.resize(size);
  return encoded;
}

// 8-bit files keep their sRGB bytes, decoded below as OpenImageIO's values were; 16-bit
// files are read as libpng's linear 16-bit values (it decodes their gamma itself), except
// with alpha, which libpng's linear output premultiplies: those are read as 8-bit sRGB.
Image read_png(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw UserError("cannot read image '" + path + "': " + png.message);
  const bool linear = (png.format & PNG_FORMAT_FLAG_LINEAR) && !(png.format & PNG_FORMAT_FLAG_ALPHA);
  png.format &= ~uint32_t(PNG_FORMAT_FLAG_COLORMAP | PNG_FORMAT_FLAG_AFIRST | PNG_FORMAT_FLAG_BGR);
  if (!linear) png.format &= ~uint32_t(PNG_FORMAT_FLAG_LINEAR);
  Image image(int(png.width), int(png.height), int(PNG_IMAGE_SAMPLE_CHANNELS(png.format)));
  if (linear) {
    std::vector<png_uint_16> samples(image.pixels.size());
    if (!png_image_finish_read(&png, nullptr, samples.data(), 0, nullptr))
      throw UserError("cannot read image '" + path + "': " + png.message);
    for (size_t i = 0; i < samples.size(); ++i) image.pixels[i] = float(samples[i]) / 65535.0f;
    return image;
  }
  std::vector<unsigned char> samples(image.pixels.size());
  if (!png_image_finish_read(&png, nullptr, samples.data(), 0, nullptr))
    throw UserError("cannot read image '" + path + "': " + png.message);
  for (size_t i = 0; i < samples.size(); ++i) {
    const float v = float(samples[i]) / 255.0f;
    image.pixels[i] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return image;
}

enum class ImageFormat { Exr, Png, Unknown };

ImageFormat sniff_format(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char head[8] = {};
  in.read(reinterpret_cast<char*>(head), sizeof(head));
  if (in.gcount() >= 4 && head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 && head[3] == 0x01)
    return ImageFormat::Exr;
  static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (in.gcount() == 8 && std::equal(head, head + 8, png_signature)) return ImageFormat::Png;
  return ImageFormat::Unknown;
}

float srgb_encode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

void write_exr(const std::string& path, const Image& image) {
  require_extension(path, ".exr", "OpenEXR");
  std::string bytes;
  try {
    bytes = encode_exr(image);
  } catch (const Iex::BaseExc& e) {
    throw UserError("cannot encode image '" + path + "': " + e.what());
  }
  write_bytes_atomically(path, bytes.data(), bytes.size());
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
  require_extension(path, ".png", "PNG");
  const std::vector<unsigned char> encoded = encode_png(path, width, height, channels, bytes);
  write_bytes_atomically(path, encoded.data(), encoded.size());
}

Image read_image(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw UserError("image '" + path + "' does not exist");
  switch (sniff_format(path)) {
    case ImageFormat::Exr:
      try {
        return read_exr(path);
      } catch (const Iex::BaseExc& e) {
        throw UserError("cannot read image '" + path + "': " + e.what());
      }
    case ImageFormat::Png:
      return read_png(path);
    case ImageFormat::Unknown:
      break;
  }
  throw UserError("cannot read image '" + path + "': neither OpenEXR nor PNG (the formats ldmbench reads)");
}

}  // namespace ldm
