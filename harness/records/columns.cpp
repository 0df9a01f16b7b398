#include "harness/records/columns.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace ldm {
namespace {

// What a configuration was measured on and whether it measures anything (issue 22;
// harness/app/scene_profile.h, the trace step counts of the LDM passes): kept apart so that
// the main list stays as it was.
std::vector<ColumnSpec> scene_profile_columns() {
  return {
      {"profile", "scene_radius", "scene units", "radius of the scene's bounding sphere (what derived settings scale with)"},
      {"profile", "scene_origin_offset", "", "world position (x y z in scene units, double) of the frame the scene is computed in: a scene file with meshes is rebased at load to its bounding-box centre"},
      {"profile", "far_file_vertices", "corners", "triangle corners the mesh file itself holds coarser than 2^-16 of the scene's extent (float coordinates far from the file's origin; named in status_detail)"},
      {"profile", "collapsed_triangles", "triangles", "triangles with an area where their mesh is placed and none once rebased into the scene's frame: detail below the float spacing where it lies (a small part far from the rest of a large scene), neither drawn nor hit; named in status_detail"},
      {"profile", "camera_source", "", "where the camera came from: generator <name>, scene file, or derived (framing the bounding sphere)"},
      {"profile", "light_source", "", "where the spot light came from: generator <name>, scene file, or derived (above the bounding sphere, 1 W/m^2 at its centre)"},
      {"profile", "d_max_source", "", "where d_max came from: generator <name>, scene file, run (--d-max), or derived (0.2 x the radius)"},
      {"profile", "depth_p50", "fragments", "median list length over the LDM pixels holding a fragment (the census)"},
      {"profile", "depth_p90", "fragments", "90th percentile of those list lengths"},
      {"profile", "depth_p99", "fragments", "99th percentile of those list lengths"},
      {"profile", "depth_histogram", "", "LDM pixels per power-of-two bin of list lengths, lo-hi:pixels;... (non-empty pixels)"},
      {"profile", "depth_share_above_k", "", "fixed arrays: share of the non-empty LDM pixels holding more than k fragments"},
      {"profile", "covered_pixel_fraction", "", "share of the image's pixels where the camera sees a surface"},
      {"profile", "d_max_ldm_pixels", "LDM pixels", "the AO range d_max in LDM pixels (attenuated AO; fewer than 3 is degenerate)"},
      {"profile", "trace_steps_max", "iterations", "LDM passes: the most loop iterations (views, list walks, the structure's own query loops) one shader invocation of the trace ran, over every frame"},
      {"profile", "trace_steps_bound", "iterations", "an upper bound on what any SIMD group of those invocations ran (llvmpipe counts a group's iterations against its loop limit)"},
      {"profile", "loop_iteration_limit", "iterations", "the device's limit on one invocation's loop iterations, after which it ends every loop silently (llvmpipe: 65535; 0: none known); a bound at or past it makes the record invalid"},
      {"profile", "degenerate", "", "why the measurement measures nothing (a reference without noise, no surface in view, an AO range below 3 LDM pixels); such records are never ranked"},
  };
}

std::vector<ColumnSpec> main_columns();

}  // namespace

const std::vector<ColumnSpec>& harness_record_columns() {
  static const std::vector<ColumnSpec> columns = [] {
    std::vector<ColumnSpec> all = main_columns();
    for (auto& column : scene_profile_columns()) all.push_back(std::move(column));
    return all;
  }();
  return columns;
}

namespace {

std::vector<ColumnSpec> main_columns() {
  return {
      {"identity", "config_id", "", "unique name of the configuration, also the image file stem"},
      {"identity", "status", "", "ok, lossy (counted loss by configured capacity), invalid (never measured) or failed"},
      {"identity", "status_detail", "", "why the status is not ok, and warnings such as a missed reference noise target"},
      {"identity", "scene", "", "the --scene value: a built-in name or a scene file path"},
      {"identity", "structure", "", "LDM structure (`ldmbench structures`), or none for a pass that reads no LDM (hbao, rtao)"},
      {"identity", "pass", "", "pass run through the structure (`ldmbench passes`)"},
      {"identity", "n_views", "views", "N, the number of LDM views"},
      {"identity", "r_ldm", "pixels", "R_LDM, the side of each view's square LDM"},
      {"identity", "width", "pixels", "output image width"},
      {"identity", "height", "pixels", "output image height"},
      {"identity", "structure_params", "", "the structure's --param values, key=value;..."},
      {"identity", "sizing_policy", "", "how the structure learned its sizes: oracle (untimed census before the run), census, previous_frame or budget (after --sizing); none for a pass that reads no LDM"},
      {"identity", "frames", "frames", "measured frames per repetition, at least (--frames; more until time_target is met)"},
      {"identity", "warmup", "frames", "warm-up frames (judged, not timed)"},
      {"identity", "ldmbench_version", "", "version of the build that measured"},
      {"identity", "git_commit", "", "commit of the build that measured"},
      {"device", "device", "", "GL_RENDERER; for a pass that runs on the CPU (rtao) the CPU model, CPU: <model name>"},
      {"device", "device_id", "", "names the device uniquely: its UUID (EGL_EXT_device_persistent_id, else GL_EXT_memory_object) or DRM node; software:<GL_RENDERER> for Mesa's software drivers; absent in records from before it (docs/guide/gpu-nodes.md#choosing-the-gpu)"},
      {"device", "gl_driver", "", "the driver's short name from GL_RENDERER, GL_VENDOR, GL_VERSION: llvmpipe, zink, nvidia, radeonsi, ...; report and compare group and match by it"},
      {"device", "gl_vendor", "", "GL_VENDOR"},
      {"device", "gl_version", "", "GL_VERSION"},
      {"device", "egl_platform", "", "EGL platform of the headless context (device or surfaceless)"},
      {"device", "int64_atomics", "", "whether GL_NV_shader_atomic_int64 is available"},
      {"device", "driver_defects", "", "what the driver self-tests found wrong (harness/gl/driver_probe.h; docs/reference/structures.md#driver-conformance): none, or each failed probe; a structure that depends on a failed one refuses to build"},
      {"device", "timer", "", "sub-pass timer: gl_timestamp, fenced_wall_clock, or cpu_wall (the CPU's steady clock alone: a pass that runs on the CPU, rtao)"},
      {"device", "host", "", "host name of the machine that measured (a merged sweep joins several)"},
      {"device", "slurm_job_id", "", "under Slurm: the job that measured (SLURM_JOB_ID; an array task's own id); absent outside Slurm"},
      {"device", "slurm_array_job_id", "", "under a Slurm job array (scripts/slurm-sweep.sh): the array's job id (SLURM_ARRAY_JOB_ID)"},
      {"device", "slurm_array_task_id", "", "the array task (SLURM_ARRAY_TASK_ID; with scripts/slurm-sweep.sh, the shard's index)"},
      {"device", "slurm_node", "", "the Slurm node that measured (SLURMD_NODENAME)"},
      {"device", "slurm_gpus", "", "the node's GPU indices Slurm allocated to the job (SLURM_JOB_GPUS, physical ids, with --gres=gpu:N): recorded only; the GPU measured is --gpu's CUDA ordinal among those visible (device_id)"},
      {"scene", "scene_name", "", "the scene's own name"},
      {"scene", "scene_hash", "", "64-bit hash of the scene's content (geometry, camera, settings)"},
      {"scene", "triangles", "triangles", "triangles in the scene"},
      {"scene", "scene_attributes", "", "vertex attributes uploaded, as the pass requires (position+normal, ...); normals the mesh file lacked and the importer derived from the faces say so: +normal(derived), or +normal(derived for D of T triangles)"},
      {"scene", "scene_gpu_bytes", "bytes", "geometry buffers on the device"},
      {"scene", "payload", "", "what the structure stores per fragment, as the pass requires (depth, ...)"},
      {"census", "fragments", "fragments", "fragments of all views, counted by the census before allocation"},
      {"census", "max_depth_complexity", "fragments", "longest list of any LDM pixel"},
      {"census", "mean_depth_complexity", "fragments", "mean list length over non-empty pixels"},
      {"census", "nonempty_pixel_fraction", "", "share of LDM pixels holding a fragment"},
      {"build", "fragments_stored", "fragments", "fragments the last build holds"},
      {"build", "fragments_lost", "fragments", "fragments the last build dropped (counted by the structure)"},
      {"build", "overflow", "", "whether any build found its storage too small"},
      {"build", "tied_depths", "fragments", "fragments stored at exactly their predecessor's depth (most of any build): coincident surfaces, or in a quantising structure (HA-buffer 24-bit keys) distinct depths collided on one key, flagged in status_detail"},
      {"build", "checksum_changes", "builds", "builds whose lists differed from the first build's (in full, or in the blocks a sampled check visited)"},
      {"build", "lists_checksum", "", "checksum of every pixel's depth list after the first build"},
      {"build", "verify_mode", "", "how builds were checked (--verify): every (the full check after every build) or sampled (in full after the first build and after the sizing policy rebuilt or reallocated; after other builds one 64-pixel block in verify_stride, compared with the last full check's lists)"},
      {"build", "verify_stride", "", "sampled: one block in this many is checked per build, rotating"},
      {"build", "verify_full_checks", "builds", "builds checked in full (stats against the census and every list walked), warm-up included"},
      {"build", "verify_sampled_checks", "builds", "builds checked on a sample of their blocks"},
      {"build", "verify_sampled_pixels", "pixels", "pixels those samples walked, in all"},
      {"build", "counter_<name>", "", "a structure's own count of its last build (max_age_used, lists_sorted_in_place, ...)"},
      {"build", "sizing_<key>", "", "what sized each buffer (pool_capacity_nodes, k, table_entries, depth_capacity, each with a ..._source: the policy or parameter), and the policy's initial guess, budget_mib, note"},
      {"build", "sizing_rebuilds", "builds", "builds redone after an overflow (previous_frame), warm-up included"},
      {"build", "sizing_rebuilds_measured", "builds", "of those, in measured frames"},
      {"build", "sizing_reallocations", "", "times the policy grew the structure's storage"},
      {"time", "repetitions", "repetitions", "independent repetitions measured (--repetitions), each in a fresh GL context or process (see isolation in the run object), round robin over the sweep"},
      {"time", "repetition", "", "in the journal only: which repetition a {\"repetition\": ...} entry is, before the configuration's repetitions are combined"},
      {"time", "frames_measured", "frames", "measured frames over every repetition"},
      {"time", "frames_per_repetition", "", "measured frames of each repetition, n;n;..."},
      {"time", "time_target", "", "the precision target: relative half-width of the 95% interval of the build and frame medians at which a repetition stops measuring frames (--time-target; 0: exactly frames)"},
      {"time", "time_cap_s", "s", "measured frames' wall time after which a repetition stops, target met or not (--time-cap)"},
      {"time", "time_target_met", "", "whether every repetition reached time_target before its cap (a miss is a warning in status_detail)"},
      {"time", "time_interval", "", "how the _ms_ci_ columns were made: order_statistics_of_frames (one repetition: distribution-free interval of the median, assumes independent frames) or t_on_log_repetition_medians (a t interval over the repetitions' medians), with +run_to_run_spread when widened to hold another run's median (time_calibration)"},
      {"time", "time_half_width_within_run", "", "relative half-width of the frame median's interval before it was widened by the run-to-run spread: what this run's own frames (or repetitions) show"},
      {"time", "time_run_to_run_spread", "", "the run-to-run spread that widened the intervals: RMS of log(median_a / median_b) between separate processes measuring the same configurations on this machine (ldmbench calibrate)"},
      {"time", "time_calibration", "", "where the run-to-run spread came from (cache FILE, file FILE, with its date and load) or that it was skipped (--calibration skip: the intervals are within-run only and do not hold another run's median)"},
      {"time", "load_average_<end>", "", "the machine's 1-minute load average at the start and end of the repetition (the last one's, with repetitions)"},
      {"time", "cpu_governor", "", "the CPU frequency governor (cpufreq scaling_governor), where the machine exposes it"},
      {"time", "cpu_mhz_<end>", "MHz", "mean CPU clock over cores (/proc/cpuinfo) at the start and end of the repetition"},
      {"time", "gpu_sm_clock_mhz_<end>", "MHz", "NVIDIA: the GPU's SM clock at the start and end of the repetition (nvidia-smi), where available"},
      {"time", "gpu_power_w_<end>", "W", "NVIDIA: the GPU's power draw at the start and end of the repetition"},
      {"time", "gpu_throttle_reasons_<end>", "", "NVIDIA: the active clock throttle reasons (a bit mask; 0x1 alone is idle) at the start and end of the repetition; a throttle or a clock change is a warning in status_detail"},
      {"time", "time_interval_coverage", "", "the frame interval's coverage: 0.95, or less when too few frames (or repetitions) reach it"},
      {"time", "time_half_width", "", "relative half-width of the frame median's interval: how precise the record's frame time is"},
      {"time", "<subpass>_ms_median", "ms", "median over the measured frames of a sub-pass (with repetitions: the median of the repetitions' medians; the sizing policy's census, readback, reallocate, rebuild among them, 0 in frames without), of build (sizing included), pass (the pass's own) or frame"},
      {"time", "<subpass>_ms_ci_low", "ms", "low end of the median's 95% interval (time_interval says how it was made)"},
      {"time", "<subpass>_ms_ci_high", "ms", "high end of the median's 95% interval"},
      {"time", "<subpass>_ms_rep_spread", "", "with repetitions: standard deviation of the logs of the repetitions' medians (about the relative spread between repetitions)"},
      {"time", "<subpass>_ms_min", "ms", "minimum over the measured frames"},
      {"time", "<subpass>_ms_max", "ms", "maximum over the measured frames"},
      {"time", "<subpass>_ms_stddev", "ms", "sample standard deviation over the measured frames (pooled over repetitions)"},
      {"time", "build_vs_raster", "", "build median over raster_baseline median (the empty raster pass)"},
      {"time", "build_vs_raster_touch", "", "build median over raster_touch median (every fragment shaded, one atomicAdd each)"},
      {"time", "baseline_frames", "frames", "measured frames on which the two raster baselines were timed: every second one from the first (over every repetition)"},
      {"time", "raster_touch_fragments", "fragments", "fragments the raster_touch baseline shaded (checked against the census)"},
      {"time", "fragments_per_second", "1/s", "census fragments over the build median"},
      {"time", "frame_samples_csv", "", "every measured frame's time of every sub-pass (repetition, frame, subpass, ms), path relative to the records"},
      {"time", "frames_timed_ms", "ms", "sum over the measured frames of every timed sub-pass (baselines included): the time the measurement itself took on the device"},
      {"time", "verify_ms", "ms", "wall time of the measured frames' build checks (untimed; the harness's own cost)"},
      {"time", "verify_warmup_ms", "ms", "wall time of the warm-up frames' build checks"},
      {"time", "verify_share", "", "verify_ms over frames_timed_ms"},
      {"time", "wall_seconds", "s", "wall time of the whole configuration (its repetitions summed), reference included"},
      {"memory", "mem_<buffer>_allocated", "bytes", "bytes reserved for one of the structure's buffers (for a pass without structure, hbao: one of its render targets; an LDM pass's own, e.g. the indirect pass's photons: not in bytes_allocated)"},
      {"memory", "mem_<buffer>_used", "bytes", "bytes of that buffer holding data after the last build"},
      {"memory", "bytes_allocated", "bytes", "sum over the structure's buffers (and the census policy's counts), or over a structureless pass's targets"},
      {"memory", "bytes_used", "bytes", "sum over the structure's buffers (or the structureless pass's targets)"},
      {"accuracy", "ref_spp", "samples", "reference samples per pixel (both halves)"},
      {"accuracy", "ref_noise_mse", "", "expected MSE of the reference itself: MSE(half A, half B) / 4"},
      {"accuracy", "ref_noise_mssim", "", "MSSIM between the reference's two halves"},
      {"accuracy", "ref_noise_target_met", "", "whether the automatic spp rule reached its noise target"},
      {"accuracy", "ref_render_seconds", "s", "time the reference took to render (when it was rendered)"},
      {"accuracy", "ref_from_cache", "", "whether the reference came from the cache"},
      {"accuracy", "ref_cache_key", "", "cache key of the reference (hash of everything it depends on)"},
      {"accuracy", "ref_ray_offset", "scene units", "largest distance the reference's secondary rays start off the surface"},
      {"accuracy", "ref_ray_offset_ok", "", "false when that offset exceeds 1e-3 of d_max or of the scene's radius (the reference may be biased)"},
      {"accuracy", "mse", "", "mean squared error against the reference, averaged over channels"},
      {"accuracy", "nrmse", "", "sqrt(MSE) over the reference's range"},
      {"accuracy", "psnr", "dB", "peak signal-to-noise ratio with the reference's peak"},
      {"accuracy", "mssim", "", "mean SSIM (Wang et al. 2004, skimage's Gaussian variant)"},
      {"accuracy", "mse_covered", "", "mse over the covered pixels alone (covered_pixel_fraction's: where the camera sees a surface), not diluted by the background"},
      {"accuracy", "nrmse_covered", "", "sqrt(mse_covered) over the reference's range on the covered pixels"},
      {"accuracy", "mssim_covered", "", "mean of the SSIM map over the covered pixels (inside mssim's 5-pixel crop)"},
      {"accuracy", "ssim_exposure", "", "exposure scale applied before SSIM (1 for AO)"},
      {"accuracy", "mse_over_noise", "", "mse over ref_noise_mse: how far the error stands above the reference's noise"},
      {"accuracy", "bias", "", "mean of image - reference over every pixel and channel (the error's systematic part; bias^2 is the MSE averaging cannot remove)"},
      {"accuracy", "bias_share", "", "bias^2 / mse: the share of the MSE that is the mean offset"},
      {"accuracy", "mean_ratio", "", "mean of the image over the mean of the reference (1: the same energy in the image)"},
      {"accuracy", "mean_ratio_se", "", "standard error of mean_ratio from the reference's noise (ref_noise_mse over the pixels and channels, as if independent)"},
      {"accuracy", "metrics_error", "", "why the image was not measured (NaN or infinity)"},
      {"accuracy", "multi_<column>", "", "indirect: each accuracy and reference-image column (ref_*, mse, nrmse, psnr, mssim, ssim_exposure, mse_over_noise, reference_exr, ssim_map_png, diff_png...) against the multi-bounce reference; the unprefixed ones are against the single-bounce reference"},
      {"images", "image_exr", "", "the pass's image, linear EXR (path relative to the records)"},
      {"images", "image_png", "", "the pass's image, sRGB PNG"},
      {"images", "image_<name>_exr", "", "the pass's further images (indirect: direct, sum), linear EXR"},
      {"images", "image_<name>_png", "", "the same, sRGB PNG"},
      {"images", "reference_exr", "", "the reference, linear EXR (one per reference)"},
      {"images", "ssim_map_png", "", "SSIM map as a heat map"},
      {"images", "diff_png", "", "absolute difference to the reference as a heat map (EXR beside it)"},
      {"images", "diff_png_max", "", "the difference that maps to the top of the heat map"},
  };
}

}  // namespace

namespace {

bool matches(const std::string& pattern, const std::string& column) {
  const auto open = pattern.find('<');
  if (open == std::string::npos) return pattern == column;
  const auto close = pattern.find('>', open);
  const std::string prefix = pattern.substr(0, open), suffix = pattern.substr(close + 1);
  return column.size() > prefix.size() + suffix.size() && column.starts_with(prefix) &&
         column.ends_with(suffix);
}

}  // namespace

const ColumnSpec* find_column_in(const std::vector<ColumnSpec>& columns, const std::string& column) {
  for (const auto& c : columns)
    if (c.name == column) return &c;
  for (const auto& c : columns)
    if (matches(c.name, column)) return &c;
  return nullptr;
}

const std::vector<ColumnLabel>& column_labels() {
  static const std::vector<ColumnLabel> labels = {
      {"config_id", "configuration"},
      {"status", "status"},
      {"build_ms_median", "build ms", -1},
      {"pass_ms_median", "pass ms", -1},
      {"frame_ms_median", "frame ms", -1},
      {"bytes_allocated", "MiB allocated", -1, 1.0 / (1024.0 * 1024.0)},
      {"bytes_used", "MiB used", -1, 1.0 / (1024.0 * 1024.0)},
      {"mse", "MSE", -1},
      {"nrmse", "NRMSE", -1},
      {"mssim", "MSSIM", +1},
      {"mse_covered", "MSE covered", -1},
      {"nrmse_covered", "NRMSE covered", -1},
      {"mssim_covered", "MSSIM covered", +1},
      {"mse_over_noise", "MSE / ref noise", -1},
      {"ref_noise_mse", "ref noise MSE", -1},
      {"covered_pixel_fraction", "covered share", 0},
  };
  return labels;
}

const ColumnLabel& column_label(const std::string& column) {
  for (const auto& l : column_labels())
    if (l.column == column) return l;
  static thread_local ColumnLabel unnamed;
  unnamed = {column, column};
  return unnamed;
}

std::string column_heading(const std::string& column) {
  const ColumnLabel& l = column_label(column);
  return l.label + (l.better < 0 ? " ↓" : l.better > 0 ? " ↑" : "");
}

std::string column_labels_json() {
  std::ostringstream out;
  out << "{\n  \"arrows\": {\"lower\": \"↓\", \"higher\": \"↑\"},\n  \"columns\": [\n";
  const auto& labels = column_labels();
  for (size_t i = 0; i < labels.size(); ++i) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.17g", labels[i].scale);
    out << "    {\"column\": \"" << labels[i].column << "\", \"label\": \"" << labels[i].label
        << "\", \"better\": " << labels[i].better << ", \"scale\": " << scale << "}"
        << (i + 1 < labels.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
  return out.str();
}

std::string columns_markdown(const std::vector<ColumnSpec>& columns) {
  std::ostringstream out;
  out << "| group | column | unit | description |\n| --- | --- | --- | --- |\n";
  std::string group;
  for (const auto& c : columns) {
    out << "| " << (c.group == group ? "" : c.group) << " | `" << c.name << "` | " << c.unit
        << " | " << c.description << " |\n";
    group = c.group;
  }
  return out.str();
}

std::string columns_text(const std::vector<ColumnSpec>& columns) {
  size_t width = 0;
  for (const auto& c : columns) width = std::max(width, c.name.size());
  std::ostringstream out;
  std::string group;
  for (const auto& c : columns) {
    if (c.group != group) out << (group.empty() ? "" : "\n") << c.group << ":\n";
    group = c.group;
    out << "  " << c.name << std::string(width + 2 - c.name.size(), ' ')
        << (c.unit.empty() ? "" : "[" + c.unit + "] ") << c.description << "\n";
  }
  return out.str();
}

}  // namespace ldm
