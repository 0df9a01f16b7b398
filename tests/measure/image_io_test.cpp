// Image files (harness/image): OpenEXR and PNG written and read back through OpenEXR and
// libpng directly. EXR keeps every float bit; PNG keeps its sRGB bytes; anything else, and
// a writer asked for the wrong extension, is a UserError naming the file.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <half.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "harness/image/image.h"
#include "harness/util/error.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

Image ramp(int width, int height, int channels) {
  Image image(width, height, channels);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::ldexp(float(i) + 0.3f, -7) - 0.25f;
  return image;
}

TEST(ImageFiles, ExrKeepsEveryFloatOfOneToFourChannels) {
  const fs::path dir = test::make_temp_dir("ldm-image-exr");
  for (int channels = 1; channels <= 4; ++channels) {
    Image image = ramp(7, 5, channels);
    image.pixels[3] = std::numeric_limits<float>::infinity();  // HDR values are kept as they are
    image.pixels[4] = 1e-30f;
    const std::string path = (dir / ("c" + std::to_string(channels) + ".exr")).string();
    write_exr(path, image);
    const Image back = read_image(path);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.channels, channels);
    EXPECT_EQ(back.pixels, image.pixels) << channels << " channels";
  }
}

// A file from elsewhere: half floats, a data window that does not start at (0, 0), and the
// channels listed by name (B, G, R) but read in the order R, G, B.
TEST(ImageFiles, ReadsHalfExrWithAnOffsetDataWindow) {
  const fs::path path = fs::path(test::make_temp_dir("ldm-image-exr-window")) / "window.exr";
  const Imath::Box2i display({0, 0}, {9, 9}), window({2, 3}, {4, 4});  // 3 x 2 pixels
  Imf::Header header(display, window);
  std::vector<half> r(6), g(6), b(6);
  for (int i = 0; i < 6; ++i) r[i] = half(float(i)), g[i] = half(10.0f + float(i)), b[i] = half(0.5f * float(i));
  Imf::FrameBuffer frame;
  const auto slice = [&](std::vector<half>& v) {
    char* origin = reinterpret_cast<char*>(v.data()) - (2 + 3 * 3) * sizeof(half);
    return Imf::Slice(Imf::HALF, origin, sizeof(half), 3 * sizeof(half));
  };
  for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::HALF));
  frame.insert("R", slice(r));
  frame.insert("G", slice(g));
  frame.insert("B", slice(b));
  {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(2);
  }
  const Image image = read_image(path.string());
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.channels, 3);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(image.at(i % 3, i / 3, 0), float(i));
    EXPECT_EQ(image.at(i % 3, i / 3, 1), 10.0f + float(i));
    EXPECT_EQ(image.at(i % 3, i / 3, 2), 0.5f * float(i));
  }
}

// PNG: the bytes written come back as their sRGB decoding, whatever the channel count.
TEST(ImageFiles, PngBytesComeBackAsTheirSrgbDecoding) {
  const fs::path dir = test::make_temp_dir("ldm-image-png");
  for (int channels = 1; channels <= 4; ++channels) {
    const int width = 16, height = 4;
    std::vector<unsigned char> bytes(size_t(width * height * channels));
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>((i * 37) % 256);
    const std::string path = (dir / ("c" + std::to_string(channels) + ".png")).string();
    write_png_bytes(path, width, height, channels, bytes);
    const Image back = read_image(path);
    ASSERT_EQ(back.channels, channels);
    ASSERT_EQ(back.pixels.size(), bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
      const double v = bytes[i] / 255.0;
      const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
      ASSERT_NEAR(back.pixels[i], linear, 1e-6) << channels << " channels, sample " << i;
    }
  }
}

// write_png's encoding (clamped, sRGB) read back: within half an 8-bit step of the value.
TEST(ImageFiles, WritePngRoundTripsWithinOneQuantisationStep) {
  const fs::path path = fs::path(test::make_temp_dir("ldm-image-png-linear")) / "a.png";
  Image image(9, 3, 1);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) / 26.0f;
  write_png(path.string(), image);
  const Image back = read_image(path.string());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double step = 1.0 / 255.0;  // in sRGB; a linear step is at most 2.4x as large
    EXPECT_NEAR(back.pixels[i], image.pixels[i], 1.2 * step) << i;
  }
}

void expect_user_error(const std::function<void()>& f, const std::string& path, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no error for " << path;
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(ImageFiles, WrongExtensionOrFormatIsAUserErrorNamingTheFile) {
  const fs::path dir = test::make_temp_dir("ldm-image-errors");
  const Image image = ramp(2, 2, 1);
  const std::string jpg = (dir / "a.jpg").string();
  expect_user_error([&] { write_png(jpg, image); }, jpg, ".png files only");
  expect_user_error([&] { write_exr(jpg, image); }, jpg, ".exr files only");
  EXPECT_FALSE(fs::exists(jpg)) << "nothing written under a name that lies";
  const std::string text = (dir / "b.exr").string();
  std::ofstream(text) << "not an image\n";
  expect_user_error([&] { read_image(text); }, text, "neither OpenEXR nor PNG");
  // A truncated EXR: the signature is right, the rest is missing.
  const std::string good = (dir / "good.exr").string(), cut = (dir / "cut.exr").string();
  write_exr(good, ramp(64, 64, 3));
  fs::copy_file(good, cut);
  fs::resize_file(cut, 40);
  expect_user_error([&] { read_image(cut); }, cut, "cannot read image");
  const std::string png = (dir / "good.png").string(), cut_png = (dir / "cut.png").string();
  write_png(png, ramp(64, 64, 3));
  fs::copy_file(png, cut_png);
  fs::resize_file(cut_png, 60);
  expect_user_error([&] { read_image(cut_png); }, cut_png, "cannot read image");
  const std::string missing = (dir / "missing.exr").string();
  expect_user_error([&] { read_image(missing); }, missing, "does not exist");
}

}  // namespace
}  // namespace ldm
