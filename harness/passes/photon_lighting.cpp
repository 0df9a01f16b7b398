#include "harness/passes/photon_lighting.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "harness/gl/bindings.h"
#include "harness/measure/work_counters.h"
#include "harness/passes/ldm_trace_defines.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

// The pass's storage bindings (after kPassBinding0; the materials follow at +4, +5).
constexpr uint32_t kPhotonsBinding = kPassBinding0;
constexpr uint32_t kCountersBinding = kPassBinding0 + 1;
constexpr uint32_t kTallyBinding = kPassBinding0 + 2;
constexpr uint32_t kDrawBinding = kPassBinding0 + 3;
constexpr uint32_t kCounterCount = 10;  // PHOTON_COUNTERS
constexpr uint64_t kPhotonBytes = sizeof(StoredPhoton);
constexpr float kMaxOuterAngleDeg = 89.0f;

ShaderDefines indirect_defines() {
  ShaderDefines d = binding_defines();
  d.set("INDIRECT_PHOTONS_BINDING", kPhotonsBinding);
  d.set("INDIRECT_COUNTERS_BINDING", kCountersBinding);
  d.set("INDIRECT_TALLY_BINDING", kTallyBinding);
  d.set("INDIRECT_DRAW_BINDING", kDrawBinding);
  d.set("INDIRECT_MATERIALS_BINDING", kMaterialsBinding);
  d.set("INDIRECT_ALBEDO_BINDING", kMaterialAlbedoBinding);
  return d;
}

void set_spot(const GlProgram& program, const SpotLight& light) {
  const glm::vec3 d = glm::normalize(light.direction);
  program.use();
  program.set("spot_position", light.position.x, light.position.y, light.position.z);
  program.set("spot_direction", d.x, d.y, d.z);
  program.set("spot_intensity", light.intensity.x, light.intensity.y, light.intensity.z);
  program.set("spot_cos_inner", float(std::cos(glm::radians(double(light.inner_angle_deg)))));
  program.set("spot_cos_outer", float(std::cos(glm::radians(double(light.outer_angle_deg)))));
}

// Splats add up: the timed splat and the untimed flux audit draw into their targets with
// the same state (no depth test, no culling, additive blending).
void bind_additive_target(const GlFramebuffer& fb, int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
}

void draw_fullscreen(const GlFramebuffer& fb, int width, int height, const GlVertexArray& vao) {
  glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace

const std::vector<std::string>& photon_emission_names() {
  static const std::vector<std::string> names = {"thesis", "normalized"};
  return names;
}

const char* photon_emission_name(PhotonEmission emission) {
  return emission == PhotonEmission::Normalized ? "normalized" : "thesis";
}

PhotonEmission parse_photon_emission(const std::string& name) {
  if (name == "thesis") return PhotonEmission::Thesis;
  if (name == "normalized") return PhotonEmission::Normalized;
  throw UserError("indirect pass: unknown emission '" + name + "' (expected thesis or normalized)");
}

Camera light_camera(const SpotLight& light) {
  if (!(light.outer_angle_deg > 0.0f && light.outer_angle_deg < kMaxOuterAngleDeg))
    throw UserError("indirect pass: the spot light's outer angle must lie in (0, 89) degrees "
                    "for its image plane (got " + std::to_string(light.outer_angle_deg) + ")");
  Camera c;
  c.eye = light.position;
  const glm::vec3 d = glm::normalize(light.direction);
  c.target = light.position + d;
  // Any up that is not along the axis: the roll of the light's image is irrelevant.
  c.up = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  c.fov_y_deg = 2.0f * light.outer_angle_deg;
  return c;
}

PhotonLighting::PhotonLighting(const LdmStructure& structure, const BuildInputs& in,
                               const Scene& scene, int width, int height,
                               const IndirectSettings& settings)
    : structure_(structure),
      views_(in.views),
      gpu_scene_(in.scene),
      scene_(scene),
      policy_(in.sizing.policy),
      strategy_(in.sizing.strategy()),
      width_(width),
      height_(height),
      settings_(settings),
      depth_threshold_(settings.depth_threshold_for(in.views.views())),
      light_camera_(light_camera(scene.light)),
      light_gbuffer_(int(settings.light_resolution), int(settings.light_resolution), true),
      indirect_(GL_RGBA32F, width, height),
      direct_(GL_RGBA32F, width, height),
      sum_(GL_RGBA32F, width, height),
      // The trace's other loops: the counters zeroed and flushed, PHOTON_COUNTERS each, the
      // tally's fates zeroed and written, and the normalized emission's sum over the views.
      steps_(uint32_t(in.views.views().size()), trace_walk_sites(settings.trace == AoTrace::Plane),
             2 * kCounterCount + 2 * kTallyEntries +
                 (settings.emission == PhotonEmission::Normalized
                      ? uint32_t(in.views.views().size())
                      : 0u)) {
  if (!in.scene.attributes().materials || !in.scene.attributes().normals)
    throw GpuError("indirect pass: the scene must be uploaded with normals and materials");
  const int r = int(settings.light_resolution);
  light_vp_ = camera_view_projection(light_camera_, r, r, scene.bounding_sphere());
  camera_vp_ = camera_view_projection(scene.camera, width, height, scene.bounding_sphere());
  indirect_fb_.attach_color(0, indirect_);
  // The counting replay's splat also blends its fragment counts into a second target
  // (photon_splat.frag, splat_fragment_count.comp); a measured splat draws into one.
  counting_ = WorkCountingScope::active();
  if (counting_) {
    splat_counts_ = GlTexture2D(GL_RG32F, width, height);
    indirect_fb_.attach_color(1, splat_counts_);
    const GLenum targets[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(indirect_fb_.id(), 2, targets);
  }
  indirect_fb_.check_complete("indirect target");
  direct_fb_.attach_color(0, direct_);
  direct_fb_.check_complete("direct target");
  sum_fb_.attach_color(0, sum_);
  sum_fb_.check_complete("sum target");
  counters_ = GlBuffer("photon_counters", kCounterCount * sizeof(uint32_t));
  tally_ = GlBuffer("photon_tally", uint64_t(r) * r * kTallyEntries * sizeof(glm::vec4));
  draw_command_ = GlBuffer("photon_draw_command", 4 * sizeof(uint32_t));

  // The photon buffer's first size, by policy (an explicit capacity wins).
  if (settings.photon_capacity) {
    capacity_fixed_ = true;
    capacity_source_ = "parameter";
    allocate_photons(*settings.photon_capacity);
  } else if (strategy_.fixed_by_budget()) {
    const double mib = settings.photon_budget_mib.value_or(double(in.sizing.budget_bytes) /
                                                           double(1u << 20));
    budget_bytes_ = uint64_t(mib * double(1u << 20));
    capacity_fixed_ = true;
    capacity_source_ = "budget";
    allocate_photons(budget_bytes_ / kPhotonBytes);
  } else if (strategy_.grows_from_counters()) {
    capacity_source_ = "previous_frame";
    allocate_photons(uint64_t(r) * r);  // the first guess: one photon per light texel
  } else {
    capacity_source_ = sizing_policy_name(policy_);
    allocate_photons(0);  // oracle and census size it from a counting trace
  }
  compile();
}

void PhotonLighting::continue_sizing_from(const PhotonLighting& measured) {
  sizing_state_ = measured.sizing_state_;
  if (measured.sized_ && !capacity_fixed_) {
    allocate_photons(measured.capacity_);
    sized_ = true;
  }
}

void PhotonLighting::allocate_photons(uint64_t capacity) {
  const uint64_t bytes = checked_storage_block("indirect", "photons",
                                               std::max<uint64_t>(capacity, 1) * kPhotonBytes);
  photons_ = GlBuffer("photons", bytes);
  capacity_ = capacity;
}

void PhotonLighting::compile() {
  generation_ = structure_.storage_generation();
  ShaderDefines defines = indirect_defines();
  add_ldm_trace_defines(defines, structure_, views_.views().size(), settings_.trace);
  trace_program_ = build_program(
      {{GL_COMPUTE_SHADER, "passes/indirect/photon_trace.comp", structure_.query_sources()}},
      defines);
  set_spot(trace_program_, scene_.light);
  const CameraFrame light = camera_frame(light_camera_, 1, 1);
  trace_program_.set("light_resolution", int(settings_.light_resolution));
  trace_program_.set("light_forward", light.forward.x, light.forward.y, light.forward.z);
  trace_program_.set("light_right", light.right.x, light.right.y, light.right.z);
  trace_program_.set("light_up", light.up.x, light.up.y, light.up.z);
  trace_program_.set("light_tan_half", light.tan_half_fov_y);
  trace_program_.set_mat4("camera_view_projection", &camera_vp_[0][0]);
  const glm::vec3 eye = scene_.camera.eye;
  trace_program_.set("camera_eye", eye.x, eye.y, eye.z);
  trace_program_.set("depth_threshold", depth_threshold_);
  trace_program_.set("footprint_threshold", settings_.footprint_threshold);
  trace_program_.set("splat_scale", settings_.splat_scale);
  trace_program_.set("normal_offset_pixels", settings_.normal_offset_pixels);
  trace_program_.set("emission_normalized", settings_.emission == PhotonEmission::Normalized ? 1 : 0);

  if (draw_count_program_) return;  // the rest does not read the structure
  const ShaderDefines plain = indirect_defines();
  draw_count_program_ = build_program(
      {{GL_COMPUTE_SHADER, "passes/indirect/splat_draw_count.comp", {}}}, plain);
  // The splat and its audit: the same vertex and geometry stages and uniforms, each its own
  // fragment stage.
  const auto build_splat = [&](const char* fragment, const ShaderDefines& defines) {
    GlProgram program = build_program({{GL_VERTEX_SHADER, "passes/indirect/photon_splat.vert", {}},
                                       {GL_GEOMETRY_SHADER, "passes/indirect/photon_splat.geom", {}},
                                       {GL_FRAGMENT_SHADER, fragment, {}}},
                                      defines);
    program.use();
    program.set("splat_scale", settings_.splat_scale);
    program.set("topological_bias", settings_.a());
    program.set_mat4("camera_view_projection", &camera_vp_[0][0]);
    return program;
  };
  splat_program_ = build_splat("passes/indirect/photon_splat.frag", plain);
  if (counting_) {
    ShaderDefines atomics = plain;
    atomics.set("SPLAT_COUNT_BY_ATOMICS", 1);
    splat_by_atomics_program_ = build_splat("passes/indirect/photon_splat.frag", atomics);
    splat_count_program_ = build_program(
        {{GL_COMPUTE_SHADER, "passes/indirect/splat_fragment_count.comp", {}}}, plain);
    splat_count_program_.set("width", width_);
    splat_count_program_.set("height", height_);
  }
  direct_program_ = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                                   {GL_FRAGMENT_SHADER, "passes/indirect/direct_light.frag", {}}},
                                  plain);
  set_spot(direct_program_, scene_.light);
  direct_program_.set_mat4("light_view_projection", &light_vp_[0][0]);
  direct_program_.set("light_texel_angle",
                      2.0f * light.tan_half_fov_y / float(settings_.light_resolution));
  composite_program_ = build_program({{GL_VERTEX_SHADER, "passes/fullscreen.vert", {}},
                                      {GL_FRAGMENT_SHADER, "passes/indirect/composite.frag", {}}},
                                     plain);
  ShaderDefines audit = indirect_defines();
  audit.set("PHOTON_SPLAT_AUDIT", 1);
  audit.set("PHOTON_SPLAT_QUAD_SCALE", glsl_float(kAuditQuadScale));
  audit_program_ = build_splat("passes/indirect/photon_splat_audit.frag", audit);
  audit_program_.set("camera_eye", eye.x, eye.y, eye.z);
}

void PhotonLighting::trace(const GBufferPass& camera, uint64_t capacity) {
  counters_.clear_to_zero();
  trace_program_.use();
  trace_program_.set("photon_capacity", unsigned(capacity));
  glBindTextureUnit(0, light_gbuffer_.positions().id());
  glBindTextureUnit(1, light_gbuffer_.normals().id());
  glBindTextureUnit(2, light_gbuffer_.albedo().id());
  glBindTextureUnit(3, camera.positions().id());
  glBindTextureUnit(4, camera.normals().id());
  photons_.bind_storage(kPhotonsBinding);
  counters_.bind_storage(kCountersBinding);
  tally_.bind_storage(kTallyBinding);
  steps_.bind();
  structure_.bind_for_query();
  views_.bind();
  const GLuint groups = (settings_.light_resolution + 7) / 8;
  glDispatchCompute(groups, groups, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_COMMAND_BARRIER_BIT);
  check_gl("photon tracing");
}

void PhotonLighting::read_counts() {
  uint32_t c[kCounterCount] = {};
  counters_.download(c, sizeof c);
  PhotonCounts& k = counts_;
  k.appended = c[0];
  k.primary = c[1];
  k.primary_degenerate = c[2];
  k.emitted = c[3];
  k.escaped = c[4];
  k.culled_depth = c[5];
  k.culled_footprint = c[6];
  k.degenerate = c[7];
  k.culled_outside = c[8];
  k.culled_backside = c[9];
  k.capacity = capacity_;
  k.stored = std::min<uint64_t>(k.appended, capacity_);
  k.overflow = k.appended - k.stored;
}

void PhotonLighting::splat(const GBufferPass& camera) {
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(indirect_fb_.id(), GL_COLOR, 0, zero);
  // A pixel gets at most one fragment per splat: up to 2^24 splats, its blended count is an
  // exact float integer; beyond, the counting replay counts with one atomic per fragment.
  const bool count_by_blending = counting_ && capacity_ <= (uint64_t(1) << 24);
  if (count_by_blending) glClearNamedFramebufferfv(indirect_fb_.id(), GL_COLOR, 1, zero);
  draw_count_program_.use();
  draw_count_program_.set("photon_capacity", unsigned(capacity_));
  counters_.bind_storage(kCountersBinding);
  draw_command_.bind_storage(kDrawBinding);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  bind_additive_target(indirect_fb_, width_, height_);
  photons_.bind_storage(kPhotonsBinding);
  glBindTextureUnit(0, camera.positions().id());
  glBindTextureUnit(1, camera.albedo().id());
  (counting_ && !count_by_blending ? splat_by_atomics_program_ : splat_program_).use();
  glBindVertexArray(empty_vao_.id());
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, draw_command_.id());
  glDrawArraysIndirect(GL_POINTS, nullptr);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (count_by_blending) {  // the blended counts, summed into the splatting sub-pass's counters
    const UncountedGpuWork counting_own_work;  // not the splat's: out of the driver's statistics
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    splat_count_program_.use();
    glBindTextureUnit(0, splat_counts_.id());
    glDispatchCompute(GLuint((width_ + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  check_gl("photon splatting");
}

void PhotonLighting::direct(const GBufferPass& camera) {
  glBindTextureUnit(0, camera.positions().id());
  glBindTextureUnit(1, camera.normals().id());
  glBindTextureUnit(2, camera.albedo().id());
  glBindTextureUnit(3, light_gbuffer_.positions().id());
  direct_program_.use();
  draw_fullscreen(direct_fb_, width_, height_, empty_vao_);
}

void PhotonLighting::composite() {
  glBindTextureUnit(0, direct_.id());
  glBindTextureUnit(1, indirect_.id());
  composite_program_.use();
  draw_fullscreen(sum_fb_, width_, height_, empty_vao_);
}

// The photon buffer as a sizing strategy sees it (ldm_impls/common/sizing_strategy.h).
class PhotonLighting::PhotonWork final : public SizedWork {
 public:
  PhotonWork(PhotonLighting& lighting, const GBufferPass& camera) : l_(lighting), camera_(camera) {}
  bool fits(const SizingNeeds& needs) const override {
    return l_.capacity_fixed_ || needs.fragments <= l_.capacity_;
  }
  void resize(const SizingNeeds& needs) override {
    l_.allocate_photons(needs.fragments);
    l_.sized_ = true;
  }
  void run(GpuTimer* timer) override {
    ScopedSubpass timed(timer, "photon_tracing");
    l_.trace(camera_, l_.capacity_);
  }
  SizingNeeds needed() override {
    l_.read_counts();
    return photon_needs();
  }
  bool has_census() const override { return true; }
  SizingNeeds census() override {
    l_.trace(camera_, 0);  // counts only: nothing stored
    l_.read_counts();
    return photon_needs();
  }
  bool sized() const override { return l_.capacity_fixed_ || l_.sized_; }

 private:
  SizingNeeds photon_needs() const {
    SizingNeeds needs;
    needs.fragments = l_.counts_.appended;
    needs.lost = l_.counts_.overflow > 0;
    return needs;
  }
  PhotonLighting& l_;
  const GBufferPass& camera_;
};

void PhotonLighting::render(const GBufferPass& camera, GpuTimer* timer) {
  if (structure_.storage_generation() != generation_) compile();  // untimed, as AoPass
  light_gbuffer_.render_view(gpu_scene_, light_vp_, scene_.light.position, timer,
                             "light_gbuffer");
  // The photon buffer under the structures' sizing strategy: the trace is its run, a
  // counting trace (capacity 0) its census, the counters its needs.
  PhotonWork work(*this, camera);
  strategy_.frame(work, timer, "photon_", sizing_state_, sizing_counts_);
  {
    ScopedSubpass timed(timer, "splatting");
    splat(camera);
  }
  {
    ScopedSubpass timed(timer, "direct");
    direct(camera);
  }
  {
    ScopedSubpass timed(timer, "composite");
    composite();
  }
  read_counts();  // untimed: for the record
}

void PhotonLighting::splat_photons(const GBufferPass& camera,
                                   const std::vector<StoredPhoton>& photons) {
  if (photons.size() > capacity_) allocate_photons(photons.size());
  if (!photons.empty()) photons_.upload(photons.data(), photons.size() * kPhotonBytes);
  uint32_t counters[kCounterCount] = {uint32_t(photons.size())};
  counters_.upload(counters, sizeof counters);
  splat(camera);
  read_counts();
}

Image PhotonLighting::read_indirect() const {
  return image_from_gl_rows(indirect_.read_floats(3), width_, height_, 3);
}
Image PhotonLighting::read_direct() const {
  return image_from_gl_rows(direct_.read_floats(3), width_, height_, 3);
}
Image PhotonLighting::read_sum() const {
  return image_from_gl_rows(sum_.read_floats(3), width_, height_, 3);
}

double float_step_at(const glm::vec3& x) {
  const float m = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  return double(std::nextafter(m, INFINITY)) - double(m);
}

PhotonResolution photon_resolution(const std::vector<StoredPhoton>& photons, float splat_scale) {
  PhotonResolution r;
  r.photons = photons.size();
  bool first = true;
  for (const auto& p : photons) {
    const glm::dvec3 du = glm::dvec3(p.du_x) * double(splat_scale);
    const glm::dvec3 dv = glm::dvec3(p.dv_x) * double(splat_scale);
    const double longest = std::max(glm::length(du), glm::length(dv));
    const double half_width = longest > 0.0 ? 0.5 * glm::length(glm::cross(du, dv)) / longest : 0.0;
    const double steps = half_width / float_step_at(p.position);
    if (!(steps >= kPhotonMinFootprintSteps)) ++r.unresolved;  // NaN counts as unresolved
    if (first || !(steps >= r.min_steps)) r.min_steps = steps;
    first = false;
  }
  return r;
}

std::string photon_resolution_detail(const PhotonResolution& r) {
  if (r.unresolved == 0) return {};
  char text[400];
  std::snprintf(text, sizeof text,
                "%llu of %llu stored photons have a splat footprint narrower than %g float steps "
                "at their position (the narrowest %.3g): floats cannot place or shape their "
                "kernels, the scene is too large for the photons' detail (photons_unresolved; "
                "a smaller R_light, a wider cone or a larger s widens them)",
                static_cast<unsigned long long>(r.unresolved),
                static_cast<unsigned long long>(r.photons), kPhotonMinFootprintSteps, r.min_steps);
  return text;
}

std::vector<StoredPhoton> PhotonLighting::read_photons() const {
  std::vector<StoredPhoton> out(counts_.stored);
  if (!out.empty()) photons_.download(out.data(), out.size() * kPhotonBytes);
  return out;
}

std::vector<glm::vec4> PhotonLighting::read_tally() const { return tally_.download_all<glm::vec4>(); }

PhotonFluxTally PhotonLighting::flux_tally() const {
  const std::vector<glm::vec4> tally = read_tally();
  double sums[kTallyEntries] = {};
  for (size_t i = 0; i + kTallyEntries <= tally.size(); i += kTallyEntries)
    for (uint32_t k = 0; k < kTallyEntries; ++k)
      sums[k] += (double(tally[i + k].x) + tally[i + k].y + tally[i + k].z) / 3.0;
  PhotonFluxTally t;
  t.primary = sums[0];
  t.emitted = sums[1];
  t.escaped = sums[2];
  t.culled_outside = sums[3];
  t.culled_hidden = sums[4];
  t.culled_backside = sums[5];
  t.culled_footprint = sums[6];
  t.degenerate = sums[7];
  t.stored = sums[8];
  t.overflow = sums[9];
  t.reflected = sums[10];
  return t;
}

std::vector<uint32_t> PhotonLighting::probe_visibility(const GBufferPass& camera,
                                                       const std::vector<glm::vec3>& x2,
                                                       const std::vector<glm::vec3>& w_o) const {
  if (x2.size() != w_o.size()) throw std::invalid_argument("probe_visibility: sizes differ");
  if (x2.empty()) return {};
  if (!probe_program_) {
    probe_program_ = build_program(
        {{GL_COMPUTE_SHADER, "passes/indirect/photon_visibility_probe.comp", {}}}, indirect_defines());
    probe_program_.use();
    probe_program_.set_mat4("camera_view_projection", &camera_vp_[0][0]);
    const glm::vec3 eye = scene_.camera.eye;
    probe_program_.set("camera_eye", eye.x, eye.y, eye.z);
    probe_program_.set("depth_threshold", depth_threshold_);
  }
  std::vector<glm::vec4> data;
  for (size_t i = 0; i < x2.size(); ++i) {
    data.emplace_back(x2[i], 0.0f);
    data.emplace_back(w_o[i], 0.0f);
  }
  GlBuffer buffer("visibility_probe", data.size() * sizeof(glm::vec4));
  buffer.upload(data.data(), data.size() * sizeof(glm::vec4));
  buffer.bind_storage(kPhotonsBinding);
  glBindTextureUnit(3, camera.positions().id());
  glBindTextureUnit(4, camera.normals().id());
  probe_program_.use();
  glDispatchCompute(GLuint(x2.size()), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  check_gl("visibility probe");
  const auto out = buffer.download_all<glm::vec4>();
  std::vector<uint32_t> verdicts;
  for (size_t i = 0; i < x2.size(); ++i) {
    uint32_t v;
    std::memcpy(&v, &out[2 * i].w, sizeof v);
    verdicts.push_back(v);
  }
  return verdicts;
}

SplatAudit PhotonLighting::audit_splat(const GBufferPass& camera, Image* pixel_areas) const {
  // Each pixel's surface patch: its solid angle (pixel on the image plane at distance 1 times
  // cos^3 of its angle off the axis) times distance^2 over |cos| of the surface's tilt.
  const CameraFrame frame = camera_frame(scene_.camera, width_, height_);
  const std::vector<float> positions = camera.positions().read_floats(4);
  const std::vector<float> normals = camera.normals().read_floats(4);
  const double pixel_side_x = 2.0 * frame.tan_half_fov_y * frame.aspect / width_;
  const double pixel_side_y = 2.0 * frame.tan_half_fov_y / height_;
  std::vector<float> area(size_t(width_) * height_, 0.0f);
  SplatAudit audit;
  for (size_t i = 0; i < area.size(); ++i) {
    if (positions[4 * i + 3] == 0.0f) continue;
    const glm::dvec3 x(positions[4 * i], positions[4 * i + 1], positions[4 * i + 2]);
    const glm::dvec3 n(normals[4 * i], normals[4 * i + 1], normals[4 * i + 2]);
    const glm::dvec3 to = x - glm::dvec3(frame.eye);
    const double d = glm::length(to);
    if (!(d > 0.0)) continue;
    const double cos_axis = glm::dot(to, glm::dvec3(frame.forward)) / d;
    const double cos_surface = std::abs(glm::dot(to, n)) / d;
    if (!(cos_axis > 0.0) || !(cos_surface > 0.0)) continue;
    const double a = pixel_side_x * pixel_side_y * cos_axis * cos_axis * cos_axis * d * d / cos_surface;
    area[i] = float(a);
    audit.visible_area += a;
  }
  if (pixel_areas) *pixel_areas = image_from_gl_rows(area, width_, height_, 1);
  if (!audit_target_.id()) {
    audit_target_ = GlTexture2D(GL_RGBA32F, width_, height_);  // lazily, once
    audit_area_ = GlTexture2D(GL_R32F, width_, height_);
    audit_fb_.attach_color(0, audit_target_);
    audit_fb_.check_complete("flux audit target");
  }
  glTextureSubImage2D(audit_area_.id(), 0, 0, 0, width_, height_, GL_RED, GL_FLOAT, area.data());
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(audit_fb_.id(), GL_COLOR, 0, zero);
  bind_additive_target(audit_fb_, width_, height_);
  photons_.bind_storage(kPhotonsBinding);
  glBindTextureUnit(0, camera.positions().id());
  glBindTextureUnit(2, camera.normals().id());
  glBindTextureUnit(3, audit_area_.id());
  audit_program_.use();
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_POINTS, 0, GLsizei(counts_.stored));
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("flux audit splat");
  const std::vector<float> sums = audit_target_.read_floats(4);
  for (size_t i = 0; i + 3 < sums.size(); i += 4) {
    audit.deposited += sums[i];
    audit.uncut += sums[i + 1];
    audit.tangent_in_quad += sums[i + 2];
    audit.tangent_all += sums[i + 3];
  }
  return audit;
}

std::vector<BufferMemory> PhotonLighting::memory() const {
  std::vector<BufferMemory> out = {{"photons", photons_.bytes(), counts_.stored * kPhotonBytes},
                                   {"photon_counters", counters_.bytes(), counters_.bytes()},
                                   {"photon_tally", tally_.bytes(), tally_.bytes()},
                                   {"photon_draw_command", draw_command_.bytes(), draw_command_.bytes()}};
  return out;
}

std::vector<std::pair<std::string, std::string>> PhotonLighting::sizing() const {
  std::vector<std::pair<std::string, std::string>> out = {
      {"photon_capacity", std::to_string(capacity_)},
      {"photon_capacity_source", capacity_source_}};
  if (budget_bytes_) out.emplace_back("photon_budget_bytes", std::to_string(budget_bytes_));
  if (strategy_.grows_from_counters() && !capacity_fixed_)
    out.emplace_back("photon_initial", "guess: one photon per light texel");
  if (strategy_.sized_by_oracle() && !capacity_fixed_)
    out.emplace_back("photon_note", "untimed counting trace before the first frame");
  return out;
}

}  // namespace ldm
