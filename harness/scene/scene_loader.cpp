#include "harness/scene/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/axes/axis.h"
#include "harness/scene/ao_axes.h"
#include "harness/scene/generators.h"
#include "harness/scene/mesh_import.h"
#include "harness/scene/scene_defaults.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/json_input.h"

namespace ldm {
namespace {

using nlohmann::json;

// Typed access to one JSON object with errors that name the file and the key's path.
class Fields {
 public:
  Fields(const json& object, std::string file, std::string path)
      : object_(object), file_(std::move(file)), path_(std::move(path)) {
    if (!object_.is_object()) fail("", "must be a JSON object");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const std::string at = path_ + (key.empty() ? "" : "/" + key);
    throw UserError(file_ + ": " + (at.empty() ? "the top level" : at) + " " + what);
  }
  bool has(const std::string& key) const { return object_.contains(key); }
  void only(std::initializer_list<const char*> keys) const {
    for (const auto& [key, value] : object_.items()) {
      bool known = false;
      for (const char* k : keys) known = known || key == k;
      if (!known) fail(key, "is not a known key here");
    }
  }
  float number(const std::string& key, float fallback) const {
    if (!has(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_number()) fail(key, "must be a number");
    return to_float(v, key);
  }
  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_boolean()) fail(key, "must be true or false");
    return v.get<bool>();
  }
  std::string string(const std::string& key) const {
    if (!has(key)) fail(key, "is required");
    const json& v = object_.at(key);
    if (!v.is_string()) fail(key, "must be a string");
    return v.get<std::string>();
  }
  // dvec3's value rounded to float (the same checks: each number within a float's range).
  glm::vec3 vec3(const std::string& key, glm::vec3 fallback) const {
    return glm::vec3(dvec3(key, glm::dvec3(fallback)));
  }
  // Three numbers (or one for all three) in double precision, as the file gives them: a
  // placement far from the origin keeps the digits a float would round away.
  glm::dvec3 dvec3(const std::string& key, glm::dvec3 fallback) const {
    if (!has(key)) return fallback;
    const json& v = object_.at(key);
    if (v.is_number()) return glm::dvec3(checked_float_range(v, key));
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
        !v[2].is_number())
      fail(key, "must be an array of 3 numbers");
    return {checked_float_range(v[0], key + "/0"), checked_float_range(v[1], key + "/1"),
            checked_float_range(v[2], key + "/2")};
  }
  // A point of the file's world, in the scene's rebased frame (Scene::origin_offset).
  glm::vec3 point(const std::string& key, glm::vec3 fallback, glm::dvec3 origin_offset) const {
    if (!has(key)) return fallback;
    const glm::dvec3 rebased = dvec3(key, glm::dvec3(0.0)) - origin_offset;
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(float(rebased[i])))
        fail(key, "lies beyond the 32-bit float range from the scene's centre");
    return glm::vec3(rebased);
  }
  const json& at(const std::string& key) const { return object_.at(key); }
  Fields child(const std::string& key) const { return Fields(object_.at(key), file_, path_ + "/" + key); }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  // The scene stores 32-bit floats: a JSON number beyond their range (1e39) would become
  // infinity, so it is an error here rather than a surprise on the GPU.
  float to_float(const json& v, const std::string& key) const {
    const double given = v.get<double>();
    const float x = float(given);
    if (!std::isfinite(x)) {
      char text[32];
      std::snprintf(text, sizeof text, "%g", given);
      fail(key, std::string("= ") + text + " is not representable as a 32-bit float (|x| <= 3.4e38)");
    }
    return x;
  }
  double checked_float_range(const json& v, const std::string& key) const {
    to_float(v, key);  // the same range as every other number
    return v.get<double>();
  }
  const json& object_;
  std::string file_;
  std::string path_;
};

void read_camera(const Fields& f, Camera& camera, glm::dvec3 origin_offset) {
  f.only({"eye", "target", "up", "fov_y_deg"});
  camera.eye = f.point("eye", camera.eye, origin_offset);
  camera.target = f.point("target", camera.target, origin_offset);
  camera.up = f.vec3("up", camera.up);
  camera.fov_y_deg = f.number("fov_y_deg", camera.fov_y_deg);
  if (!(camera.fov_y_deg > 0 && camera.fov_y_deg < 180)) f.fail("fov_y_deg", "must lie in (0, 180)");
  if (glm::length(camera.up) == 0.0f) f.fail("up", "must not be zero");
  if (!(glm::length(camera.target - camera.eye) > 0.0f)) f.fail("target", "must differ from eye");
  if (!camera_up_is_usable(camera))
    f.fail("up", "is parallel to the view direction (target - eye): the camera has no "
                 "defined roll; give an up vector that is not along the view direction");
}

void read_light(const Fields& f, SpotLight& light, glm::dvec3 origin_offset) {
  f.only({"type", "position", "direction", "intensity", "inner_angle_deg", "outer_angle_deg"});
  if (f.has("type") && f.string("type") != "spot") f.fail("type", "must be \"spot\"");
  light.position = f.point("position", light.position, origin_offset);
  light.direction = f.vec3("direction", light.direction);
  if (glm::length(light.direction) == 0.0f) f.fail("direction", "must not be zero");
  light.direction = glm::normalize(light.direction);
  light.intensity = f.vec3("intensity", light.intensity);
  light.inner_angle_deg = f.number("inner_angle_deg", light.inner_angle_deg);
  light.outer_angle_deg = f.number("outer_angle_deg", light.outer_angle_deg);
  if (!(light.inner_angle_deg >= 0 && light.inner_angle_deg <= light.outer_angle_deg &&
        light.outer_angle_deg <= 180))
    f.fail("outer_angle_deg", "needs 0 <= inner_angle_deg <= outer_angle_deg <= 180");
}

void read_ao_fields(const Fields& f, AoSettings& ao) {
  f.only({"attenuated", "d_max", "falloff_exponent", "normal_offset"});
  ao.attenuated = f.boolean("attenuated", ao.attenuated);
  // Checked by the axes' own declarations (harness/scene/ao_axes.cpp), as --d-max and
  // --normal-offset are: a value the command line refuses is refused from a file too.
  ao.d_max = f.number("d_max", ao.d_max);
  if (const std::string problem = axis_real_problem(ao_axis(AoAxis::DMax), ao.d_max); !problem.empty())
    f.fail("d_max", "must be a positive distance in scene units: " + problem);
  ao.falloff_exponent = f.number("falloff_exponent", ao.falloff_exponent);
  if (!(ao.falloff_exponent > 0)) f.fail("falloff_exponent", "must be positive");
  ao.normal_offset_pixels = f.number("normal_offset", ao.normal_offset_pixels);
  if (const std::string problem = axis_real_problem(ao_axis(AoAxis::NormalOffset), ao.normal_offset_pixels);
      !problem.empty())
    f.fail("normal_offset", "must be a number of LDM pixels: " + problem);
}

// The bytes of a file, hashed (0 when it cannot be read: the importer then says why).
uint64_t file_bytes_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  Fnv1a h;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    if (in.gcount() <= 0) break;
    h.add_string(std::string_view(buffer, size_t(in.gcount())));
  }
  return h.value();
}

// Where the meshes' vertices were placed: each mesh's floats are relative to its own
// translate (its anchor), until rebase_to_centre moves them all into one frame.
struct Placements {
  struct Range {
    size_t begin, end;
    glm::dvec3 anchor;
  };
  std::vector<Range> ranges;
  std::vector<float> file_spacing;  // per vertex: MeshImportOptions::file_spacing (0: generated)
};

void append_mesh(Scene& scene, const Fields& f, const std::filesystem::path& base_dir,
                 Fnv1a& source, Placements& placements) {
  f.only({"file", "material", "scale", "translate"});
  const std::string file = f.string("file");
  std::filesystem::path path = file;
  if (path.is_relative()) path = base_dir / path;
  MeshImportOptions options;
  options.scale = f.dvec3("scale", glm::dvec3(1.0));
  if (options.scale.x == 0.0 || options.scale.y == 0.0 || options.scale.z == 0.0)
    f.fail("scale", "must be non-zero in every component (a zero scale flattens the mesh "
                    "into zero-area triangles)");
  options.translate = f.dvec3("translate", glm::dvec3(0.0));
  options.anchor = options.translate;
  if (f.has("material")) options.override_material = f.string("material");
  placements.file_spacing.resize(scene.mesh.positions.size(), 0.0f);
  options.file_spacing = &placements.file_spacing;
  const size_t begin = scene.mesh.positions.size();
  import_mesh_into(scene, path.string(), options, f.file() + ": " + f.path() + "/file");
  placements.ranges.push_back({begin, scene.mesh.positions.size(), options.anchor});
  source.add(file_bytes_hash(path.string()));
}

// Moves the scene (its vertices, and the camera and light it has so far) to the centre of
// its bounding box, computed in double precision from every vertex's anchored position, and
// records that centre as origin_offset; counts the far_file_vertices. Afterwards 32-bit
// floats hold the scene to its extent's precision wherever the file placed it (issue 35).
void rebase_to_centre(Scene& scene, Placements& placements, const std::string& where) {
  auto& positions = scene.mesh.positions;
  std::vector<glm::dvec3> anchor(positions.size(), glm::dvec3(0.0));
  for (const auto& r : placements.ranges)
    for (size_t i = r.begin; i < r.end; ++i) anchor[i] = r.anchor;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3 p = glm::dvec3(positions[i]) + anchor[i];
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  if (positions.empty()) return;
  const glm::dvec3 centre = 0.5 * (lo + hi);
  auto has_area = [&](const glm::uvec3& t) {
    return glm::length(glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x])) > 0.0f;
  };
  std::vector<bool> had_area(scene.mesh.triangles.size());
  for (size_t t = 0; t < had_area.size(); ++t) had_area[t] = has_area(scene.mesh.triangles[t]);
  for (size_t i = 0; i < positions.size(); ++i)
    positions[i] = glm::vec3(glm::dvec3(positions[i]) + anchor[i] - centre);
  uint64_t collapsed = 0;
  for (size_t t = 0; t < had_area.size(); ++t)
    if (had_area[t] && !has_area(scene.mesh.triangles[t])) ++collapsed;
  scene.collapsed_triangles = collapsed;
  scene.camera.eye = glm::vec3(glm::dvec3(scene.camera.eye) - centre);
  scene.camera.target = glm::vec3(glm::dvec3(scene.camera.target) - centre);
  scene.light.position = glm::vec3(glm::dvec3(scene.light.position) - centre);
  scene.origin_offset += centre;

  const double extent = glm::length(hi - lo), limit = extent * kFarFileSpacing;
  placements.file_spacing.resize(positions.size(), 0.0f);
  uint64_t far = 0;
  float coarsest = 0.0f;
  for (float spacing : placements.file_spacing)
    if (double(spacing) > limit) ++far, coarsest = std::max(coarsest, spacing);
  scene.far_file_vertices = far;
  if (far > 0) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "%llu triangle corners lie so far from the origin in their mesh file that its "
                  "32-bit floats hold them only to %.3g, coarser than 2^-16 of the scene's extent "
                  "%.3g (far_file_vertices): detail lost in the file itself",
                  static_cast<unsigned long long>(far), double(coarsest), extent);
    scene.warnings.push_back(where + ": " + text);
  }
  if (collapsed > 0) {
    const float largest = std::max({std::abs(float(lo.x - centre.x)), std::abs(float(lo.y - centre.y)),
                                    std::abs(float(lo.z - centre.z))});
    char text[320];
    std::snprintf(text, sizeof text,
                  "%llu triangles have an area where their mesh is placed and none in the scene's "
                  "frame (collapsed_triangles): smaller than the float spacing (%.3g at the scene's "
                  "edge, extent %.3g) where they lie, they are neither drawn nor hit",
                  static_cast<unsigned long long>(collapsed),
                  double(std::nextafter(largest, INFINITY) - largest), extent);
    scene.warnings.push_back(where + ": " + text);
  }
}

}  // namespace

Scene parse_scene_file(const std::string& text, const std::string& path) {
  const json root = parse_json_strictly(text, path);
  Fields top(root, path, "");
  top.only({"name", "generator", "meshes", "materials", "camera", "light", "ao"});
  if (!top.has("generator") && !top.has("meshes"))
    throw UserError(path + ": needs \"generator\" or \"meshes\" (or both)");

  Scene scene;
  if (top.has("generator")) {
    Fields g = top.child("generator");
    const std::string type = g.string("type");
    scene = generate_scene(type, root.at("generator"), path + ": /generator");
  }
  scene.origin = path;
  Fnv1a source;
  source.add_string("scene file");
  source.add_string(root.dump());  // canonical: nlohmann sorts keys, whitespace is gone
  // The file's own name, else its file name: never the generator's, which would give two
  // files of one generator (and the built-in scene) the same configuration ids.
  scene.name = top.has("name") ? top.string("name") : std::string();
  if (scene.name.empty()) scene.name = std::filesystem::path(path).stem().string();

  if (top.has("materials")) {
    Fields m = top.child("materials");
    for (const auto& [name, value] : root.at("materials").items()) {
      Material material{name, m.vec3(name, glm::vec3(0.8f))};
      bool replaced = false;
      for (auto& existing : scene.materials)
        if (existing.name == name) existing = material, replaced = true;
      if (!replaced) scene.materials.push_back(material);
    }
  }
  if (top.has("meshes")) {
    const json& meshes = root.at("meshes");
    if (!meshes.is_array()) throw UserError(path + ": /meshes must be an array");
    const auto base = std::filesystem::path(path).parent_path();
    Placements placements;
    for (size_t i = 0; i < meshes.size(); ++i)
      append_mesh(scene, Fields(meshes[i], path, "/meshes/" + std::to_string(i)), base, source,
                  placements);
    rebase_to_centre(scene, placements, path);
  }
  // Without a generator, nothing but the geometry is known yet: what the file does not
  // set follows the scene's size (harness/scene/scene_defaults.h). The file's own keys are
  // applied over that.
  if (!top.has("generator")) derive_size_defaults(scene, {});
  if (top.has("camera")) {
    read_camera(top.child("camera"), scene.camera, scene.origin_offset);
    scene.sources.camera = "scene file";
  }
  if (top.has("light")) {
    read_light(top.child("light"), scene.light, scene.origin_offset);
    scene.sources.light = "scene file";
  }
  if (top.has("ao")) {
    read_ao_fields(top.child("ao"), scene.ao);
    if (root.at("ao").is_object() && root.at("ao").contains("d_max")) scene.sources.d_max = "scene file";
  }
  scene.source_hash = source.value();
  scene.validate();
  return scene;
}

std::string scene_id_name(const std::string& spec) {
  const std::string stem = std::filesystem::path(spec).stem().string();
  if (find_scene_generator(spec)) return spec;
  if (std::filesystem::path(spec).extension() != ".json") return stem;
  // A file that cannot be read or does not parse keeps its stem here; loading it reports
  // what is wrong.
  json root;
  try {
    root = parse_json_strictly(read_input_file(spec, "--scene: scene file"), spec);
  } catch (const std::exception&) {
    return stem;
  }
  if (root.is_object() && root.contains("name") && root.at("name").is_string() &&
      !root.at("name").get<std::string>().empty())
    return root.at("name").get<std::string>();
  return stem;
}

Scene load_mesh_scene(const std::string& path) {
  Scene scene;
  scene.name = std::filesystem::path(path).stem().string();
  scene.origin = path;
  Placements placements;
  MeshImportOptions options;
  options.file_spacing = &placements.file_spacing;
  import_mesh_into(scene, path, options, "--scene " + path);
  rebase_to_centre(scene, placements, path);
  scene.source_hash = file_bytes_hash(path);
  derive_size_defaults(scene, {});
  scene.validate();
  return scene;
}

Scene load_scene(const std::string& spec) {
  if (find_scene_generator(spec)) return generate_scene(spec, nlohmann::json(), "--scene " + spec);
  std::error_code error;
  if (std::filesystem::is_regular_file(spec, error) && is_mesh_file(spec)) return load_mesh_scene(spec);
  if (std::filesystem::is_directory(spec, error))
    throw UserError("--scene: '" + spec + "' is a folder, not a scene file (.json) or mesh file");
  std::ifstream in(spec, std::ios::binary);
  if (!in) {
    std::string known;
    for (const auto& g : scene_generators()) known += (known.empty() ? "" : ", ") + g.name;
    throw UserError("--scene: '" + spec + "' is neither a built-in scene (" + known +
                    ") nor a readable scene file (.json) or mesh file (glTF/GLB, PLY, FBX, "
                    "Collada, 3DS, STL, OFF, OBJ, IFC, ...)");
  }
  in.close();
  const std::string text = read_input_file(spec, "--scene: scene file");
  // Its canonical JSON and its meshes' bytes are the scene's source_hash (parse_scene_file):
  // any edited setting is another sweep, a reformatting is not.
  return parse_scene_file(text, spec);
}

}  // namespace ldm
