#pragma once
// The interface every layered-depth-map structure implements (the heart of ldmbench).
//
// C++ side: prepare() sizes GPU storage from the sizing plan (ldm_impls/common/sizing.h:
// the policy and what it lets the structure know; never the census itself) and the
// structure's parameters; build() runs the construction sub-passes, each timed; stats()
// reports what the last build stored and lost; memory() breaks storage down by buffer.
// needed()/fits()/resize() let a sizing policy grow the storage between builds
// (ldm_impls/common/sizing_driver.h).
// GLSL side: query_sources()/query_defines() implement the query API of
// shaders/common/ldm_query_api.glsl, which is all a pass ever reads.
//
// Adding a structure touches ldm_impls/<name>/ and shaders/ldm/<name>/ only; register it in
// ldm_impls/structure_registry.cpp.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harness/axes/axis.h"
#include "harness/gl/shader_program.h"
#include "harness/measure/gpu_timer.h"
#include "harness/measure/work_counters.h"
#include "harness/scene/gpu_scene.h"
#include "harness/util/error.h"
#include "harness/views/view_set.h"
#include "ldm_impls/common/fragment_source.h"
#include "ldm_impls/common/sizing.h"

namespace ldm {

// Per-fragment data the enabled passes need stored besides depth. AO needs nothing more;
// the indirect-light pass (a later issue) will ask for normals and albedo.
struct FragmentPayload {
  bool normal = false;
  bool albedo = false;
  std::string describe() const;  // "depth", "depth+normal", ...
};

struct BuildInputs {
  const GpuScene& scene;
  const GpuViewSet& views;
  // Everything a structure may size from. The untimed census is verification only and is
  // deliberately not reachable from here (harness/measuring/ldm_setup.h keeps it).
  const SizingPlan& sizing;
  FragmentPayload payload;
  // Compiles and runs the geometry-pass fragment shaders: the scene rasterised into the views
  // (RasterFragmentSource), or a synthetic fragment list in the contention tests. A
  // structure's fragment shaders go through it and nothing else.
  const FragmentSource& fragments;
};

struct BufferMemory {
  std::string name;
  uint64_t allocated = 0;  // bytes reserved on the device
  uint64_t used = 0;       // bytes holding data after the last build
};

struct BuildStats {
  // Fragments the construction tried to store, from the structure's own GPU state: the
  // lists' node counter, the DF-buffer's scan, PPFLA's per-pixel counts; for PSPPFLA and the
  // HA-buffer, the entries found in storage plus the fragments counted as dropped (an
  // untimed reduction in stats()). The per-build integrity check
  // (BuildHealth, ldm_impls/common/build_health.h) compares it with the census, so a fragment the
  // device silently failed to store is flagged as invalid.
  uint64_t fragments_rasterized = 0;
  uint64_t fragments_stored = 0;      // fragments the structure holds
  uint64_t fragments_lost = 0;        // rasterized - stored: overflow, drops, aborted inserts
  bool overflow = false;              // storage too small for the fragments
  // Structure-specific counts, e.g. {"lists_sorted_in_place", 3}.
  std::vector<std::pair<std::string, double>> counters;
};

// key=value parameters of a structure (--param ppfla:k=4) or of a pass
// (harness/passes/pass.h), read against the owner's declarations (harness/axes/axis.h: the
// parameter's kind, range or choices, default, unit and description, written once beside
// the code that reads it). declare() gives the declarations; check() refuses a key the owner
// does not declare (a typo) and a value outside its declaration, before any GPU work; the
// getters return the value given, else the declared default.
class StructureParams {
 public:
  StructureParams() = default;
  explicit StructureParams(std::map<std::string, std::string> values, std::string context = {})
      : values_(std::move(values)), context_(std::move(context)) {}
  void declare(std::vector<AxisSpec> specs) { specs_ = std::move(specs); }
  // `owner` names whose parameters these are in the message, e.g. "structure psppsll".
  void check(const std::string& owner) const;
  uint64_t get_uint(const std::string& key) const;
  double get_double(const std::string& key) const;
  std::string get_choice(const std::string& key) const;
  bool get_bool(const std::string& key) const;
  // Whether `key` was given (a parameter whose declaration has no default: the scene's value
  // or an automatic size applies otherwise).
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  const std::map<std::string, std::string>& values() const { return values_; }

 private:
  // The canonical text of `key`: given or the declared default (throws when neither).
  std::string text(const std::string& key, AxisKind kind) const;
  const AxisSpec& spec(const std::string& key) const;

  std::map<std::string, std::string> values_;
  std::string context_;
  std::vector<AxisSpec> specs_;
};

class LdmStructure {
 public:
  virtual ~LdmStructure() = default;

  virtual std::string name() const = 0;
  // Sizes storage and compiles the construction shaders. Throws UserError when the
  // configuration cannot run here (e.g. a buffer larger than the device's storage block).
  virtual void prepare(const BuildInputs& in) = 0;
  // One construction: every sub-pass (clear, count, scan, store, sort...) timed by `timer`.
  virtual void build(const BuildInputs& in, GpuTimer* timer) = 0;
  // What the last build stored and lost (reads small counters back; never timed). Any
  // number of calls, in any order with memory(), give the same answer.
  virtual BuildStats stats() const = 0;

  // Sizing between builds (driven by ldm_impls/common/sizing_driver.h, never by the census):
  // what the last build would have needed, from the structure's own GPU counters, even when
  // it overflowed (a small read-back the caller times); whether the storage holds `needs`;
  // and growing it to hold them (buffers reallocated, size-dependent shaders recompiled).
  // A storage size fixed by the budget policy or by an explicit parameter always "fits".
  virtual SizingNeeds needed() = 0;
  virtual bool fits(const SizingNeeds& needs) const = 0;
  virtual void resize(const SizingNeeds& needs) = 0;
  // True when build() counts its own fragments before storing them (the DF-buffer): under
  // the census policy it then sizes itself inside build() and no separate census runs.
  virtual bool counts_own_fragments() const { return false; }
  // What a second build does to the storage before building, after a first build whose
  // sizing held (the HA-buffer leaves previous_frame's guess and frees its third counter
  // word). Only the memory plan calls it, for a run of more than one build, so that the plan
  // is the storage such a run records (harness/run/memory_plan.h); builds do it themselves.
  virtual void settle_after_first_build() {}
  // Changes whenever resize() changed query_defines(): passes recompile their programs.
  uint64_t storage_generation() const { return storage_generation_; }

  // The query API implementation: files prepended to a pass's shader, their defines, and
  // the bindings they read.
  virtual std::vector<std::string> query_sources() const = 0;
  virtual ShaderDefines query_defines() const = 0;
  virtual void bind_for_query() const = 0;

  // Every buffer, allocated and used by the last build (reads back what it needs itself).
  virtual std::vector<BufferMemory> memory() const = 0;
  // How storage was sized, for records: e.g. {"pool_policy", "counted"}.
  virtual std::vector<std::pair<std::string, std::string>> sizing() const = 0;
  // Worst-case depth error of the stored depths against the rasterised float depth, in
  // scene units (0 for structures that store the float itself).
  virtual double depth_quantum(const LdmView& view) const {
    (void)view;
    return 0.0;
  }

 protected:
  void query_defines_changed() { ++storage_generation_; }

 private:
  uint64_t storage_generation_ = 0;
};

// What every structure declares, written once: its static declarations (registered in
// ldm_structure.cpp's table) and the overrides of LdmStructure's pure virtual functions,
// which all six structures implement alike. Optional overrides (counts_own_fragments,
// settle_after_first_build, depth_quantum) follow the macro in the structures that have them.
#define LDM_STRUCTURE_DECLARATIONS(NAME)                                              \
  /* The parameters --param NAME:KEY=VALUE sets, declared (harness/axes/axis.h). */   \
  static std::vector<AxisSpec> parameters();                                          \
  /* What its build counts in the counting replay (harness/measure/work_counters.h). */ \
  static std::vector<WorkCounter> work_counters();                                    \
  /* What its query code counts in a pass's sub-pass (filled in by the caller). */    \
  static std::vector<WorkCounter> query_work_counters();                              \
                                                                                      \
  std::string name() const override { return NAME; }                                 \
  void prepare(const BuildInputs& in) override;                                       \
  void build(const BuildInputs& in, GpuTimer* timer) override;                        \
  BuildStats stats() const override;                                                  \
  SizingNeeds needed() override;                                                      \
  bool fits(const SizingNeeds& needs) const override;                                 \
  void resize(const SizingNeeds& needs) override;                                     \
  std::vector<std::string> query_sources() const override;                            \
  ShaderDefines query_defines() const override;                                       \
  void bind_for_query() const override;                                               \
  std::vector<BufferMemory> memory() const override;                                  \
  std::vector<std::pair<std::string, std::string>> sizing() const override

std::vector<std::string> structure_names();
// The parameters a structure declares (its --param STRUCTURE:KEY=VALUE), owner set; throws
// UserError for an unknown name.
std::vector<AxisSpec> structure_parameters(const std::string& name);
// The work a structure's build counts in the counting replay (harness/measure/
// work_counters.h), declared by the structure beside the shaders that count it.
std::vector<WorkCounter> structure_work_counters(const std::string& name);
// The work its query code (query_sources()) counts inside a pass's sub-pass `subpass` (the
// pass declares which of its sub-passes read the structure: pass_query_subpasses()).
std::vector<WorkCounter> structure_query_work_counters(const std::string& name, const std::string& subpass);
// What every geometry sub-pass counts without the structure's help: vertex shader
// invocations (ldm_raster.vert) and fragments shaded (LDM_SKIP_HELPER_INVOCATIONS).
std::vector<WorkCounter> geometry_work_counters(const std::string& subpass);
// The two counters of a draw under `subpass`, which every geometry sub-pass and G-buffer
// declares: "vertices" (vertex shader invocations) and "fragments" (fragments shaded), each
// described after "<subpass>: ".
std::vector<WorkCounter> draw_work_counters(const std::string& subpass,
                                            const std::string& vertices_what,
                                            const std::string& fragments_what);
// Throws UserError for an unknown name (listing the known ones) or bad parameters.
std::unique_ptr<LdmStructure> make_structure(const std::string& name, StructureParams params);

// checked_storage_block's refusal, with what did not fit, so that a caller who knows the
// scene's census can say what would (ldm_impls/common/storage_fit.h).
class StorageBlockExceeded : public UserError {
 public:
  StorageBlockExceeded(const std::string& message, std::string structure, std::string buffer,
                       uint64_t bytes, uint64_t limit, uint32_t entries_per_pixel)
      : UserError(message),
        structure(std::move(structure)),
        buffer(std::move(buffer)),
        bytes(bytes),
        limit(limit),
        entries_per_pixel(entries_per_pixel) {}
  std::string structure, buffer;
  uint64_t bytes, limit;
  uint32_t entries_per_pixel;  // a fixed array's k (its bytes grow with it); 0 otherwise
};

// Helpers shared by implementations.
// Throws StorageBlockExceeded when `bytes` exceed the device's block size; a fixed array
// passes its k as `entries_per_pixel`.
uint64_t checked_storage_block(const std::string& structure, const std::string& buffer,
                               uint64_t bytes, uint32_t entries_per_pixel = 0);
// LDM_HEADS_TOTAL and LDM_MAX_LIST_LENGTH = kMaxListWalk.
ShaderDefines common_structure_defines(const BuildInputs& in);
ShaderDefines common_structure_defines(uint64_t ldm_pixels);
// LDM_MAX_LIST_LENGTH, the bound on every list walk (the trace, the inspector): only a
// safety net, since the query API ends each list itself. A constant, the same for every
// structure and policy, because no structure may size from the census; large enough for
// any scene here (a census deeper than this makes the measurement invalid).
constexpr uint32_t kMaxListWalk = 1u << 16;
// "oracle", "census", "previous_frame", "budget" or "parameter": where a size came from.
std::string size_source(const SizingPlan& plan, bool explicit_parameter);
// The bytes the budget policy leaves for a structure's sized storage after its fixed
// buffers; throws UserError naming the structure when the budget cannot hold them.
uint64_t budget_after(const std::string& structure, const SizingPlan& plan, uint64_t fixed_bytes);

}  // namespace ldm
