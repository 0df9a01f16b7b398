#pragma once
// Shared by every test suite: one headless GL context per test process, and small helpers.
#include <memory>
#include <string>

#include "harness/gl/egl_context.h"

namespace ldm::test {

// The process's GL context, created on first use (tests need not care which platform).
HeadlessContext& gl_context();

// Runs a shell command; returns its exit status and captures stdout+stderr into *output.
int run_command(const std::string& command, std::string* output);

// A fresh empty directory under the system temp dir, removed when the test process ends.
std::string make_temp_dir(const std::string& prefix);

}  // namespace ldm::test
