// PSPPSLL against an independent oracle: Embree's all-hits along the same orthographic
// pixel-centre rays. Lists must be complete (same count per pixel), sorted, at the same
// depths, identical from build to build; overflow must be detected and counted exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "harness/gl/gl_api.h"
#include "harness/reference/embree_scene.h"
#include "harness/util/error.h"
#include "ldm_impls/psppsll/psppsll.h"
#include "support/ldm_fixture.h"

namespace ldm {
namespace {

using Params = std::map<std::string, std::string>;

struct OracleComparison {
  uint64_t pixels = 0;
  uint64_t mismatches = 0;              // pixels whose list differs from Embree's
  uint64_t unexplained_mismatches = 0;  // ... and not only at a triangle edge (see below)
  double max_depth_error = 0;           // over matching lists
};

// How far a rasterised depth may lie from the exact one. The rasteriser snaps vertices to a
// grid of 1/2^GL_SUBPIXEL_BITS pixel, moving a surface sideways by up to one step along each
// axis (rounding or truncating); its depth at the pixel centre then moves by the surface's
// depth slope, tan(angle between normal and view direction), times that shift. On top of
// that, float interpolation over the depth range costs a few ulps.
double depth_tolerance(const LdmView& view, glm::vec3 normal) {
  GLint subpixel_bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
  const double cos_angle = std::abs(glm::dot(normal, view.forward));
  const double slope = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle)) / cos_angle;
  const double shift = view.pixel_size() * std::ldexp(1.0, -subpixel_bits) * std::sqrt(2.0);
  return slope * shift + 4e-6 * view.depth_range;
}

// True when the GPU list has the same length as Embree's and every depth lies within its
// hit's tolerance; `max_error` collects the largest difference.
bool lists_match(const std::vector<float>& gpu, const std::vector<RayHit>& hits,
                 const LdmView& view, const EmbreeScene& embree, double* max_error) {
  if (gpu.size() != hits.size()) return false;
  double worst = 0;
  for (size_t k = 0; k < hits.size(); ++k) {
    const double error = std::abs(double(hits[k].t) - gpu[k]);
    if (error > depth_tolerance(view, embree.geometric_normal(hits[k].triangle))) return false;
    worst = std::max(worst, error);
  }
  if (max_error) *max_error = std::max(*max_error, worst);
  return true;
}

// The scene's triangles projected into one view: image-plane coordinates and depth range.
struct ProjectedTriangle {
  glm::dvec2 corner[3];
  double depth_min, depth_max;
};

std::vector<ProjectedTriangle> project_triangles(const Scene& scene, const LdmView& view) {
  std::vector<ProjectedTriangle> out;
  for (const auto& t : scene.mesh.triangles) {
    ProjectedTriangle p;
    p.depth_min = INFINITY;
    p.depth_max = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 q = glm::dvec3(scene.mesh.positions[t[k]]) - glm::dvec3(view.eye);
      p.corner[k] = {glm::dot(q, glm::dvec3(view.right)), glm::dot(q, glm::dvec3(view.up))};
      const double depth = glm::dot(q, glm::dvec3(view.forward));
      p.depth_min = std::min(p.depth_min, depth);
      p.depth_max = std::max(p.depth_max, depth);
    }
    out.push_back(p);
  }
  return out;
}

double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

// Whether triangle `t`'s projected boundary passes within `epsilon` of image point `p`: then
// whether the rasteriser covers the pixel centre depends on vertex snapping and tie rules,
// and either answer is right. Thin, nearly edge-on triangles are near everywhere they cover.
bool ambiguous_coverage(const ProjectedTriangle& t, glm::dvec2 p, double epsilon) {
  for (int k = 0; k < 3; ++k)
    if (distance_to_segment(p, t.corner[k], t.corner[(k + 1) % 3]) <= epsilon) return true;
  return false;
}

// Compares one view's lists with Embree's all-hits along the same pixel-centre rays. Lists
// are merged by depth; a fragment present on one side only is "explained" when it belongs to
// a triangle whose edge passes within the rasteriser's snapping distance of the pixel centre
// (GL's top-left rule after vertex snapping and Embree's watertight test may then disagree)
// at a depth within that triangle's range. Any other difference is a real error.
OracleComparison compare_view(const test::LdmFixture& f, const LdmInspector& inspector,
                              const EmbreeScene& embree, uint32_t view_index) {
  const LdmView& view = f.views.views[view_index];
  const auto lists = inspector.read_back(view_index);
  const auto triangles = project_triangles(f.scene, view);
  GLint subpixel_bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
  const double epsilon = 2.0 * std::sqrt(2.0) * std::ldexp(1.0, -subpixel_bits) * view.pixel_size();
  OracleComparison c;
  const uint32_t r = view.resolution;
  for (uint32_t j = 0; j < r; ++j)
    for (uint32_t i = 0; i < r; ++i) {
      ++c.pixels;
      const auto& gpu = lists[size_t(j) * r + i];
      const glm::vec3 origin = view.pixel_centre(i, j);
      const auto hits = embree.all_hit_records(origin, view.forward, 0.0f, view.depth_range);
      if (lists_match(gpu, hits, view, embree, &c.max_depth_error)) continue;
      ++c.mismatches;
      const glm::dvec2 centre(glm::dot(glm::dvec3(origin - view.eye), glm::dvec3(view.right)),
                              glm::dot(glm::dvec3(origin - view.eye), glm::dvec3(view.up)));
      auto explains_gpu_fragment = [&](double depth) {
        for (const auto& t : triangles)
          if (depth >= t.depth_min - 1e-4 && depth <= t.depth_max + 1e-4 &&
              ambiguous_coverage(t, centre, epsilon))
            return true;
        return false;
      };
      // Is there an alignment of the two sorted lists in which every fragment is either
      // matched within tolerance or explained? (Dynamic programming over list prefixes:
      // greedy pairing can match a fragment to the wrong one of two near-equal depths.)
      const size_t m = gpu.size(), n = hits.size();
      std::vector<char> gpu_ok(m), hit_ok(n);
      for (size_t a = 0; a < m; ++a) gpu_ok[a] = explains_gpu_fragment(gpu[a]);
      for (size_t b = 0; b < n; ++b)
        hit_ok[b] = ambiguous_coverage(triangles[hits[b].triangle], centre, epsilon);
      std::vector<std::vector<char>> reachable(m + 1, std::vector<char>(n + 1, 0));
      reachable[0][0] = 1;
      for (size_t a = 0; a <= m; ++a)
        for (size_t b = 0; b <= n; ++b) {
          if (!reachable[a][b]) continue;
          if (a < m && b < n &&
              std::abs(double(gpu[a]) - hits[b].t) <=
                  depth_tolerance(view, embree.geometric_normal(hits[b].triangle)))
            reachable[a + 1][b + 1] = 1;
          if (a < m && gpu_ok[a]) reachable[a + 1][b] = 1;
          if (b < n && hit_ok[b]) reachable[a][b + 1] = 1;
        }
      const bool explained = reachable[m][n];
      c.unexplained_mismatches += !explained;
    }
  return c;
}

void expect_matches_embree(const std::string& scene, uint32_t n, uint32_t r) {
  const test::LdmFixture f(scene, n, r);
  const auto structure = f.build("psppsll");
  const LdmInspector inspector(*structure, *f.inputs);
  const EmbreeScene embree(f.scene);
  OracleComparison total;
  for (uint32_t v = 0; v < f.views.size(); ++v) {
    const OracleComparison c = compare_view(f, inspector, embree, v);
    total.pixels += c.pixels;
    total.mismatches += c.mismatches;
    total.unexplained_mismatches += c.unexplained_mismatches;
    total.max_depth_error = std::max(total.max_depth_error, c.max_depth_error);
  }
  const double match = 1.0 - double(total.mismatches) / double(total.pixels);
  ::testing::Test::RecordProperty("match_fraction", std::to_string(match));
  EXPECT_GE(match, 0.99) << scene << ": " << total.mismatches << " of " << total.pixels;
  EXPECT_EQ(total.unexplained_mismatches, 0u) << scene;
  std::printf("%s N=%u R=%u: %llu/%llu pixels match Embree's all-hits (the rest at triangle "
              "edges), max depth error %.3g\n",
              scene.c_str(), n, r, (unsigned long long)(total.pixels - total.mismatches),
              (unsigned long long)total.pixels, total.max_depth_error);
}

TEST(PsppsllOracle, CornellListsMatchEmbreeAllHits) { expect_matches_embree("cornell", 8, 64); }
TEST(PsppsllOracle, AtriumListsMatchEmbreeAllHits) { expect_matches_embree("atrium", 6, 64); }

TEST(Psppsll, BuildStoresEveryFragmentSorted) {
  const test::LdmFixture f("atrium", 8, 48);
  auto s = f.build("psppsll");
  const BuildStats stats = s->stats();
  EXPECT_EQ(stats.fragments_rasterized, f.census.total_fragments);
  EXPECT_EQ(stats.fragments_stored, f.census.total_fragments);
  EXPECT_EQ(stats.fragments_lost, 0u);
  EXPECT_FALSE(stats.overflow);
  const LdmIntegrity integrity = LdmInspector(*s, *f.inputs).check();
  EXPECT_EQ(integrity.fragments, f.census.total_fragments);
  EXPECT_EQ(integrity.unsorted_pixels, 0u);
  EXPECT_EQ(integrity.overlong_pixels, 0u);
  // Per-pixel lengths equal the census's counts.
  const LdmInspector inspector(*s, *f.inputs);
  for (uint32_t v = 0; v < f.views.size(); ++v) {
    const auto lists = inspector.read_back(v);
    for (size_t p = 0; p < lists.size(); ++p)
      ASSERT_EQ(lists[p].size(), f.census.counts[v * f.views.pixels_per_view() + p]);
  }
}

// The thesis (§3.4.3) met drivers that dropped nodes at random: repeated builds must give the
// very same lists, and the harness's checksum must see it.
TEST(Psppsll, RepeatedBuildsGiveIdenticalLists) {
  const test::LdmFixture f("atrium", 8, 48);
  auto s = f.build("psppsll");
  const LdmInspector inspector(*s, *f.inputs);
  const LdmIntegrity first = inspector.check();
  const auto first_lists = inspector.read_back(3);
  for (int i = 0; i < 6; ++i) {
    s->build(*f.inputs, nullptr);
    EXPECT_EQ(inspector.check(), first) << "build " << i;
  }
  EXPECT_EQ(inspector.read_back(3), first_lists);
  // The atomic-read workaround builds the same lists.
  auto workaround = f.build("psppsll", {{"atomic_reads", "1"}});
  EXPECT_EQ(LdmInspector(*workaround, *f.inputs).check(), first);
}

// A fixed pool that is too small: the overflow is flagged and the loss counted exactly;
// what was stored is still a sorted subset of every list.
TEST(Psppsll, FixedPoolOverflowIsDetectedAndCountedExactly) {
  test::expect_fixed_pool_overflow_counted(test::LdmFixture("cornell", 8, 48), "psppsll");
}

TEST(Psppsll, RejectsBadParameters) {
  test::expect_params_checked("psppsll",
                              {{{"pool", "huge"}}, {{"pol", "grow"}}, {{"pool", "fixed"}}, {{"capacity", "0"}}});
  EXPECT_THROW(make_structure("nosuch", StructureParams()), UserError);
}

// A driver whose self-test lost invocations at memoryBarrier() in a divergent loop (the
// barrier of the insertion loop) gets no PSPPSLL build in that stage, and the refusal names
// the failed probe; a failure of memoryBarrierBuffer() alone, which PSPPSLL does not use,
// refuses nothing (harness/gl/driver_probe.h).
TEST(Psppsll, RefusesToBuildWhereTheDriverFailedItsBarrierSelfTest) {
  const auto probe = [](ProbeStage stage, ProbeBarrier barrier, uint32_t completed) {
    BarrierProbeResult r;
    r.stage = stage;
    r.barrier = barrier;
    r.invocations = 64;
    r.completed = completed;
    return r;
  };
  DriverConformance driver;
  for (ProbeStage stage : {ProbeStage::Compute, ProbeStage::Fragment})
    for (ProbeBarrier barrier : {ProbeBarrier::MemoryBarrier, ProbeBarrier::MemoryBarrierBuffer})
      driver.barrier_probes.push_back(probe(stage, barrier, 64));
  EXPECT_FALSE(psppsll_driver_refusal(driver, ProbeStage::Compute));
  EXPECT_FALSE(psppsll_driver_refusal(driver, ProbeStage::Fragment));
  driver.barrier_probes[1].completed = 8;  // memoryBarrierBuffer(), compute: not PSPPSLL's
  EXPECT_FALSE(psppsll_driver_refusal(driver, ProbeStage::Compute));
  driver.barrier_probes[0].completed = 8;  // memoryBarrier(), compute
  const auto refusal = psppsll_driver_refusal(driver, ProbeStage::Compute);
  ASSERT_TRUE(refusal);
  EXPECT_NE(refusal->find("memoryBarrier() in a divergent compute loop: 56 of 64 invocations lost"),
            std::string::npos) << *refusal;
  EXPECT_FALSE(psppsll_driver_refusal(driver, ProbeStage::Fragment));
}

}  // namespace
}  // namespace ldm
