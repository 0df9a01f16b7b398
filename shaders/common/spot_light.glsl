// The scene's spot light (harness/scene/spot_light.h is the C++ copy the references use; the
// indirect tests check that the two agree): radiant intensity `intensity` (W/sr) along
// `direction`, scaled by a smoothstep in the cosine of the angle to it, from 0 at
// cos(outer) to 1 at cos(inner).
#ifndef SPOT_LIGHT_GLSL
#define SPOT_LIGHT_GLSL

uniform vec3 spot_position;
uniform vec3 spot_direction;  // unit
uniform vec3 spot_intensity;  // W/sr on the axis
uniform float spot_cos_inner;
uniform float spot_cos_outer;

// Written out rather than GLSL's smoothstep, which is undefined for edge0 >= edge1 (a spot
// whose inner and outer angles coincide is a hard-edged cone).
float spot_falloff(float cos_angle) {
  if (spot_cos_inner <= spot_cos_outer) return cos_angle >= spot_cos_inner ? 1.0 : 0.0;
  const float t = clamp((cos_angle - spot_cos_outer) / (spot_cos_inner - spot_cos_outer), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// W/sr toward `direction_from_light` (any length but zero).
vec3 spot_radiant_intensity(vec3 direction_from_light) {
  return spot_intensity * spot_falloff(dot(normalize(direction_from_light), spot_direction));
}

#endif
