#pragma once
// measure()'s frames one at a time. measure() runs a session for warm-up + measured frames
// and returns its result(); the interactive viewer (`ldmbench view`) runs the same session
// frame by frame, moving the camera in between, and shows the same Measurement after each
// frame. So what the viewer shows is what `ldmbench run` records, by construction.
//
// A pass that reads a structure gets the whole LDM frame (raster baselines │ build under the
// sizing policy │ pass, judged after every frame: ldm_impls/common/build_verifier.h); the
// raster baselines only on every kBaselineFrameStride-th measured frame (and the first
// warm-up frame). A peer pass (requirements().needs_structure false) gets its frames alone.
#include <memory>

#include "harness/measuring/measurement.h"

namespace ldm {

struct LdmSetup;

inline constexpr int kBaselineFrameStride = 2;

class MeasurementSession {
 public:
  // Throws what measure() throws (UserError, GpuError).
  MeasurementSession(const Scene& scene, const MeasurementRequest& request);
  ~MeasurementSession();
  MeasurementSession(const MeasurementSession&) = delete;
  MeasurementSession& operator=(const MeasurementSession&) = delete;

  // Runs one frame and judges it. The first request.warmup frames are warm-up (judged, not
  // kept); every later frame is kept in result().frames. Returns the frame's times, with
  // the sums "build" (LDM passes), "pass" and "frame" added for kept frames.
  FrameTimes run_frame();
  int frames_run() const;
  bool in_warmup() const;
  // Makes the next frame one more warm-up frame (the clock warm-up's, clock_warmup.h).
  void add_warmup_frame();

  // The untimed counting replay, after the measured frames: the structure and the pass
  // prepared again inside a WorkCountingScope (their counting variants,
  // harness/measure/work_counters.h), one frame to settle the sizing, then one counted frame.
  // Its sorted lists (the inspector's checksum) and its images must equal the measured
  // frames': counting provably changed nothing, else result() is invalid. Its wall time is
  // the harness's own (work_replay_ms), never a measured frame's.
  void count_work();

  // What measure() returns for the frames run so far (the last frame's images read back).
  // After count_work(), what the measured instances read back was taken before the replay
  // (which borrows their storage, gl_objects.h), with the replay's counters and verdict.
  Measurement result() const;

  // The scene the GPU computes in (LdmSetup's centred frame for LDM passes; the scene as
  // given for peers). Its camera is the one the pass renders from.
  const Scene& scene() const;
  // Moves the pass's camera (in scene()'s frame). The pass is prepared anew, since a pass
  // may read the camera when it is prepared; the structure, its build and the frames kept
  // so far stay.
  void set_camera(const Camera& camera);

  const Pass& pass() const;
  // Null for a peer pass.
  const LdmSetup* setup() const;
  const LdmStructure* structure() const;

 private:
  // The measured instances' readings: images, results, memory, loss and the builds' verdict.
  Measurement measured_result() const;

  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace ldm
