#pragma once
#include <string>

#include "harness/scene/scene.h"

namespace ldm {

// `spec` is a built-in scene name (see scene_generators()), the path of a scene file
// (format: scenes/README.md) or of a mesh file any importer reads (mesh_import.h), whose
// camera, light and AO distance then follow its size (scene_defaults.h). Throws UserError
// naming the file, line or key at fault.
Scene load_scene(const std::string& spec);

// The name a scene spec is known by in configuration ids, without loading the scene: a
// built-in's name, a scene file's "name" (else its file name), a mesh file's file name.
// The same as load_scene(spec).name.
std::string scene_id_name(const std::string& spec);

// A mesh file as a whole scene: named after the file, everything else derived from its size.
Scene load_mesh_scene(const std::string& path);

// Parses a scene file's text; `path` is used for messages and to resolve mesh paths.
Scene parse_scene_file(const std::string& text, const std::string& path);

}  // namespace ldm
