#pragma once
// The harness's own record columns, each declared once as a typed constant (group, name, unit,
// description, kind, whether it varies between two runs of the same configuration, whether it is
// deterministic, which way is better). The code that writes a column names it by its constant
// (Record::set(const Column&, ...)); harness_record_columns() lists them in the order of the
// records table (docs/reference/records.md). A name in angle brackets (<subpass>) is a pattern:
// one declaration for many columns, written by name (Record::set checks it against the schema).
#include "harness/records/columns.h"

namespace ldm::columns {

inline const Column kSceneRadius{"profile", "scene_radius", "scene units",
    "radius of the scene's bounding sphere (what derived settings scale with)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kSceneOriginOffset{"profile", "scene_origin_offset", "",
    "world position (x y z in scene units, double) of the frame the scene is computed in: a scene file with meshes is rebased at load to its bounding-box centre",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kFarFileVertices{"profile", "far_file_vertices", "corners",
    "triangle corners the mesh file itself holds coarser than 2^-16 of the scene's extent (float coordinates far from the file's origin; named in status_detail)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kCollapsedTriangles{"profile", "collapsed_triangles", "triangles",
    "triangles with an area where their mesh is placed and none once rebased into the scene's frame: detail below the float spacing where it lies (a small part far from the rest of a large scene), neither drawn nor hit; named in status_detail",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kCameraSource{"profile", "camera_source", "",
    "where the camera came from: generator <name>, scene file, or derived (framing the bounding sphere)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kLightSource{"profile", "light_source", "",
    "where the spot light came from: generator <name>, scene file, or derived (above the bounding sphere, 1 W/m^2 at its centre)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDMaxSource{"profile", "d_max_source", "",
    "where d_max came from: generator <name>, scene file, run (--d-max), or derived (0.2 x the radius)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDepthP50{"profile", "depth_p50", "fragments",
    "median list length over the LDM pixels holding a fragment (the census)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kDepthP90{"profile", "depth_p90", "fragments",
    "90th percentile of those list lengths",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kDepthP99{"profile", "depth_p99", "fragments",
    "99th percentile of those list lengths",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kDepthHistogram{"profile", "depth_histogram", "",
    "LDM pixels per power-of-two bin of list lengths, lo-hi:pixels;... (non-empty pixels)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDepthShareAboveK{"profile", "depth_share_above_k", "",
    "fixed arrays: share of the non-empty LDM pixels holding more than k fragments",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kCoveredPixelFraction{"profile", "covered_pixel_fraction", "",
    "share of the image's pixels where the camera sees a surface",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kDMaxLdmPixels{"profile", "d_max_ldm_pixels", "LDM pixels",
    "the AO range d_max in LDM pixels (attenuated AO; fewer than 3 is degenerate)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTraceStepsMax{"profile", "trace_steps_max", "iterations",
    "LDM passes: the most loop iterations (views, list walks, the structure's own query loops) one shader invocation of the trace ran, over every frame",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTraceStepsBound{"profile", "trace_steps_bound", "iterations",
    "an upper bound on what any SIMD group of those invocations ran (llvmpipe counts a group's iterations against its loop limit)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kLoopIterationLimit{"profile", "loop_iteration_limit", "iterations",
    "the device's limit on one invocation's loop iterations, after which it ends every loop silently (llvmpipe: 65535; 0: none known); a bound at or past it makes the record invalid",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kDegenerate{"profile", "degenerate", "",
    "why the measurement measures nothing (a reference without noise, no surface in view, an AO range below 3 LDM pixels); such records are never ranked",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kConfigId{"identity", "config_id", "",
    "unique name of the configuration, also the image file stem",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kStatus{"identity", "status", "",
    "ok, lossy (counted loss by configured capacity), invalid (never measured) or failed",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kStatusDetail{"identity", "status_detail", "",
    "why the status is not ok, and warnings such as a missed reference noise target",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kScene{"identity", "scene", "",
    "the --scene value: a built-in name or a scene file path",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kStructure{"identity", "structure", "",
    "LDM structure (`ldmbench structures`), or none for a pass that reads no LDM (hbao, rtao)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kPass{"identity", "pass", "",
    "pass run through the structure (`ldmbench passes`)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kNViews{"identity", "n_views", "views",
    "N, the number of LDM views",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRLdm{"identity", "r_ldm", "pixels",
    "R_LDM, the side of each view's square LDM",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kWidth{"identity", "width", "pixels",
    "output image width",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kHeight{"identity", "height", "pixels",
    "output image height",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kStructureParams{"identity", "structure_params", "",
    "the structure's --param values, key=value;...",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kSizingPolicy{"identity", "sizing_policy", "",
    "how the structure learned its sizes: oracle (untimed census before the run), census, previous_frame or budget (after --sizing); none for a pass that reads no LDM",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kFrames{"identity", "frames", "frames",
    "measured frames per repetition, at least (--frames; more until time_target is met)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kWarmup{"identity", "warmup", "frames",
    "warm-up frames (judged, not timed)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kLdmbenchVersion{"identity", "ldmbench_version", "",
    "version of the build that measured",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kGitCommit{"identity", "git_commit", "",
    "commit of the build that measured",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kShaderDir{"identity", "shader_dir", "",
    "LDM_SHADER_DIR when it was set: the folder whose shader files replaced the build's (absent: the build's own shaders)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDevice{"device", "device", "",
    "GL_RENDERER; for a pass that runs on the CPU (rtao) the CPU model, CPU: <model name>",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDeviceId{"device", "device_id", "",
    "names the device uniquely: its UUID (EGL_EXT_device_persistent_id, else GL_EXT_memory_object) or DRM node; software:<GL_RENDERER> for Mesa's software drivers; absent in records from before it (docs/guide/gpu-nodes.md#choosing-the-gpu)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kGlDriver{"device", "gl_driver", "",
    "the driver's short name from GL_RENDERER, GL_VENDOR, GL_VERSION: llvmpipe, zink, nvidia, radeonsi, ...; report and compare group and match by it",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kGlVendor{"device", "gl_vendor", "",
    "GL_VENDOR",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kGlVersion{"device", "gl_version", "",
    "GL_VERSION",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kEglPlatform{"device", "egl_platform", "",
    "EGL platform of the headless context (device or surfaceless)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kInt64Atomics{"device", "int64_atomics", "",
    "whether GL_NV_shader_atomic_int64 is available",
    ColumnKind::Flag, VariesBetweenRuns::No, Better::Neither};
inline const Column kDriverDefects{"device", "driver_defects", "",
    "what the driver self-tests found wrong (harness/gl/driver_probe.h; docs/reference/structures.md#driver-conformance): none, or each failed probe; a structure that depends on a failed one refuses to build",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimer{"device", "timer", "",
    "sub-pass timer: gl_timestamp, fenced_wall_clock, or cpu_wall (the CPU's steady clock alone: a pass that runs on the CPU, rtao)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kHost{"device", "host", "",
    "host name of the machine that measured (a merged sweep joins several)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSlurmJobId{"device", "slurm_job_id", "",
    "under Slurm: the job that measured (SLURM_JOB_ID; an array task's own id); absent outside Slurm",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSlurmArrayJobId{"device", "slurm_array_job_id", "",
    "under a Slurm job array (scripts/slurm-sweep.sh): the array's job id (SLURM_ARRAY_JOB_ID)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSlurmArrayTaskId{"device", "slurm_array_task_id", "",
    "the array task (SLURM_ARRAY_TASK_ID; with scripts/slurm-sweep.sh, the shard's index)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSlurmNode{"device", "slurm_node", "",
    "the Slurm node that measured (SLURMD_NODENAME)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSlurmGpus{"device", "slurm_gpus", "",
    "the node's GPU indices Slurm allocated to the job (SLURM_JOB_GPUS, physical ids, with --gres=gpu:N): recorded only; the GPU measured is --gpu's CUDA ordinal among those visible (device_id)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSceneName{"scene", "scene_name", "",
    "the scene's own name",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kSceneHash{"scene", "scene_hash", "",
    "64-bit hash of the scene's content (geometry, camera, settings)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kTriangles{"scene", "triangles", "triangles",
    "triangles in the scene",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kSceneAttributes{"scene", "scene_attributes", "",
    "vertex attributes uploaded, as the pass requires (position+normal, ...); normals the mesh file lacked and the importer derived from the faces say so: +normal(derived), or +normal(derived for D of T triangles)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kSceneGpuBytes{"scene", "scene_gpu_bytes", "bytes",
    "geometry buffers on the device",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kPayload{"scene", "payload", "",
    "what the structure stores per fragment, as the pass requires (depth, ...)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kFragments{"census", "fragments", "fragments",
    "fragments of all views, counted by the census before allocation",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kMaxDepthComplexity{"census", "max_depth_complexity", "fragments",
    "longest list of any LDM pixel",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kMeanDepthComplexity{"census", "mean_depth_complexity", "fragments",
    "mean list length over non-empty pixels",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kNonemptyPixelFraction{"census", "nonempty_pixel_fraction", "",
    "share of LDM pixels holding a fragment",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kFragmentsStored{"build", "fragments_stored", "fragments",
    "fragments the last build holds",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kFragmentsLost{"build", "fragments_lost", "fragments",
    "fragments the last build dropped (counted by the structure)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kOverflow{"build", "overflow", "",
    "whether any build found its storage too small",
    ColumnKind::Flag, VariesBetweenRuns::No, Better::Neither};
inline const Column kTiedDepths{"build", "tied_depths", "fragments",
    "fragments stored at exactly their predecessor's depth (most of any build): coincident surfaces, or in a quantising structure (HA-buffer 24-bit keys) distinct depths collided on one key, flagged in status_detail",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kChecksumChanges{"build", "checksum_changes", "builds",
    "builds whose lists differed from the first build's (in full, or in the blocks a sampled check visited)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kListsChecksum{"build", "lists_checksum", "",
    "checksum of every pixel's depth list after the first build",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kVerifyMode{"build", "verify_mode", "",
    "how builds were checked (--verify): every (the full check after every build) or sampled (in full after the first build and after the sizing policy rebuilt or reallocated; after other builds one 64-pixel block in verify_stride, compared with the last full check's lists)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kVerifyStride{"build", "verify_stride", "",
    "sampled: one block in this many is checked per build, rotating",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kVerifyFullChecks{"build", "verify_full_checks", "builds",
    "builds checked in full (stats against the census and every list walked), warm-up included",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kVerifySampledChecks{"build", "verify_sampled_checks", "builds",
    "builds checked on a sample of their blocks",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kVerifySampledPixels{"build", "verify_sampled_pixels", "pixels",
    "pixels those samples walked, in all",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kCounterNamePattern{"build", "counter_<name>", "",
    "a structure's own count of its last build (max_age_used, lists_sorted_in_place, ...)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kSizingKeyPattern{"build", "sizing_<key>", "",
    "what sized each buffer (pool_capacity_nodes, k, table_entries, depth_capacity, each with a ..._source: the policy or parameter), and the policy's initial guess, budget_mib, note",
    ColumnKind::Mixed, VariesBetweenRuns::No, Better::Neither};
inline const Column kSizingRebuilds{"build", "sizing_rebuilds", "builds",
    "builds redone after an overflow (previous_frame), warm-up included",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kSizingRebuildsMeasured{"build", "sizing_rebuilds_measured", "builds",
    "of those, in measured frames",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kSizingReallocations{"build", "sizing_reallocations", "",
    "times the policy grew the structure's storage",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRepetitions{"time", "repetitions", "repetitions",
    "independent repetitions measured (--repetitions), each in a fresh GL context or process (see isolation in the run object), round robin over the sweep",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRepetition{"time", "repetition", "",
    "in the journal only: which repetition a {\"repetition\": ...} entry is, before the configuration's repetitions are combined",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kFramesMeasured{"time", "frames_measured", "frames",
    "measured frames over every repetition",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kFramesPerRepetition{"time", "frames_per_repetition", "",
    "measured frames of each repetition, n;n;...",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeTarget{"time", "time_target", "",
    "the precision target: relative half-width of the 95% interval of the build and frame medians at which a repetition stops measuring frames (--time-target; 0: exactly frames)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeCapS{"time", "time_cap_s", "s",
    "measured frames' wall time after which a repetition stops, target met or not (--time-cap)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeTargetEffective{"time", "time_target_effective", "",
    "the precision target the frames aimed at where the run-to-run spread raised time_target: a third of the spread between two processes' medians (z x time_run_to_run_spread / (3 sqrt 2)), past which more frames narrow the widened interval by at most 5 % (absent: time_target itself)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kTimeTargetMet{"time", "time_target_met", "",
    "whether every repetition reached its target (time_target_effective where written, else time_target) before its cap (a miss is a warning in status_detail)",
    ColumnKind::Flag, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kTimeInterval{"time", "time_interval", "",
    "how the _ms_ci_ columns were made: order_statistics_of_frames (one repetition: distribution-free interval of the median, assumes independent frames) or t_on_log_repetition_medians (a t interval over the repetitions' medians), with +run_to_run_spread when widened to hold another run's median (time_calibration)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeHalfWidthWithinRun{"time", "time_half_width_within_run", "",
    "relative half-width of the frame median's interval before it was widened by the run-to-run spread: what this run's own frames (or repetitions) show",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kTimeRunToRunSpread{"time", "time_run_to_run_spread", "",
    "the run-to-run spread that widened the intervals: RMS of log(median_a / median_b) between separate processes measuring the same configurations on this machine (ldmbench calibrate)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kTimeCalibration{"time", "time_calibration", "",
    "where the run-to-run spread came from (cache FILE, file FILE, with its date and load) or that it was skipped (--calibration skip: the intervals are within-run only and do not hold another run's median)",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kLoadAverageEndPattern{"time", "load_average_<end>", "",
    "the machine's 1-minute load average at the start and end of the repetition (the last one's, with repetitions)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kCpuGovernor{"time", "cpu_governor", "",
    "the CPU frequency governor (cpufreq scaling_governor), where the machine exposes it",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kCpuMhzEndPattern{"time", "cpu_mhz_<end>", "MHz",
    "mean CPU clock over cores (/proc/cpuinfo) at the start and end of the repetition",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kGpuSmClockMhzEndPattern{"time", "gpu_sm_clock_mhz_<end>", "MHz",
    "NVIDIA: the GPU's SM clock at the first and after the last measured frame of the repetition (nvidia-smi), where available",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kGpuSmClockMaxMhz{"time", "gpu_sm_clock_max_mhz", "MHz",
    "NVIDIA: the most the GPU's SM clock can reach (nvidia-smi clocks.max.sm); a repetition that starts or ends below 90 % of it is a warning in status_detail",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeClockWarmupS{"time", "time_clock_warmup_s", "s",
    "NVIDIA: the longest the warm-up may run on, after its fixed frames, until the GPU's SM clock reaches its working level (--clock-warmup; 0: off)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kClockWarmupFrames{"time", "clock_warmup_frames", "frames",
    "NVIDIA: warm-up frames added until the GPU's SM clock reached its working level (90 % of its maximum, or steady at 75 %), the last repetition's; not timed",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kClockWarmupSeconds{"time", "clock_warmup_seconds", "s",
    "NVIDIA: the wall time of those added warm-up frames, the last repetition's",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kGpuPowerWEndPattern{"time", "gpu_power_w_<end>", "W",
    "NVIDIA: the GPU's power draw at the start and end of the repetition",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kGpuThrottleReasonsEndPattern{"time", "gpu_throttle_reasons_<end>", "",
    "NVIDIA: the active clock throttle reasons (a bit mask; 0x1 alone is idle) at the start and end of the repetition; a throttle or a clock change is a warning in status_detail",
    ColumnKind::Text, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kTimeIntervalCoverage{"time", "time_interval_coverage", "",
    "the frame interval's coverage: 0.95, or less when too few frames (or repetitions) reach it",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kTimeHalfWidth{"time", "time_half_width", "",
    "relative half-width of the frame median's interval: how precise the record's frame time is",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsMedianPattern{"time", "<subpass>_ms_median", "ms",
    "median over the measured frames of a sub-pass (with repetitions: the median of the repetitions' medians; the sizing policy's census, readback, reallocate, rebuild among them, 0 in frames without), of build (sizing included), pass (the pass's own) or frame",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Lower};
inline const Column kSubpassMsCiLowPattern{"time", "<subpass>_ms_ci_low", "ms",
    "low end of the median's 95% interval (time_interval says how it was made)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsCiHighPattern{"time", "<subpass>_ms_ci_high", "ms",
    "high end of the median's 95% interval",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsRepSpreadPattern{"time", "<subpass>_ms_rep_spread", "",
    "with repetitions: standard deviation of the logs of the repetitions' medians (about the relative spread between repetitions)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsMinPattern{"time", "<subpass>_ms_min", "ms",
    "minimum over the measured frames",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsMaxPattern{"time", "<subpass>_ms_max", "ms",
    "maximum over the measured frames",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kSubpassMsStddevPattern{"time", "<subpass>_ms_stddev", "ms",
    "sample standard deviation over the measured frames (pooled over repetitions)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kBuildVsRaster{"time", "build_vs_raster", "",
    "build median over raster_baseline median (the empty raster pass)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kBuildVsRasterTouch{"time", "build_vs_raster_touch", "",
    "build median over raster_touch median (every fragment shaded, one atomicAdd each)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kBaselineFrames{"time", "baseline_frames", "frames",
    "measured frames on which the two raster baselines were timed: every second one from the first (over every repetition)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRasterTouchFragments{"time", "raster_touch_fragments", "fragments",
    "fragments the raster_touch baseline shaded (checked against the census)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kFragmentsPerSecond{"time", "fragments_per_second", "1/s",
    "census fragments over the build median",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kFrameSamplesCsv{"time", "frame_samples_csv", "",
    "every measured frame's time of every sub-pass (repetition, frame, subpass, ms), path relative to the records",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kFramesTimedMs{"time", "frames_timed_ms", "ms",
    "sum over the measured frames of every timed sub-pass (baselines included): the time the measurement itself took on the device",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kVerifyMs{"time", "verify_ms", "ms",
    "wall time of the measured frames' build checks (untimed; the harness's own cost)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kVerifyWarmupMs{"time", "verify_warmup_ms", "ms",
    "wall time of the warm-up frames' build checks",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kWorkReplayMs{"time", "work_replay_ms", "ms",
    "wall time of the untimed counting replay that gives the work_* columns and of its checks against the measured frames (the harness's own cost)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kVerifyShare{"time", "verify_share", "",
    "verify_ms over frames_timed_ms",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kWallSeconds{"time", "wall_seconds", "s",
    "wall time of the whole configuration (its repetitions summed), reference included",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kMemBufferAllocatedPattern{"memory", "mem_<buffer>_allocated", "bytes",
    "bytes reserved for one of the structure's buffers (for a pass without structure, hbao: one of its render targets; an LDM pass's own, e.g. the indirect pass's photons: not in bytes_allocated)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kMemBufferUsedPattern{"memory", "mem_<buffer>_used", "bytes",
    "bytes of that buffer holding data after the last build",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kBytesAllocated{"memory", "bytes_allocated", "bytes",
    "sum over the structure's buffers (and the census policy's counts), or over a structureless pass's targets",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower};
inline const Column kBytesUsed{"memory", "bytes_used", "bytes",
    "sum over the structure's buffers (or the structureless pass's targets)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower};
inline const Column kRefSpp{"accuracy", "ref_spp", "samples",
    "reference samples per pixel (both halves)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRefNoiseMse{"accuracy", "ref_noise_mse", "",
    "expected MSE of the reference itself: MSE(half A, half B) / 4",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower};
inline const Column kRefNoiseMssim{"accuracy", "ref_noise_mssim", "",
    "MSSIM between the reference's two halves",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRefNoiseTargetMet{"accuracy", "ref_noise_target_met", "",
    "whether the automatic spp rule reached its noise target",
    ColumnKind::Flag, VariesBetweenRuns::No, Better::Neither};
inline const Column kRefRenderSeconds{"accuracy", "ref_render_seconds", "s",
    "time the reference took to render (when it was rendered)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kRefFromCache{"accuracy", "ref_from_cache", "",
    "whether the reference came from the cache",
    ColumnKind::Flag, VariesBetweenRuns::Yes, Better::Neither};
// The multi-bounce reference's counterparts of the two above vary as they do (the pattern
// multi_<column> below declares the rest).
inline const Column kMultiRefRenderSeconds{"accuracy", "multi_ref_render_seconds", "s",
    "indirect: time the multi-bounce reference took to render (when it was rendered)",
    ColumnKind::Number, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kMultiRefFromCache{"accuracy", "multi_ref_from_cache", "",
    "indirect: whether the multi-bounce reference came from the cache",
    ColumnKind::Flag, VariesBetweenRuns::Yes, Better::Neither};
inline const Column kRefCacheKey{"accuracy", "ref_cache_key", "",
    "cache key of the reference (hash of everything it depends on)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kRefRayOffset{"accuracy", "ref_ray_offset", "scene units",
    "largest distance the reference's secondary rays start off the surface",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kRefRayOffsetOk{"accuracy", "ref_ray_offset_ok", "",
    "false when that offset exceeds 1e-3 of d_max or of the scene's radius (the reference may be biased)",
    ColumnKind::Flag, VariesBetweenRuns::No, Better::Neither};
inline const Column kMse{"accuracy", "mse", "",
    "mean squared error against the reference, averaged over channels",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower, Summation::ArrivalOrder};
inline const Column kNrmse{"accuracy", "nrmse", "",
    "sqrt(MSE) over the reference's range",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower, Summation::ArrivalOrder};
inline const Column kPsnr{"accuracy", "psnr", "dB",
    "peak signal-to-noise ratio with the reference's peak",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kMssim{"accuracy", "mssim", "",
    "mean SSIM (Wang et al. 2004, skimage's Gaussian variant)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Higher, Summation::ArrivalOrder};
inline const Column kMseCovered{"accuracy", "mse_covered", "",
    "mse over the covered pixels alone (covered_pixel_fraction's: where the camera sees a surface), not diluted by the background",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower, Summation::ArrivalOrder};
inline const Column kNrmseCovered{"accuracy", "nrmse_covered", "",
    "sqrt(mse_covered) over the reference's range on the covered pixels",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower, Summation::ArrivalOrder};
inline const Column kMssimCovered{"accuracy", "mssim_covered", "",
    "mean of the SSIM map over the covered pixels (inside mssim's 5-pixel crop)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Higher, Summation::ArrivalOrder};
inline const Column kSsimExposure{"accuracy", "ssim_exposure", "",
    "exposure scale applied before SSIM (1 for AO)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither};
inline const Column kMseOverNoise{"accuracy", "mse_over_noise", "",
    "mse over ref_noise_mse: how far the error stands above the reference's noise",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Lower, Summation::ArrivalOrder};
inline const Column kBias{"accuracy", "bias", "",
    "mean of image - reference over every pixel and channel (the error's systematic part; bias^2 is the MSE averaging cannot remove)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kBiasShare{"accuracy", "bias_share", "",
    "bias^2 / mse: the share of the MSE that is the mean offset",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kMeanRatio{"accuracy", "mean_ratio", "",
    "mean of the image over the mean of the reference (1: the same energy in the image)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kMeanRatioSe{"accuracy", "mean_ratio_se", "",
    "standard error of mean_ratio from the reference's noise (ref_noise_mse over the pixels and channels, as if independent)",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kMetricsError{"accuracy", "metrics_error", "",
    "why the image was not measured (NaN or infinity)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kMultiColumnPattern{"accuracy", "multi_<column>", "",
    "indirect: each accuracy and reference-image column (ref_*, mse, nrmse, psnr, mssim, ssim_exposure, mse_over_noise, reference_exr, ssim_map_png, diff_png...) against the multi-bounce reference; the unprefixed ones are against the single-bounce reference",
    ColumnKind::Mixed, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};
inline const Column kImageExr{"images", "image_exr", "",
    "the pass's image, linear EXR (path relative to the records)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kImagePng{"images", "image_png", "",
    "the pass's image, sRGB PNG",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kImageNameExrPattern{"images", "image_<name>_exr", "",
    "the pass's further images (indirect: direct, sum), linear EXR",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kImageNamePngPattern{"images", "image_<name>_png", "",
    "the same, sRGB PNG",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kReferenceExr{"images", "reference_exr", "",
    "the reference, linear EXR (one per reference)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kSsimMapPng{"images", "ssim_map_png", "",
    "SSIM map as a heat map",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDiffPng{"images", "diff_png", "",
    "absolute difference to the reference as a heat map (EXR beside it)",
    ColumnKind::Text, VariesBetweenRuns::No, Better::Neither};
inline const Column kDiffPngMax{"images", "diff_png_max", "",
    "the difference that maps to the top of the heat map",
    ColumnKind::Number, VariesBetweenRuns::No, Better::Neither, Summation::ArrivalOrder};

}  // namespace ldm::columns
