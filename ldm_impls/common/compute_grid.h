#pragma once
// One-dimensional work over a two-dimensional grid of compute workgroups. A pass over every
// LDM pixel (N * R_LDM^2, up to 32 M within a 128 MiB storage block) needs more workgroups
// than the 65535 that GL guarantees along x, so the groups are laid out in rows of at most
// kMaxGroupsPerRow. Shaders recover the linear index with shaders/ldm/common/compute_grid.glsl
// and must ignore the groups of the last row that lie past the end.
//
// Shared by the PPSLL sort, the DF-buffer's scan and sort, and the inspector.
#include <cstdint>
#include <string>

#include "harness/gl/shader_program.h"

namespace ldm {

constexpr uint64_t kMaxGroupsPerRow = 32768;

// glDispatchCompute of at least `groups` workgroups (none when groups == 0).
void dispatch_linear_groups(uint64_t groups);

// A compute program from shaders/`file` with the binding defines and `defines`.
GlProgram build_compute_program(const std::string& file, const ShaderDefines& defines);

inline uint64_t groups_for(uint64_t items, uint64_t items_per_group) {
  return (items + items_per_group - 1) / items_per_group;
}

// One pass of `program` over `items` (its buffers bound, its uniforms set): uses it,
// dispatches groups_for(items, items_per_group) workgroups and waits with
// glMemoryBarrier(barriers).
void run_linear_compute(const GlProgram& program, uint64_t items, uint64_t items_per_group,
                        unsigned barriers);

}  // namespace ldm
