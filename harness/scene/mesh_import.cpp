#include "harness/scene/mesh_import.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "harness/scene/assimp_reader.h"
#include "harness/scene/mesh_builder.h"
#include "harness/scene/obj_syntax.h"
#include "harness/util/error.h"
#include "harness/util/files.h"
#include "harness/util/hash.h"
#include "harness/util/isolated_call.h"
#include "harness/util/json_input.h"
#include "harness/util/text.h"

namespace ldm {
namespace {

// Assimp names the material it makes up for a file without any this way; such triangles get
// ldmbench's default grey, as a file without materials always did.
constexpr const char* kAssimpDefaultMaterial = "DefaultMaterial";
constexpr const char* kDefaultMaterial = "default";
constexpr float kDefaultAlbedo = 0.8f;

// More would not fit the GPU's geometry buffers of any device this runs on, and a node tree
// that instances a mesh without end must stop before memory does.
constexpr uint64_t kMaxImportedTriangles = uint64_t(1) << 27;

// A long import (the 4 MB IFC house takes a second) is fine; a hang is not.
constexpr double kImportSeconds = 600;

std::string format_point(glm::vec3 p) {
  return "(" + format_significant(p.x) + ", " + format_significant(p.y) + ", " + format_significant(p.z) + ")";
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The child may use what memory this process has mapped already plus half the machine's
// memory: enough for any real model, not enough to take the machine down.
unsigned long long child_address_space_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  unsigned long long mapped = 0;
  if (std::ifstream statm("/proc/self/statm"); statm) {
    unsigned long long size_pages = 0;
    statm >> size_pages;
    mapped = size_pages * static_cast<unsigned long long>(page > 0 ? page : 4096);
  }
  if (pages <= 0 || page <= 0) return 0;
  return mapped + static_cast<unsigned long long>(pages) * static_cast<unsigned long long>(page) / 2;
}

ImportedModel read_isolated(const std::function<ImportedModel()>& read, const std::string& label,
                            double seconds) {
  IsolationLimits limits;
  limits.seconds = seconds;
  limits.address_space_bytes = child_address_space_limit();
  const IsolatedOutcome outcome = run_isolated([&] { return encode_imported_model(read()); }, limits);
  const std::string importer = "the importer (Assimp " + assimp_version() + ")";
  switch (outcome.kind) {
    case IsolatedOutcome::Kind::Returned:
      try {
        return decode_imported_model(outcome.bytes);
      } catch (const std::exception& e) {
        throw GpuError(label + ": " + importer + " returned a model this build cannot decode: " + e.what());
      }
    case IsolatedOutcome::Kind::Threw:
      throw UserError(label + ": " + importer + " cannot read it: " + outcome.message);
    case IsolatedOutcome::Kind::Crashed:
      throw UserError(label + ": " + importer + " crashed on it (" +
                      (outcome.signal ? describe_signal(outcome.signal)
                                      : "exit status " + std::to_string(outcome.exit_status)) +
                      "): the file is malformed, or a variant of its format Assimp does not read");
    case IsolatedOutcome::Kind::TimedOut: {
      char text[64];
      std::snprintf(text, sizeof text, "%g", seconds);
      throw UserError(label + ": " + importer + " took longer than " + text +
                      " s on it and was stopped: the file is malformed or too large");
    }
    case IsolatedOutcome::Kind::NotStarted:
      break;
  }
  throw UserError(label + ": cannot start the isolated importer: " + outcome.message);
}

// Where a problem lies, for messages: the mesh and the node by name, else by index.
std::string describe_place(const ImportedModel& model, size_t mesh, size_t node) {
  const std::string& mesh_name = model.meshes[mesh].name;
  const std::string& node_name = model.nodes[node].name;
  return "mesh " + (mesh_name.empty() ? "#" + std::to_string(mesh) : "'" + mesh_name + "'") +
         " (node " + (node_name.empty() ? "#" + std::to_string(node) : "'" + node_name + "'") + ")";
}

// The scene material each of the file's materials becomes. A scene material of the same
// name (the scene file's "materials", or an earlier mesh's) wins; the file's own colour
// otherwise; unnamed materials, and same-named ones of different colours within the file,
// are told apart by their index.
class MaterialMap {
 public:
  MaterialMap(Scene& scene, const ImportedModel& model, const std::string& stem,
              const MeshImportOptions& options, const std::string& where)
      : scene_(scene), model_(model), stem_(stem), options_(options), where_(where) {}

  uint32_t scene_index(uint32_t file_index, const std::string& place) {
    if (options_.override_material) {
      for (uint32_t i = 0; i < scene_.materials.size(); ++i)
        if (scene_.materials[i].name == *options_.override_material) return i;
      throw UserError(where_ + ": material '" + *options_.override_material +
                      "' is not defined in the scene's \"materials\"");
    }
    if (const auto found = cache_.find(file_index); found != cache_.end()) return found->second;
    MeshBuilder builder(scene_);
    uint32_t index;
    if (file_index >= model_.materials.size()) {
      // Assimp gives every mesh a material; a file without any gets its default one.
      if (!model_.materials.empty())
        throw UserError(where_ + ": " + place + " names material " + std::to_string(file_index) +
                        " of " + std::to_string(model_.materials.size()));
      index = builder.material(kDefaultMaterial, glm::vec3(kDefaultAlbedo));
    } else {
      const ImportedMaterial& m = model_.materials[file_index];
      if (m.has_albedo && !finite(m.albedo))
        throw UserError(where_ + ": material '" + m.name + "' has a non-finite diffuse colour " +
                        format_point(m.albedo));
      const bool defined = !options_.defined_materials || options_.defined_materials->count(m.name);
      const bool named_in_scene = std::any_of(scene_.materials.begin(), scene_.materials.end(),
                                              [&](const Material& s) { return s.name == m.name; });
      if (m.name == kAssimpDefaultMaterial || (!defined && !named_in_scene)) {
        index = builder.material(kDefaultMaterial, glm::vec3(kDefaultAlbedo));
      } else {
        const glm::vec3 albedo = m.has_albedo ? m.albedo : glm::vec3(kDefaultAlbedo);
        std::string name = m.name.empty() ? stem_ + ":" + std::to_string(file_index) : m.name;
        if (!m.name.empty() && differs_from_a_namesake(file_index))
          name += ":" + std::to_string(file_index);
        index = builder.material(name, albedo);
      }
    }
    cache_[file_index] = index;
    return index;
  }

 private:
  bool differs_from_a_namesake(uint32_t file_index) const {
    const ImportedMaterial& m = model_.materials[file_index];
    for (uint32_t j = 0; j < model_.materials.size(); ++j) {
      const ImportedMaterial& other = model_.materials[j];
      if (j != file_index && other.name == m.name &&
          (other.has_albedo != m.has_albedo || other.albedo != m.albedo))
        return true;
    }
    return false;
  }

  Scene& scene_;
  const ImportedModel& model_;
  std::string stem_;
  const MeshImportOptions& options_;
  std::string where_;
  std::map<uint32_t, uint32_t> cache_;
};

std::string trimmed(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return {};
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

// The materials the .mtl files an OBJ names (`mtllib`, beside it) define (`newmtl`), the
// name being the rest of the line, as Assimp reads it. A missing .mtl defines none.
// A .mtl that is not there is a warning on the scene (its materials become the default
// grey); each .mtl read adds its bytes to the scene's source hash.
std::set<std::string> obj_defined_materials(const std::string& obj_text, const std::string& obj_path,
                                            Scene& scene) {
  std::set<std::string> names;
  const std::filesystem::path dir = std::filesystem::path(obj_path).parent_path();
  std::istringstream lines(obj_text);
  size_t line_number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_number;
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword != "mtllib") continue;
    for (std::string file; words >> file;) {
      std::ifstream mtl(dir / file, std::ios::binary);
      if (!mtl) {
        scene.warnings.push_back(obj_path + ":" + std::to_string(line_number) + ": mtllib '" + file +
                                 "' cannot be read (" + (dir / file).string() +
                                 "); the materials it should define are the default grey");
        continue;
      }
      std::stringstream bytes;
      bytes << mtl.rdbuf();
      Fnv1a h;
      h.add(scene.source_hash);
      h.add_string(bytes.str());
      scene.source_hash = h.value();
      for (std::string entry; std::getline(bytes, entry);) {
        const std::string t = trimmed(entry);
        if (t.rfind("newmtl", 0) == 0 && t.size() > 6 && (t[6] == ' ' || t[6] == '\t'))
          names.insert(trimmed(t.substr(7)));
      }
    }
  }
  return names;
}

// Assimp, like every OBJ reader, reads malformed numbers and short statements without a
// word: the strict checker (obj_syntax.h) names the line first. An OBJ has no node
// transforms, so the scene file's scale and translate alone place its vertices, and one
// beyond the scene extent is named by its line too.
void check_obj_placement(const std::string& text, const std::string& path,
                         const MeshImportOptions& options, const std::string& context) {
  const ObjSyntax syntax = [&] {
    try {
      return check_obj_syntax(text, path);
    } catch (const UserError& e) {
      throw UserError(context + ": " + e.what());
    }
  }();
  for (size_t i = 0; i < syntax.vertices.size(); ++i) {
    const glm::dvec3 placed = glm::dvec3(syntax.vertices[i]) * options.scale + options.translate;
    const glm::vec3 p(placed);
    const double largest = std::max({std::abs(placed.x), std::abs(placed.y), std::abs(placed.z)});
    if (!(largest <= double(kMaxSceneCoordinate)))
      throw UserError(path + ":" + std::to_string(syntax.vertex_lines[i]) + ": the vertex lies at " +
                      format_point(p) + " after " + context +
                      "'s scale and translate, beyond the representable scene extent (|x| <= " +
                      format_significant(kMaxSceneCoordinate) + ")");
  }
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext != ".json" && assimp_reads_extension(ext);
}

void import_mesh_bytes_into(Scene& scene, const std::string& bytes, const std::string& extension,
                            const std::string& label, double seconds, const std::string& context) {
  MeshImportOptions options;
  if (extension == "obj") {
    check_obj_placement(bytes, label, options, context);
    options.defined_materials = std::set<std::string>();  // no .mtl beside bytes
  }
  const ImportedModel model = read_isolated(
      [&] { return read_model_with_assimp(bytes, extension); }, context + ": '" + label + "'", seconds);
  append_imported_model(scene, model, label, options, context);
}

void append_imported_model(Scene& scene, const ImportedModel& model, const std::string& path,
                           const MeshImportOptions& options, const std::string& context) {
  const std::string where = context + ": '" + path + "'";
  MaterialMap materials(scene, model, std::filesystem::path(path).stem().string(), options, where);
  // Node i's frame in the file's world: parents come first, so one pass suffices.
  std::vector<glm::mat4> world(model.nodes.size());
  uint64_t triangles = 0, degenerate = 0, instanced = 0;
  // Triangles with an area in the file whose area the scene file's placement rounds away
  // (a translate far from the origin, where 32-bit floats are farther apart than the
  // mesh is large), and the largest coordinate placed.
  uint64_t collapsed_by_placement = 0;
  float largest_placed = 0.0f;
  const glm::vec3 float_scale(options.scale);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const ImportedNode& node = model.nodes[n];
    if (node.parent >= int32_t(n) || node.parent < -1)
      throw UserError(where + ": node #" + std::to_string(n) + " has parent #" +
                      std::to_string(node.parent) + ", which does not precede it");
    world[n] = node.parent < 0 ? node.transform : world[size_t(node.parent)] * node.transform;
    for (uint32_t mesh_index : node.meshes) {
      if (mesh_index >= model.meshes.size())
        throw UserError(where + ": node '" + node.name + "' places mesh " + std::to_string(mesh_index) +
                        " of " + std::to_string(model.meshes.size()));
      const ImportedMesh& mesh = model.meshes[mesh_index];
      const std::string place = describe_place(model, mesh_index, n);
      const glm::mat4& to_file = world[n];  // the file's own frame, in its float
      for (int c = 0; c < 4; ++c)
        if (!finite(glm::vec3(to_file[c])) || !std::isfinite(to_file[c][3]))
          throw UserError(where + ": " + place + " has a non-finite node transform");
      const glm::mat3 linear = glm::mat3(glm::scale(glm::mat4(1.0f), float_scale)) * glm::mat3(to_file);
      const bool invertible = std::abs(glm::determinant(linear)) > 0.0f;
      const glm::mat3 normal_matrix = invertible ? glm::transpose(glm::inverse(linear)) : glm::mat3(1.0f);
      const bool smooth = !mesh.normals.empty();
      if (smooth && mesh.normals.size() != mesh.positions.size())
        throw UserError(where + ": " + place + " has " + std::to_string(mesh.normals.size()) +
                        " normals for " + std::to_string(mesh.positions.size()) + " vertices");
      const uint32_t material = materials.scene_index(mesh.material, place);
      ++instanced;

      auto vertex = [&](uint32_t i) {
        if (i >= mesh.positions.size())
          throw UserError(where + ": " + place + ": a face names vertex " + std::to_string(i) +
                          " of " + std::to_string(mesh.positions.size()));
        const glm::vec3 local = mesh.positions[i];
        if (!finite(local))
          throw UserError(where + ": " + place + ": vertex " + std::to_string(i) + " is not finite " +
                          format_point(local));
        const glm::vec3 in_file = glm::vec3(to_file * glm::vec4(local, 1.0f));
        const glm::dvec3 placed = glm::dvec3(in_file) * options.scale + options.translate;
        const glm::vec3 p(placed - options.anchor);
        const double largest_world = std::max({std::abs(placed.x), std::abs(placed.y), std::abs(placed.z)});
        const float largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        largest_placed = std::max(largest_placed, largest);
        if (!(largest_world <= double(kMaxSceneCoordinate)) || !(largest <= kMaxSceneCoordinate))  // also catches inf and NaN
          throw UserError(where + ": " + place + ": vertex " + std::to_string(i) + " lies at " +
                          format_point(glm::vec3(placed)) + " after the node transforms and " + context +
                          "'s scale and translate, beyond the representable scene extent (|x| <= " +
                          format_significant(kMaxSceneCoordinate) + ")");
        return std::pair(p, in_file);
      };

      size_t corner = 0;
      for (size_t f = 0; f < mesh.face_sizes.size(); ++f) {
        const uint32_t corners = mesh.face_sizes[f];
        if (corners > mesh.indices.size() - corner)
          throw UserError(where + ": " + place + ": face " + std::to_string(f) +
                          " runs past the mesh's index list");
        const uint32_t* idx = &mesh.indices[corner];
        corner += corners;
        if (corners < 3) continue;  // points and lines: no surface
        if (corners > 3)
          throw UserError(where + ": " + place + ": face " + std::to_string(f) + " has " +
                          std::to_string(corners) + " corners, which the importer did not triangulate");
        const auto [a, file_a] = vertex(idx[0]);
        const auto [b, file_b] = vertex(idx[1]);
        const auto [c, file_c] = vertex(idx[2]);
        const glm::vec3 face = glm::cross(b - a, c - a);
        if (!(glm::length(face) > 0.0f)) {  // zero area: no surface to rasterise or hit
          ++degenerate;
          auto unplaced = [&](uint32_t i) { return glm::vec3(world[n] * glm::vec4(mesh.positions[i], 1.0f)); };
          const glm::vec3 ua = unplaced(idx[0]);
          if (glm::length(glm::cross(unplaced(idx[1]) - ua, unplaced(idx[2]) - ua)) > 0.0f) ++collapsed_by_placement;
          continue;
        }
        if (++triangles > kMaxImportedTriangles)
          throw UserError(where + ": more than " + std::to_string(kMaxImportedTriangles) +
                          " triangles after the node transforms (nodes instance meshes " +
                          std::to_string(instanced) + " times)");
        auto& m = scene.mesh;
        const auto base = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        if (options.file_spacing)
          for (const glm::vec3& q : {file_a, file_b, file_c}) {
            const float largest = std::max({std::abs(q.x), std::abs(q.y), std::abs(q.z)});
            const double scale = std::max({std::abs(options.scale.x), std::abs(options.scale.y), std::abs(options.scale.z)});
            options.file_spacing->push_back(float(double(std::nextafter(largest, INFINITY) - largest) * scale));
          }
        const glm::vec3 face_normal = glm::normalize(face);
        bool derived = false;
        for (int k = 0; k < 3; ++k) {
          glm::vec3 n = face_normal;
          bool from_file = false;
          if (smooth && invertible) {
            const glm::vec3 file_normal = normal_matrix * mesh.normals[idx[k]];
            // A zero or non-finite normal in the file says nothing: the face's own.
            if (finite(file_normal) && glm::length(file_normal) > 0.0f) {
              n = glm::normalize(file_normal);
              from_file = true;
            }
          }
          derived = derived || !from_file;
          m.normals.push_back(n);
        }
        if (derived) ++scene.derived_normal_triangles;
        m.triangles.emplace_back(base, base + 1, base + 2);
        m.triangle_materials.push_back(material);
      }
      if (corner != mesh.indices.size())
        throw UserError(where + ": " + place + ": the mesh's index list is longer than its faces");
    }
  }
  if (triangles == 0 && collapsed_by_placement > 0) {
    const float spacing = std::nextafter(largest_placed, INFINITY) - largest_placed;
    throw UserError(where + ": " + std::to_string(collapsed_by_placement) + " of its " +
                    std::to_string(degenerate) + " triangles have an area in the file but none after " +
                    context + "'s scale and translate: they place the mesh at coordinates up to " +
                    format_significant(largest_placed) + ", where 32-bit floats are " + format_significant(spacing) +
                    " apart, more than the mesh's own size; move it nearer the origin or scale it up");
  }
  if (triangles == 0 && degenerate > 0)
    throw UserError(where + ": all " + std::to_string(degenerate) +
                    " triangles have zero area (in the file, after its node transforms)");
  if (triangles == 0)
    throw UserError(where + ": has no triangles (" + std::to_string(model.meshes.size()) +
                    " meshes placed " + std::to_string(instanced) + " times by " +
                    std::to_string(model.nodes.size()) + " nodes)");
}

void import_mesh_into(Scene& scene, const std::string& path, const MeshImportOptions& options,
                      const std::string& context) {
  std::error_code error;
  const auto kind = std::filesystem::status(path, error).type();
  if (kind == std::filesystem::file_type::not_found)
    throw UserError(context + ": mesh file '" + path + "' does not exist");
  if (kind == std::filesystem::file_type::directory)
    throw UserError(context + ": mesh file '" + path + "' is a directory, not a file");
  if (kind != std::filesystem::file_type::regular)
    throw UserError(context + ": mesh file '" + path + "' is not a regular file");
  const std::string ext = lower_extension(path);
  if (!assimp_reads_extension(ext))
    throw UserError(context + ": mesh file '" + path + "': no importer reads '" + ext +
                    "' files (Assimp " + assimp_version() +
                    " reads glTF/GLB, PLY, FBX, Collada, 3DS, STL, OFF, OBJ, IFC and more)");
  // Refused by its size before anything reads it (a 1 GB OBJ took 3 GB and 17 s to refuse).
  check_input_size(path, context + ": mesh file");
  MeshImportOptions placed = options;
  uint64_t bytes_hash = 0;
  if (ext == ".obj") {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) throw UserError(context + ": mesh file '" + path + "' cannot be read");
    check_obj_placement(text.str(), path, options, context);
    placed.defined_materials = obj_defined_materials(text.str(), path, scene);
    Fnv1a h;
    h.add_string(text.str());
    bytes_hash = h.value();
  } else {
    bytes_hash = hash_file(path);
  }
  // Every byte of every mesh identifies the sweep (scene.h source_hash).
  Fnv1a h;
  h.add(scene.source_hash);
  h.add(bytes_hash);
  scene.source_hash = h.value();
  const ImportedModel model =
      read_isolated([&] { return read_model_with_assimp(path); }, context + ": '" + path + "'", kImportSeconds);
  append_imported_model(scene, model, path, placed, context);
}

}  // namespace ldm
