#include "harness/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/text.h"

namespace ldm {
namespace {

}  // namespace

bool camera_up_is_usable(const Camera& camera) {
  const glm::vec3 view = camera.target - camera.eye;
  const float view_length = glm::length(view), up_length = glm::length(camera.up);
  if (!(view_length > 0.0f) || !(up_length > 0.0f)) return false;
  // |sin| of the angle between up and the view direction.
  const float sine = glm::length(glm::cross(view / view_length, camera.up / up_length));
  return sine > 1e-3f;
}

Bounds Scene::bounds() const {
  Bounds b;
  b.lo = glm::vec3(std::numeric_limits<float>::max());
  b.hi = glm::vec3(-std::numeric_limits<float>::max());
  for (const auto& p : mesh.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

BoundingSphere Scene::bounding_sphere() const {
  const Bounds b = bounds();
  BoundingSphere s;
  s.centre = 0.5f * (b.lo + b.hi);
  float r2 = 0.0f;
  for (const auto& p : mesh.positions) {
    glm::vec3 d = p - s.centre;
    r2 = std::max(r2, glm::dot(d, d));
  }
  s.radius = std::sqrt(r2);
  return s;
}

Scene centred_on_bounding_sphere(const Scene& scene) {
  Scene centred = scene;
  const glm::vec3 centre = scene.bounding_sphere().centre;
  for (glm::vec3& p : centred.mesh.positions) p -= centre;
  centred.camera.eye -= centre;
  centred.camera.target -= centre;
  centred.light.position -= centre;
  centred.frame_origin += centre;
  return centred;
}

uint64_t Scene::content_hash() const {
  Fnv1a h;
  h.add_vector(mesh.positions);
  h.add_vector(mesh.normals);
  h.add_vector(mesh.triangles);
  h.add_vector(mesh.triangle_materials);
  for (const auto& m : materials) {
    h.add_string(m.name);
    h.add(m.albedo);
  }
  h.add(camera);
  h.add(light);
  // Field by field: AoSettings has padding after its bool. The normal offset is left out:
  // it belongs to the LDM pass, and no reference image depends on it.
  h.add(uint8_t(ao.attenuated));
  h.add(ao.d_max);
  h.add(ao.falloff_exponent);
  return h.value();
}

uint64_t Scene::identity_hash() const {
  Fnv1a h;
  h.add(content_hash());
  h.add(source_hash);
  h.add_string(name);
  h.add(ao.normal_offset_pixels);
  h.add_string(ao_trace_name(ao.trace));
  h.add_string(ao_estimator_name(ao.estimator));
  h.add_string(sources.camera);
  h.add_string(sources.light);
  h.add_string(sources.d_max);
  h.add(frame_origin);
  h.add(origin_offset);
  h.add(far_file_vertices);
  return h.value();
}

void Scene::validate() const {
  const std::string where = "scene '" + name + "' (" + origin + ")";
  if (mesh.triangles.empty()) throw UserError(where + ": has no triangles");
  if (mesh.normals.size() != mesh.positions.size())
    throw UserError(where + ": normals and positions differ in count");
  if (mesh.triangle_materials.size() != mesh.triangles.size())
    throw UserError(where + ": every triangle needs a material");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw UserError(where + ": vertex " + std::to_string(i) + " is not finite");
    const float largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    if (largest > kMaxSceneCoordinate)
      throw UserError(where + ": vertex " + std::to_string(i) + " has a coordinate of magnitude " +
                      format_significant(largest) + ", beyond the representable scene extent (|x| <= " +
                      format_significant(kMaxSceneCoordinate) + ")");
  }
  const auto vertex_count = mesh.positions.size();
  for (const auto& t : mesh.triangles)
    if (t.x >= vertex_count || t.y >= vertex_count || t.z >= vertex_count)
      throw UserError(where + ": a triangle indexes past the vertex list");
  for (auto m : mesh.triangle_materials)
    if (m >= materials.size()) throw UserError(where + ": a triangle names a missing material");
  if (!(ao.d_max > 0.0f) || !std::isfinite(ao.d_max))
    throw UserError(where + ": ao.d_max must be positive and finite");
  if (!(ao.falloff_exponent > 0.0f) || !std::isfinite(ao.falloff_exponent))
    throw UserError(where + ": ao.falloff_exponent must be positive and finite");
  if (!(ao.normal_offset_pixels >= 0.0f) || !std::isfinite(ao.normal_offset_pixels))
    throw UserError(where + ": ao.normal_offset must be >= 0 and finite");
  if (!(camera.fov_y_deg > 0.0f && camera.fov_y_deg < 180.0f))
    throw UserError(where + ": camera.fov_y_deg must lie in (0, 180)");
  for (const glm::vec3 v : {camera.eye, camera.target, camera.up})
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw UserError(where + ": camera eye, target and up must be finite");
  if (!(glm::length(camera.target - camera.eye) > 0.0f))
    throw UserError(where + ": camera.eye and camera.target coincide");
  if (!camera_up_is_usable(camera))
    throw UserError(where + ": camera.up is parallel to the view direction (target - eye)");
}

AoSettings apply_ao_overrides(AoSettings ao, const AoOverrides& overrides) {
  if (overrides.d_max) ao.d_max = *overrides.d_max;
  if (overrides.attenuated) ao.attenuated = *overrides.attenuated;
  if (overrides.normal_offset_pixels) ao.normal_offset_pixels = *overrides.normal_offset_pixels;
  if (overrides.trace) ao.trace = *overrides.trace;
  if (overrides.estimator) ao.estimator = *overrides.estimator;
  return ao;
}

}  // namespace ldm
