#include "harness/scene/generators.h"

#include <algorithm>

#include "harness/util/error.h"

namespace ldm {

GeneratorParams::GeneratorParams(const nlohmann::json& params, std::string context)
    : params_(params), context_(std::move(context)) {
  if (!params_.is_null() && !params_.is_object())
    throw UserError(context_ + ": generator parameters must be a JSON object");
}

float GeneratorParams::number(const std::string& key, float fallback, float lo, float hi) {
  used_.push_back(key);
  if (params_.is_null() || !params_.contains(key)) return fallback;
  const auto& v = params_.at(key);
  if (!v.is_number()) throw UserError(context_ + ": '" + key + "' must be a number");
  const float x = v.get<float>();
  if (!(x >= lo && x <= hi))
    throw UserError(context_ + ": '" + key + "' = " + std::to_string(x) + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

int GeneratorParams::integer(const std::string& key, int fallback, int lo, int hi) {
  used_.push_back(key);
  if (params_.is_null() || !params_.contains(key)) return fallback;
  const auto& v = params_.at(key);
  if (!v.is_number_integer()) throw UserError(context_ + ": '" + key + "' must be an integer");
  const int x = v.get<int>();
  if (x < lo || x > hi)
    throw UserError(context_ + ": '" + key + "' = " + std::to_string(x) + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

bool GeneratorParams::boolean(const std::string& key, bool fallback) {
  used_.push_back(key);
  if (params_.is_null() || !params_.contains(key)) return fallback;
  const auto& v = params_.at(key);
  if (!v.is_boolean()) throw UserError(context_ + ": '" + key + "' must be true or false");
  return v.get<bool>();
}

void GeneratorParams::finish() const {
  if (params_.is_null()) return;
  for (const auto& [key, value] : params_.items()) {
    if (key == "type") continue;
    if (std::find(used_.begin(), used_.end(), key) == used_.end())
      throw UserError(context_ + ": unknown parameter '" + key + "'");
  }
}

const std::vector<SceneGenerator>& scene_generators() {
  auto wrap = [](Scene (*make)(GeneratorParams&), const char* name) {
    return [make, name](const nlohmann::json& params) {
      GeneratorParams p(params, std::string("generator '") + name + "'");
      Scene scene = make(p);
      p.finish();
      scene.origin = std::string("built-in:") + name;
      if (scene.name.empty()) scene.name = name;
      return scene;
    };
  };
  static const std::vector<SceneGenerator> generators = {
      {"cornell", "Cornell box with a short and a tall block (the default scene, 001 §6.1)",
       wrap(make_cornell_scene, "cornell")},
      {"atrium",
       "Two storeys of columns and arches around a courtyard, hanging curtains, small occluders",
       wrap(make_atrium_scene, "atrium")},
      {"plane", "One open square plane (analytic: AO = 1 under any quadrature)",
       wrap(make_plane_scene, "plane")},
      {"parallel-planes", "A floor and a parallel ceiling at height h (analytic AO)",
       wrap(make_parallel_planes_scene, "parallel-planes")},
      {"wall", "A floor meeting a vertical wall (analytic AO near the wall)",
       wrap(make_wall_scene, "wall")},
  };
  return generators;
}

const SceneGenerator* find_scene_generator(const std::string& name) {
  for (const auto& g : scene_generators())
    if (g.name == name) return &g;
  return nullptr;
}

Scene generate_scene(const std::string& name, const nlohmann::json& params,
                     const std::string& context) {
  const SceneGenerator* generator = find_scene_generator(name);
  if (!generator) {
    std::string known;
    for (const auto& g : scene_generators()) known += (known.empty() ? "" : ", ") + g.name;
    throw UserError(context + ": unknown scene generator '" + name + "' (known: " + known + ")");
  }
  Scene scene = generator->make(params);
  scene.validate();
  return scene;
}

}  // namespace ldm
