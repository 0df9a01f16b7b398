#pragma once
// One configuration of `ldmbench run` as a record: measure() (harness/measuring/measurement.h),
// then the pass's images written, scored against its reference, and everything laid out in
// the record's columns (harness/records/columns.h describes each).
#include <string>

#include "harness/measuring/measurement.h"
#include "harness/settings/run_settings.h"
#include "harness/gl/egl_context.h"
#include "harness/records/record.h"
#include "harness/scene/scene.h"

namespace ldm {

struct MeasurementPaths {
  std::string out_dir;     // where records.csv lives; image paths are relative to it
  std::string images_dir;  // absolute or relative to the working directory
  // Collects every file the configuration writes (images, samples), when given.
  std::vector<std::string>* written = nullptr;
};

// The measurement a configuration of a sweep asks for.
MeasurementRequest measurement_request(const Configuration& config, const RunSettings& settings,
                                       const DeviceInfo& device);

// Which repetition of how many a record measures (harness/measuring/repetitions.h): repetition 0
// is the whole record (images, accuracy against the reference); later ones are timed and
// judged only. With one repetition the record is final; with more, each one's frames go to
// samples/<id>-rep<index>-frames.csv until the repetitions are combined.
struct Repetition {
  size_t index = 0, count = 1;
};

// Throws (UserError or GpuError) when the configuration cannot be measured; the caller turns
// that into a "failed" record and goes on with the sweep.
Record measure_configuration(const Scene& scene, const Configuration& config,
                             const RunSettings& settings, const DeviceInfo& device,
                             const MeasurementPaths& paths, Repetition repetition = {});

// Fields every record carries, also failed ones: identity of the configuration and device.
void describe_configuration(Record& record, const Configuration& config,
                            const RunSettings& settings, const DeviceInfo& device);

// The samples file of a configuration's repetition: "<id>-frames.csv" for the only or the
// combined one, "<id>-rep<index>-frames.csv" for one of several before they are combined.
std::string samples_file_name(const std::string& config_id, Repetition repetition);

}  // namespace ldm
