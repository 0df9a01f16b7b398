#include "harness/metrics/ao_range.h"

#include <algorithm>

#include "harness/metrics/image_checks.h"
#include "harness/util/error.h"

namespace ldm {

AoRange ao_range(const Image& ao, const Image& positions) {
  require_nonempty(ao, "AO image");
  require_nonempty(positions, "G-buffer positions");
  if (ao.channels != 1 || positions.channels != 4 || ao.width != positions.width ||
      ao.height != positions.height)
    throw UserError("ao_range: expected a 1-channel AO image and 4-channel positions of the "
                    "same size, got " + shape_string(ao) + " and " + shape_string(positions));
  AoRange range;
  uint64_t above = 0;
  for (int y = 0; y < ao.height; ++y)
    for (int x = 0; x < ao.width; ++x) {
      if (positions.at(x, y, 3) == 0.0f) continue;  // background
      const double value = ao.at(x, y);
      range.max = range.covered == 0 ? value : std::max(range.max, value);
      ++range.covered;
      if (value > 1.0) ++above;
    }
  if (range.covered > 0) range.fraction_above_1 = double(above) / double(range.covered);
  return range;
}

Image coverage_mask(const Image& positions) {
  require_nonempty(positions, "G-buffer positions");
  if (positions.channels != 4)
    throw UserError("coverage: expected 4-channel positions, got " + shape_string(positions));
  Image mask(positions.width, positions.height, 1);
  for (int y = 0; y < positions.height; ++y)
    for (int x = 0; x < positions.width; ++x) mask.at(x, y) = positions.at(x, y, 3) != 0.0f ? 1.0f : 0.0f;
  return mask;
}

double covered_pixel_fraction(const Image& positions) {
  const Image mask = coverage_mask(positions);
  double covered = 0;
  for (float v : mask.pixels) covered += v;
  return covered / double(mask.pixel_count());
}

std::vector<std::pair<std::string, RecordValue>> ao_range_results(const Image& ao,
                                                                  const Image& positions) {
  const AoRange range = ao_range(ao, positions);
  return {{"ao_max", range.max},
          {"ao_fraction_above_1", range.fraction_above_1},
          {"covered_pixel_fraction", covered_pixel_fraction(positions)}};
}

}  // namespace ldm
