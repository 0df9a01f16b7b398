#pragma once
// A disk cache of reference images. An entry is keyed by a JSON object of everything that
// affects the image (scene content hash, pass, size, settings, spp rule, seed, renderer
// version); the key is the 64-bit FNV-1a hash of that object's canonical text. In the cache
// directory an entry is
//   <key>.exr, <key>.a.exr, <key>.b.exr   the reference and its two independent halves
//   <key>.json                            the sidecar: inputs, spp, noise, time, checksums
// The sidecar is written last (atomically, like the images), so it marks a complete entry.
// An entry is used only if its sidecar parses, its inputs equal the request's exactly and
// every image matches its recorded shape and pixel checksum; anything else is a miss.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "harness/reference/reference_image.h"

namespace ldm {

// Where references are cached when no --cache-dir is given: the user's cache folder, as the
// XDG base directory specification puts it, $XDG_CACHE_HOME/ldmbench/references (an
// absolute XDG_CACHE_HOME only), else $HOME/.cache/ldmbench/references. Entries are keyed by
// content and renderer version and written atomically, so one cache serves every checkout,
// build, working folder and concurrent process (docs/reference/accuracy.md, "Cache").
// Throws UserError when neither variable gives a folder.
std::string default_reference_cache_dir();
// `given`, or the default when it is empty.
std::string reference_cache_dir(const std::string& given);
// How --help and the man page state the default (no machine's path).
std::string reference_cache_default_text();

std::string reference_cache_key(const nlohmann::json& inputs);
// The spp rule as a key's "spp" field: the fixed count, or the automatic rule's parameters.
nlohmann::json spp_rule_inputs(const SppRule& rule);

// The cached result (from_cache = true) or nothing; never throws on a bad entry.
std::optional<ReferenceResult> load_cached_reference(const std::string& cache_dir,
                                                     const nlohmann::json& inputs);
// Throws UserError naming the path if the directory or a file cannot be written.
void store_cached_reference(const std::string& cache_dir, const nlohmann::json& inputs,
                            const ReferenceResult& result);

}  // namespace ldm
