#pragma once
// One configuration of `ldmbench run` as a record: measure() (harness/app/measurement.h),
// then the pass's images written, scored against its reference, and everything laid out in
// the record's columns (harness/records/columns.h describes each).
#include <string>

#include "harness/app/measurement.h"
#include "harness/app/run_settings.h"
#include "harness/gl/egl_context.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

struct MeasurementPaths {
  std::string out_dir;     // where records.csv lives; image paths are relative to it
  std::string images_dir;  // absolute or relative to the working directory
};

// The measurement a configuration of a sweep asks for.
MeasurementRequest measurement_request(const Configuration& config, const RunSettings& settings,
                                       const DeviceInfo& device);

// Throws (UserError or GpuError) when the configuration cannot be measured; the caller turns
// that into a "failed" record and goes on with the sweep.
Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths);

// Fields every record carries, also failed ones: identity of the configuration and device.
void describe_configuration(Record& record, const Configuration& config,
                            const RunSettings& settings, const DeviceInfo& device);

// The measured columns of a record, in the order records have always had them.
void add_measurement(Record& record, const Measurement& measurement);

}  // namespace ldm
