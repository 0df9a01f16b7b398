// The point cloud of `ldmbench view` (harness/viewer/point_cloud.h): every depth a built
// structure stores for the pixels [first, first + count) is read back through the query API
// (as passes read it), reconstructed to a point in the scene's frame on the GPU, and written
// to slot pixel * POINT_LAYERS + layer (w = layer index, view index in the high half;
// w < 0: an empty slot). Nothing of the structure is copied to the CPU.
layout(local_size_x = 64) in;

#include "common/ldm_query_api.glsl"
#include "ldm/common/compute_grid.glsl"

struct CloudPoint {
  vec4 position;  // xyz in the scene's frame; w: layer + 65536 * view, or -1 (empty)
};

layout(std430, binding = LDM_VALIDATION_BINDING) restrict buffer Cloud {
  uint cloud_stored;  // depths read (all layers)
  uint cloud_shown;   // depths written (the first POINT_LAYERS of each pixel)
  uint cloud_pad[2];
  CloudPoint cloud_points[];
};

uniform uint cloud_first_pixel;
uniform uint cloud_pixel_count;

// The view holding all-view pixel index `pixel` (views are contiguous, in order).
uint view_of(uint pixel) {
  uint view = 0u;
  while (view + 1u < uint(ldm_views.length()) && ldm_views[view + 1u].dims.z <= pixel) ++view;
  return view;
}

void main() {
  const uint local = linear_invocation_index();
  if (local >= cloud_pixel_count) return;
  const uint pixel = cloud_first_pixel + local;
  const uint view = view_of(pixel);
  const LdmView v = ldm_views[view];
  const uint texel = pixel - v.dims.z;
  const uvec2 ij = uvec2(texel % v.dims.x, texel / v.dims.x);
  // The pixel centre on the image plane (harness/views/view_set.h).
  const vec2 ndc = (vec2(ij) + 0.5) / vec2(v.dims.xy) * 2.0 - 1.0;
  const vec3 on_plane = v.eye.xyz + v.right.xyz * v.right.w * ndc.x + v.up.xyz * v.up.w * ndc.y;
  uint layer = 0u;
  for (LdmCursor c = ldm_begin(pixel); ldm_valid(c) && layer < LDM_MAX_LIST_LENGTH;
       c = ldm_next(c)) {
    if (layer < POINT_LAYERS) {
      const vec3 p = on_plane + v.forward.xyz * ldm_depth(c);
      cloud_points[local * POINT_LAYERS + layer].position =
          vec4(p, float(layer) + 65536.0 * float(view));
    }
    ++layer;
  }
  for (uint k = layer; k < POINT_LAYERS; ++k) cloud_points[local * POINT_LAYERS + k].position = vec4(0, 0, 0, -1);
  atomicAdd(cloud_stored, layer);
  atomicAdd(cloud_shown, min(layer, POINT_LAYERS));
}
