#include "ldm_impls/common/compute_grid.h"

#include <algorithm>

#include "harness/gl/bindings.h"
#include "harness/gl/gl_api.h"

namespace ldm {

void dispatch_linear_groups(uint64_t groups) {
  if (groups == 0) return;
  const uint64_t row = std::min(groups, kMaxGroupsPerRow);
  const uint64_t rows = groups_for(groups, row);
  glDispatchCompute(GLuint(row), GLuint(rows), 1);
}

void run_linear_compute(const GlProgram& program, uint64_t items, uint64_t items_per_group,
                        unsigned barriers) {
  program.use();
  dispatch_linear_groups(groups_for(items, items_per_group));
  glMemoryBarrier(barriers);
}

GlProgram build_compute_program(const std::string& file, const ShaderDefines& defines) {
  ShaderDefines all = binding_defines();
  all.values.insert(all.values.end(), defines.values.begin(), defines.values.end());
  return build_program({{GL_COMPUTE_SHADER, file, {}}}, all);
}

}  // namespace ldm
