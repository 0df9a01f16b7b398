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
#include <memory>
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

// How a primary photon's reflected flux rho * Phi1 is split among its N secondaries
// (shaders/passes/indirect/photon_trace.comp): `thesis` weighs each by |cos| * 2 / N, the
// thesis's rho/pi * cos times the 2 pi / N steradians each direction stands for, a quadrature
// that sums to rho * Phi1 only on average (as AO's Eq. 13); `normalized` by
// |cos| / (sum of |cos| over the N directions), exactly rho * Phi1 (as --ao-estimator
// normalized).
enum class PhotonEmission { Thesis, Normalized };
const char* photon_emission_name(PhotonEmission emission);
const std::vector<std::string>& photon_emission_names();
PhotonEmission parse_photon_emission(const std::string& name);  // throws UserError

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
  PhotonEmission emission = PhotonEmission::Thesis;

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
  // Of culled_depth: off the image (or over background), and arriving on the side of the
  // surface the camera does not see; the rest were hidden behind the surface the camera sees.
  uint64_t culled_outside = 0, culled_backside = 0;
  uint64_t capacity = 0;
  uint64_t culled_hidden() const { return culled_depth - culled_outside - culled_backside; }
};

// The flux audit, first half: where the light's flux went in the last trace, summed over the
// light texels (W, mean of the RGB channels). emitted = escaped + culled_outside +
// culled_hidden + culled_backside + culled_footprint + degenerate + stored + overflow (up to
// float rounding); primary * rho is what a perfect split would emit.
struct PhotonFluxTally {
  double primary = 0, emitted = 0, escaped = 0, culled_outside = 0, culled_hidden = 0,
         culled_backside = 0, culled_footprint = 0, degenerate = 0, stored = 0, overflow = 0;
  double reflected = 0;  // rho * Phi1 summed over the primary photons that were split
};

// The flux audit, second half: the stored photons' flux followed into the image (W, mean of
// RGB), from an untimed audit splat of the last trace's photons over the camera G-buffer.
// With the splat's kernel K (unit integral over its footprint's ellipse on the photon's
// tangent plane) each photon's flux Phi is E * A_ellipse; summed over the photons:
//   tangent_all       Phi * K over the tangent plane, where that plane lies over a surface the
//                     camera sees (the orthogonal projection along the photon's normal of
//                     every image pixel's surface patch, within a quad enlarged by
//                     kAuditQuadScale). stored - tangent_all: the kernel's mass over no
//                     visible surface (off the image, over background, hidden), plus the
//                     pixel quadrature's error.
//   tangent_in_quad   the same, over the pixels the splat's quad covers: tangent_all minus
//                     what the quad leaves out where the surface curves away from the plane
//                     (the pixel ray meets the plane outside the quad).
//   uncut             Phi * K(in-plane distance) over those pixels' surface areas (not
//                     projected): uncut - tangent_in_quad is the surface's area beyond its
//                     projection (a gain where it curves).
//   deposited         what the splats put into the image: K including the topological
//                     bias, over the surface areas: the integral of pi L / rho over the image's
//                     surfaces. uncut - deposited: the kernel's mass cut by the topological bias.
// visible_area: the area of the surfaces the image shows (the sum of its pixels' areas).
struct SplatAudit {
  double tangent_all = 0, tangent_in_quad = 0, uncut = 0, deposited = 0;
  double visible_area = 0;
};
// The audit splat's quad, relative to the splat's: large enough to hold the kernel's support
// on a surface curving away from the photon's plane.
constexpr float kAuditQuadScale = 2.0f;

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

// Whether 32-bit floats hold the stored photons' splats where they lie (issue 35). The photon
// buffer holds full floats in the scene's rebased frame (translation never reaches them); what
// a float cannot hold is a footprint too small for its position: the splat's quad is
// x_p +- s Du x / 2 +- s Dv x / 2 and its kernel's argument M (x - x_p), both rounded to the
// float grid at x_p, so a footprint whose half-width spans few float steps there is placed
// and shaped by rounding (under one step its quad collapses to a point). The half-width is
// half the parallelogram's smaller altitude, |s Du x s Dv| / (2 max(|s Du|, |s Dv|)); the
// float step at x is the spacing of floats at max_i |x_i|.
struct PhotonResolution {
  uint64_t photons = 0;     // photons looked at
  uint64_t unresolved = 0;  // of them, footprint half-width under kPhotonMinFootprintSteps steps
  double min_steps = 0;     // the narrowest half-width in float steps (0 when no photons)
};
// Under 16 steps the kernel's argument carries a rounding error above 1/16 of its radius at
// every pixel: the splat's shape and weight are rounding, not the photon's differential.
constexpr double kPhotonMinFootprintSteps = 16.0;
double float_step_at(const glm::vec3& x);
PhotonResolution photon_resolution(const std::vector<StoredPhoton>& photons, float splat_scale);
// The status_detail sentence for unresolved photons; empty when every photon is resolved.
std::string photon_resolution_detail(const PhotonResolution& r);

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
  // Per light texel of the last trace, kTallyEntries entries (photon.glsl's PHOTON_TALLY_*):
  // the primary flux (rgb, w = 1 where a primary photon was emitted), the flux emitted into
  // secondaries (rgb), and that flux by its fate (escaped, culled outside, hidden, backside,
  // by footprint, degenerate, stored, overflow), and rho * Phi1 where the primary was split.
  std::vector<glm::vec4> read_tally() const;
  static constexpr uint32_t kTallyEntries = 11;
  // The tally summed over the texels (mean of RGB).
  PhotonFluxTally flux_tally() const;
  // The audit splat of the last trace's photons (untimed; see SplatAudit). Also the area of
  // every image pixel's surface patch, top row first (0 on background), for tests.
  SplatAudit audit_splat(const GBufferPass& camera, Image* pixel_areas = nullptr) const;
  const GBufferPass& light_gbuffer() const { return light_gbuffer_; }
  glm::mat4 light_view_projection() const { return light_vp_; }

  // Test hook: the trace's camera depth test (shaders/passes/indirect/photon_visibility.glsl)
  // on hits `x2` of photons travelling along `w_o`, with the trace's uniforms (the effective
  // depth_threshold()): per point 0 where the camera sees it, else the culled fate's tally
  // index (3 outside, 4 hidden, 5 backside).
  std::vector<uint32_t> probe_visibility(const GBufferPass& camera, const std::vector<glm::vec3>& x2,
                                         const std::vector<glm::vec3>& w_o) const;

  // The photon buffer and its bookkeeping buffers (allocated; used by the last trace).
  std::vector<BufferMemory> memory() const;
  // How the photon buffer was sized: capacity, its source, the policy's notes.
  std::vector<std::pair<std::string, std::string>> sizing() const;
  uint64_t rebuilds() const { return sizing_counts_.rebuilds; }
  uint64_t reallocations() const { return sizing_counts_.reallocations; }
  // Takes the photon buffer's sizing state of `measured` (the same configuration's), so that
  // this one's first render is sized as `measured`'s next would be: the counting replay's.
  // (The oracle's counting trace, which sized `measured`'s buffer, is not run again.)
  void continue_sizing_from(const PhotonLighting& measured);
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
  // The counting replay's (prepared inside a WorkCountingScope): the splat's fragment counts,
  // blended, and their sum into the work counters; the splat counting with atomics, for
  // photon buffers too large for blended float counts.
  bool counting_ = false;
  GlTexture2D splat_counts_;
  GlProgram splat_count_program_, splat_by_atomics_program_;
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
      composite_program_, audit_program_;
  mutable GlProgram probe_program_;                 // made by the first probe
  mutable GlTexture2D audit_target_, audit_area_;  // made by the first audit
  mutable GlFramebuffer audit_fb_;
  uint64_t generation_ = 0;
};

}  // namespace ldm
