#include "harness/util/version.h"

namespace ldm {

std::string version_line(const std::string& program) {
  return program + " " + ldmbench_version() + " (commit " + git_commit() +
         (git_tree_dirty() ? ", dirty" : "") + ")";
}

}  // namespace ldm
