#include "harness/reference/reference_cache.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/util/error.h"
#include "harness/util/files.h"
#include "harness/util/hash.h"
#include "harness/util/json_input.h"

namespace ldm {

std::string default_reference_cache_dir() {
  const std::string folder = ldmbench_cache_dir("references");
  if (!folder.empty()) return folder;
  throw UserError("the reference cache has no default folder: neither XDG_CACHE_HOME (absolute) "
                  "nor HOME is set; give --cache-dir");
}

std::string reference_cache_dir(const std::string& given) {
  return given.empty() ? default_reference_cache_dir() : given;
}

std::string reference_cache_default_text() {
  return "The reference cache's folder when --cache-dir is not given: "
         "$XDG_CACHE_HOME/ldmbench/references, else ~/.cache/ldmbench/references";
}

namespace {

struct EntryPaths {
  std::string image, half_a, half_b, sidecar;
};

EntryPaths entry_paths(const std::string& cache_dir, const std::string& key) {
  const std::filesystem::path base = std::filesystem::path(cache_dir) / key;
  return {base.string() + ".exr", base.string() + ".a.exr", base.string() + ".b.exr",
          base.string() + ".json"};
}

std::string pixel_checksum(const Image& image) {
  Fnv1a h;
  h.add(image.width);
  h.add(image.height);
  h.add(image.channels);
  h.add_vector(image.pixels);
  return hex64(h.value());
}

nlohmann::json image_record(const Image& image) {
  return {{"width", image.width},
          {"height", image.height},
          {"channels", image.channels},
          {"checksum", pixel_checksum(image)}};
}

// The image at `path` if it is exactly the one the sidecar describes.
std::optional<Image> read_verified(const std::string& path, const nlohmann::json& record) {
  Image image = read_image(path);
  if (image_record(image) != record) return std::nullopt;
  return image;
}

// The checksum of a sidecar's content without its "checksum" field: the metadata (noise,
// spp, time) is covered like the pixels, so an edited noise_mse is a miss, not a result.
std::string metadata_checksum(nlohmann::json sidecar) {
  sidecar.erase("checksum");
  Fnv1a h;
  h.add_string(sidecar.dump());  // std::map-ordered keys: the text is canonical
  return hex64(h.value());
}

std::optional<ReferenceResult> try_load(const std::string& cache_dir,
                                        const nlohmann::json& inputs) {
  const std::string key = reference_cache_key(inputs);
  const EntryPaths paths = entry_paths(cache_dir, key);
  std::ifstream in(paths.sidecar, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json sidecar = parse_json_strictly(text.str(), paths.sidecar);  // throws on corrupt text
  // An entry of a build before the checksum, or one whose metadata was edited: a miss.
  if (!sidecar.is_object() || !sidecar.contains("checksum") ||
      sidecar.at("checksum") != metadata_checksum(sidecar))
    return std::nullopt;
  if (sidecar.at("key").get<std::string>() != key || sidecar.at("inputs") != inputs)
    return std::nullopt;
  const nlohmann::json& images = sidecar.at("images");
  ReferenceResult r;
  auto image = read_verified(paths.image, images.at("reference"));
  auto half_a = read_verified(paths.half_a, images.at("half_a"));
  auto half_b = read_verified(paths.half_b, images.at("half_b"));
  if (!image || !half_a || !half_b) return std::nullopt;
  r.image = std::move(*image);
  r.half_a = std::move(*half_a);
  r.half_b = std::move(*half_b);
  r.spp_per_half = sidecar.at("spp_per_half").get<uint32_t>();
  r.spp_total = sidecar.at("spp_total").get<uint32_t>();
  r.noise_mse = sidecar.at("noise_mse").get<double>();
  r.noise_target_met = sidecar.at("noise_target_met").get<bool>();
  r.render_seconds = sidecar.at("render_seconds").get<double>();
  r.from_cache = true;
  r.cache_key = key;
  return r;
}

}  // namespace

nlohmann::json spp_rule_inputs(const SppRule& rule) {
  if (rule.spp_per_half > 0) return {{"per_half", rule.spp_per_half}};
  return {{"auto_target_noise_mse", rule.target_noise_mse},
          {"auto_max_per_half", rule.max_spp_per_half},
          {"auto_start_per_half", rule.start_spp_per_half}};
}

std::string reference_cache_key(const nlohmann::json& inputs) {
  Fnv1a h;
  h.add_string(inputs.dump());  // std::map-ordered keys: the text is canonical
  return hex64(h.value());
}

std::optional<ReferenceResult> load_cached_reference(const std::string& cache_dir,
                                                     const nlohmann::json& inputs) {
  try {
    return try_load(cache_dir, inputs);
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable or inconsistent entry: render again and overwrite
  }
}

void store_cached_reference(const std::string& cache_dir, const nlohmann::json& inputs,
                            const ReferenceResult& result) {
  const std::string key = reference_cache_key(inputs);
  const EntryPaths paths = entry_paths(cache_dir, key);
  try {
    std::filesystem::create_directories(cache_dir);
  } catch (const std::filesystem::filesystem_error& e) {
    throw UserError("cannot create reference cache directory '" + cache_dir + "': " + e.what());
  }
  write_exr(paths.image, result.image);
  write_exr(paths.half_a, result.half_a);
  write_exr(paths.half_b, result.half_b);
  nlohmann::json sidecar = {
      {"key", key},
      {"inputs", inputs},
      {"spp_per_half", result.spp_per_half},
      {"spp_total", result.spp_total},
      {"noise_mse", result.noise_mse},
      {"noise_target_met", result.noise_target_met},
      {"render_seconds", result.render_seconds},
      {"images",
       {{"reference", image_record(result.image)},
        {"half_a", image_record(result.half_a)},
        {"half_b", image_record(result.half_b)}}}};
  sidecar["checksum"] = metadata_checksum(sidecar);
  write_text_atomically(paths.sidecar, sidecar.dump(2) + "\n");
}

}  // namespace ldm
