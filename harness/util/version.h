#pragma once
// The version stamp of records and of `--version`: the commit the binary was built from
// and the project version. Defined in one small file generated at build time
// (cmake/VersionStamp.cmake from cmake/version.cpp.in), so that a new commit recompiles
// that one file rather than every file including this header.
#include <string>

namespace ldm {
// The commit's short hash, or "unknown" when built outside a git checkout (a tarball).
const char* git_commit();
// Whether tracked files differed from that commit when the binary was built.
bool git_tree_dirty();
// The project version of CMakeLists.txt's project() ("0.1.0").
const char* ldmbench_version();
// "<program> 0.1.0 (commit abc123def456, dirty)"; "(commit unknown)" without git.
std::string version_line(const std::string& program);
}  // namespace ldm
