// Ground-truth ambient occlusion (Jimenez, Wu, Pesce and Jarabo 2016, "Practical Real-Time
// Strategies for Accurate Indirect Occlusion", Algorithm 1) from the camera's position/normal
// G-buffer, with the reference's attenuation applied to each rise of the horizon.
//
// The hemisphere around the shading normal n is cut into GTAO_SLICES planes that all contain
// the view vector v (x towards the eye); slice k holds the direction d_k at angle
// phi_k = (k + noise) / GTAO_SLICES * pi about v (uniform about v, where the paper steps
// uniformly in screen space: the same about the image's centre, biased off it), its axis
// a = d x v; on screen it is the line through x's pixel along d's projection. In a slice, a
// direction is the angle theta from v (positive towards +d), the cosine-weighted integrand is
// cos(theta - gamma) |sin theta| (gamma the angle of n's projection n_p into the slice) and its
// integral has the closed form of the paper's Eq. 10:
//   G(theta) = (2 theta sin gamma - cos(2 theta - gamma)) / 4   (theta >= 0),
// so that a slice's open hemisphere [gamma - pi/2, gamma + pi/2] integrates to
// cos gamma + gamma sin gamma, and |n_p| times that, averaged over phi, is exactly 1.
//
// On each side of x, GTAO_STEPS samples march out to the radius R (scene units, projected at
// x's depth) at distances ((j + noise) / GTAO_STEPS)^power of it. A sample within R, above x's
// tangent plane and above the current horizon raises the horizon from theta_h to its angle
// theta_s, and the directions between them count as occluded with the weight
//   W(r) = 1 - V(r), V the reference's visibility of a hit at the sample's distance r
//   (attenuated: min(r / d_max, 1)^e; unattenuated: 0, so W = 1 within R),
// times an optional linear fade over the last `falloff` fraction of R (XeGTAO's falloff).
// GTAO_REFERENCE_WEIGHTS 0 (gtao:attenuation=binary) sets W = 1 within R whatever the
// reference's visibility, the engines' binary horizon with only the fade: what the
// reference's attenuation is worth is the difference.
// With W = 1 the sum telescopes to the paper's single-horizon integral; with the reference's
// V it is exact in the limit of many steps wherever the surface seen along the slice's screen
// line is what the slice's rays hit first (a height field seen from the camera): the sample
// that raises the horizon to theta is then the hit of the ray at theta. What the depth buffer
// does not hold (occluders behind visible surfaces, off screen, beyond R) it cannot weigh.
//
// Thickness (the paper's §4.3 heuristic, beta = gtao_thickness): a sample below the horizon
// pulls the horizon towards itself, theta_h += beta (theta_s - theta_h), so that rays may pass
// behind thin occluders; the band it uncovers gives back its occlusion at the band's mean
// weight (the weights are not kept per direction). beta = 0 is the height-field assumption.
//
// The slices combine as the paper's mean of |n_p| times the slice's visibility
// (GTAO_NORMALIZED 0), or as that sum over the sum of the open hemispheres' |n_p| (cos gamma +
// gamma sin gamma) (GTAO_NORMALIZED 1): then an unoccluded point is exactly 1 for any slice
// count, where the mean has the quadrature error of GTAO_SLICES directions.
#include "common/work_counters.glsl"
layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D gbuffer_normal;
uniform vec3 camera_eye;
uniform vec3 camera_forward;
uniform vec3 camera_right;
uniform vec3 camera_up;
uniform float focal_pixels;         // (height / 2) / tan(fov_y / 2)
uniform float gtao_radius;          // R, scene units
uniform float gtao_d_max;           // the reference's d_max
uniform float gtao_falloff_exponent;  // e of V = min(r / d_max, 1)^e
uniform float gtao_falloff;         // fraction of R over which W fades to 0 at R (0: none)
uniform float gtao_thickness;       // beta of the thickness heuristic (0: height field)
uniform float gtao_step_power;      // sample distribution: distance = R * u^power
uniform float gtao_sin_bias;        // a sample must rise this much (sin of an angle) above x's tangent plane
uniform int gtao_jitter;            // 1: per-pixel slice rotation and step offset
layout(location = 0) out float out_ao;

const float kPi = 3.14159265358979;

#if WORK_COUNTING
uint work_samples = 0u, work_rises = 0u;  // of the pixel: G-buffer samples read, horizon rises
#endif

// The 4x4 Bayer matrix: 16 stratified values in every 4x4 block of pixels, so that a denoise
// over a few pixels averages evenly spread slice rotations and step offsets.
float bayer4(ivec2 p) {
  const int m[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
  return (float(m[(p.y & 3) * 4 + (p.x & 3)]) + 0.5) / 16.0;
}

// The antiderivative of cos(theta - gamma) sin(theta) for theta >= 0 (see the header).
float arc_integral(float theta, float gamma) {
  return (2.0 * theta * sin(gamma) - cos(2.0 * theta - gamma)) * 0.25;
}

// The weight W(r) of an occluder at distance r: 1 - V(r), faded over the last falloff of R.
float occluder_weight(float r) {
#if GTAO_REFERENCE_WEIGHTS
  const float ratio = min(r / gtao_d_max, 1.0);
  float w = 1.0 - (gtao_falloff_exponent == 2.0 ? ratio * ratio : pow(ratio, gtao_falloff_exponent));
#else
  float w = 1.0;
#endif
  if (gtao_falloff > 0.0) w *= clamp((gtao_radius - r) / (gtao_falloff * gtao_radius), 0.0, 1.0);
  return w;
}

// The visible part of one side of a slice: the integral from 0 (v) to the hemisphere's edge
// gamma + pi/2, less the occluded bands. `side` is +1 (towards +d) or -1; on the -d side the
// angles are mirrored, which turns gamma into -gamma.
float side_visibility(vec2 pixel, vec2 direction, float side, float gamma, vec3 x, vec3 n,
                      vec3 v, float radius_pixels, float step_noise, vec2 size) {
  const float g = side * gamma;
  const float theta_low = g + 0.5 * kPi;
  const float low_integral = arc_integral(theta_low, g);
  float theta_h = theta_low;
  float occlusion = 0.0;
  for (int j = 0; j < GTAO_STEPS; ++j) {
    const float u = pow((float(j) + step_noise) / float(GTAO_STEPS), gtao_step_power);
    // From 1 pixel (x's own never tells anything) out to R.
    const vec2 sample_pixel = pixel + side * direction * (1.0 + u * (radius_pixels - 1.0));
    if (any(lessThan(sample_pixel, vec2(0.0))) || any(greaterThanEqual(sample_pixel, size)))
      break;  // off screen: the depth buffer knows nothing there
#if WORK_COUNTING
    ++work_samples;
#endif
    const vec4 sample_position = texelFetch(gbuffer_position, ivec2(sample_pixel), 0);
    if (sample_position.w == 0.0) continue;  // background occludes nothing
    const vec3 delta = sample_position.xyz - x;
    const float r = length(delta);
    if (r == 0.0 || r > gtao_radius) continue;
    // On or below x's tangent plane (x's own surface, read a little off the slice's line):
    // no occluder of x's hemisphere.
    if (dot(delta, n) <= gtao_sin_bias * r) continue;
    const float theta_s = acos(clamp(dot(delta, v) / r, -1.0, 1.0));
    if (theta_s < theta_h) {
      occlusion += occluder_weight(r) * (arc_integral(theta_h, g) - arc_integral(theta_s, g));
      theta_h = theta_s;
#if WORK_COUNTING
      ++work_rises;
#endif
    } else if (gtao_thickness > 0.0) {
      const float theta_new = min(theta_h + gtao_thickness * (theta_s - theta_h), theta_low);
      const float band = low_integral - arc_integral(theta_h, g);
      if (band > 0.0) {
        const float uncovered = arc_integral(theta_new, g) - arc_integral(theta_h, g);
        occlusion -= occlusion / band * uncovered;
      }
      theta_h = theta_new;
    }
  }
  return low_integral - arc_integral(0.0, g) - occlusion;
}

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 position = texelFetch(gbuffer_position, pixel, 0);
  work_add(fragments, 1);
  if (position.w == 0.0) {  // background
    out_ao = 0.0;
    return;
  }
  work_add(covered_pixels, 1);
#if WORK_COUNTING
  uint work_slices = 0u;  // slices marched (both sides), of the pixel
#endif
  const vec3 x = position.xyz;
  const vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  const vec3 v = normalize(camera_eye - x);
  const float view_depth = dot(x - camera_eye, camera_forward);
  const float radius_pixels = gtao_radius * focal_pixels / view_depth;
  const vec2 size = vec2(textureSize(gbuffer_position, 0));
  const float slice_noise = gtao_jitter != 0 ? bayer4(pixel) : 0.5;
  // An orthonormal pair about v: the slices' directions.
  const vec3 to_x = x - camera_eye;
  const vec3 t1 = normalize(camera_right - dot(camera_right, v) * v);
  const vec3 t2 = cross(v, t1);
  const float step_noise = gtao_jitter != 0 ? bayer4(pixel.yx + ivec2(1, 2)) : 0.5;

  float visible = 0.0, open = 0.0;
  for (int k = 0; k < GTAO_SLICES; ++k) {
    // The slice's direction d, at angle phi about v from t1: uniform about the view vector,
    // as the integral over phi assumes (uniform screen directions are not, off the image's
    // centre, and would bias the mean estimator there).
    const float phi = (float(k) + slice_noise) / float(GTAO_SLICES) * kPi;
    const vec3 d = cos(phi) * t1 + sin(phi) * t2;
    const vec3 axis = cross(d, v);
    // The slice plane holds the eye: on screen it is the line through x's pixel along the
    // projection of d (the derivative of x + s d's pixel position at s = 0; GL rows, y up).
    const vec2 along = vec2(dot(d, camera_right), dot(d, camera_up)) * view_depth -
                       vec2(dot(to_x, camera_right), dot(to_x, camera_up)) * dot(d, camera_forward);
    if (dot(along, along) == 0.0) continue;  // d along the pixel's ray: no slice on screen
    const vec2 direction = normalize(along);
    const vec3 n_p = n - axis * dot(n, axis);
    const float n_p_length = length(n_p);
    if (n_p_length < 1e-6) continue;  // n normal to the slice: it weighs nothing
    const float gamma = sign(dot(n_p, d)) * acos(clamp(dot(n_p, v) / n_p_length, -1.0, 1.0));
    if (radius_pixels >= 1.0) {
#if WORK_COUNTING
      ++work_slices;
#endif
      visible += n_p_length * (side_visibility(gl_FragCoord.xy, direction, 1.0, gamma, x, n, v,
                                               radius_pixels, step_noise, size) +
                               side_visibility(gl_FragCoord.xy, direction, -1.0, gamma, x, n, v,
                                               radius_pixels, step_noise, size));
    } else {  // R covers no pixel: nothing to see, the slice is open
      visible += n_p_length * (cos(gamma) + gamma * sin(gamma));
    }
    open += n_p_length * (cos(gamma) + gamma * sin(gamma));
  }
  work_add(slices, work_slices);
  work_add(samples, work_samples);
  work_add(horizon_rises, work_rises);
  work_sample(steps, work_samples);
#if GTAO_NORMALIZED
  out_ao = open > 0.0 ? visible / open : 1.0;
#else
  out_ao = visible / float(GTAO_SLICES);
#endif
}
