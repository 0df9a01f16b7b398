#include "ldm_impls/psppsll/psppsll.h"

#include "harness/util/error.h"
#include "ldm_impls/common/structure_counters.h"

namespace ldm {

Psppsll::Psppsll(StructureParams& params) : pool_("psppsll", params) {
  atomic_reads_ = params.get_bool("atomic_reads");
}

// A data table of its own counters, alike in form only to the other structures' (see
// ldm_impls/common/structure_counters.h).
std::vector<WorkCounter> Psppsll::work_counters() {
  // shaders/ldm/psppsll/build.frag: where an insertion walks, and how often its
  // compare-and-swap loses, depends on the order the fragments arrive.
  return with_geometry_counters({"construct"}, {
      {"construct", "atomic_add", WorkShape::Total, "atomics",
       "construct: atomic counter increments (PSPPSLL, PPSLL: one node allocation per fragment, "
       "and PSPPSLL's abandoned insertions)"},
      {"construct", "atomic_cas", WorkShape::Total, "atomics",
       "construct: compare-and-swaps that publish a PSPPSLL node (one per fragment and one per retry)",
       kArrival},
      {"construct", "atomic_cas_failed", WorkShape::Total, "atomics",
       "construct: PSPPSLL compare-and-swaps that lost to a concurrent insertion (each a retry)",
       kArrival},
      {"construct", "insert_steps", WorkShape::Distribution, "steps",
       "construct: iterations of one PSPPSLL insertion's loop (one per node passed or retry, "
       "plus the one that inserts; one value per fragment given a node)", kArrival},
      bytes_loaded("construct", "heads", "PSPPSLL list heads read (the walk's start, 4 bytes per fragment)"),
      bytes_loaded("construct", "nodes",
          "PSPPSLL node bytes the insertion walks read (depths and next indices, 4 bytes "
          "each; compare-and-swaps not included)", kArrival),
      bytes_stored("construct", "nodes",
          "PSPPSLL or PPSLL node bytes written: each new node's depth and its next "
          "index (8 bytes per fragment stored; PSPPSLL's rewrites after a lost compare-and-swap "
          "apart)"),
      bytes_stored("construct", "nodes_relinked",
          "PSPPSLL next indices rewritten after a lost compare-and-swap (4 bytes each)", kArrival),
  });
}

std::vector<WorkCounter> Psppsll::query_work_counters() { return ListNodePool::query_work_counters(); }

std::vector<AxisSpec> Psppsll::parameters() {
  AxisSpec atomic_reads;
  atomic_reads.key = "atomic_reads";
  atomic_reads.kind = AxisKind::Bool;
  atomic_reads.default_value = "false";
  atomic_reads.description = "read list links with atomics (the thesis's §3.4.3 workaround)";
  return {ListNodePool::capacity_parameter(), atomic_reads};
}

std::optional<std::string> psppsll_driver_refusal(const DriverConformance& driver,
                                                  ProbeStage stage) {
  const BarrierProbeResult* defect = driver.barrier_defect(stage, ProbeBarrier::MemoryBarrier);
  if (!defect) return std::nullopt;
  return "psppsll cannot be measured on this driver: its insertion loop needs memoryBarrier() "
         "in a loop that invocations leave at different iterations, and the driver's self-test "
         "of exactly that failed (" +
         defect->describe() +
         "): its builds would lose fragments (docs/reference/structures.md#driver-conformance)";
}

void Psppsll::prepare(const BuildInputs& in) {
  if (auto refusal = psppsll_driver_refusal(driver_conformance(), in.fragments.stage()))
    throw UserError(*refusal);
  query_defines_ = common_structure_defines(in);
  ShaderDefines defines;
  // Each step passes one node or retries after a concurrent insertion, so a conforming
  // device needs at most about twice the longest list; beyond 4x the walk bound + 64 an
  // insertion is abandoned and counted, so that a defective device cannot hang the GPU. (No
  // tighter bound is known without the census, which the structure does not see.)
  defines.set("LDM_MAX_INSERT_STEPS", std::to_string(4ull * kMaxListWalk + 64) + "u");
  defines.set("LDM_ATOMIC_READS", atomic_reads_ ? 1 : 0);
  pool_.prepare(in, "ldm/psppsll/build.frag", defines);
}

void Psppsll::build(const BuildInputs& in, GpuTimer* timer) { pool_.build(in, timer); }
SizingNeeds Psppsll::needed() { return pool_.needed(); }
bool Psppsll::fits(const SizingNeeds& needs) const { return pool_.fits(needs); }
void Psppsll::resize(const SizingNeeds& needs) { pool_.resize(needs); }

BuildStats Psppsll::stats() const {
  const auto counters = pool_.read_counters();  // [1]: insertions abandoned
  BuildStats s = pool_.stats(counters, counters[1]);
  s.counters.emplace_back("aborted_insertions", double(counters[1]));
  return s;
}

std::vector<std::string> Psppsll::query_sources() const { return {"ldm/common/list_query.glsl"}; }
ShaderDefines Psppsll::query_defines() const { return query_defines_; }
void Psppsll::bind_for_query() const { pool_.bind(); }
std::vector<BufferMemory> Psppsll::memory() const { return pool_.memory(stats().fragments_stored); }

std::vector<std::pair<std::string, std::string>> Psppsll::sizing() const {
  auto s = pool_.sizing();
  s.emplace_back("atomic_reads", atomic_reads_ ? "1" : "0");
  return s;
}

}  // namespace ldm
