#pragma once
// The record columns that say what a configuration was measured on, and whether the
// measurement measures anything (issue 22):
//  - the scene's size (bounding-sphere radius) and where its camera, light and d_max came
//    from (generator, scene file, --d-max, or derived from the size: scene_defaults.h);
//  - the depth-complexity profile of the configuration's census (p50, p90, p99, the
//    histogram, and for a fixed array the share of pixels beyond its k), which explains a
//    ranking;
//  - degenerate measurements: a reference without noise (every sample agreed: a constant
//    image, e.g. AO = 1 where d_max reaches no occluder), an image in which the camera sees
//    no surface, an AO range shorter than a few LDM pixels. They are listed in `degenerate`
//    and in status_detail, and the report never ranks them (scripts/report).
#include "harness/measuring/measurement.h"
#include "harness/settings/run_settings.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

// An AO range (d_max) shorter than this many LDM pixels is resolved by the LDMs only as a
// few depth samples: the trace cannot tell the occluders within it apart.
inline constexpr double kMinAoRangeLdmPixels = 3.0;

// Adds scene_radius, the *_source columns, the depth_* profile and d_max_ldm_pixels.
void add_scene_profile(Record& record, const Scene& scene, const Configuration& config,
                       const Measurement& measurement);

// After the accuracy columns: `degenerate` (the reasons, "; "-separated, empty when none),
// each reason appended to status_detail too. Reads the record's own columns.
void flag_degenerate_measurement(Record& record);

}  // namespace ldm
