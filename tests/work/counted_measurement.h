#pragma once
// The work suite's shared fixture: one AO measurement of a structure on the Cornell box at
// test size, its work_* fields as numbers, and sums over the census's depth profile.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <variant>

#include "harness/measuring/measurement.h"
#include "harness/records/harness_columns.h"
#include "harness/scene/scene_loader.h"
#include "support/test_support.h"

namespace ldm::work_test {

struct Counted {
  Measurement m;
  std::map<std::string, double> work;  // work_* fields as numbers
  double fragments = 0;                // the census's fragments (count() expects some)
  // A counter the record must carry.
  double operator[](const std::string& column) const {
    const auto found = work.find(column);
    EXPECT_NE(found, work.end()) << column << " missing from the record";
    return found == work.end() ? -1.0 : found->second;
  }
};

inline double as_number(const RecordValue& value) {
  if (const auto* i = std::get_if<int64_t>(&value)) return double(*i);
  if (const auto* d = std::get_if<double>(&value)) return *d;
  ADD_FAILURE() << "a work field that is not a number";
  return -1.0;
}

// Measures `structure` with the AO pass (48x40, 1 warm-up, 2 frames) and its counting
// replay, whose check (sorted lists and images equal the measured frames') must pass.
inline Counted count(const std::string& structure, uint32_t views, uint32_t resolution,
                     const std::map<std::string, std::string>& params = {}) {
  test::gl_context();
  static const Scene scene = load_scene("cornell");
  MeasurementRequest request;
  request.configuration.structure = structure;
  request.configuration.params = params;
  request.configuration.pass = "ao";
  request.configuration.views = views;
  request.configuration.resolution = resolution;
  request.configuration.width = 48;
  request.configuration.height = 40;
  request.warmup = 1;
  request.frames = 2;
  Counted c{measure(scene, request), {}};
  for (const auto& [name, value] : c.m.columns.fields())
    if (name.rfind("work_", 0) == 0 && name != columns::kWorkReplayMs.name) c.work[name] = as_number(value);
  c.fragments = c.m.number(columns::kFragments);
  EXPECT_GT(c.fragments, 0) << structure << ": the census counted no fragments";
  EXPECT_TRUE(c.m.columns.get(columns::kWorkReplayMs)) << structure << ": no counting replay";
  EXPECT_EQ(c.m.status(), BuildStatus::Ok) << structure << ": " << c.m.status_detail();
  return c;
}

// Σ over pixels of f(fragments of the pixel), from the census's depth profile.
template <typename F>
double over_pixels(const Counted& c, F f) {
  double sum = 0;
  const auto& by_length = c.m.depth_profile.pixels_by_length;
  for (size_t n = 0; n < by_length.size(); ++n) sum += double(by_length[n]) * f(double(n));
  return sum;
}

}  // namespace ldm::work_test
