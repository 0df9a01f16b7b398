#pragma once
// Measures one configuration of a sweep: builds the structure for the scene's LDM views,
// runs the pass, times every sub-pass over the measured frames, checks every build's
// integrity, writes the images and returns the record.
#include <string>

#include "harness/app/run_settings.h"
#include "harness/gl/egl_context.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

struct MeasurementPaths {
  std::string out_dir;     // where records.csv lives; image paths are relative to it
  std::string images_dir;  // absolute or relative to the working directory
};

// Throws (UserError or GpuError) when the configuration cannot be measured; the caller turns
// that into a "failed" record and goes on with the sweep.
Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths);

// Fields every record carries, also failed ones: identity of the configuration and device.
void describe_configuration(Record& record, const Configuration& config,
                            const RunSettings& settings, const DeviceInfo& device);

}  // namespace ldm
