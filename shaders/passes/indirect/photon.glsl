// One stored photon differential (thesis §5.3.2, Listing 10), as the photon buffer holds it.
// position.w and normal.w carry, as bits, the light texel and the direction the photon came
// from (texel index; view * 2 + (ahead ? 1 : 0)), so that tests can recompute its flux.
#ifndef PHOTON_GLSL
#define PHOTON_GLSL
struct Photon {
  vec4 position;  // xyz: where it landed (scene frame)
  vec4 normal;    // xyz: the receiving surface's normal (camera G-buffer, faces the camera)
  vec4 du;        // xyz: positional differential D_u x for one light texel (unscaled)
  vec4 dv;        // xyz: D_v x
  vec4 flux;      // rgb: radiant flux (W)
};

// Counters of one photon-tracing pass (the C++ side reads them back, photon_lighting.cpp).
#define PHOTON_COUNT_APPENDS 0u          // append attempts: stored + overflow
#define PHOTON_COUNT_PRIMARY 1u          // light texels in the cone that hit a surface
#define PHOTON_COUNT_PRIMARY_DEGENERATE 2u
#define PHOTON_COUNT_EMITTED 3u          // secondary photons into the hit's hemisphere
#define PHOTON_COUNT_ESCAPED 4u          // traced, nothing hit
#define PHOTON_COUNT_CULLED_DEPTH 5u     // hit not seen by the camera (the three below)
#define PHOTON_COUNT_CULLED_FOOTPRINT 6u
#define PHOTON_COUNT_DEGENERATE 7u       // secondary differential degenerate
#define PHOTON_COUNT_CULLED_OUTSIDE 8u   //   of CULLED_DEPTH: off the image or over background
#define PHOTON_COUNT_CULLED_BACKSIDE 9u  //   of CULLED_DEPTH: on the side the camera does not see
#define PHOTON_COUNTERS 10u              //   (the rest of CULLED_DEPTH: hidden, behind the surface seen)

// The flux tally, PHOTON_TALLY_ENTRIES vec4 per light texel (rgb; the flux audit,
// harness/passes/photon_lighting.h): where each texel's flux went.
#define PHOTON_TALLY_PRIMARY 0u          // w = 1 where a primary photon was emitted
#define PHOTON_TALLY_EMITTED 1u          // into secondaries (the sum of the fates below)
#define PHOTON_TALLY_ESCAPED 2u
#define PHOTON_TALLY_CULLED_OUTSIDE 3u
#define PHOTON_TALLY_CULLED_HIDDEN 4u
#define PHOTON_TALLY_CULLED_BACKSIDE 5u
#define PHOTON_TALLY_CULLED_FOOTPRINT 6u
#define PHOTON_TALLY_DEGENERATE 7u
#define PHOTON_TALLY_STORED 8u
#define PHOTON_TALLY_OVERFLOW 9u
#define PHOTON_TALLY_REFLECTED 10u       // rho * Phi1 of a primary that was split
#define PHOTON_TALLY_ENTRIES 11u
#endif
