#include "harness/metrics/image_checks.h"

#include <cmath>

#include "harness/util/error.h"

namespace ldm {

std::string shape_string(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
         std::to_string(image.channels);
}

void require_nonempty(const Image& image, const std::string& name) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw UserError(name + " image is empty (" + shape_string(image) +
                    ", width x height x channels)");
  if (image.pixels.size() != image.pixel_count() * size_t(image.channels))
    throw UserError(name + " image holds " + std::to_string(image.pixels.size()) +
                    " values but its shape " + shape_string(image) + " needs " +
                    std::to_string(image.pixel_count() * size_t(image.channels)));
}

void require_finite(const Image& image, const std::string& name) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float value = image.pixels[i];
    if (std::isfinite(value)) continue;
    const size_t pixel = i / size_t(image.channels);
    throw UserError(name + " image has a non-finite value (" + std::to_string(value) +
                    ") at pixel (x=" + std::to_string(pixel % size_t(image.width)) +
                    ", y=" + std::to_string(pixel / size_t(image.width)) +
                    ", channel=" + std::to_string(i % size_t(image.channels)) + ")");
  }
}

}  // namespace ldm
