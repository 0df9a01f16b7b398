// Per-triangle diffuse albedo (GpuScene's material buffers, uploaded when a pass asks for
// materials): gl_PrimitiveID of a non-instanced glDrawElements is the triangle's index.
#ifndef SURFACE_ALBEDO_GLSL
#define SURFACE_ALBEDO_GLSL
layout(std430, binding = INDIRECT_MATERIALS_BINDING) readonly restrict buffer TriangleMaterials {
  uint triangle_material[];
};
layout(std430, binding = INDIRECT_ALBEDO_BINDING) readonly restrict buffer MaterialAlbedo {
  vec4 material_albedo[];
};
vec3 surface_albedo(int triangle) { return material_albedo[triangle_material[triangle]].rgb; }
#endif
