#include "harness/scene/generators.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "harness/scene/scene_defaults.h"
#include "harness/util/error.h"
#include "harness/util/hash.h"
#include "harness/util/text.h"

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
  if (!v.is_number()) throw UserError(where(key) + " must be a number");
  // Checked after the conversion to float, the type the scene stores.
  const double given = v.get<double>();
  const float x = float(given);
  if (!(x >= lo && x <= hi))
    throw UserError(where(key) + " = " + format_significant(given) + " is outside [" +
                    format_significant(lo) + ", " + format_significant(hi) + "]");
  return x;
}

int GeneratorParams::integer(const std::string& key, int fallback, int lo, int hi) {
  used_.push_back(key);
  if (params_.is_null() || !params_.contains(key)) return fallback;
  const auto& v = params_.at(key);
  if (!v.is_number_integer()) throw UserError(where(key) + " must be an integer");
  // Compared as 64-bit values: get<int>() would wrap 2^32 + 1 to 1.
  const int64_t x = v.is_number_unsigned()
                        ? int64_t(std::min<uint64_t>(v.get<uint64_t>(), uint64_t(INT64_MAX)))
                        : v.get<int64_t>();
  if (x < lo || x > hi)
    throw UserError(where(key) + " = " + std::to_string(x) + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return int(x);
}

bool GeneratorParams::boolean(const std::string& key, bool fallback) {
  used_.push_back(key);
  if (params_.is_null() || !params_.contains(key)) return fallback;
  const auto& v = params_.at(key);
  if (!v.is_boolean()) throw UserError(where(key) + " must be true or false");
  return v.get<bool>();
}

std::string GeneratorParams::where(const std::string& key) const {
  return context_ + "/" + key;
}

void GeneratorParams::finish() const {
  if (params_.is_null()) return;
  for (const auto& [key, value] : params_.items()) {
    if (key == "type") continue;
    if (std::find(used_.begin(), used_.end(), key) == used_.end())
      throw UserError(where(key) + " is unknown: not a parameter of this generator");
  }
}

const std::vector<SceneGenerator>& scene_generators() {
  auto wrap = [](Scene (*make)(GeneratorParams&), const char* name) {
    return [make, name](const nlohmann::json& params, const std::string& context) {
      GeneratorParams p(params, context);
      Scene scene = make(p);
      p.finish();
      scene.origin = std::string("built-in:") + name;
      set_setting_sources(scene, std::string("generator ") + name);
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
      {"spot-bounce",
       "A spot light on a floor beside a perpendicular wall lit only by the floor's reflection "
       "(analytic single-bounce light)",
       wrap(make_spot_bounce_scene, "spot-bounce")},
      {"closed-sphere",
       "The inside of a closed diffuse sphere around a spot light (analytic indirect light: "
       "an integrating sphere)",
       wrap(make_closed_sphere_scene, "closed-sphere")},
      {"hairball",
       "Thousands of thin curved tubes inside a sphere: even, high depth complexity (the "
       "thesis's second workload)",
       wrap(make_hairball_scene, "hairball")},
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
  Scene scene = generator->make(params, context);
  Fnv1a source;
  source.add_string("generator " + name);
  source.add_string(params.dump());  // sorted keys: the parameters, not their spelling
  scene.source_hash = source.value();
  scene.validate();
  return scene;
}

}  // namespace ldm
