#pragma once
// The ambient-occlusion settings as axes (d_max, visibility, the normal offset, the LDM
// trace variant and the AO estimator), declared once here, below the passes, so that the
// scene loader checks a scene file's d_max and normal offset by the same declarations the
// command line uses. The passes read them through harness/passes/ao_parameters.h.
#include "harness/axes/axis.h"

namespace ldm {

enum class AoAxis { DMax, Visibility, NormalOffset, Trace, Estimator };

// The harness axis (key as in sweep files, command-line flags, record column).
AxisSpec ao_axis(AoAxis which);
// The same declaration as the pass reads it (key = the pass parameter's name).
AxisSpec ao_pass_parameter(AoAxis which);

}  // namespace ldm
