#pragma once
// The cross-driver fixture (issue 31): the same work under Mesa's two OpenGL drivers for CPUs,
// llvmpipe (Mesa's GLSL compiler straight to gallivm; the fragments of a pixel never race)
// and zink over lavapipe (GLSL through SPIR-V to the Vulkan driver; real 64-bit atomics), each
// in a child process of its own, since the driver is chosen when EGL starts. What differs
// between the two is what a user's GPU driver may do differently, so every property that
// should not depend on the driver is tested here once: records and images of ldmbench runs,
// and the lists a structure built, read back through the query API.
//
// Other suites' cross-driver checks belong here too (work counters, translation invariance):
// run what they need through ldmbench_on_both_drivers() or a child test.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ldm::test {

enum class GlDriver { Llvmpipe, Zink };
const char* gl_driver_name(GlDriver driver);
// Shell assignments that make a child process open `driver` (zink needs a private
// XDG_RUNTIME_DIR and LIBGL_ALWAYS_SOFTWARE, without which EGL finds no device).
std::string driver_environment(GlDriver driver);

// One driver's run: its records by config_id, and where they are.
struct DriverRecords {
  std::string out;       // the run's folder (images/ inside)
  std::string renderer;  // the records' device column
  std::map<std::string, nlohmann::json> by_id;
};
struct CrossDriverRun {
  DriverRecords llvmpipe, zink;
};
// `ldmbench ARGS --out DIR` under each driver (once per process and ARGS); fails the test
// when a run fails or does not run on the driver asked for.
const CrossDriverRun& ldmbench_on_both_drivers(const std::string& args);

// A child test: this test binary's test `name` run alone under each driver, with
// LDM_CROSS_DRIVER_OUT naming a fresh folder per driver for it to write to. Returns those
// folders (once per process and name); fails the test when a child fails.
struct CrossDriverFolders {
  std::string llvmpipe, zink;
};
const CrossDriverFolders& child_test_on_both_drivers(const std::string& name);
// The folder a child test writes to; empty when the test runs as itself (it then skips).
std::string cross_driver_child_out();

// Every pixel's sorted depths of every view, as the query API returns them.
using DepthLists = std::vector<std::vector<std::vector<float>>>;  // [view][pixel][entry]
void write_depth_lists(const std::string& path, const DepthLists& lists);
DepthLists read_depth_lists(const std::string& path);

}  // namespace ldm::test
