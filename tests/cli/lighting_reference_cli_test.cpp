// `ldmbench reference --kind`: the spot light's references from the command line.
#include <gtest/gtest.h>

#include <filesystem>

#include "harness/image/image.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

int ldmbench(const std::string& args, std::string* output) {
  return test::run_command(std::string(LDM_BINARY_PATH) + " " + args, output);
}

TEST(Cli, ReferenceKindRendersTheSpotLightsComponents) {
  const std::string dir = test::make_temp_dir("ldm-cli-lighting");
  for (const char* kind : {"direct", "single_bounce", "multi_bounce"}) {
    const std::string out = (fs::path(dir) / (std::string(kind) + ".exr")).string();
    std::string output;
    ASSERT_EQ(ldmbench(std::string("reference --scene spot-bounce --kind ") + kind +
                           " --width 16 --height 12 --spp 4 --no-cache --out " + out,
                       &output),
              0)
        << output;
    EXPECT_NE(output.find("exposure (SSIM and PNG)"), std::string::npos) << output;
    EXPECT_TRUE(fs::is_regular_file(fs::path(dir) / (std::string(kind) + ".png")));
    const Image image = read_image(out);
    EXPECT_EQ(image.width, 16);
    EXPECT_EQ(image.channels, 3);
    double sum = 0.0;
    for (float v : image.pixels) sum += v;
    EXPECT_GT(sum, 0.0) << kind;  // each component lights some pixel of this scene
  }
  // AO's options have no meaning for the spot light: an error, nothing written.
  std::string output;
  const std::string bad = (fs::path(dir) / "bad.exr").string();
  EXPECT_EQ(ldmbench("reference --scene spot-bounce --kind direct --d-max 1 --out " + bad, &output),
            2);
  EXPECT_NE(output.find("--d-max"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(bad));
  EXPECT_EQ(ldmbench("reference --kind sideways --out " + bad, &output), 2);
}

}  // namespace
}  // namespace ldm
