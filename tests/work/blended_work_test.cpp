// The construction totals counted by blending (ldm_impls/common/blended_work_counts.h,
// issue 33): the counting replay's fragment stages of the LDM geometry pass add their totals
// to float targets instead of atomics. They must count exactly what one atomic per site
// counts. LDM_WORK_BLEND_EXACT_LIMIT=1 makes every blended sum "inexact", so each replay is
// run again with atomics (the fallback a pixel past 2^24 takes): the two runs' records must
// agree in every work column, and the fallback must say that it ran.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace ldm {
namespace blended_work_test {
namespace {

namespace fs = std::filesystem;

struct BlendedRun {
  std::map<std::string, nlohmann::json> records;  // by config_id
  std::string output;
};

BlendedRun run_counted(const std::string& args, const std::string& environment = "") {
  const fs::path out = fs::path(test::make_temp_dir("ldm-blended-work")) / "run";
  const test::Outcome run = test::ldmbench(
      "run " + args + " --frames 1 --warmup 0 --time-target 0 --no-images --no-reference --out " +
      out.string() + " 2>&1", environment);
  EXPECT_EQ(run.status, 0) << run.output;
  BlendedRun result{{}, run.output};
  const nlohmann::json json = nlohmann::json::parse(test::read_text(out / "records.json"));
  for (const auto& r : json["records"]) {
    EXPECT_EQ(r["status"], "ok") << r["config_id"] << ": " << r.value("status_detail", "");
    result.records[r["config_id"].get<std::string>()] = r;
  }
  return result;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The shaders' own counts: not the driver's pipeline statistics (work_*_gl_*), nor the
// replay's time.
bool shader_count(const std::string& column) {
  return column.rfind("work_", 0) == 0 && column.find("_gl_") == std::string::npos &&
         column != "work_replay_ms";
}

TEST(BlendedWork, ConstructionTotalsCountedByBlendingEqualOneAtomicPerSite) {
  // Every structure (each build's own fragment shaders, the DF-buffer's two passes, the
  // HA-buffer's guess and build), both scenes, the AO pass and the indirect pass. At R_LDM 32
  // every view fits one 64x64 tile, which llvmpipe (and lavapipe under zink) shades on one
  // thread in order: the counts that depend on arrival order (the HA-buffer's probes) are
  // the same in both runs too, so every count is compared exactly.
  const std::string args = "--scene cornell,atrium --structure all --pass ao,indirect -N 4 -R 32 "
                           "--image-size 64x48 --param indirect:r_light=16";
  const BlendedRun blended = run_counted(args);
  const BlendedRun atomics = run_counted(args, "LDM_WORK_BLEND_EXACT_LIMIT=1");
  ASSERT_EQ(blended.records.size(), 24u) << blended.output;
  ASSERT_EQ(atomics.records.size(), blended.records.size());
  EXPECT_EQ(occurrences(blended.output, "counted again with atomics"), 0u) << blended.output;
  EXPECT_EQ(occurrences(atomics.output, "counted again with atomics"), blended.records.size()) << atomics.output;
  for (const auto& [id, b] : blended.records) {
    const nlohmann::json& a = atomics.records.at(id);
    EXPECT_GT(b.value("work_construct_fragments", 0), 0) << id;
    int64_t atomics_counted = 0;  // every build counts some kind of atomic per fragment
    for (const char* kind : {"atomic_add", "atomic_min", "atomic_max", "atomic_exchange"})
      atomics_counted += b.value("work_construct_" + std::string(kind), int64_t(0));
    EXPECT_GT(atomics_counted, 0) << id;
    size_t compared = 0;
    for (const auto& [column, value] : b.items()) {
      if (!shader_count(column)) continue;
      ++compared;
      EXPECT_EQ(value, a.value(column, nlohmann::json())) << id << " " << column;
    }
    EXPECT_GT(compared, 10u) << id;
  }
}

TEST(BlendedWork, ALimitThatIsNotACountIsRefusedByName) {
  const fs::path out = fs::path(test::make_temp_dir("ldm-blended-limit")) / "run";
  const test::Outcome run = test::ldmbench(
      "run --scene cornell --structure ppfla --pass ao -N 2 -R 16 --image-size 32x32 --frames 1 "
      "--warmup 0 --time-target 0 --no-images --no-reference --out " + out.string() + " 2>&1",
      "LDM_WORK_BLEND_EXACT_LIMIT=lots");
  EXPECT_NE(run.output.find("LDM_WORK_BLEND_EXACT_LIMIT"), std::string::npos) << run.output;
  if (run.status == 0) {  // a sweep records a failing configuration and goes on
    const auto records = nlohmann::json::parse(test::read_text(out / "records.json"))["records"];
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0]["status"], "failed");
  }
}

}  // namespace
}  // namespace blended_work_test
}  // namespace ldm
