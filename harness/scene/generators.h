#pragma once
// Built-in procedural scenes, addressable by name (`--scene cornell`) or from a scene file
// (`"generator": {"type": "atrium", ...}`). Each takes a JSON object of parameters; an
// unknown or out-of-range parameter is a UserError naming it.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/scene/scene.h"

namespace ldm {

struct SceneGenerator {
  std::string name;
  std::string description;
  // `context` prefixes errors: "scene.json: /generator" names a key "scene.json: /generator/h".
  std::function<Scene(const nlohmann::json& params, const std::string& context)> make;
};

const std::vector<SceneGenerator>& scene_generators();
const SceneGenerator* find_scene_generator(const std::string& name);
// Builds a built-in scene; `context` names where the parameters came from, as the JSON path
// of the generator object ("scene.json: /generator", "--scene cornell"); errors append "/key".
Scene generate_scene(const std::string& name, const nlohmann::json& params,
                     const std::string& context);

// Reads generator parameters with defaults and range checks, and rejects unknown keys, so
// that a typo in a scene file is an error rather than a silently ignored value.
class GeneratorParams {
 public:
  GeneratorParams(const nlohmann::json& params, std::string context);
  float number(const std::string& key, float fallback, float lo, float hi);
  int integer(const std::string& key, int fallback, int lo, int hi);
  bool boolean(const std::string& key, bool fallback);
  void finish() const;  // throws on keys that no getter asked for

 private:
  std::string where(const std::string& key) const;  // "<context>/<key>"
  const nlohmann::json& params_;
  std::string context_;
  std::vector<std::string> used_;
};

Scene make_cornell_scene(GeneratorParams& params);
Scene make_atrium_scene(GeneratorParams& params);
Scene make_plane_scene(GeneratorParams& params);
Scene make_parallel_planes_scene(GeneratorParams& params);
Scene make_wall_scene(GeneratorParams& params);
Scene make_spot_bounce_scene(GeneratorParams& params);
Scene make_closed_sphere_scene(GeneratorParams& params);
Scene make_hairball_scene(GeneratorParams& params);

}  // namespace ldm
