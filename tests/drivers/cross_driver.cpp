#include "cross_driver.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <mutex>

#include "support/test_support.h"

namespace ldm::test {
namespace {

constexpr GlDriver kDrivers[] = {GlDriver::Llvmpipe, GlDriver::Zink};

std::string this_binary() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

// The renderer a driver names itself by (GL_RENDERER): zink says "zink (llvmpipe ...)".
bool renderer_is(GlDriver driver, const std::string& renderer) {
  return driver == GlDriver::Zink ? renderer.rfind("zink", 0) == 0
                                  : renderer.rfind("llvmpipe", 0) == 0;
}

}  // namespace

const char* gl_driver_name(GlDriver driver) {
  return driver == GlDriver::Zink ? "zink" : "llvmpipe";
}

std::string driver_environment(GlDriver driver) {
  if (driver == GlDriver::Llvmpipe)
    return "env -u MESA_LOADER_DRIVER_OVERRIDE -u LIBGL_ALWAYS_SOFTWARE -u GALLIUM_DRIVER";
  static const std::string runtime_dir = make_temp_dir("ldm-zink-runtime");
  return "env MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1 XDG_RUNTIME_DIR=" +
         runtime_dir;
}

namespace {

// make(key) once per key (the tests that share a run ask for it again); later calls return
// the first one's result.
template <typename T, typename Make>
const T& once_per_key(const std::string& key, Make make) {
  static std::mutex mutex;
  static std::map<std::string, T> done;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto found = done.find(key); found != done.end()) return found->second;
  return done.emplace(key, make(key)).first->second;
}

CrossDriverRun run_on_both_drivers(const std::string& args) {
  CrossDriverRun run;
  const std::string dir = make_temp_dir("ldm-cross-driver");
  for (GlDriver driver : kDrivers) {
    DriverRecords& side = driver == GlDriver::Zink ? run.zink : run.llvmpipe;
    side.out = dir + "/" + gl_driver_name(driver);
    const Outcome o = ldmbench(args + " --out " + side.out, driver_environment(driver));
    EXPECT_EQ(o.status, 0) << gl_driver_name(driver) << ": ldmbench " << args << "\n" << o.output;
    const auto json = nlohmann::json::parse(read_text(side.out + "/records.json"), nullptr, false);
    if (json.is_discarded() || !json.contains("records")) {
      ADD_FAILURE() << gl_driver_name(driver) << ": no records in " << side.out;
      continue;
    }
    for (const auto& record : json["records"]) {
      side.by_id[record["config_id"].get<std::string>()] = record;
      if (record.value("structure", "") != "none") side.renderer = record.value("device", "");
    }
    EXPECT_TRUE(renderer_is(driver, side.renderer))
        << "asked for " << gl_driver_name(driver) << ", ran on '" << side.renderer << "'";
  }
  return run;
}

CrossDriverFolders child_test_folders(const std::string& name) {
  CrossDriverFolders folders;
  const std::string dir = make_temp_dir("ldm-cross-driver-child");
  for (GlDriver driver : kDrivers) {
    std::string& out = driver == GlDriver::Zink ? folders.zink : folders.llvmpipe;
    out = dir + "/" + gl_driver_name(driver);
    std::filesystem::create_directories(out);
    const Outcome o = run_shell(driver_environment(driver) + " LDM_CROSS_DRIVER_OUT=" + out + " " +
                                this_binary() + " --gtest_filter=" + name);
    EXPECT_EQ(o.status, 0) << gl_driver_name(driver) << ": " << name << "\n" << o.output;
    EXPECT_NE(o.output.find("[  PASSED  ] 1 test"), std::string::npos)
        << gl_driver_name(driver) << ": " << name << " did not run\n" << o.output;
  }
  return folders;
}

}  // namespace

const CrossDriverRun& ldmbench_on_both_drivers(const std::string& args) {
  return once_per_key<CrossDriverRun>(args, run_on_both_drivers);
}

const CrossDriverFolders& child_test_on_both_drivers(const std::string& name) {
  return once_per_key<CrossDriverFolders>(name, child_test_folders);
}

std::string cross_driver_child_out() {
  const char* out = std::getenv("LDM_CROSS_DRIVER_OUT");
  return out ? out : "";
}

void write_depth_lists(const std::string& path, const DepthLists& lists) {
  std::ofstream out(path, std::ios::binary);
  const auto put = [&](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), sizeof v); };
  put(uint32_t(lists.size()));
  for (const auto& view : lists) {
    put(uint32_t(view.size()));
    for (const auto& pixel : view) {
      put(uint32_t(pixel.size()));
      out.write(reinterpret_cast<const char*>(pixel.data()), std::streamsize(pixel.size() * sizeof(float)));
    }
  }
  if (!out) ADD_FAILURE() << "cannot write " << path;
}

DepthLists read_depth_lists(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const auto get = [&] {
    uint32_t v = 0;
    in.read(reinterpret_cast<char*>(&v), sizeof v);
    return v;
  };
  DepthLists lists(get());
  for (auto& view : lists) {
    view.resize(get());
    for (auto& pixel : view) {
      pixel.resize(get());
      in.read(reinterpret_cast<char*>(pixel.data()), std::streamsize(pixel.size() * sizeof(float)));
    }
  }
  if (!in) ADD_FAILURE() << "cannot read " << path;
  return lists;
}

}  // namespace ldm::test
