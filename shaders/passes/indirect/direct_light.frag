// Direct light from the spot at the camera G-buffer's points, shadowed by the light's
// G-buffer used as a shadow map: L = rho/pi * I(x - light) * max(0, n.l) / r^2, where the
// light's texel toward x holds a surface no nearer than x (within a slope-scaled bias).
#include "common/spot_light.glsl"
#include "common/work_counters.glsl"

layout(binding = 0) uniform sampler2D camera_position;
layout(binding = 1) uniform sampler2D camera_normal;
layout(binding = 2) uniform sampler2D camera_albedo;
layout(binding = 3) uniform sampler2D light_position;  // the shadow map
uniform mat4 light_view_projection;
uniform float light_texel_angle;  // 2 tan(outer) / R_light: a texel's width at distance 1
layout(location = 0) out vec4 out_radiance;

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 x = texelFetch(camera_position, pixel, 0);
  out_radiance = vec4(0.0);
  work_add(fragments, 1);
  if (x.w == 0.0) return;
  work_add(covered_pixels, 1);
  const vec3 n = texelFetch(camera_normal, pixel, 0).xyz;
  const vec3 to_light = spot_position - x.xyz;
  const float r = length(to_light);
  const vec3 l = to_light / r;
  const float cos_x = dot(n, l);
  if (!(cos_x > 0.0)) return;
  const vec4 clip = light_view_projection * vec4(x.xyz, 1.0);
  if (!(clip.w > 0.0)) return;
  const vec2 ndc = clip.xy / clip.w;
  if (any(greaterThan(abs(ndc), vec2(1.0)))) return;  // outside the cone's square
  const ivec2 size = textureSize(light_position, 0);
  const ivec2 texel = min(ivec2((ndc * 0.5 + 0.5) * vec2(size)), size - 1);
  const vec4 occluder = texelFetch(light_position, texel, 0);
  // A texel spans r * light_texel_angle here; on a surface tilted by theta its depths vary by
  // that times tan(theta) (capped), plus a texel's worth for the rasterised centre.
  const float tan_x = min(sqrt(max(0.0, 1.0 - cos_x * cos_x)) / cos_x, 8.0);
  const float bias = r * light_texel_angle * (1.0 + tan_x);
  if (occluder.w != 0.0 && distance(occluder.xyz, spot_position) < r - bias) return;
  const vec3 rho = texelFetch(camera_albedo, pixel, 0).rgb;
  out_radiance = vec4(rho / 3.14159265358979 * spot_radiant_intensity(-to_light) * cos_x / (r * r), 0.0);
}
