// The one measurement path (harness/measuring/measurement.h) and the integrity policy every
// consumer shares (ldm_impls/common/build_health.h), and the pass registry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "harness/records/harness_columns.h"
#include "harness/measuring/measurement.h"
#include "harness/measuring/measurement_session.h"
#include "harness/passes/pass.h"
#include "harness/records/output_folder.h"
#include "harness/scene/gpu_scene.h"
#include "harness/scene/scene_loader.h"
#include "harness/util/error.h"
#include "support/measurement_request.h"
#include "support/test_support.h"

namespace ldm {
namespace {

FragmentCensus census_of(uint64_t fragments, uint32_t max_depth) {
  FragmentCensus c;
  c.total_fragments = fragments;
  c.max_depth_complexity = max_depth;
  return c;
}

BuildStats stats(uint64_t rasterized, uint64_t stored) {
  BuildStats s;
  s.fragments_rasterized = rasterized;
  s.fragments_stored = stored;
  s.fragments_lost = rasterized - stored;
  return s;
}

LdmIntegrity integrity(uint64_t fragments, uint64_t checksum) {
  LdmIntegrity i;
  i.fragments = fragments;
  i.checksum = checksum;
  return i;
}

TEST(BuildHealth, SoundBuildsAreOk) {
  const FragmentCensus census = census_of(100, 4);
  BuildHealth health(census);
  for (int i = 0; i < 3; ++i) health.observe(stats(100, 100), integrity(100, 7));
  EXPECT_EQ(health.status(), BuildStatus::Ok);
  EXPECT_EQ(health.detail(), "");
  EXPECT_EQ(health.builds(), 3u);
  EXPECT_EQ(health.first_checksum(), 7u);
}

TEST(BuildHealth, CountedLossIsLossyAndMayChangeTheChecksum) {
  const FragmentCensus census = census_of(100, 4);
  BuildHealth health(census);
  health.observe(stats(100, 60), integrity(60, 1));
  health.observe(stats(100, 60), integrity(60, 2));
  EXPECT_EQ(health.status(), BuildStatus::Lossy);
  EXPECT_EQ(health.checksum_changes(), 1u);
  EXPECT_NE(health.detail().find("40 fragments lost"), std::string::npos) << health.detail();
}

TEST(BuildHealth, EveryKindOfSilentFaultIsInvalid) {
  const FragmentCensus census = census_of(100, 4);
  auto verdict = [&](const BuildStats& s, const LdmIntegrity& first, const LdmIntegrity& second) {
    BuildHealth health(census);
    health.observe(s, first);
    health.observe(s, second);
    return std::make_pair(health.status(), health.detail());
  };
  // The build saw fewer fragments than the census counted.
  EXPECT_EQ(verdict(stats(90, 90), integrity(90, 1), integrity(90, 1)).first, BuildStatus::Invalid);
  // Stored fragments the query API cannot reach.
  EXPECT_EQ(verdict(stats(100, 100), integrity(99, 1), integrity(99, 1)).first,
            BuildStatus::Invalid);
  // Lists changed between identical lossless builds.
  const auto changed = verdict(stats(100, 100), integrity(100, 1), integrity(100, 2));
  EXPECT_EQ(changed.first, BuildStatus::Invalid);
  EXPECT_NE(changed.second.find("changed between identical builds"), std::string::npos);
  LdmIntegrity unsorted = integrity(100, 1);
  unsorted.unsorted_pixels = 3;
  EXPECT_EQ(verdict(stats(100, 100), unsorted, unsorted).second, "3 pixels with unsorted depths");
  LdmIntegrity overlong = integrity(100, 1);
  overlong.overlong_pixels = 2;
  EXPECT_EQ(verdict(stats(100, 100), overlong, overlong).first, BuildStatus::Invalid);
  // A fault found outside the build (the image) is invalid too, and reported once.
  BuildHealth health(census);
  health.observe(stats(100, 100), integrity(100, 1));
  health.report_problem("image not measured");
  health.report_problem("image not measured");
  EXPECT_EQ(health.status(), BuildStatus::Invalid);
  EXPECT_EQ(health.detail(), "image not measured");
}

TEST(PassRegistry, AoIsRegisteredAndParametersAreChecked) {
  EXPECT_EQ(pass_names(), (std::vector<std::string>{"ao", "hbao", "gtao", "rtao", "rtao_gpu", "indirect"}));
  try {
    make_pass("photons", StructureParams());
    FAIL() << "an unknown pass was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("known: ao, hbao, gtao, rtao, rtao_gpu, indirect"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_pass("ao", StructureParams({{"dmax", "1"}}, "--pass ao")), UserError);
  EXPECT_THROW(make_pass("ao", StructureParams({{"d_max", "-1"}}, "--pass ao")), UserError);
  EXPECT_THROW(make_pass("ao", StructureParams({{"visibility", "half"}}, "--pass ao")), UserError);
  // Parameters override the scene's settings; absent ones keep them.
  const Scene scene = load_scene("cornell");
  const std::map<std::string, std::string> values = {{"d_max", "0.25"}, {"visibility", "unattenuated"}};
  const auto pass = make_pass("ao", StructureParams(values));
  bool saw_d_max = false;
  for (const auto& [key, value] : pass->describe(scene)) {
    if (key == "d_max") saw_d_max = std::get<double>(value) == 0.25;
    if (key == "visibility") EXPECT_EQ(std::get<std::string>(value), "unattenuated");
    if (key == "normal_offset_pixels")
      EXPECT_EQ(std::get<double>(value), double(scene.ao.normal_offset_pixels));
  }
  EXPECT_TRUE(saw_d_max);
  EXPECT_TRUE(pass->requirements().needs_structure);
  EXPECT_TRUE(pass->requirements().scene_attributes.normals);
}

TEST(Measurement, KeepsEveryFrameAndSplitsBuildFromThePass) {
  MeasurementRequest request = test::measurement_request("dfbuffer", 4, 32, 32, 1, 3);
  request.configuration.sizing.policy = SizingPolicy::PreviousFrame;  // its read-back is part of the build
  int seen = 0;
  request.on_frame = [&](const FrameTimes&) { ++seen; };
  const Measurement m = measure(load_scene("cornell"), request);
  EXPECT_EQ(m.status(), BuildStatus::Ok) << m.status_detail();
  EXPECT_GT(m.count(columns::kFragments), 0u);
  EXPECT_EQ(m.count(columns::kFragmentsStored), m.count(columns::kFragments));
  ASSERT_EQ(m.frames.size(), 3u);
  EXPECT_EQ(seen, 3);
  EXPECT_EQ(m.pass_subpasses, (std::vector<std::string>{"gbuffer", "ao"}));
  for (size_t i = 0; i < m.frames.size(); ++i) {
    std::map<std::string, double> t(m.frames[i].begin(), m.frames[i].end());
    for (const char* name : {"clear", "count", "prefix_sum", "construct", "sort", "readback",
                             "gbuffer", "ao", "build", "frame"})
      EXPECT_TRUE(t.count(name)) << name;
    // The raster yardsticks on every kBaselineFrameStride-th measured frame from the first.
    const bool yardsticks = i % kBaselineFrameStride == 0;
    EXPECT_EQ(t.count("raster_baseline"), yardsticks ? 1u : 0u) << "frame " << i;
    EXPECT_EQ(t.count("raster_touch"), yardsticks ? 1u : 0u) << "frame " << i;
    EXPECT_DOUBLE_EQ(t["build"], t["clear"] + t["count"] + t["prefix_sum"] + t["construct"] +
                                     t["sort"] + t["readback"]);
    EXPECT_DOUBLE_EQ(t["frame"], t["build"] + t["gbuffer"] + t["ao"]);
    EXPECT_DOUBLE_EQ(t["pass"], t["frame"] - t["build"]);  // the pass's own, summed per frame
  }
  EXPECT_EQ(m.count(columns::kRasterTouchFragments), m.count(columns::kFragments));
  const std::vector<TimingSummary> summaries = m.summaries();
  EXPECT_EQ(find_summary(summaries, "build")->samples, 3u);
  EXPECT_EQ(find_summary(summaries, "raster_baseline")->samples, 2u);  // frames 0 and 2
  // Every frame's every time, one CSV row each, in order.
  const std::string csv = frame_samples_csv(m);
  size_t rows = 0, expected_rows = 1;
  for (char c : csv) rows += c == '\n';
  for (const FrameTimes& frame : m.frames) expected_rows += frame.size();
  EXPECT_EQ(rows, expected_rows);
  EXPECT_EQ(csv.rfind("repetition,frame,subpass,ms\n0,0,", 0), 0u) << csv.substr(0, 40);
  EXPECT_NE(csv.find("\n0,2,frame,"), std::string::npos);
  EXPECT_NE(frame_samples_csv(m, 4).find("\n4,2,frame,"), std::string::npos);  // a repetition's own
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].name, "ao");
  EXPECT_EQ(m.images[0].image.width, 32);
  EXPECT_GT(m.count(columns::kBytesAllocated), 0u);
  EXPECT_EQ(m.columns.text(columns::kSceneAttributes), "position+normal");
}

// A measurement's columns are a record of declared columns, written by the code that knows
// each value (no mirror of the record to copy from): an undeclared column is refused at its
// first use, and a peer pass, which has no census and no structure, writes none of their
// columns instead of zeros that would read as measured.
TEST(Measurement, ItsColumnsAreDeclaredAndAPeerWritesNoStructureColumns) {
  MeasurementRequest request = test::measurement_request("psppsll", 2, 16, 16, 0, 1);
  const Measurement ldm = measure(load_scene("cornell"), request);
  EXPECT_TRUE(ldm.columns.checked());
  Measurement copy = ldm;
  EXPECT_THROW(copy.columns.set("not_a_declared_column", 1), std::logic_error);
  for (const Column* column : {&columns::kFragments, &columns::kFragmentsStored, &columns::kListsChecksum,
                               &columns::kTiedDepths, &columns::kVerifyMode, &columns::kSizingRebuilds,
                               &columns::kRasterTouchFragments, &columns::kBytesAllocated,
                               &columns::kFramesTimedMs, &columns::kWorkReplayMs})
    EXPECT_TRUE(ldm.columns.get(*column)) << column->name;

  request.configuration.structure = "none";
  request.configuration.pass = "hbao";
  const Measurement peer = measure(load_scene("cornell"), request);
  EXPECT_EQ(peer.status(), BuildStatus::Ok) << peer.status_detail();
  for (const Column* column : {&columns::kFragments, &columns::kMaxDepthComplexity, &columns::kFragmentsStored,
                               &columns::kListsChecksum, &columns::kOverflow, &columns::kTiedDepths,
                               &columns::kSizingRebuilds, &columns::kRasterTouchFragments})
    EXPECT_EQ(peer.columns.get(*column), nullptr) << column->name << " written for a peer pass";
  EXPECT_GT(peer.count(columns::kBytesAllocated), 0u);  // the pass's own buffers
  EXPECT_TRUE(peer.columns.get(columns::kFramesTimedMs));
}

// The record's typed readers read a value of their type and nothing else.
TEST(Record, TypedReadersReadOnlyTheirType) {
  Record r;
  r.set("count", 7);
  r.set("ratio", 0.5);
  r.set("name", "psppsll");
  r.set("on", true);
  EXPECT_EQ(r.integer("count"), 7);
  EXPECT_EQ(r.number("count"), 7.0);
  EXPECT_EQ(r.number("ratio"), 0.5);
  EXPECT_EQ(r.integer("ratio"), std::nullopt);
  EXPECT_EQ(r.number("name"), std::nullopt);
  EXPECT_EQ(r.text("name"), "psppsll");
  EXPECT_EQ(r.text("count"), "");
  EXPECT_TRUE(r.flag("on"));
  EXPECT_FALSE(r.flag("count"));
  EXPECT_EQ(r.number("absent"), std::nullopt);
  Record more;
  more.set("ratio", 0.25);
  more.set("extra", 1);
  r.put_all(more);  // replaced in place, new ones appended
  EXPECT_EQ(r.fields()[1].first, "ratio");
  EXPECT_EQ(r.number("ratio"), 0.25);
  EXPECT_EQ(r.fields().back().first, "extra");
  append_note(r, columns::kStatusDetail, "");
  EXPECT_EQ(r.get(columns::kStatusDetail), nullptr);
  append_note(r, columns::kStatusDetail, "one");
  append_note(r, columns::kStatusDetail, "two");
  EXPECT_EQ(r.text(columns::kStatusDetail), "one; two");
}

// Normals the importer derived (issue 37): an OBJ without `vn` gets face normals, and the
// record says so in scene_attributes; the same mesh with its normals says plain "+normal".
TEST(Measurement, DerivedNormalsAreRecordedInSceneAttributes) {
  test::gl_context();
  const std::filesystem::path dir = test::make_temp_dir("ldm-derived-normals");
  const std::string corners = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0.6\n";
  std::ofstream(dir / "bare.obj") << corners << "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n";
  std::ofstream(dir / "smooth.obj") << corners << "vn 0 0 1\n"
                                    << "f 1//1 2//1 5//1\nf 2//1 3//1 5//1\nf 3//1 4//1 5//1\nf 4//1 1//1 5//1\n"
                                    << "f 1//1 4//1 3//1 2//1\n";
  const Scene bare = load_scene((dir / "bare.obj").string());
  const Scene smooth = load_scene((dir / "smooth.obj").string());
  EXPECT_EQ(bare.derived_normal_triangles, bare.mesh.triangle_count());
  EXPECT_EQ(smooth.derived_normal_triangles, 0u);
  MeasurementRequest request = test::measurement_request("dfbuffer", 2, 16, 16, 0, 1);
  const Measurement derived = measure(bare, request);
  EXPECT_EQ(derived.status(), BuildStatus::Ok) << derived.status_detail();
  EXPECT_EQ(derived.columns.text(columns::kSceneAttributes), "position+normal(derived)");
  EXPECT_EQ(measure(smooth, request).columns.text(columns::kSceneAttributes), "position+normal");
  // Some triangles' normals derived: how many of how many.
  AttributeSet normals;
  normals.normals = true;
  EXPECT_EQ(normals.describe(2, 6), "position+normal(derived for 2 of 6 triangles)");
  EXPECT_EQ(normals.describe(0, 6), "position+normal");
  EXPECT_EQ(AttributeSet{}.describe(6, 6), "position");  // no normals uploaded: nothing derived to say
}

TEST(Measurement, AnExternalLoopDecidesHowManyFramesRun) {
  // 100 frames, ignored: the loop below decides, as Google Benchmark's does.
  MeasurementRequest request = test::measurement_request("psppsll", 2, 16, 16, 0, 100);
  int left = 2;
  request.keep_running = [&] { return left-- > 0; };
  const Measurement m = measure(load_scene("cornell"), request);
  EXPECT_EQ(m.frames.size(), 2u);
}

}  // namespace
}  // namespace ldm

namespace ldm {
namespace {

// Image paths in records are relative to the folder holding records.csv, wherever the
// images folder is given from.
TEST(OutputFolder, WritesImagesAndReturnsPathsRelativeToTheRecords) {
  const std::filesystem::path dir = test::make_temp_dir("ldm-output-folder");
  const std::filesystem::path images = dir / "run" / "images";
  std::filesystem::create_directories(images);
  const OutputFolder folder((dir / "run").string(), images.string());
  Image image(4, 2, 1);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) / 8.0f;
  EXPECT_EQ(folder.write_png("a.png", image), "images/a.png");
  EXPECT_EQ(folder.write_exr("a.exr", image), "images/a.exr");
  EXPECT_TRUE(folder.contains("a.png"));
  EXPECT_FALSE(folder.contains("b.png"));
  EXPECT_EQ(read_image((images / "a.exr").string()).pixels, image.pixels);
  const OutputFolder outside((dir / "run").string(), (dir / "elsewhere").string());
  EXPECT_EQ(outside.record_path("c.png"), "../elsewhere/c.png");
}

}  // namespace
}  // namespace ldm
