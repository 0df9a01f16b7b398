#include "harness/metrics/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "harness/metrics/image_checks.h"
#include "harness/util/error.h"

namespace ldm {

namespace {

// matplotlib's viridis (CC0) sampled at t = i / 16, sRGB-encoded. Linear interpolation
// between these 17 samples stays within 6/255 per channel of matplotlib's 256-entry table
// (worst near the yellow end), which is plenty for viewing and keeps lightness monotonic.
constexpr std::array<std::array<double, 3>, 17> kViridisSrgb{{
    {0.267004, 0.004874, 0.329415}, {0.282327, 0.094955, 0.417331},
    {0.278826, 0.175490, 0.483397}, {0.258965, 0.251537, 0.524736},
    {0.229739, 0.322361, 0.545706}, {0.199430, 0.387607, 0.554642},
    {0.172719, 0.448791, 0.557885}, {0.149039, 0.508051, 0.557250},
    {0.127568, 0.566949, 0.550556}, {0.120638, 0.625828, 0.533488},
    {0.157851, 0.683765, 0.501686}, {0.246070, 0.738910, 0.452024},
    {0.369214, 0.788888, 0.382914}, {0.515992, 0.831158, 0.294279},
    {0.678489, 0.863742, 0.189503}, {0.845561, 0.887322, 0.099702},
    {0.993248, 0.906157, 0.143936},
}};

// The inverse of the encoding write_png applies, so the PNG shows the ramp's sRGB colour.
double srgb_to_linear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

std::array<double, 3> viridis_srgb(double t) {
  const double position = std::clamp(t, 0.0, 1.0) * double(kViridisSrgb.size() - 1);
  const size_t lower = std::min(size_t(position), kViridisSrgb.size() - 2);
  const double fraction = position - double(lower);
  std::array<double, 3> colour{};
  for (size_t c = 0; c < 3; ++c)
    colour[c] = kViridisSrgb[lower][c] +
                fraction * (kViridisSrgb[lower + 1][c] - kViridisSrgb[lower][c]);
  return colour;
}

}  // namespace

Image heat_map(const Image& single_channel, double max_value) {
  require_nonempty(single_channel, "heat map input");
  if (single_channel.channels != 1)
    throw UserError("heat map input must have 1 channel; it is " + shape_string(single_channel));
  require_finite(single_channel, "heat map input");
  if (!std::isfinite(max_value) || max_value <= 0.0)
    throw UserError("heat map max_value must be a finite positive number, got " +
                    std::to_string(max_value));

  Image result(single_channel.width, single_channel.height, 3);
  for (int y = 0; y < single_channel.height; ++y)
    for (int x = 0; x < single_channel.width; ++x) {
      const auto colour = viridis_srgb(double(single_channel.at(x, y)) / max_value);
      for (int c = 0; c < 3; ++c) result.at(x, y, c) = float(srgb_to_linear(colour[size_t(c)]));
    }
  return result;
}

}  // namespace ldm
