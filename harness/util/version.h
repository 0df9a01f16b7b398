#pragma once
// The version stamp of records: the commit the binary was built from and the project
// version. Defined in a file generated at configure time (cmake/version.cpp.in), so that a
// new commit recompiles that one file rather than every file of the library.
namespace ldm {
const char* git_commit();
const char* ldmbench_version();
}  // namespace ldm
