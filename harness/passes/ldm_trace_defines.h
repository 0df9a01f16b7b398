#pragma once
// The defines every shader that traces an LDM (passes/ao.frag, passes/indirect/
// photon_trace.comp) takes besides its own: the structure's query defines, the view count,
// the trace variant (LDM_TRACE_*), the plane trace's tolerances (harness/scene/ao_variants.h)
// and the trace-step counter's binding (trace_steps.h).
#include <cstddef>
#include <string>

#include "harness/gl/shader_program.h"
#include "harness/scene/ao_variants.h"
#include "ldm_impls/ldm_structure.h"

namespace ldm {

// A GLSL float literal that round-trips the double (as a float; the constants are exact).
std::string glsl_float(double value);

void add_ldm_trace_defines(ShaderDefines& defines, const LdmStructure& structure,
                           size_t view_count, AoTrace trace);

}  // namespace ldm
