// The LDM views (harness/views/view_set.h, GpuViewSet): one entry per view direction.
#ifndef LDM_VIEWS_GLSL
#define LDM_VIEWS_GLSL

struct LdmView {
  mat4 view_projection;  // world -> clip, orthographic
  vec4 eye;              // xyz: centre of the image plane; w: pixel size (scene units)
  vec4 forward;          // xyz: viewing direction; w: depth range (far plane)
  vec4 right;            // xyz: image x axis; w: half extent of the image plane
  vec4 up;               // xyz: image y axis; w: half extent
  uvec4 dims;            // x, y: resolution; z: first pixel of this view in all-view arrays; w: view index
};

layout(std430, binding = LDM_VIEWS_BINDING) readonly restrict buffer LdmViews {
  LdmView ldm_views[];
};

#endif
