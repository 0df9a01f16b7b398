#pragma once
// Input checks shared by the metrics: each throws UserError with a message naming the image.
#include <string>

#include "harness/image/image.h"

namespace ldm {

// "16x16x3" (width x height x channels), for messages.
std::string shape_string(const Image& image);

// Throws if width, height or channels is not positive, or if the pixel buffer does not hold
// width * height * channels values.
void require_nonempty(const Image& image, const std::string& name);

// Throws at the first NaN or infinity in row-major order, naming the pixel (x, y, channel)
// and the value.
void require_finite(const Image& image, const std::string& name);

}  // namespace ldm
