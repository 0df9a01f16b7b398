// The CI regression guard (scripts/regression-guard.sh) guards performance by work: three
// deliberate slowdowns, each a shader patched through LDM_SHADER_DIR (a copy of shaders/
// whose files replace the build's), change no image, no list and no status, only what the
// shaders do, and each fails the guard with a work verdict naming the counter that grew.
// Counters only: nothing here is timed. The A/A run is RegressionGuard.PassesOnTheCommittedBaseline
// (tests/compare/guard_test.cpp) and the unpatched copy below.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using test::Outcome;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A copy of the source tree's shaders/ with `file`'s `from` replaced by `to` (which must
// occur exactly once: a patch that no longer applies fails the test, never passes it).
fs::path patched_shaders(const std::string& file, const std::string& from, const std::string& to) {
  const fs::path source = fs::path(LDM_TEST_SOURCE_DIR) / ".." / "shaders";
  const fs::path copy = fs::path(test::make_temp_dir("ldm-slowdown")) / "shaders";
  fs::copy(source, copy, fs::copy_options::recursive);
  if (file.empty()) return copy;
  const fs::path target = copy / file;
  std::string text = read_text(target);
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << file << " no longer holds the patched text:\n" << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << file << " holds the patched text twice";
  if (at == std::string::npos) return copy;
  text.replace(at, from.size(), to);
  std::ofstream(target) << text;
  return copy;
}

Outcome guard_with_shaders(const fs::path& shaders) {
  const fs::path script = fs::path(LDM_TEST_SOURCE_DIR) / ".." / "scripts" / "regression-guard.sh";
  return test::run_shell("LDM_SHADER_DIR=" + shaders.string() + " LDMBENCH=" + std::string(LDM_BINARY_PATH) +
                         " " + script.string());
}

// The guard over the shaders with `file`'s `from` patched to `to`: its summary says how many
// configurations regressed in work; the table names the counters that grew (the first three
// of each configuration; `counter` may be a prefix).
void expect_work_regression(const std::string& file, const std::string& from, const std::string& to,
                            const std::string& counter) {
  const Outcome o = guard_with_shaders(patched_shaders(file, from, to));
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("MORE work_"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(counter), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find(" work 0"), std::string::npos) << o.output;
  // Work alone: the slowdowns change no status, no memory and no image.
  EXPECT_NE(o.output.find("memory 0 accuracy 0 status 0"), std::string::npos) << o.output;
}

TEST(WorkGuard, AnUnpatchedCopyOfTheShadersPasses) {
  const Outcome o = guard_with_shaders(patched_shaders("", "", ""));
  EXPECT_EQ(o.status, 0) << o.output;
  EXPECT_NE(o.output.find(" work 0"), std::string::npos) << o.output;
}

// 1. The AO trace no longer stops at the first occluder ahead (the plane trace, the default,
// walks with ldm_walk_interval): the nearest one is kept, the walk reads the whole list.
TEST(WorkGuard, ATraceThatNoLongerStopsEarlyFails) {
  expect_work_regression(
      "passes/ldm_trace.glsl", "      result.ahead = depth - depth_x;   // the first one above x\n      break;\n",
      "      if (isinf(result.ahead)) result.ahead = depth - depth_x;  // slowdown: no early stop\n",
      "work_ao_entries_read");
}

// 2. PPSLL's sort walks every list once more after sorting it locally (through the sort's
// own node accessor, whose loads are counted).
TEST(WorkGuard, OneMorePassOverEveryListInTheSortFails) {
  expect_work_regression(
      "ldm/ppsll/sort.comp", "  insertion_sort_local(count);\n",
      "  insertion_sort_local(count);\n"
      "  for (uint again = head; again != 0u; again = next_node(again)) {}  // slowdown: one more pass\n",
      "work_sort_bytes_loaded_nodes");
}

// 3. The HA-buffer's query probes one slot more before its probe sequence (the key it reads
// is ignored): every query's probe count grows by one, its result stays.
TEST(WorkGuard, AHashProbeSequenceOneStepLongerFails) {
  expect_work_regression(
      "ldm/habuffer/ha_query.glsl", "  for (; c.age < c.end; ++c.age) {\n",
      "  if (c.age < c.end) ha_probe(c.pixel, c.age);  // slowdown: one probe more, its key ignored\n"
      "  for (; c.age < c.end; ++c.age) {\n",
      "work_ao_hash_probes");
}

}  // namespace
}  // namespace ldm
