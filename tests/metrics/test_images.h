#pragma once
// Helpers shared by the metrics tests: deterministic synthetic images and a UserError check.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "harness/image/image.h"
#include "harness/util/error.h"

namespace ldm::test {

using Fill = std::function<float(int x, int y, int c)>;

inline Image make_image(int width, int height, int channels, const Fill& fill) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y, c) = fill(x, y, c);
  return image;
}

// Uniform noise in [lowest, highest), the same on every platform: raw mt19937 output is
// specified by the standard, the distributions of <random> are not.
inline Image noise_image(int width, int height, int channels, float lowest, float highest,
                         unsigned seed) {
  std::mt19937 random(seed);
  return make_image(width, height, channels, [&](int, int, int) {
    return lowest + (highest - lowest) * float(double(random()) / 4294967296.0);
  });
}

// Runs `call` and requires a UserError whose message contains every one of `fragments`.
inline void expect_user_error(const std::function<void()>& call,
                              const std::vector<std::string>& fragments) {
  try {
    call();
    ADD_FAILURE() << "expected a UserError";
  } catch (const UserError& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message '" << message << "' lacks '" << fragment << "'";
  }
}

}  // namespace ldm::test
