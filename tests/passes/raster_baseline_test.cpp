// The raster baselines: the touch pass really shades every fragment of the geometry pass
// once (its counts add up to the census, pixel by pixel), so build_vs_raster_touch relates a
// construction to touching each fragment once.
#include <gtest/gtest.h>

#include "harness/passes/raster_baseline.h"
#include "support/ldm_fixture.h"

namespace ldm {
namespace {

TEST(RasterBaseline, TouchPassCountsEveryFragmentOfTheCensus) {
  const test::LdmFixture f("cornell", 8, 32);
  ASSERT_GT(f.census.total_fragments, 0u);
  const RasterBaseline baseline(*f.raster, f.views);
  for (int frame = 0; frame < 2; ++frame) {  // cleared each frame, not accumulated
    baseline.render(nullptr);
    EXPECT_EQ(baseline.touched_fragments(), f.census.total_fragments) << "frame " << frame;
  }
}

TEST(RasterBaseline, BothSubpassesAreTimed) {
  const test::LdmFixture f("cornell", 4, 32);
  const RasterBaseline baseline(*f.raster, f.views);
  GpuTimer timer(TimerSource::FencedWallClock);
  timer.begin_frame();
  baseline.render(&timer);
  const FrameTimes times = timer.end_frame();
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0].first, "raster_baseline");
  EXPECT_EQ(times[1].first, "raster_touch");
  EXPECT_GE(times[1].second, 0.0);
}

}  // namespace
}  // namespace ldm
