#pragma once
// The scene: one triangle soup with per-triangle materials, a camera, a spot light and the
// ambient-occlusion settings. Everything a pass or a reference renderer reads comes from here.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/scene/ao_variants.h"

namespace ldm {

struct Material {
  std::string name;
  glm::vec3 albedo{0.8f};  // diffuse reflectance, linear RGB
};

// Vertex positions and shading normals (same length), triangles as index triples, one
// material index per triangle. Flat-shaded geometry simply repeats vertices per face.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::uvec3> triangles;
  std::vector<uint32_t> triangle_materials;

  size_t triangle_count() const { return triangles.size(); }
};

// A pinhole camera. Pixel (x, y) of a W x H image (y = 0 the top row) looks through
//   ndc = ((x + 0.5) / W * 2 - 1, 1 - (y + 0.5) / H * 2),
//   dir = normalize(forward + ndc.x * tan(fov_y / 2) * W / H * right + ndc.y * tan(fov_y / 2) * up)
// on both the GPU (rasterised pixel centres) and the reference renderer (primary rays).
struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 40.0f;
};

// Whether `up` fixes the camera's roll: it must not lie within ~0.06 degrees of the view
// direction, where right = normalize(cross(forward, up)) would be rounding noise (or NaN).
bool camera_up_is_usable(const Camera& camera);

// The largest coordinate magnitude a scene may have. Bounding spheres, view matrices and the
// reference's BVH square and sum coordinate differences in 32-bit floats: with |x| <= 1e18,
// (2|x|)^2 * 3 stays below FLT_MAX (3.4e38) with a margin of 20x; beyond it they overflow to inf.
inline constexpr float kMaxSceneCoordinate = 1e18f;

// A spot light: radiant intensity `intensity` (W/sr, RGB) along `direction`, smoothly
// falling to zero between the inner and outer cone angles.
struct SpotLight {
  glm::vec3 position{0.0f, 1.0f, 0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  glm::vec3 intensity{10.0f};
  float inner_angle_deg = 30.0f;
  float outer_angle_deg = 45.0f;
};

// Ambient occlusion settings of thesis §4.1.2 and §4.4.2.
struct AoSettings {
  bool attenuated = true;        // V = min(d / d_max, 1)^falloff; otherwise V = (no hit) ? 1 : 0
  float d_max = 1.0f;            // attenuation distance, scene units
  float falloff_exponent = 2.0f;
  // Normal offset of §4.4.2, in LDM pixels: x += n * sin(angle(n, w)) * normal_offset * pixel.
  // Expressed in pixels (not scene units) so that it scales with R_LDM. The default, 0.5, is
  // the measured best compromise for the default (plane) trace (docs/measured/trace-variants.md).
  float normal_offset_pixels = 0.5f;
  // LDM pass only (run axes, not scene properties; no reference depends on them).
  AoTrace trace = kDefaultAoTrace;
  AoEstimatorChoice estimator = AoEstimatorChoice::Eq13;
};

// What a run or a reference asks to change in the scene's AO settings; unset fields keep
// the scene's own.
struct AoOverrides {
  std::optional<float> d_max;
  std::optional<bool> attenuated;
  std::optional<float> normal_offset_pixels;
  std::optional<AoTrace> trace;
  std::optional<AoEstimatorChoice> estimator;
};
AoSettings apply_ao_overrides(AoSettings scene_ao, const AoOverrides& overrides);

struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
};

// The precision a mesh file must hold its coordinates to, relative to the scene's extent
// (bounding-box diagonal): 2^-16, the AO trace's own depth resolution (range / 65536), so a
// coarser rounding is detail the LDMs would resolve.
inline constexpr double kFarFileSpacing = 1.0 / 65536.0;

struct Bounds {
  glm::vec3 lo{0.0f}, hi{0.0f};
};

// Where a scene's camera, light and AO distance came from, for the record: "generator
// <name>", "scene file", or "derived (...)" from its size (harness/scene/scene_defaults.h).
struct SettingSources {
  std::string camera, light, d_max;
};

struct Scene {
  std::string name;
  std::string origin;  // "built-in:<generator>" or the scene file's path
  TriangleMesh mesh;
  std::vector<Material> materials;
  Camera camera;
  SpotLight light;
  AoSettings ao;
  SettingSources sources;
  // World position of this scene's coordinate origin: zero for a scene as loaded, the
  // bounding-sphere centre for the centred copy that the GPU and the reference compute in
  // (centred_on_bounding_sphere). World point = scene point + frame_origin.
  glm::vec3 frame_origin{0.0f};
  // World position (the scene file's coordinates, in double precision) of the loaded scene's
  // origin: a scene file with meshes is rebased at load to the centre of its bounding box,
  // computed in double from the meshes' `translate` (scene_loader.cpp), so that its floats
  // hold the scene's detail wherever the file places it. Zero for a built-in scene.
  glm::dvec3 origin_offset{0.0};
  // Triangle corners whose coordinates the mesh file itself holds (as 32-bit floats, after
  // its node transforms and the scale) coarser than kFarFileSpacing of the scene's extent:
  // detail lost before any placement (a mesh file in georeferenced coordinates), counted and
  // named in the scene's warnings.
  uint64_t far_file_vertices = 0;
  // Triangles whose normals the mesh file did not give (none in the file, or a zero or
  // non-finite one at a corner) and the importer derived from the face: recorded in
  // scene_attributes ("position+normal(derived)"), since a pass reading normals then shades
  // flat what the file may have meant smooth (issue 37). Zero for a built-in scene, whose
  // generators define face normals. A function of the source bytes: not in identity_hash.
  uint64_t derived_normal_triangles = 0;
  // Triangles with an area where their mesh was placed (its frame anchored at its
  // `translate`) and none once rebased into the scene's frame: detail smaller than the float
  // spacing at its distance from the scene's centre (a small part far from the rest of a
  // large scene), which no stage can draw or hit; counted and named in the scene's warnings.
  uint64_t collapsed_triangles = 0;
  // What the scene was made from: a generator's name and parameters, or a scene file's JSON
  // (canonical: formatting and key order do not count) and the bytes of every mesh file it
  // names (and an OBJ's .mtl files), or a mesh file's bytes. Set by the loader
  // (harness/scene/scene_loader.h).
  uint64_t source_hash = 0;
  // What the loader could not honour and replaced by a default (an OBJ's mtllib that is not
  // there: its materials get the default grey), one sentence each naming the file: printed
  // on stderr by the commands that load the scene and appended to every record's
  // status_detail. Not part of the hashes (the source bytes are).
  std::vector<std::string> warnings;

  Bounds bounds() const;
  // Centre of the bounds and the largest vertex distance from it: every vertex lies inside.
  BoundingSphere bounding_sphere() const;
  // A 64-bit FNV-1a hash of everything that affects a reference image (geometry, materials,
  // camera, light, AO visibility and d_max; not the LDM-only normal offset), for caching.
  uint64_t content_hash() const;
  // Everything that can change a measurement of this scene, for the resume identity of a
  // run: the source (source_hash) and every field of the loaded scene, the LDM-only normal
  // offset included. Editing any key of a scene file or any byte of its meshes changes it.
  uint64_t identity_hash() const;
  // Throws UserError (naming the scene) on empty geometry, NaN coordinates, bad indices.
  void validate() const;
};

// The one frame every computation on a scene works in: the scene translated so that its
// bounding sphere is centred on the origin (camera and light with it; frame_origin records
// the shift). AO is translation invariant. The loader has already placed a scene file's
// meshes in double and rebased the scene to its bounding-box centre (origin_offset), so its
// floats hold each coordinate to 2^-24 of the scene's half-extent wherever the file places
// it; this frame is a float shift of that (one more rounding of the same size). Not
// covered: detail a mesh file's own floats (coordinates, node transforms) lost
// (far_file_vertices). The GPU (LdmSetup: geometry, LDM views, G-buffer camera) and the
// reference (render_ao_half) both use it.
Scene centred_on_bounding_sphere(const Scene& scene);

}  // namespace ldm
