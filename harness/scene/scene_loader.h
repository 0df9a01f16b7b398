#pragma once
#include <string>

#include "harness/scene/scene.h"

namespace ldm {

// `spec` is a built-in scene name (see scene_generators()) or the path of a scene file
// (format: scenes/README.md). Throws UserError naming the file, line or key at fault.
Scene load_scene(const std::string& spec);

// Parses a scene file's text; `path` is used for messages and to resolve mesh paths.
Scene parse_scene_file(const std::string& text, const std::string& path);

}  // namespace ldm
