#include "harness/gl/bindings.h"

namespace ldm {

ShaderDefines binding_defines() {
  ShaderDefines d;
  d.set("LDM_STRUCTURE_BINDING0", kStructureBinding0);
  d.set("LDM_STRUCTURE_BINDING1", kStructureBinding0 + 1);
  d.set("LDM_STRUCTURE_BINDING2", kStructureBinding0 + 2);
  d.set("LDM_STRUCTURE_BINDING3", kStructureBinding0 + 3);
  d.set("LDM_COUNTER_BINDING", kStructureCounterBinding);
  d.set("LDM_VIEWS_BINDING", kViewsBinding);
  d.set("LDM_CENSUS_BINDING", kCensusBinding);
  d.set("LDM_VALIDATION_BINDING", kValidationBinding);
  d.set("LDM_INSPECT_BLOCKS_BINDING", kInspectBlocksBinding);
  d.set("LDM_PASS_BINDING0", kPassBinding0);
  d.set("LDM_PASS_BINDING1", kPassBinding0 + 1);
  return d;
}

}  // namespace ldm
