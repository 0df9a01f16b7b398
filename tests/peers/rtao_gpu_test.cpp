// The GPU ray-traced AO peer (harness/passes/rtao_gpu.h).
#include <gtest/gtest.h>

#include <cmath>

#include "harness/passes/rtao.h"
#include "harness/passes/rtao_gpu.h"
#include "harness/reference/ao_reference.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "harness/scene/generators.h"
#include <functional>
#include <limits>
#include <optional>
#include "harness/passes/gbuffer_pass.h"
#include "harness/reference/surface_point.h"
#include "harness/reference/hemisphere.h"
#include "harness/passes/gpu_bvh.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/embree_scene.h"
#include "harness/scene/camera.h"
#include "support/ao_reference_request.h"
#include "support/ao_closed_forms.h"
#include "support/ao_convergence.h"
#include "support/pass_run.h"
#include "support/test_support.h"

namespace ldm {
namespace {

struct GpuRun {
  Image image;
  RtaoGpuWork work;
  std::vector<std::string> problems;
  std::vector<uint32_t> triangle_ids;  // the G-buffer's (traced or rasterised), GL rows
};

GpuRun rtao_gpu_run(const Scene& scene, int size, std::map<std::string, std::string> params) {
  test::PassRun<RtaoGpu> run("rtao_gpu", scene, size, size, std::move(params));
  const Image image = run.render();
  RtaoGpu& pass = *run.pass;
  return {image, pass.work(), pass.problems(), pass.read_triangle_ids()};
}

Image rtao_cpu_image(const Scene& scene, int size, std::map<std::string, std::string> params) {
  return test::PassRun<Rtao>("rtao", scene, size, size, std::move(params), AttributeSet{}).render();
}

// The triangle each pixel's primary ray hits in Embree (the reference's and the CPU RTAO's
// point), +1, 0 on a miss; and that point's shading normal.
struct PrimaryHits {
  std::vector<uint32_t> ids;  // image rows top first
  std::vector<glm::vec3> normals;
};
PrimaryHits embree_primary_hits(const Scene& scene, int size) {
  const Scene centred = centred_on_bounding_sphere(scene);  // as the CPU RTAO traces
  const EmbreeScene embree(centred);
  const CameraFrame camera = camera_frame(centred.camera, size, size);
  PrimaryHits hits;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const auto point = camera_surface_point(embree, camera, x, y, size, size);
      hits.ids.push_back(point ? point->triangle + 1 : 0);
      hits.normals.push_back(point ? point->shading_normal : glm::vec3(0.0f));
    }
  return hits;
}

// Where the GPU and the CPU start a pixel's rays from the same point in the same frame: the
// GPU's G-buffer shows the triangle Embree's primary ray hits, and (for the rasterised one)
// its normal's z has the sign bit of the CPU's (Duff's frame turns with copysign(1, n.z); the
// rasteriser's interpolation drops a mesh normal's -0, the traced G-buffer interpolates as
// Embree does). The rasteriser differs at silhouettes (it snaps vertices to 1/256 px).
std::vector<bool> same_ray_starts(const Scene& scene, int size, const GpuRun& gpu, bool raster) {
  const PrimaryHits embree = embree_primary_hits(scene, size);
  Image normals;
  if (raster) {
    AttributeSet attributes;
    attributes.normals = true;
    const GpuScene gpu_scene(scene, attributes);
    GBufferPass gbuffer(size, size, false, true);
    gbuffer.render(gpu_scene, scene, nullptr);
    normals = gbuffer.read_normals();
  }
  std::vector<bool> same(size_t(size) * size, false);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const size_t i = size_t(y) * size + x;
      same[i] = gpu.triangle_ids[size_t(size - 1 - y) * size + x] == embree.ids[i] &&
                (!raster || embree.ids[i] == 0 ||
                 std::signbit(normals.at(x, y, 2)) == std::signbit(embree.normals[i].z));
    }
  return same;
}

// With the CPU RTAO's seed the GPU draws the CPU's random numbers, so wherever both start a
// pixel's rays from the same point in the same frame they trace the same rays: the images
// agree up to the two tracers' rounding of the hit distances (V = (t / d_max)^2: measured
// 2.8e-5 at most; 1e-4 allowed). Any traversal bug that loses or invents a hit changes a
// pixel by at least a quarter of V at 4 spp. The traced G-buffer is the reference's in all
// but the pixels whose centre's ray meets an edge (none here); the rasterised one differs at
// silhouettes and in the frame where a normal's z is -0 (here up to 1.5 % of the pixels).
TEST(RtaoGpu, SameSeedTracesTheCpuRtaosRays) {
  for (const char* name : {"cornell", "atrium"})
    for (bool raster : {false, true}) {
      const Scene scene = load_scene(name);
      const int size = 64;
      const GpuRun gpu = rtao_gpu_run(scene, size, {{"spp", "4"}, {"seed", std::to_string(0x5254414f)},
                                                    {"primary", raster ? "raster" : "trace"}});
      const Image cpu = rtao_cpu_image(scene, size, {{"spp", "4"}});  // rtao's default seed
      const std::vector<bool> same = same_ray_starts(scene, size, gpu, raster);
      int checked = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          if (!same[size_t(y) * size + x]) continue;
          ++checked;
          ASSERT_NEAR(gpu.image.at(x, y), cpu.at(x, y), 1e-4)
              << name << (raster ? " raster" : " trace") << " pixel " << x << "," << y;
        }
      EXPECT_GE(checked, raster ? size * size * 9 / 10 : size * size) << name << (raster ? " raster" : " trace");
      EXPECT_TRUE(gpu.problems.empty()) << name;
    }
}

// Per-pixel squared differences of two images: their mean and its standard error.
struct MeanSquare {
  double mean = 0, standard_error = 0;
};
MeanSquare mean_square(const Image& a, const Image& b) {
  double sum = 0, sum_sq = 0;
  const int n = a.width * a.height;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double d = double(a.at(x, y)) - double(b.at(x, y));
      sum += d * d;
      sum_sq += d * d * d * d;
    }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n)};
}

// Independent samples: MSE(GPU, CPU) at equal k is 2 sigma^2 / k, as is MSE(A, B) of two
// independent halves of the reference's random sampler at k samples each. They must agree
// within 4 standard errors of the two means (the per-pixel squares' spread over 4096 pixels).
TEST(RtaoGpu, AgreesWithTheCpuRtaoWithinTheirNoise) {
  const Scene scene = load_scene("cornell");
  const int size = 64;
  for (uint32_t k : {1u, 4u}) {
    const GpuRun gpu = rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}});  // its own seed
    const Image cpu = rtao_cpu_image(scene, size, {{"spp", std::to_string(k)}});
    AoReferenceRequest request = test::ao_reference_request(size, k);
    request.sampler = AoSampler::Random;
    const ReferenceResult halves = render_ao_reference(scene, request);
    const MeanSquare between = mean_square(gpu.image, cpu);
    const MeanSquare expected = mean_square(halves.half_a, halves.half_b);
    EXPECT_NEAR(between.mean, expected.mean,
                4.0 * std::hypot(between.standard_error, expected.standard_error))
        << "k = " << k;
    EXPECT_GT(between.mean, 0.5 * expected.mean) << "independent samples, not the CPU's own";
  }
}

// The error beyond the reference's noise is the estimator's variance, sigma^2 / k: with
// e_k = MSE_k - ref_noise_mse, e_k * k / e_1 = 1 within 4 standard errors of the ratio (the
// two MSEs' standard errors over the pixels, combined to first order; the nested prefixes of
// one random stream correlate e_1 and e_k positively, which only narrows the true spread).
TEST(RtaoGpu, ErrorBeyondTheReferenceNoiseFallsAsOneOverK) {
  for (const char* name : {"cornell", "atrium"}) {
    const Scene scene = load_scene(name);
    const int size = 64;
    const ReferenceResult reference = render_ao_reference(scene, test::ao_reference_request(size, 1024));
    std::vector<MeanSquare> mse;
    const std::vector<uint32_t> ks = {1, 4, 16, 64};
    for (uint32_t k : ks)
      mse.push_back(mean_square(rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}}).image, reference.image));
    const double e1 = mse[0].mean - reference.noise_mse;
    ASSERT_GT(e1, 100.0 * reference.noise_mse) << name << ": the reference is converged far beyond 1 spp";
    for (size_t i = 1; i < ks.size(); ++i) {
      const double ek = mse[i].mean - reference.noise_mse;
      const double ratio = ek * ks[i] / e1;
      const double se = ratio * std::hypot(mse[i].standard_error / ek, mse[0].standard_error / e1);
      EXPECT_NEAR(ratio, 1.0, 4.0 * se) << name << ", k = " << ks[i] << ": e_k = " << ek << ", e_1 = " << e1;
    }
  }
}

// The GPU's arithmetic is held to 1e-5 (the reference's to float rounding), over at least
// half the pixels (the closed forms cover less of the image than the reference's scenes).
constexpr test::AoConvergence kGpuConvergence{1e-5, 0.5};

// Where pixel (x, y)'s primary ray meets the floor y = 0.
glm::dvec3 rtao_floor_point(const Scene& scene, int x, int y, int size) {
  const CameraFrame camera = camera_frame(scene.camera, size, size);
  const glm::dvec3 d(camera.ray_direction(x, y, size, size));
  const glm::dvec3 eye(camera.eye);
  return eye + d * (-eye.y / d.y);
}

// At large k the GPU RTAO converges to the closed forms: the parallel planes (attenuated: the
// closest hit within d_max), the square ceiling (unattenuated: any hit ends the ray) and the
// wall. The rays start kRayOffsetUlps ulps of the floor's largest coordinate (4) above it:
// the ceiling is that much closer.
TEST(RtaoGpu, ConvergesToTheClosedFormsAtLargeK) {
  const int size = 32;
  const uint32_t k = 1024;
  const double offset = kRayOffsetUlps * 1.1920928955078125e-7 * 4.0;
  {
    const Scene scene = load_scene("parallel-planes");
    const double ao = test::parallel_planes_ao(1.0 - offset, 2.0, 2.0);
    test::expect_ao_converged(rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}}).image, k, kGpuConvergence,
                     [&](int, int) { return ao; });
  }
  {
    const double w = 1.5;
    const Scene scene = generate_scene("parallel-planes", {{"half_size", w}, {"attenuated", false}}, "test");
    const double h = 1.0 - kRayOffsetUlps * 1.1920928955078125e-7 * w;
    test::expect_ao_converged(rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}}).image, k, kGpuConvergence, [&](int x, int y) {
      const glm::dvec3 p = rtao_floor_point(scene, x, y, size);
      return test::square_ceiling_ao(p.x, p.z, w, h);
    });
  }
  {
    const Scene scene = generate_scene("wall", {{"d_max", 1.0}}, "test");
    test::expect_ao_converged(rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}}).image, k, kGpuConvergence, [&](int x, int y) {
      return test::wall_ao(rtao_floor_point(scene, x, y, size).x, 1.0);
    });
  }
}

// The one loop runs a ray start, a node (both boxes of the plane's single leaf miss: the rays
// leave its plane) and a ray end per ray: 2 spp + 1 iterations an invocation, counted exactly.
// Past llvmpipe's 65,535 iterations the device ends the loop (the count stops at 65,536) and
// the record must say the image may be wrong; below it, nothing is said.
TEST(RtaoGpu, CountsItsLoopAndDetectsTheDevicesLoopLimit) {
  Scene scene = load_scene("plane");
  const int size = 16;
  const GpuRun below = rtao_gpu_run(scene, size, {{"spp", "30000"}});
  EXPECT_EQ(below.work.ao.steps_max, 60001u);
  EXPECT_TRUE(below.problems.empty());
  EXPECT_DOUBLE_EQ(below.work.ao.nodes_mean, 1.0);
  EXPECT_DOUBLE_EQ(below.work.ao.triangles_mean, 0.0);
  EXPECT_EQ(below.work.ao.rays % 30000, 0u);
  const GpuRun above = rtao_gpu_run(scene, size, {{"spp", "40000"}});
  if (above.work.loop_limit == 0) {
    EXPECT_EQ(above.work.ao.steps_max, 80001u);
    EXPECT_TRUE(above.problems.empty());
    GTEST_SKIP() << "this device has no known loop limit";
  }
  EXPECT_EQ(above.work.loop_limit, 65535u);
  EXPECT_EQ(above.work.ao.steps_max, 65536u) << "llvmpipe ends the loop after 65,535 back edges";
  ASSERT_EQ(above.problems.size(), 1u);
  EXPECT_NE(above.problems[0].find("65535"), std::string::npos) << above.problems[0];
}

// The counting replay's per-ray work equals a CPU walk of the same BVH with the same rays:
// each GPU pixel's AO rays rebuilt from its (rasterised) G-buffer point, normal and triangle
// and its random stream, and the traced G-buffer's primary rays, walked by trace_gpu_bvh (the
// shaders' algorithm). Box and triangle decisions at float boundaries may differ between the
// two; none do here.
TEST(RtaoGpu, CountsMatchACpuWalkOfTheSameRays) {
  const Scene scene = load_scene("cornell");
  const int size = 32;
  const uint32_t k = 4;
  const GpuRun gpu = rtao_gpu_run(scene, size, {{"spp", std::to_string(k)}, {"seed", "99"}, {"primary", "raster"}});
  AttributeSet attributes;
  attributes.normals = true;
  const GpuScene gpu_scene(scene, attributes);
  GBufferPass gbuffer(size, size, false, true);
  gbuffer.render(gpu_scene, scene, nullptr);
  const Image positions = gbuffer.read_positions(), normals = gbuffer.read_normals();
  const std::vector<uint32_t> ids = gbuffer.read_triangle_ids();
  const GpuBvh bvh = build_gpu_bvh(scene.mesh);
  uint64_t rays = 0, nodes = 0, triangles = 0, nodes_max = 0, triangles_max = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const uint32_t id = ids[size_t(size - 1 - y) * size + x];
      if (id == 0) continue;
      const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
      const glm::vec3 n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
      const GpuBvhTriangle& t = bvh.triangles[bvh.slots[id - 1]];
      glm::vec3 geometric = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
      if (glm::dot(geometric, scene.camera.eye - p) < 0.0f) geometric = -geometric;
      const glm::vec3 largest = glm::max(glm::abs(t.v0), glm::max(glm::abs(t.v1), glm::abs(t.v2)));
      const float offset = kRayOffsetUlps * 1.1920928955078125e-7f * std::max({largest.x, largest.y, largest.z});
      Pcg32 rng = pixel_stream(99, kRtaoStreamPass, uint64_t(y) * size + x);
      for (uint32_t i = 0; i < k; ++i) {
        const float u1 = rng.next_float(), u2 = rng.next_float();
        const glm::vec3 d = NormalFrame(n).to_world(cosine_weighted_direction(u1, u2));
        GpuBvhHit hit;
        trace_gpu_bvh(bvh, p + offset * geometric, d, scene.ao.d_max, false, &hit);
        ++rays;
        nodes += hit.nodes_visited;
        triangles += hit.triangles_tested;
        nodes_max = std::max<uint64_t>(nodes_max, hit.nodes_visited);
        triangles_max = std::max<uint64_t>(triangles_max, hit.triangles_tested);
      }
    }
  EXPECT_EQ(gpu.work.ao.rays, rays);
  EXPECT_DOUBLE_EQ(gpu.work.ao.nodes_mean, double(nodes) / double(rays));
  EXPECT_DOUBLE_EQ(gpu.work.ao.triangles_mean, double(triangles) / double(rays));
  EXPECT_EQ(gpu.work.ao.nodes_max, nodes_max);
  EXPECT_EQ(gpu.work.ao.triangles_max, triangles_max);
  EXPECT_TRUE(gpu.work.image_matches);
  EXPECT_EQ(gpu.work.primary.rays, 0u) << "a rasterised G-buffer traces no primary rays";

  // The traced G-buffer's primary rays: the camera's, closest hit at any distance.
  const GpuRun traced = rtao_gpu_run(scene, size, {{"spp", "1"}, {"primary", "trace"}});
  const CameraFrame camera = camera_frame(scene.camera, size, size);
  uint64_t primary_nodes = 0, primary_triangles = 0, primary_nodes_max = 0, primary_triangles_max = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      GpuBvhHit hit;
      trace_gpu_bvh(bvh, camera.eye, camera.ray_direction(x, y, size, size),
                    std::numeric_limits<float>::infinity(), false, &hit);
      primary_nodes += hit.nodes_visited;
      primary_triangles += hit.triangles_tested;
      primary_nodes_max = std::max<uint64_t>(primary_nodes_max, hit.nodes_visited);
      primary_triangles_max = std::max<uint64_t>(primary_triangles_max, hit.triangles_tested);
    }
  EXPECT_EQ(traced.work.primary.rays, uint64_t(size) * size);
  EXPECT_DOUBLE_EQ(traced.work.primary.nodes_mean, double(primary_nodes) / (size * size));
  EXPECT_DOUBLE_EQ(traced.work.primary.triangles_mean, double(primary_triangles) / (size * size));
  EXPECT_EQ(traced.work.primary.nodes_max, primary_nodes_max);
  EXPECT_EQ(traced.work.primary.triangles_max, primary_triangles_max);
  EXPECT_GT(traced.work.primary.steps_max, primary_nodes_max);
}

TEST(RtaoGpu, RefusesABvhBeyondTheStorageBlock) {
  const uint64_t block = uint64_t(128) << 20;  // llvmpipe's
  EXPECT_EQ(gpu_bvh_storage_refusal(100000, block), "");
  // 64 bytes a node, fewer nodes than triangles: 2^21 triangles may need 128 MiB of nodes.
  const std::string refusal = gpu_bvh_storage_refusal(uint64_t(1) << 21 | 1, block);
  EXPECT_NE(refusal.find("bvh_nodes"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE of 128 MiB"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("2097153 triangles"), std::string::npos) << refusal;
}

TEST(RtaoGpu, ParametersMemoryAndBvhColumns) {
  // Timed on the GPU like every GL pass (not runs_on_cpu).
  test::expect_parameters_checked("rtao_gpu",
                                  {{"spp", "0"}, {"spp", "65537"}, {"seed", "-1"}, {"visibility", "half"},
                                   {"d_max", "0"}, {"threads", "2"}, {"trace", "plane"}, {"primary", "none"}},
                                  "spp", 8, "rtao_gpu_spp", false);

  const Scene scene = load_scene("cornell");
  test::PassRun<RtaoGpu> run("rtao_gpu", scene, 32, 32, {{"spp", "2"}});
  RtaoGpu& pass = *run.pass;
  GpuTimer timer(TimerSource::FencedWallClock);
  timer.begin_frame();
  run.render(&timer);
  std::vector<std::string> names;
  for (const auto& [name, ms] : timer.end_frame()) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"rtao_gpu_primary", "rtao_gpu"}));
  uint64_t bvh_bytes = 0;
  for (const BufferMemory& b : pass.memory())
    if (b.name.rfind("bvh_", 0) == 0) bvh_bytes += b.allocated;
  EXPECT_EQ(bvh_bytes, pass.bvh().bytes());
  std::map<std::string, RecordValue> results;
  for (const auto& [key, value] : pass.results()) results[key] = value;
  EXPECT_EQ(std::get<int64_t>(results.at("rtao_gpu_bvh_bytes")), int64_t(bvh_bytes));
  EXPECT_GT(std::get<double>(results.at("rtao_gpu_bvh_ms")), 0.0);
  // The record's work_rtao_gpu_* come from the shared counting replay (tests/work); work()
  // is the pass's own replay, judged for the loop limit.
  EXPECT_EQ(double(pass.work().ao.rays), std::get<double>(results.at("covered_pixel_fraction")) * 32 * 32 * 2);
  EXPECT_GE(pass.work().ao.nodes_mean, 1.0);
}

}  // namespace
}  // namespace ldm
