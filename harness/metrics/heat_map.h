#pragma once
// False colour for looking at error maps (abs_diff, SSIM) as PNG.
#include "harness/image/image.h"

namespace ldm {

// Maps each value v of a 1-channel image to the viridis colour ramp (matplotlib's
// perceptually uniform map, dark blue-purple -> green -> yellow, lightness increasing
// monotonically) at t = clamp(v / max_value, 0, 1). The result is a 3-channel LINEAR image
// whose sRGB encoding, as write_png applies it with exposure 1, is exactly the ramp's colour.
// For an SSIM map, pass max_value 1 (negative SSIM shows as the darkest colour).
// Throws UserError if the image does not have exactly 1 channel, holds a NaN or infinity, or
// if max_value is not finite and positive.
Image heat_map(const Image& single_channel, double max_value);

}  // namespace ldm
