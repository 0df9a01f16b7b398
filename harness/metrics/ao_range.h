#pragma once
// How far an AO image leaves [0, 1]. Eq. 13's estimator (2/N sum V |cos|) is a quadrature of
// the cosine and can exceed 1 where little occludes (2.0 at N = 1); a reader who takes AO as
// a fraction must see that, so the records carry the maximum and the share above 1.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "harness/image/image.h"
#include "harness/records/record.h"

namespace ldm {

struct AoRange {
  double max = 0.0;               // largest AO value over the covered pixels (0 if none)
  double fraction_above_1 = 0.0;  // covered pixels with AO > 1, over covered pixels
  uint64_t covered = 0;           // pixels with geometry (G-buffer position alpha != 0)
};

// ao: one channel; positions: the G-buffer positions (4 channels, alpha 0 = background), the
// same size. Throws UserError on a shape mismatch.
AoRange ao_range(const Image& ao, const Image& positions);

// The share of the image's pixels where the camera sees a surface (G-buffer position alpha
// != 0): 0 means the image measures nothing (the record's covered_pixel_fraction).
double covered_pixel_fraction(const Image& positions);

// The same pixels as a mask: one channel, 1 where the camera sees a surface, 0 elsewhere
// (the error over the covered pixels, mse_covered ..., is measured on it).
Image coverage_mask(const Image& positions);

// An AO pass's results() for its image: ao_max and ao_fraction_above_1 (ao_range()), and
// covered_pixel_fraction.
std::vector<std::pair<std::string, RecordValue>> ao_range_results(const Image& ao,
                                                                  const Image& positions);

}  // namespace ldm
