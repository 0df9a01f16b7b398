#pragma once
// The small measurements the measurement, timing and conformance tests run: `structure`
// with the AO pass, N = views, R_LDM = resolution, a size x size image, `warmup` then
// `frames` frames (the rest as MeasurementRequest's defaults). Makes the GL context current.
#include <cstdint>
#include <string>

#include "harness/measuring/measurement.h"
#include "support/test_support.h"

namespace ldm::test {

inline MeasurementRequest measurement_request(const std::string& structure, uint32_t views,
                                              uint32_t resolution, int size, int warmup,
                                              int frames) {
  gl_context();
  MeasurementRequest request;
  request.configuration.structure = structure;
  request.configuration.views = views;
  request.configuration.resolution = resolution;
  request.configuration.width = request.configuration.height = size;
  request.warmup = warmup;
  request.frames = frames;
  return request;
}

}  // namespace ldm::test
