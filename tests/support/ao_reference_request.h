#pragma once
// The AO references the tests render: a size x size image, `spp_per_half` samples per pixel
// in each half, without progress output (the rest as AoReferenceRequest's defaults).
#include <cstdint>

#include "harness/reference/ao_reference.h"

namespace ldm::test {

inline AoReferenceRequest ao_reference_request(int size, uint32_t spp_per_half) {
  AoReferenceRequest request;
  request.width = request.height = size;
  request.spp.spp_per_half = spp_per_half;
  request.progress = false;
  return request;
}

}  // namespace ldm::test
