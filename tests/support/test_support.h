#pragma once
// Shared by every test suite: one headless GL context per test process, and small helpers.
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/gl/egl_context.h"
#include "harness/util/error.h"

namespace ldm::test {

// The process's GL context, created on first use (tests need not care which platform).
HeadlessContext& gl_context();

// Runs a shell command; returns its exit status and captures stdout+stderr into *output.
int run_command(const std::string& command, std::string* output);

// A command's exit status and its stdout+stderr.
struct Outcome {
  int status = 0;
  std::string output;
};
Outcome run_shell(const std::string& command);
// The ldmbench binary under test with `args`, after the shell assignments in `environment`
// (e.g. "LDM_FOO=1").
Outcome ldmbench(const std::string& args, const std::string& environment = "");

// A whole file as text ("" when it cannot be read).
std::string read_text(const std::string& path);

// A fresh empty directory under the system temp dir, removed when the test process ends.
std::string make_temp_dir(const std::string& prefix);

// Writes `text` to dir/name (as bytes); returns the path.
std::string write_file(const std::string& dir, const std::string& name, const std::string& text);

// The UserError message of f(), or "" (and a failure) when nothing was thrown.
template <typename F>
std::string user_error(F f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError thrown";
  return "";
}

// Expects `message` to contain every fragment.
void expect_contains(const std::string& message, std::initializer_list<std::string> fragments);

// An axis-aligned cube [0, side]^3 as an OFF mesh (six quads).
std::string cube_off(int side);

// The cells of one CSV line, split at the commas outside double quotes (the quotes kept).
std::vector<std::string> split_csv_line(const std::string& line);

// Bad input to `ldmbench run ARGS --out DIR`: exit status 2, a message naming `culprit`, and
// nothing written (DIR, a fresh temporary path, is not created).
void expect_run_rejected(const std::string& args, const std::string& culprit);

}  // namespace ldm::test
