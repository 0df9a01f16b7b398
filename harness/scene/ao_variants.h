#pragma once
// Variants of the LDM AO pass that are run axes (`ldmbench run --trace`, `--ao-estimator`):
// how the trace tells x's own surface from its occluders (shaders/passes/ldm_trace.glsl), and
// how the N directions' contributions are combined (shaders/passes/ao.frag). The reference
// depends on neither.
#include <string>
#include <vector>

namespace ldm {

enum class AoTrace {
  Listing5,  // thesis Listing 5: the fragment nearest x in depth is x's own surface
  Interval,  // behind: last fragment below x's depth, ahead: first above; needs offset >= ~0.7
  Plane,     // skip fragments near x's own plane predicted at the LDM pixel centre
};

enum class AoEstimatorChoice {
  Eq13,        // thesis Eq. 13: 2/N sum V |cos|; may exceed 1 (a quadrature of the cosine)
  Normalized,  // sum V |cos| / sum |cos|: exactly 1 where nothing occludes, at any N
};

// The default of the --trace axis (chosen from measurements, see docs/measured/trace-variants.md).
inline constexpr AoTrace kDefaultAoTrace = AoTrace::Plane;

// `interval` leaves x's own surface behind x only if the offset (k·s·tan a in depth) beats
// the pixel-centre error ((s/sqrt 2)·tan a): k > 1/sqrt(2) px at every angle a.
inline constexpr double kIntervalMinNormalOffset = 0.70710678118654752;

// The plane trace's tolerance in LDM pixels: kPlaneToleranceConstant + kPlaneToleranceSlope *
// min(tan(angle(n, view axis)), kPlaneMaxSlope). The prediction is exact for a planar surface,
// so the tolerance covers only rasterisation and float error; the slope term grows with how
// fast the surface's depth changes across a pixel. Passed to the shader as defines.
inline constexpr double kPlaneToleranceConstant = 0.0625;
inline constexpr double kPlaneToleranceSlope = 0.25;
inline constexpr double kPlaneMaxSlope = 16.0;

std::string ao_trace_name(AoTrace t);                  // "listing5", "interval", "plane"
std::string ao_estimator_name(AoEstimatorChoice e);          // "eq13", "normalized"
std::vector<std::string> ao_trace_names();
std::vector<std::string> ao_estimator_names();
AoTrace parse_ao_trace(const std::string& name);       // throws UserError naming the choices
AoEstimatorChoice parse_ao_estimator(const std::string& name);

}  // namespace ldm
