// The work counters of the passes' own sub-passes (issue 33): the G-buffer, the indirect
// pass's photon tracing, splatting, direct light and composite, HBAO and its blur, GTAO and
// its denoise, the GPU ray tracer's rays. Each is checked against a fact that does not come
// from the counters (the image's size, the pass's own photon tallies, the scene's
// geometry, a sampling pattern that stays on screen), deterministic counters must repeat
// exactly, and the splat fragments grow as the thesis says (§6.2.2: with s^2).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/settings/record_schema.h"
#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using Records = std::map<std::string, nlohmann::json>;  // by config_id

// `ldmbench run ARGS` into a fresh folder: its records, each checked ok (or lossy, where
// `lossy_ok`) with no problem of the counting replay.
Records run_records(const std::string& args, bool lossy_ok = false, const std::string& environment = "") {
  const fs::path out = fs::path(test::make_temp_dir("ldm-pass-work")) / "run";
  const test::Outcome run = test::ldmbench(
      "run " + args + " --frames 1 --warmup 0 --time-target 0 --no-images --no-reference --out " +
      out.string() + " 2>&1", environment);
  EXPECT_EQ(run.status, 0) << run.output;
  const auto json = nlohmann::json::parse(test::read_text(out / "records.json"));
  Records records;
  for (const auto& r : json["records"]) {
    const std::string status = r["status"];
    EXPECT_TRUE(status == "ok" || (lossy_ok && status == "lossy"))
        << r["config_id"] << ": " << status << " " << r.value("status_detail", "");
    EXPECT_EQ(r.value("status_detail", "").find("counting replay"), std::string::npos) << r["status_detail"];
    records[r["config_id"].get<std::string>()] = r;
  }
  return records;
}

int64_t count(const nlohmann::json& r, const std::string& column) {
  EXPECT_TRUE(r.contains(column) && r[column].is_number()) << r["config_id"] << ": no " << column;
  return r.contains(column) && r[column].is_number() ? r[column].get<int64_t>() : -1;
}

// How many values a distribution counted: its total over its mean.
int64_t samples_of(const nlohmann::json& r, const std::string& distribution) {
  const double mean = r.value(distribution + "_mean", 0.0);
  return mean > 0 ? std::llround(double(count(r, distribution + "_total")) / mean) : 0;
}

const nlohmann::json& only(const Records& records, const std::string& pass, const std::string& with = "") {
  const nlohmann::json* found = nullptr;
  for (const auto& [id, r] : records)
    if (r["pass"] == pass && id.find(with) != std::string::npos) {
      EXPECT_EQ(found, nullptr) << "two records of " << pass << " " << with;
      found = &r;
    }
  if (!found) throw std::runtime_error("no record of " + pass + " " + with);
  return *found;
}

constexpr int kWidth = 64, kHeight = 48;
constexpr int64_t kPixels = int64_t(kWidth) * kHeight;

// Every pass on the Cornell box in one run (the GPU ray tracer both ways).
const std::string kCornellArgs =
    "--scene cornell --structure psppsll --pass ao,indirect,hbao,gtao,rtao_gpu -N 4 -R 32 "
    "--image-size 64x48 --param indirect:r_light=16 --param hbao:blur=2 --param gtao:denoise=1 "
    "--param gtao:slices=4 --param gtao:steps=6 --param rtao_gpu:spp=2 "
    "--param rtao_gpu:primary=raster,trace";

const Records& cornell_run() {
  static const Records records = run_records(kCornellArgs);
  return records;
}

TEST(PassWork, GBufferCountsAreBoundedByTheScene) {
  const Records& records = cornell_run();
  ASSERT_EQ(records.size(), 6u);
  const int64_t triangles = records.begin()->second["triangles"].get<int64_t>();
  for (const auto& [id, r] : records) {
    if (r["pass"] == "rtao_gpu" && r["rtao_gpu_primary"] == "trace") {
      EXPECT_FALSE(r.contains("work_gbuffer_fragments")) << id << ": traced primary rays draw no G-buffer";
      continue;
    }
    const int64_t covered = std::llround(r["covered_pixel_fraction"].get<double>() * kPixels);
    const int64_t fragments = count(r, "work_gbuffer_fragments");
    // Every covered pixel shades its nearest surface at least; no pixel more than every triangle.
    EXPECT_GE(fragments, covered) << id;
    EXPECT_GT(fragments, covered) << id << ": the Cornell box hides surfaces behind its blocks";
    EXPECT_LE(fragments, kPixels * triangles) << id;
    if (r.contains("work_gbuffer_gl_fragment_invocations"))  // the driver's, helpers included
      EXPECT_LE(fragments, r["work_gbuffer_gl_fragment_invocations"].get<int64_t>()) << id;
    const int64_t vertices = count(r, "work_gbuffer_vertices");
    EXPECT_GT(vertices, 0) << id;
    EXPECT_LE(vertices, 3 * triangles) << id;
  }
  // The same camera, scene and image: the same G-buffer work in every pass that draws it.
  EXPECT_EQ(count(only(records, "ao"), "work_gbuffer_fragments"), count(only(records, "hbao"), "work_gbuffer_fragments"));
  EXPECT_EQ(count(only(records, "indirect"), "work_gbuffer_fragments"),
            count(only(records, "gtao"), "work_gbuffer_fragments"));
  EXPECT_EQ(count(only(records, "hbao"), "work_hbao_covered_pixels"), count(only(records, "ao"), "work_ao_covered_pixels"));
}

// One open plane filling the image: depth complexity 1, so the G-buffer shades exactly the
// covered pixels; and with a radius far below a pixel no HBAO march leaves the image, so it
// reads exactly directions x steps samples per pixel.
TEST(PassWork, HbaoOnAPlaneSamplesEveryDirectionAndStep) {
  const Records records = run_records(
      "--scene plane --pass hbao --d-max 0.0001 --param hbao:directions=4 --param hbao:steps=3 "
      "--param hbao:blur=0,2 --image-size 40x32");
  ASSERT_EQ(records.size(), 2u);
  const int64_t pixels = 40 * 32;
  for (const auto& [id, r] : records) {
    const int64_t covered = count(r, "work_hbao_covered_pixels");
    EXPECT_EQ(covered, std::llround(r["covered_pixel_fraction"].get<double>() * pixels)) << id;
    EXPECT_EQ(covered, pixels) << id << ": the plane fills the image";
    EXPECT_EQ(count(r, "work_gbuffer_fragments"), covered) << id;
    EXPECT_EQ(count(r, "work_gbuffer_vertices"), 6) << id << ": two triangles, not indexed-shared beyond them";
    EXPECT_EQ(count(r, "work_hbao_fragments"), pixels) << id;
    EXPECT_EQ(count(r, "work_hbao_directions"), covered * 4) << id;
    EXPECT_EQ(count(r, "work_hbao_samples"), covered * 4 * 3) << id;
    EXPECT_EQ(count(r, "work_hbao_steps_total"), count(r, "work_hbao_samples")) << id;
    EXPECT_EQ(count(r, "work_hbao_steps_max"), 12) << id;
    EXPECT_EQ(samples_of(r, "work_hbao_steps"), covered) << id;
    EXPECT_EQ(count(r, "work_hbao_horizon_rises"), 0) << id << ": a plane never rises above itself";
    if (r["hbao_blur"] == 2) {
      EXPECT_EQ(count(r, "work_blur_fragments"), 2 * pixels) << id;
      // Radius 2, both directions: 4 taps a pixel less those past the image's edges.
      EXPECT_EQ(count(r, "work_blur_taps"), 32 * (4 * 40 - 6) + 40 * (4 * 32 - 6)) << id;
    } else {
      EXPECT_FALSE(r.contains("work_blur_fragments")) << id << ": no blur ran";
    }
  }
}

TEST(PassWork, HbaoAndGtaoStayWithinTheirSamplingPattern) {
  const Records& records = cornell_run();
  const nlohmann::json& h = only(records, "hbao");
  const int64_t covered = count(h, "work_hbao_covered_pixels");
  EXPECT_EQ(count(h, "work_hbao_fragments"), kPixels);
  EXPECT_LE(count(h, "work_hbao_directions"), covered * 8);
  EXPECT_GT(count(h, "work_hbao_directions"), covered * 8 / 2);
  EXPECT_LE(count(h, "work_hbao_samples"), count(h, "work_hbao_directions") * 8);
  EXPECT_GT(count(h, "work_hbao_samples"), count(h, "work_hbao_directions") * 8 / 2);
  EXPECT_EQ(count(h, "work_hbao_steps_total"), count(h, "work_hbao_samples"));
  EXPECT_EQ(samples_of(h, "work_hbao_steps"), covered);
  EXPECT_LE(count(h, "work_hbao_horizon_rises"), count(h, "work_hbao_samples"));
  EXPECT_EQ(count(h, "work_blur_fragments"), 2 * kPixels);
  EXPECT_LE(count(h, "work_blur_taps"), 2 * covered * 4);

  const nlohmann::json& g = only(records, "gtao");
  EXPECT_EQ(count(g, "work_gtao_fragments"), kPixels);
  EXPECT_EQ(count(g, "work_gtao_covered_pixels"), covered);
  EXPECT_LE(count(g, "work_gtao_slices"), covered * 4);
  EXPECT_GT(count(g, "work_gtao_slices"), covered * 4 / 2);
  EXPECT_LE(count(g, "work_gtao_samples"), count(g, "work_gtao_slices") * 2 * 6);
  EXPECT_GT(count(g, "work_gtao_samples"), 0);
  EXPECT_EQ(count(g, "work_gtao_steps_total"), count(g, "work_gtao_samples"));
  EXPECT_LE(count(g, "work_gtao_horizon_rises"), count(g, "work_gtao_samples"));
  EXPECT_EQ(count(g, "work_denoise_fragments"), 2 * kPixels);
  EXPECT_LE(count(g, "work_denoise_taps"), 2 * covered * 2);
}

TEST(PassWork, IndirectCountsWhatItsPhotonTalliesCount) {
  const nlohmann::json& r = only(cornell_run(), "indirect");
  EXPECT_EQ(count(r, "work_photon_tracing_invocations"), 16 * 16) << "one invocation per light texel";
  EXPECT_EQ(count(r, "work_photon_tracing_photons_primary"), count(r, "photons_primary"));
  EXPECT_EQ(count(r, "work_photon_tracing_photons_traced"), count(r, "photons_emitted"));
  EXPECT_EQ(count(r, "work_photon_tracing_photons_appended"), count(r, "photons_stored") + count(r, "photons_overflow"));
  EXPECT_EQ(count(r, "work_photon_tracing_photons_stored"), count(r, "photons_stored"));
  EXPECT_EQ(samples_of(r, "work_photon_tracing_trace_steps"), count(r, "photons_emitted"));
  EXPECT_EQ(samples_of(r, "work_photon_tracing_entries_read"), count(r, "photons_emitted"));
  EXPECT_LE(count(r, "work_photon_tracing_trace_steps_max"), count(r, "trace_steps_max"));
  EXPECT_EQ(count(r, "work_light_gbuffer_vertices"), count(r, "work_gbuffer_vertices"));
  EXPECT_GT(count(r, "work_light_gbuffer_fragments"), 0);
  EXPECT_LE(count(r, "work_light_gbuffer_fragments"), 16 * 16 * count(r, "triangles"));
  // One point and one quad per stored photon; its fragments cover at least a pixel or so each.
  EXPECT_EQ(count(r, "work_splatting_vertices"), count(r, "photons_stored"));
  EXPECT_EQ(count(r, "work_splatting_quads"), count(r, "photons_stored"));
  EXPECT_GT(count(r, "work_splatting_fragments"), count(r, "photons_stored"));
  EXPECT_LE(count(r, "work_splatting_fragments_in_kernel"), count(r, "work_splatting_fragments"));
  EXPECT_GT(count(r, "work_splatting_fragments_in_kernel"), 0);
  EXPECT_EQ(count(r, "work_direct_fragments"), kPixels);
  EXPECT_EQ(count(r, "work_direct_covered_pixels"), std::llround(r["covered_pixel_fraction"].get<double>() * kPixels));
  EXPECT_EQ(count(r, "work_composite_fragments"), kPixels);
  EXPECT_FALSE(r.contains("work_photon_census_invocations")) << "previous_frame runs no census";
}

// The census policy traces twice a frame, the census storing nothing; an overflowing photon
// buffer stores its capacity, and splats only those.
TEST(PassWork, IndirectCensusAndOverflow) {
  const Records records = run_records(
      "--scene cornell --structure ppsll --pass indirect --sizing census,previous_frame -N 4 -R 32 "
      "--image-size 48x40 --param indirect:r_light=16 --param indirect:photon_capacity=100,1000",
      true);
  ASSERT_EQ(records.size(), 4u);
  for (const auto& [id, r] : records) {
    const bool census = id.find("census") != std::string::npos;
    const bool overflow = id.find("photon_capacity=1000") == std::string::npos;
    EXPECT_EQ(r["status"], overflow ? "lossy" : "ok") << id;
    EXPECT_EQ(count(r, "work_photon_tracing_photons_appended"), 359) << id << " (the Cornell box at R_light 16)";
    EXPECT_EQ(count(r, "work_photon_tracing_photons_stored"), overflow ? 100 : 359) << id;
    EXPECT_EQ(count(r, "work_splatting_quads"), overflow ? 100 : 359) << id;
    if (census) {
      EXPECT_EQ(count(r, "work_photon_census_photons_appended"), 359) << id;
      EXPECT_EQ(count(r, "work_photon_census_photons_stored"), 0) << id << ": the census counts only";
      EXPECT_EQ(count(r, "work_photon_census_trace_steps_total"), count(r, "work_photon_tracing_trace_steps_total")) << id;
    } else {
      EXPECT_FALSE(r.contains("work_photon_census_invocations")) << id;
    }
  }
}

// Every counter the schema calls deterministic counts the same in a second run; the
// arrival-dependent splat fragments too, where the photon buffer did not overflow.
TEST(PassWork, DeterministicCountersRepeat) {
  const Records& first = cornell_run();
  const Records second = run_records(kCornellArgs);
  ASSERT_EQ(first.size(), second.size());
  size_t compared = 0;
  for (const auto& [id, a] : first) {
    ASSERT_TRUE(second.count(id)) << id;
    const nlohmann::json& b = second.at(id);
    for (const auto& [column, value] : a.items()) {
      if (column.rfind("work_", 0) != 0 || column == "work_replay_ms") continue;
      const ColumnSpec* spec = find_column(column);
      ASSERT_NE(spec, nullptr) << column << " is not in the schema";
      if (!spec->deterministic && column.rfind("work_splatting_", 0) != 0) continue;
      ++compared;
      EXPECT_EQ(value, b.value(column, nlohmann::json())) << id << " " << column;
    }
  }
  std::cout << compared << " work counters compared between two runs\n";
  EXPECT_GE(compared, 100u);
}

TEST(PassWork, RtaoGpuCountsItsRays) {
  const Records& records = cornell_run();
  for (const char* primary : {"primary=raster", "primary=trace"}) {
    const nlohmann::json& r = only(records, "rtao_gpu", primary);
    const int64_t covered = std::llround(r["covered_pixel_fraction"].get<double>() * kPixels);
    EXPECT_EQ(count(r, "work_rtao_gpu_invocations"), kPixels) << primary;
    EXPECT_EQ(count(r, "work_rtao_gpu_rays"), covered * 2) << primary;
    EXPECT_EQ(samples_of(r, "work_rtao_gpu_nodes"), covered * 2) << primary;
    EXPECT_GE(r["work_rtao_gpu_nodes_mean"].get<double>(), 1.0) << primary;
    EXPECT_LE(count(r, "work_rtao_gpu_nodes_max"), count(r, "rtao_gpu_steps_max")) << primary;
    EXPECT_LE(count(r, "work_rtao_gpu_triangles_p50"), count(r, "work_rtao_gpu_triangles_max")) << primary;
    if (std::string(primary) == "primary=trace") {
      EXPECT_EQ(count(r, "work_rtao_gpu_primary_invocations"), kPixels);
      EXPECT_EQ(samples_of(r, "work_rtao_gpu_primary_nodes"), kPixels);
      EXPECT_LE(count(r, "work_rtao_gpu_primary_nodes_max"), count(r, "rtao_gpu_primary_steps_max"));
    } else {
      EXPECT_FALSE(r.contains("work_rtao_gpu_primary_nodes_mean")) << "a rasterised G-buffer traces no primary rays";
    }
  }
}

// Thesis §6.2.2: splatting costs grow with s^2 (a splat's footprint is s^2 times one light
// texel's beam). Measured on llvmpipe: x3.74 from s = 1 to 2 (R_light 32, 128x128); the
// image's edges and surfaces' ends clip the larger quads, so somewhat under 4.
TEST(PassWork, SplatFragmentsGrowWithTheSquareOfTheFootprintScale) {
  const Records records = run_records(
      "--scene cornell --structure psppsll --pass indirect -N 4 -R 32 --image-size 128x128 "
      "--param indirect:r_light=32 --param indirect:s=1,2");
  ASSERT_EQ(records.size(), 2u);
  const nlohmann::json& small = only(records, "indirect", "s=1");
  const nlohmann::json& large = only(records, "indirect", "s=2");
  EXPECT_EQ(count(small, "work_splatting_quads"), count(large, "work_splatting_quads"));
  const double ratio = double(count(large, "work_splatting_fragments")) / double(count(small, "work_splatting_fragments"));
  const double kernel_ratio = double(count(large, "work_splatting_fragments_in_kernel")) /
                              double(count(small, "work_splatting_fragments_in_kernel"));
  std::cout << "splat fragments, s = 1 -> 2: x" << ratio << " (in the kernel: x" << kernel_ratio << ")\n";
  EXPECT_GE(ratio, 2.5);
  EXPECT_LE(ratio, 5.0);
  EXPECT_GE(kernel_ratio, 2.5);
  EXPECT_LE(kernel_ratio, 5.0);
}

// `text` of the shader file `file` (under `shaders`) replaced by `with`, checked to be there once.
void patch_shader(const fs::path& shaders, const std::string& file, const std::string& text, const std::string& with) {
  std::stringstream in;
  in << std::ifstream(shaders / file).rdbuf();
  std::string source = in.str();
  const size_t at = source.find(text);
  ASSERT_NE(at, std::string::npos) << file << " no longer holds:\n" << text;
  ASSERT_EQ(source.find(text, at + 1), std::string::npos) << file << " holds twice:\n" << text;
  source.replace(at, text.size(), with);
  std::ofstream(shaders / file) << source;
}

// The splat's fragments are counted by blending (photon_splat.frag writes its counts to a
// second target, splat_fragment_count.comp sums it): the same totals as one atomic per
// fragment, the counting variant the pass uses beyond 2^24 photons (SPLAT_COUNT_BY_ATOMICS),
// forced here in a patched copy of the shaders (LDM_SHADER_DIR) whose sum adds nothing, on
// both scenes, at two footprint scales and two structures, with photons over the
// background and outside the kernels. That it changes no image (a rejected fragment adds
// zero radiance) run_records checks: the replay compares its images with the measured
// frames' and the record says so.
TEST(PassWork, SplatFragmentsCountedByBlendingEqualOneAtomicPerFragment) {
  const fs::path copy = fs::path(test::make_temp_dir("ldm-splat-atomics")) / "shaders";
  fs::copy(fs::path(LDM_TEST_SOURCE_DIR) / ".." / "shaders", copy, fs::copy_options::recursive);
  patch_shader(copy, "passes/indirect/photon_splat.frag", "#if WORK_COUNTING && !SPLAT_COUNT_BY_ATOMICS\n",
               "#ifndef SPLAT_COUNT_BY_ATOMICS\n#define SPLAT_COUNT_BY_ATOMICS 1\n#endif\n"
               "#if WORK_COUNTING && !SPLAT_COUNT_BY_ATOMICS\n");
  patch_shader(copy, "passes/indirect/splat_fragment_count.comp",
               "  work_add_words(uint(WORK_fragments), fragments_lo, fragments_hi);\n"
               "  work_add_words(uint(WORK_fragments_in_kernel), in_kernel_lo, in_kernel_hi);\n",
               "");
  const std::string args = "--scene cornell,atrium --structure psppsll,ppfla --pass indirect -N 4 -R 32 "
                           "--image-size 96x80 --param indirect:r_light=32 --param indirect:s=1,4";
  const Records blended = run_records(args), atomics = run_records(args, false, "LDM_SHADER_DIR=" + copy.string());
  ASSERT_EQ(blended.size(), 8u);
  ASSERT_EQ(atomics.size(), blended.size());
  for (const auto& [id, r] : blended) {
    const nlohmann::json& a = atomics.at(id);
    EXPECT_GT(count(r, "work_splatting_fragments"), count(r, "work_splatting_fragments_in_kernel")) << id;
    EXPECT_GT(count(r, "work_splatting_fragments_in_kernel"), 0) << id;
    EXPECT_EQ(count(r, "work_splatting_fragments"), count(a, "work_splatting_fragments")) << id;
    EXPECT_EQ(count(r, "work_splatting_fragments_in_kernel"), count(a, "work_splatting_fragments_in_kernel")) << id;
  }
}

}  // namespace
}  // namespace ldm
