#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>
#include <vector>
#include <sys/wait.h>
#include <cstdlib>

namespace ldm::test {

namespace {

std::vector<std::filesystem::path>& temp_dirs() {
  static std::vector<std::filesystem::path> dirs;
  return dirs;
}

// Every test process gets its GL context before the first test, so that no test can run GL
// calls without one (they would silently do nothing), and leaves no temporary folders.
class GlEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { gl_context(); }
  void TearDown() override {
    std::error_code ignored;
    for (const auto& dir : temp_dirs()) std::filesystem::remove_all(dir, ignored);
  }
};
const auto* const registered = ::testing::AddGlobalTestEnvironment(new GlEnvironment);

// Tests measure no machine: the run-to-run probe (harness/measuring/calibration.h, about 30 s) is
// skipped explicitly in every test process and the ldmbench it starts, and every record
// says so in time_calibration. A test of the calibration passes --calibration itself, which
// wins over the variable; one that sets the variable itself keeps it.
const bool calibration_skipped = [] { return ::setenv("LDM_CALIBRATION", "skip", /*overwrite=*/0) == 0; }();
}  // namespace

HeadlessContext& gl_context() {
  static std::unique_ptr<HeadlessContext> context = HeadlessContext::create(default_context_options());
  return *context;
}

int run_command(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer;
  std::string text;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) text.append(buffer.data(), n);
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string make_temp_dir(const std::string& prefix) {
  std::random_device random;
  const auto dir = std::filesystem::temp_directory_path() /
                   (prefix + "-" + std::to_string(random()) + std::to_string(random()));
  std::filesystem::create_directories(dir);
  temp_dirs().push_back(dir);
  return dir.string();
}

std::string write_file(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::path(dir) / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

void expect_contains(const std::string& message, std::initializer_list<std::string> fragments) {
  for (const auto& fragment : fragments)
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "message '" << message << "' lacks '" << fragment << "'";
}

std::string cube_off(int side) {
  std::string off = "OFF\n8 6 0\n";
  for (int i = 0; i < 8; ++i)
    off += std::to_string((i & 1) * side) + " " + std::to_string((i >> 1 & 1) * side) + " " +
           std::to_string((i >> 2 & 1) * side) + "\n";
  off += "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  return off;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) cells.push_back(cell), cell.clear();
    else cell += c;
  }
  cells.push_back(cell);
  return cells;
}

void expect_run_rejected(const std::string& args, const std::string& culprit) {
  const std::filesystem::path out = std::filesystem::path(make_temp_dir("ldm-rejected")) / "out";
  const Outcome o = ldmbench("run " + args + " --out " + out.string());
  EXPECT_EQ(o.status, 2) << args << "\n" << o.output;
  EXPECT_NE(o.output.find(culprit), std::string::npos) << args << "\n" << o.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << args << ": an output folder was created";
}

Outcome run_shell(const std::string& command) {
  Outcome o;
  o.status = run_command(command, &o.output);
  return o;
}

Outcome ldmbench(const std::string& args, const std::string& environment) {
  return run_shell((environment.empty() ? "" : environment + " ") + std::string(LDM_BINARY_PATH) +
                   " " + args);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ldm::test
