#pragma once
// The GPU half of the indirect-lighting pass (thesis §5.3-5.4) over any structure, through
// its query API: the light's G-buffer, photon tracing through the LDM into a photon buffer,
// splatting, shadow-mapped direct light and their sum. The camera G-buffer (with albedo) is
// rendered by the caller (IndirectLighting) and passed in.
//
// The photon buffer is sized by the run's sizing policy, like a structure's storage
// (docs/reference/structures.md): oracle (an untimed counting trace before the first frame),
// census (a timed counting trace every frame, `photon_census`), previous_frame (the last
// trace's append counter, `photon_readback`; a trace that overflowed is resized and run
// again, `photon_rebuild`) or budget (what the budget holds; the rest is counted as
// overflow). A `photon_capacity` parameter fixes it under every policy.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/gl/gl_objects.h"
#include "harness/image/image.h"
#include "harness/measure/gpu_timer.h"
#include "harness/passes/gbuffer_pass.h"
#include "harness/passes/trace_steps.h"
#include "harness/scene/scene.h"
#include "ldm_impls/common/sizing_strategy.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

struct IndirectSettings {
  uint32_t light_resolution = 64;       // R_light: the light's G-buffer is R_light^2
  float splat_scale = 4.0f;             // s: footprints scaled by s (1: one light texel's beam)
  std::optional<float> topological_bias;  // a; unset: a = s (the thesis's choice)
  float footprint_threshold = INFINITY;  // T_foot: max norm of s * D x, scene units (inf: off)
  // scene units; unset: kDefaultDepthThresholdPixels LDM pixels (an LDM hit lies at its
  // pixel's depth, off the true surface by up to about a pixel times the slope)
  std::optional<float> depth_threshold;
  AoTrace trace = kDefaultAoTrace;       // the LDM trace variant (as the AO pass's)
  float normal_offset_pixels = 0.5f;     // the §4.4.2 offset at the traced point x1
  std::optional<uint64_t> photon_capacity;  // fixes the photon buffer (photons)
  std::optional<double> photon_budget_mib;  // budget policy: the photon buffer's own budget

  float a() const { return topological_bias.value_or(splat_scale); }
  float depth_threshold_for(const ViewSet& views) const {
    return depth_threshold.value_or(kDefaultDepthThresholdPixels *
                                    (views.views.empty() ? 0.0f : views.views[0].pixel_size()));
  }
  static constexpr float kDefaultDepthThresholdPixels = 3.0f;
};

// The photon tracing pass's counts (shaders/passes/indirect/photon.glsl).
struct PhotonCounts {
  uint64_t primary = 0, primary_degenerate = 0, emitted = 0, escaped = 0, culled_depth = 0,
           culled_footprint = 0, degenerate = 0, appended = 0, stored = 0, overflow = 0;
  uint64_t capacity = 0;
};

// One stored photon as the tests read it back (std430 layout of `Photon`).
struct StoredPhoton {
  glm::vec3 position;
  uint32_t light_texel;
  glm::vec3 normal;
  uint32_t direction;  // view * 2 + (along +forward ? 1 : 0)
  glm::vec3 du_x;
  float pad0;
  glm::vec3 dv_x;
  float pad1;
  glm::vec3 flux;
  float pad2;
};
static_assert(sizeof(StoredPhoton) == 80, "std430 Photon is five vec4");

// The light as a pinhole camera: fov 2 * outer angle, square R_light image; its inscribed
// circle is the spot's cone.
Camera light_camera(const SpotLight& light);

class PhotonLighting {
 public:
  // `scene` in the centred frame the geometry was uploaded in; `gpu_scene` with normals and
  // materials. Throws UserError for a spot the light camera cannot hold (outer angle >= 89).
  PhotonLighting(const LdmStructure& structure, const BuildInputs& in, const Scene& scene,
                 int width, int height, const IndirectSettings& settings);

  // One frame after the camera G-buffer (with albedo): light G-buffer, tracing (under the
  // sizing policy), splatting, direct light, composite.
  void render(const GBufferPass& camera, GpuTimer* timer);

  // Splats exactly `photons` (in place of a trace's) into the indirect image: the splatting
  // stage alone, for tests of the kernel and footprint.
  void splat_photons(const GBufferPass& camera, const std::vector<StoredPhoton>& photons);

  Image read_indirect() const;  // rgb
  Image read_direct() const;
  Image read_sum() const;
  PhotonCounts counts() const { return counts_; }
  // Every photon the last trace stored (tests; a read-back).
  std::vector<StoredPhoton> read_photons() const;
  // Per light texel of the last trace: the primary flux (rgb, w = 1 where a primary photon
  // was emitted) and the flux emitted into secondaries (rgb).
  std::vector<glm::vec4> read_tally() const;
  const GBufferPass& light_gbuffer() const { return light_gbuffer_; }
  glm::mat4 light_view_projection() const { return light_vp_; }

  // The photon buffer and its bookkeeping buffers (allocated; used by the last trace).
  std::vector<BufferMemory> memory() const;
  // How the photon buffer was sized: capacity, its source, the policy's notes.
  std::vector<std::pair<std::string, std::string>> sizing() const;
  uint64_t rebuilds() const { return sizing_counts_.rebuilds; }
  uint64_t reallocations() const { return sizing_counts_.reallocations; }
  float depth_threshold() const { return depth_threshold_; }  // the effective one
  // The photon trace's loop iterations over every trace so far (harness/passes/trace_steps.h).
  TraceStepCounts trace_steps() const { return steps_.read(); }

 private:
  void compile();
  void allocate_photons(uint64_t capacity);
  // One trace; capacity 0 only counts. Leaves the counts in counts_ (a read-back).
  void trace(const GBufferPass& camera, uint64_t capacity);
  void read_counts();
  void splat(const GBufferPass& camera);
  void direct(const GBufferPass& camera);
  void composite();

  const LdmStructure& structure_;
  const GpuViewSet& views_;
  const GpuScene& gpu_scene_;
  const Scene& scene_;
  class PhotonWork;
  SizingPolicy policy_;
  const SizingStrategy& strategy_;
  uint64_t budget_bytes_ = 0;
  int width_, height_;
  IndirectSettings settings_;
  float depth_threshold_;
  Camera light_camera_;
  glm::mat4 light_vp_{1.0f}, camera_vp_{1.0f};
  GBufferPass light_gbuffer_;
  GlTexture2D indirect_, direct_, sum_;
  GlFramebuffer indirect_fb_, direct_fb_, sum_fb_;
  GlVertexArray empty_vao_;
  GlBuffer photons_, counters_, tally_, draw_command_;
  uint64_t capacity_ = 0;
  bool capacity_fixed_ = false;  // by photon_capacity or the budget
  std::string capacity_source_;
  bool sized_ = false;  // oracle: the untimed counting trace ran
  SizingState sizing_state_;
  SizingCounts sizing_counts_;
  PhotonCounts counts_;
  TraceStepCounter steps_;
  GlProgram trace_program_, draw_count_program_, splat_program_, direct_program_,
      composite_program_;
  uint64_t generation_ = 0;
};

}  // namespace ldm
