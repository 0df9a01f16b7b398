#include "harness/passes/rtao_gpu.h"

#include <chrono>
#include <cstring>

#include "harness/gl/bindings.h"
#include "harness/gl/shader_program.h"
#include "harness/metrics/ao_range.h"
#include "harness/passes/ao_parameters.h"
#include "harness/passes/rtao.h"
#include "harness/passes/trace_steps.h"
#include "harness/reference/ao_reference.h"
#include "harness/reference/pcg32.h"
#include "harness/reference/reference_settings.h"
#include "harness/reference/surface_point.h"
#include "harness/scene/camera.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

constexpr uint64_t kRtaoGpuDefaultSeed = 0x52544147u;  // "RTAG"
constexpr int kGroupSize = 8;                   // the shader's local_size_x and _y

constexpr uint32_t kNodesBinding = kPassBinding0;
constexpr uint32_t kTrianglesBinding = kPassBinding0 + 1;
constexpr uint32_t kSlotsBinding = kPassBinding0 + 2;
constexpr uint32_t kCountsBinding = kPassBinding0 + 3;
constexpr uint32_t kSceneNormalsBinding = kPassBinding0 + 4;
constexpr uint32_t kSceneIndicesBinding = kPassBinding0 + 5;

const GlBuffer& scene_buffer(const GpuScene& scene, const std::string& name) {
  for (const GlBuffer* b : scene.buffers())
    if (b->name() == name) return *b;
  throw GpuError("GPU RTAO: the scene's buffer '" + name + "' was not uploaded");
}

// The counting replay's words (bvh_traversal.glsl's RtaoGpuCounts) of `pixels` pixels, `rays`
// rays each where `covered` (a pixel's count of 0 nodes means background too).
RayWork ray_work(const std::vector<uint32_t>& words, const std::vector<bool>& covered,
                 uint64_t rays_per_pixel) {
  RayWork w;
  w.nodes_max = words[0];
  w.triangles_max = words[1];
  w.steps_max = words[2];
  uint64_t nodes = 0, triangles = 0;
  for (size_t p = 0; p < covered.size(); ++p) {
    if (!covered[p]) continue;
    w.rays += rays_per_pixel;
    nodes += words[4 + 2 * p];
    triangles += words[4 + 2 * p + 1];
  }
  w.nodes_mean = w.rays ? double(nodes) / double(w.rays) : 0.0;
  w.triangles_mean = w.rays ? double(triangles) / double(w.rays) : 0.0;
  return w;
}

std::string loop_problem(const char* what, uint64_t steps, uint32_t limit, const std::string& fix) {
  return std::string("the GPU ray tracer's ") + what + " may have been cut short: one shader "
         "invocation looped " + std::to_string(steps) + " times (BVH nodes and triangles of its "
         "rays), and this device ends every loop of an invocation silently after " +
         std::to_string(limit) + " iterations in all (llvmpipe); " + fix;
}

void set_uvec2(const GlProgram& program, const char* name, uint64_t value) {
  glProgramUniform2ui(program.id(), program.uniform(name), uint32_t(value), uint32_t(value >> 32));
}

// The BVH traversal's defines, shared by the AO and the primary-ray shaders: the stack
// size, counting or not, and the BVH's and the counts' bindings.
ShaderDefines traversal_defines(uint32_t bvh_depth, bool counting) {
  ShaderDefines defines = binding_defines();
  defines.set("RTAO_GPU_STACK", std::max<uint32_t>(bvh_depth, 1));
  defines.set("RTAO_GPU_COUNT", counting ? 1 : 0);
  defines.set("RTAO_GPU_NODES_BINDING", kNodesBinding);
  defines.set("RTAO_GPU_TRIANGLES_BINDING", kTrianglesBinding);
  defines.set("RTAO_GPU_SLOTS_BINDING", kSlotsBinding);
  defines.set("RTAO_GPU_COUNTS_BINDING", kCountsBinding);
  return defines;
}

}  // namespace

RtaoGpu::RtaoGpu(StructureParams& params) : AoPassBase(params) {
  spp_ = uint32_t(params.get_uint("spp"));
  seed_ = params.get_uint("seed");
  trace_primary_ = params.get_choice("primary") == "trace";
}

// Each parameter in one designated initializer (the fields in AxisSpec's order), as
// harness/scene/ao_axes.cpp declares the AO axes; the fields left out keep their defaults.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
std::vector<AxisSpec> RtaoGpu::parameters() {
  return {{.key = "spp", .kind = AxisKind::UInt, .min = 1, .max = 65536, .default_value = "1",
           .unit = "samples per pixel", .description = "rays per pixel k (cosine-weighted, traced on the GPU)",
           .column = "rtao_gpu_spp"},
          {.key = "seed", .kind = AxisKind::UInt, .min = 0, .max = double(uint64_t(1) << 53),  // exact in JSON
           .default_value = std::to_string(kRtaoGpuDefaultSeed),
           .description = "seed of the sample stream (the CPU RTAO's numbers for the same seed)",
           .column = "rtao_gpu_seed"},
          {.key = "primary", .kind = AxisKind::Choice, .choices = {"trace", "raster"}, .default_value = "trace",
           .description = "where the pixels' points come from: traced primary rays (the reference's) or the rasterised G-buffer",
           .column = "rtao_gpu_primary"},
          ao_pass_parameter(AoAxis::DMax), ao_pass_parameter(AoAxis::Visibility)};
}
#pragma GCC diagnostic pop

// Its own columns after the AO settings': a data table, alike in form only to the other
// passes'.
std::vector<ColumnSpec> RtaoGpu::columns() {
  return ao_pass_columns(false, {
      {"pass", "rtao_gpu_bvh_ms", "ms", "GPU RTAO: CPU wall time of the BVH build (Embree's rtcBuildBVH and the flattening), once before the frames (static scene; not in frame)",
       ColumnKind::Number, VariesBetweenRuns::Yes},
      {"pass", "rtao_gpu_bvh_upload_ms", "ms", "GPU RTAO: wall time of uploading the BVH to storage buffers, once before the frames (not in frame)",
       ColumnKind::Number, VariesBetweenRuns::Yes},
      {"pass", "rtao_gpu_bvh_bytes", "bytes", "GPU RTAO: the BVH's storage buffers (nodes 64 B, triangles 48 B, slots 4 B each; also mem_bvh_*)"},
      {"pass", "rtao_gpu_bvh_nodes", "", "GPU RTAO: inner nodes of the binary BVH"},
      {"pass", "rtao_gpu_bvh_leaves", "", "GPU RTAO: leaves of the BVH (at most 4 triangles each)"},
      {"pass", "rtao_gpu_bvh_depth", "", "GPU RTAO: inner-node levels on the BVH's longest path (the traversal stack's size)"},
      {"pass", "rtao_gpu_steps_max", "iterations", "GPU RTAO: loop iterations of the longest AO shader invocation (nodes, triangles and ray starts of its k rays), from the counting replay; at or past loop_iteration_limit the record is invalid"},
      {"pass", "rtao_gpu_primary_steps_max", "iterations", "GPU RTAO: loop iterations of the longest primary-ray invocation (primary=trace; 0 with raster), judged as rtao_gpu_steps_max"},
  }, false);
}

// The record's work_rtao_gpu_* columns come from the shared counting replay (the same names
// and meaning they had when work() wrote them: per ray means and maxima, now with p50, p99
// and totals). work() stays for what must be judged on the measured instance, also under
// --no-work: the loop limit (problems()) and the replayed image.
// A data table of the pass's own counters, alike in form only to the other passes' and
// structures' (see ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> RtaoGpu::work_counters() {
  return with_gbuffer_counters({  // the G-buffer's: primary=raster
      {"rtao_gpu_primary", "invocations", WorkShape::Total, "invocations",
       "rtao_gpu_primary: compute invocations, one primary ray each (every image pixel; primary=trace)"},
      {"rtao_gpu_primary", "nodes", WorkShape::Distribution, "nodes",
       "rtao_gpu_primary: BVH inner nodes visited per primary ray (each tests both children's boxes)"},
      {"rtao_gpu_primary", "triangles", WorkShape::Distribution, "triangles",
       "rtao_gpu_primary: triangles tested per primary ray"},
      {"rtao_gpu", "invocations", WorkShape::Total, "invocations", "rtao_gpu: compute invocations (every image pixel)"},
      {"rtao_gpu", "rays", WorkShape::Total, "rays", "rtao_gpu: AO rays traced in one frame (covered pixels x k)"},
      {"rtao_gpu", "nodes", WorkShape::Distribution, "nodes",
       "rtao_gpu: BVH inner nodes visited per AO ray (each tests both children's boxes)"},
      {"rtao_gpu", "triangles", WorkShape::Distribution, "triangles", "rtao_gpu: triangles tested per AO ray"},
  });
}

RtaoGpu::~RtaoGpu() = default;

PassRequirements RtaoGpu::requirements() const {
  PassRequirements r;
  r.scene_attributes.normals = true;  // the G-buffer's shading normals
  r.needs_structure = false;
  return r;
}

std::vector<TimedSubpass> RtaoGpu::subpasses() const {
  TimedSubpass first =
      trace_primary_
          ? TimedSubpass{"rtao_gpu_primary", "GPU RTAO: each pixel's primary ray through the BVH to its closest hit (the traced G-buffer)"}
          : TimedSubpass{"gbuffer", "G-buffer: world positions, camera-facing normals and triangle ids from the camera"};
  return {first, {"rtao_gpu", "GPU RTAO: k cosine-weighted rays per pixel through the BVH in a compute shader"}};
}

std::vector<std::pair<std::string, RecordValue>> RtaoGpu::describe(const Scene& scene) const {
  return ao_setting_values(settings_for(scene), false);
}

GlProgram RtaoGpu::build(bool counting) const {
  ShaderDefines defines = traversal_defines(bvh_.depth, counting);
  defines.set("RTAO_GPU_SPP", std::to_string(spp_) + "u");
  defines.set("RTAO_GPU_ATTENUATED", ao_.attenuated ? 1 : 0);
  GlProgram program = build_program({{GL_COMPUTE_SHADER, "passes/rtao_gpu.comp", {}}}, defines);
  const glm::vec3 eye = scene_->camera.eye;
  program.set("camera_eye", eye.x, eye.y, eye.z);
  set_uvec2(program, "rng_seed_mixed", mix64(seed_));
  set_uvec2(program, "rng_pass_term", uint64_t(kRtaoStreamPass) * 0xd1b54a32d192ed03ull + 1u);
  program.set("ao_d_max", ao_.d_max);
  program.set("ao_falloff_exponent", ao_.falloff_exponent);
  program.set("ray_offset_ulps", kRayOffsetUlps);
  check_gl("GPU RTAO uniforms");
  return program;
}

GlProgram RtaoGpu::build_primary(bool counting) const {
  ShaderDefines defines = traversal_defines(bvh_.depth, counting);
  defines.set("RTAO_GPU_SCENE_NORMALS_BINDING", kSceneNormalsBinding);
  defines.set("RTAO_GPU_SCENE_INDICES_BINDING", kSceneIndicesBinding);
  GlProgram program = build_program({{GL_COMPUTE_SHADER, "passes/rtao_gpu_primary.comp", {}}}, defines);
  const CameraFrame c = camera_frame(scene_->camera, width_, height_);
  program.set("camera_eye", c.eye.x, c.eye.y, c.eye.z);
  program.set("camera_forward", c.forward.x, c.forward.y, c.forward.z);
  program.set("camera_right", c.right.x, c.right.y, c.right.z);
  program.set("camera_up", c.up.x, c.up.y, c.up.z);
  program.set("camera_tan_half_fov_y", c.tan_half_fov_y);
  program.set("camera_aspect", c.aspect);
  check_gl("GPU RTAO primary uniforms");
  return program;
}

void RtaoGpu::prepare(const PassInputs& in) {
  in.scene.validate();
  scene_ = &in.scene;
  gpu_scene_ = &in.gpu_scene;
  width_ = in.width;
  height_ = in.height;
  ao_ = settings_for(in.scene);
  // Refused before anything is built: a storage block past the device's limit.
  GLint64 block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  const std::string refusal = gpu_bvh_storage_refusal(in.scene.mesh.triangles.size(), uint64_t(block));
  if (!refusal.empty()) throw UserError(refusal);
  bvh_ = build_gpu_bvh(in.scene.mesh);  // times itself (bvh_.build_ms)
  const auto upload_start = std::chrono::steady_clock::now();
  nodes_ = GlBuffer("bvh_nodes", bvh_.node_bytes(), bvh_.nodes.data(), 0);
  triangles_ = GlBuffer("bvh_triangles", bvh_.triangle_bytes(), bvh_.triangles.data(), 0);
  slots_ = GlBuffer("bvh_slots", bvh_.slot_bytes(), bvh_.slots.data(), 0);
  glFinish();  // the upload's whole cost, not its queuing
  upload_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - upload_start).count();
  check_gl("uploading the BVH");
  if (trace_primary_) {
    traced_positions_ = GlTexture2D(GL_RGBA32F, in.width, in.height);
    traced_normals_ = GlTexture2D(GL_RGBA32F, in.width, in.height);
    traced_ids_ = GlTexture2D(GL_R32UI, in.width, in.height);
    primary_program_ = build_primary(false);
  } else {
    gbuffer_ = std::make_unique<GBufferPass>(in.width, in.height, false, true);
  }
  ao_target_ = GlTexture2D(GL_R32F, in.width, in.height);
  program_ = build(false);
}

const GlTexture2D& RtaoGpu::positions() const {
  return trace_primary_ ? traced_positions_ : gbuffer_->positions();
}
const GlTexture2D& RtaoGpu::normals() const {
  return trace_primary_ ? traced_normals_ : gbuffer_->normals();
}
const GlTexture2D& RtaoGpu::triangle_ids() const {
  return trace_primary_ ? traced_ids_ : gbuffer_->triangle_ids();
}

void RtaoGpu::bind_bvh() const {
  nodes_.bind_storage(kNodesBinding);
  triangles_.bind_storage(kTrianglesBinding);
  slots_.bind_storage(kSlotsBinding);
}

void RtaoGpu::trace_primary(const GlProgram& program) const {
  bind_bvh();
  scene_buffer(*gpu_scene_, "scene_normals").bind_storage(kSceneNormalsBinding);
  scene_buffer(*gpu_scene_, "scene_indices").bind_storage(kSceneIndicesBinding);
  glBindImageTexture(0, traced_positions_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(1, traced_normals_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, traced_ids_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
  program.use();
  dispatch();
}

void RtaoGpu::trace_ao(const GlProgram& program, const GlTexture2D& target) const {
  bind_bvh();
  glBindTextureUnit(0, positions().id());
  glBindTextureUnit(1, normals().id());
  glBindTextureUnit(2, triangle_ids().id());
  glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  program.use();
  dispatch();
}

void RtaoGpu::dispatch() const {
  glDispatchCompute(GLuint((width_ + kGroupSize - 1) / kGroupSize),
                    GLuint((height_ + kGroupSize - 1) / kGroupSize), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void RtaoGpu::render(GpuTimer* timer) {
  if (trace_primary_) {
    ScopedSubpass timed(timer, "rtao_gpu_primary");
    trace_primary(primary_program_);
  } else {
    gbuffer_->render(*gpu_scene_, *scene_, timer);
  }
  {
    ScopedSubpass timed(timer, "rtao_gpu");
    trace_ao(program_, ao_target_);
  }
  work_.reset();  // a new frame: count it again when asked
}

const RtaoGpuWork& RtaoGpu::work() const {
  if (work_) return *work_;
  // Untimed, after the measured frames: the counting variants (the primary rays into the same
  // targets, which they fill as before; the AO rays into a target of their own), then the
  // replayed image compared with the measured frames'.
  const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
  RtaoGpuWork w;
  w.loop_limit = shader_loop_iteration_limit();
  if (trace_primary_) {
    GlBuffer counts("rtao_gpu_primary_counts", 16 + 8 * pixels);
    counts.clear_to_zero();
    counts.bind_storage(kCountsBinding);
    trace_primary(build_primary(true));
    w.primary = ray_work(counts.download_all<uint32_t>(), std::vector<bool>(pixels, true), 1);
  }
  const std::vector<uint32_t> ids = read_triangle_ids();
  std::vector<bool> covered(pixels);
  for (uint64_t p = 0; p < pixels; ++p) covered[p] = ids[p] != 0;
  GlBuffer counts("rtao_gpu_counts", 16 + 8 * pixels);
  counts.clear_to_zero();
  counts.bind_storage(kCountsBinding);
  const GlTexture2D replay(GL_R32F, width_, height_);
  trace_ao(build(true), replay);
  w.ao = ray_work(counts.download_all<uint32_t>(), covered, spp_);
  const std::vector<float> measured = ao_target_.read_floats(1), replayed = replay.read_floats(1);
  w.image_matches = std::memcmp(measured.data(), replayed.data(), measured.size() * sizeof(float)) == 0;
  work_ = w;
  return *work_;
}

std::vector<uint32_t> RtaoGpu::read_triangle_ids() const {
  const GlTexture2D& ids = triangle_ids();
  std::vector<uint32_t> out(size_t(width_) * size_t(height_));
  glGetTextureImage(ids.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.size() * sizeof(uint32_t)), out.data());
  check_gl("reading the GPU RTAO's triangle ids");
  return out;
}

Image RtaoGpu::read_positions() const {
  return image_from_gl_rows(positions().read_floats(4), width_, height_, 4);
}

std::vector<PassImage> RtaoGpu::images() const {
  return {{"ao", image_from_gl_rows(ao_target_.read_floats(1), width_, height_, 1)}};
}

Image RtaoGpu::coverage() const { return coverage_mask(read_positions()); }

std::vector<std::pair<std::string, RecordValue>> RtaoGpu::results() const {
  const RtaoGpuWork& w = work();
  return {{"rtao_gpu_bvh_ms", bvh_.build_ms},
          {"rtao_gpu_bvh_upload_ms", upload_ms_},
          {"rtao_gpu_bvh_bytes", int64_t(bvh_.bytes())},
          {"rtao_gpu_bvh_nodes", int64_t(bvh_.nodes.size())},
          {"rtao_gpu_bvh_leaves", int64_t(bvh_.leaves)},
          {"rtao_gpu_bvh_depth", int64_t(bvh_.depth)},
          {"rtao_gpu_steps_max", int64_t(w.ao.steps_max)},
          {"rtao_gpu_primary_steps_max", int64_t(w.primary.steps_max)},
          {"loop_iteration_limit", int64_t(w.loop_limit)},
          {"covered_pixel_fraction", covered_pixel_fraction(read_positions())}};
}

std::vector<std::string> RtaoGpu::problems() const {
  const RtaoGpuWork& w = work();
  std::vector<std::string> out;
  // One loop a shader (bvh_traversal.glsl): a SIMD group runs as many iterations as its
  // longest invocation, which the replay counted.
  if (w.loop_limit != 0 && w.ao.steps_max >= w.loop_limit)
    out.push_back(loop_problem("AO pass", w.ao.steps_max, w.loop_limit, "lower rtao_gpu:spp"));
  if (w.loop_limit != 0 && w.primary.steps_max >= w.loop_limit)
    out.push_back(loop_problem("primary rays", w.primary.steps_max, w.loop_limit,
                               "use rtao_gpu:primary=raster"));
  if (!w.image_matches)
    out.push_back("the GPU ray tracer's counting replay drew another image than the measured "
                  "frames: its counts do not describe them");
  return out;
}

std::vector<BufferMemory> RtaoGpu::memory() const {
  // The G-buffer and AO target (every texel written each frame) and the BVH (all of it
  // read-only data): allocated = used. The counting replay's buffer is not the pass's.
  std::vector<BufferMemory> out;
  if (trace_primary_) {
    for (const auto& [name, target] : {std::pair{"rtao_gpu_positions", &traced_positions_},
                                       std::pair{"rtao_gpu_normals", &traced_normals_},
                                       std::pair{"rtao_gpu_triangle_ids", &traced_ids_}})
      out.push_back({name, target->bytes(), target->bytes()});
  } else {
    out = gbuffer_->memory();
  }
  out.push_back({"rtao_gpu_ao", ao_target_.bytes(), ao_target_.bytes()});
  for (const GlBuffer* b : {&nodes_, &triangles_, &slots_}) out.push_back({b->name(), b->bytes(), b->bytes()});
  return out;
}

ReferenceResult RtaoGpu::reference(const Scene& scene, int width, int height,
                                   const ReferenceSettings& settings) const {
  return ao_reference_for_run(scene, settings_for(scene), width, height, settings);
}

}  // namespace ldm
