#include "harness/measure/work_counters.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "harness/gl/bindings.h"
#include "harness/gl/egl_context.h"

namespace ldm {
namespace {

// A distribution's words before its bins: the sum (lo, hi) and the max of the values at or
// above kWorkExactBins only. A value below it (nearly every one) costs the replay a single
// atomic, its bin's: the count, the sum and the max of the small values follow exactly from
// the exact bins (work_distribution_stats).
constexpr uint32_t kDistributionHeader = 3;

uint32_t counter_words(WorkShape shape) {
  return shape == WorkShape::Total ? 2 : kDistributionHeader + kWorkBins;
}

uint64_t word_pair(const uint32_t* words) { return uint64_t(words[0]) | (uint64_t(words[1]) << 32); }

// The smallest value a bin holds (exact bins: the value itself; then powers of two).
uint32_t bin_floor(uint32_t bin) {
  if (bin < kWorkExactBins) return bin;
  return uint32_t(1) << (bin - kWorkExactBins + kWorkExactBits);
}

std::string distribution_description(const WorkCounter& c, const std::string& suffix) {
  if (suffix == "_mean") return c.description + ", mean per query";
  if (suffix == "_p50") return c.description + ", median (exact below 256, else a power-of-two floor)";
  if (suffix == "_p99") return c.description + ", 99th percentile (exact below 256, else a power-of-two floor)";
  if (suffix == "_max") return c.description + ", most in one query";
  return c.description + ", summed over the frame";
}

}  // namespace

const std::vector<PipelineStatistic>& pipeline_statistics() {
  static const std::vector<PipelineStatistic> statistics = {
      {GL_VERTICES_SUBMITTED, "vertices_submitted", "vertices", "vertices the draws submitted (the driver's count)"},
      {GL_VERTEX_SHADER_INVOCATIONS, "vertex_invocations", "invocations", "vertex shader invocations (the driver's count)"},
      {GL_FRAGMENT_SHADER_INVOCATIONS, "fragment_invocations", "invocations",
       "fragment shader invocations (the driver's count: llvmpipe's includes helper and masked-off lanes of its raster blocks)"},
      {GL_COMPUTE_SHADER_INVOCATIONS, "compute_invocations", "invocations", "compute shader invocations (the driver's count)"},
  };
  return statistics;
}

const std::vector<std::string>& work_distribution_suffixes() {
  static const std::vector<std::string> suffixes = {"_mean", "_p50", "_p99", "_max", "_total"};
  return suffixes;
}

std::vector<ColumnSpec> work_columns(const std::vector<WorkCounter>& counters) {
  std::vector<ColumnSpec> columns;
  auto add = [&](const std::string& name, const std::string& unit, const std::string& description,
                 bool deterministic) {
    for (ColumnSpec& c : columns)
      if (c.name == name) {  // a second owner: deterministic only if both are
        if (!deterministic) {
          c.deterministic = false;
          c.varies_between_runs = true;
        }
        if (c.description.find(description) == std::string::npos) c.description += "; or: " + description;
        return;
      }
    ColumnSpec c("work", name, unit, description, ColumnKind::Number,
                 deterministic ? VariesBetweenRuns::No : VariesBetweenRuns::Yes, Better::Lower);
    columns.push_back(std::move(c));
  };
  for (const WorkCounter& counter : counters) {
    const std::string note = counter.deterministic() ? "" : " (depends on arrival order)";
    if (counter.shape == WorkShape::Total) {
      add(counter.column(), counter.unit, counter.description + note, counter.deterministic());
    } else {
      for (const auto& suffix : work_distribution_suffixes())
        add(counter.column() + suffix, counter.unit,
            distribution_description(counter, suffix) + note, counter.deterministic());
    }
  }
  return columns;
}

uint32_t work_histogram_quantile(const uint32_t* bins, uint64_t count, double q) {
  if (count == 0) return 0;
  // The smallest value with at least ceil(q * count) values at or below it.
  const uint64_t rank = std::max<uint64_t>(1, uint64_t(std::ceil(q * double(count))));
  uint64_t seen = 0;
  for (uint32_t bin = 0; bin < kWorkBins; ++bin) {
    seen += bins[bin];
    if (seen >= rank) return bin_floor(bin);
  }
  return bin_floor(kWorkBins - 1);
}

WorkDistributionStats work_distribution_stats(const uint32_t* words) {
  WorkDistributionStats s;
  const uint32_t* bins = words + kDistributionHeader;
  s.sum = word_pair(words);  // of the large values
  s.max = words[2];          // of the large values (0: none)
  for (uint32_t bin = 0; bin < kWorkBins; ++bin) {
    s.count += bins[bin];
    if (bin < kWorkExactBins && bins[bin] != 0) {
      s.sum += uint64_t(bin) * bins[bin];
      s.max = std::max(s.max, bin);
    }
  }
  s.p50 = work_histogram_quantile(bins, s.count, 0.50);
  s.p99 = work_histogram_quantile(bins, s.count, 0.99);
  return s;
}

WorkCounterBuffer::WorkCounterBuffer(std::vector<WorkCounter> counters) : counters_(std::move(counters)) {
  uint32_t words = 0;
  std::map<std::string, WorkShape> shape_of;
  for (const WorkCounter& c : counters_) {
    auto [it, fresh] = shape_of.emplace(c.name, c.shape);
    if (!fresh && it->second != c.shape)
      throw std::logic_error("work counter '" + c.name + "' is declared both a total and a distribution");
    if (fresh) {
      slot_[c.name] = words;
      words += counter_words(c.shape);
    }
    block_of_.emplace(c.subpass, block_of_.size());
  }
  GLint alignment = 4;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const uint32_t align_words = std::max<uint32_t>(1, uint32_t(alignment) / 4);
  block_words_ = std::max<uint32_t>(1, (words + align_words - 1) / align_words * align_words);
  scratch_ = block_of_.size();
  ran_.assign(scratch_ + 1, false);
  if (has_gl_extension("GL_ARB_pipeline_statistics_query")) {
    statistic_queries_.resize(pipeline_statistics().size());
    glGenQueries(GLsizei(statistic_queries_.size()), statistic_queries_.data());
  }
  buffer_ = GlBuffer("work counters", uint64_t(block_words_) * 4 * (scratch_ + 1));
  clear();
}

WorkCounterBuffer::~WorkCounterBuffer() {
  if (!statistic_queries_.empty()) glDeleteQueries(GLsizei(statistic_queries_.size()), statistic_queries_.data());
}

ShaderDefines WorkCounterBuffer::defines() const {
  ShaderDefines d;
  d.set("LDM_WORK_COUNT", 1);
  d.set("WORK_COUNTERS_BINDING", kWorkCountersBinding);
  d.set("WORK_EXACT_BINS", kWorkExactBins);
  d.set("WORK_EXACT_BITS", kWorkExactBits);
  d.set("WORK_DISTRIBUTION_HEADER", kDistributionHeader);
  for (const auto& [name, slot] : slot_) d.set("WORK_" + name, slot);
  return d;
}

void WorkCounterBuffer::clear() {
  // Every shader write counted so far lands before the zeroes (a software rasteriser may
  // still be shading the last draw when the clear is issued).
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  glFinish();
  buffer_.clear_to_zero();
  std::fill(ran_.begin(), ran_.end(), false);
  statistic_sums_.assign(scratch_ + 1, std::vector<uint64_t>(statistic_queries_.size(), 0));
  undeclared_seen_.clear();
  began_.clear();
  bind_block(scratch_);
}

void WorkCounterBuffer::bind_block(size_t block) const {
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kWorkCountersBinding, buffer_.id(),
                    GLintptr(uint64_t(block) * block_words_ * 4), GLsizeiptr(uint64_t(block_words_) * 4));
}

void WorkCounterBuffer::subpass_begun(const std::string& subpass) {
  const auto found = block_of_.find(subpass);
  const size_t block = found == block_of_.end() ? scratch_ : found->second;
  if (found == block_of_.end()) undeclared_seen_.push_back(subpass);
  began_.insert(subpass);
  ran_[block] = true;
  running_ = block;
  in_subpass_ = true;
  bind_block(block);
  begin_statistics();
}

void WorkCounterBuffer::subpass_ended(const std::string& /*subpass*/) {
  end_statistics();
  running_ = scratch_;
  in_subpass_ = false;
  bind_block(scratch_);
}

void WorkCounterBuffer::begin_statistics() {
  for (size_t i = 0; i < statistic_queries_.size(); ++i)
    glBeginQuery(pipeline_statistics()[i].target, statistic_queries_[i]);
  statistics_running_ = !statistic_queries_.empty();
}

void WorkCounterBuffer::end_statistics() {
  if (!statistics_running_) return;
  statistics_running_ = false;
  for (size_t i = 0; i < statistic_queries_.size(); ++i) glEndQuery(pipeline_statistics()[i].target);
  for (size_t i = 0; i < statistic_queries_.size(); ++i) {  // the replay may wait: it is untimed
    GLuint64 value = 0;
    glGetQueryObjectui64v(statistic_queries_[i], GL_QUERY_RESULT, &value);
    if (running_ < statistic_sums_.size()) statistic_sums_[running_][i] += value;
  }
}

void WorkCounterBuffer::pause_statistics() { end_statistics(); }

void WorkCounterBuffer::resume_statistics() {
  if (in_subpass_) begin_statistics();
}

std::vector<std::pair<std::string, RecordValue>> WorkCounterBuffer::read(
    std::vector<std::string>* problems) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<uint32_t> words = buffer_.download_all<uint32_t>();
  std::vector<std::pair<std::string, RecordValue>> fields;
  for (const WorkCounter& c : counters_) {
    const size_t block = block_of_.at(c.subpass);
    if (!ran_[block]) continue;  // the sub-pass did not run in the replayed frame
    const uint32_t* at = words.data() + size_t(block) * block_words_ + slot_.at(c.name);
    if (c.shape == WorkShape::Total) {
      fields.emplace_back(c.column(), int64_t(word_pair(at)));
      continue;
    }
    const WorkDistributionStats s = work_distribution_stats(at);
    if (s.count == 0) continue;
    fields.emplace_back(c.column() + "_mean", s.mean());
    fields.emplace_back(c.column() + "_p50", int64_t(s.p50));
    fields.emplace_back(c.column() + "_p99", int64_t(s.p99));
    fields.emplace_back(c.column() + "_max", int64_t(s.max));
    fields.emplace_back(c.column() + "_total", int64_t(s.sum));
  }
  for (const auto& [subpass, block] : block_of_) {
    if (!ran_[block] || statistic_queries_.empty()) continue;
    for (size_t i = 0; i < statistic_queries_.size(); ++i)
      fields.emplace_back("work_" + subpass + "_gl_" + pipeline_statistics()[i].name,
                          int64_t(statistic_sums_[block][i]));
  }
  if (problems) {
    // Work counted where no declaration names it would be missing from the record: a
    // counter a shader uses in a sub-pass its owner did not declare it for.
    for (const auto& [subpass, block] : block_of_)
      for (const auto& [name, slot] : slot_) {
        const bool declared = std::any_of(counters_.begin(), counters_.end(), [&](const WorkCounter& c) {
          return c.subpass == subpass && c.name == name;
        });
        if (declared || words[size_t(block) * block_words_ + slot] == 0) continue;
        problems->push_back("the counting replay counted " + name + " in sub-pass " + subpass +
                            ", which does not declare it (work_columns)");
      }
    const uint32_t* scratch = words.data() + size_t(scratch_) * block_words_;
    if (std::any_of(scratch, scratch + block_words_, [](uint32_t w) { return w != 0; })) {
      std::string where;
      for (const auto& name : undeclared_seen_) where += (where.empty() ? "" : ", ") + name;
      problems->push_back("the counting replay counted work outside the sub-passes that declare counters" +
                          (where.empty() ? std::string() : " (in " + where + ")"));
    }
  }
  return fields;
}

namespace {
struct CountingScopeState {
  bool alive = false;
  bool blend_totals = false;
  WorkCounterBuffer* counts = nullptr;
  std::vector<std::string> inexact_blends;
};
CountingScopeState& counting_scope() {
  static CountingScopeState state;
  return state;
}
}  // namespace

WorkCountingScope::WorkCountingScope(const ShaderDefines& defines, bool blend_totals,
                                     WorkCounterBuffer* counts) {
  static ShaderDefines active;
  active = defines;
  set_program_wide_defines(&active);
  counting_scope() = {true, blend_totals, counts, {}};
}

WorkCountingScope::~WorkCountingScope() {
  set_program_wide_defines(nullptr);
  counting_scope().alive = false;
}

bool WorkCountingScope::blending_totals() { return counting_scope().alive && counting_scope().blend_totals; }

void WorkCountingScope::report_inexact_blend(const std::string& where) {
  if (counting_scope().alive) counting_scope().inexact_blends.push_back(where);
}

const std::vector<std::string>& WorkCountingScope::inexact_blends() const {
  return counting_scope().inexact_blends;
}

bool WorkCountingScope::active() { return counting_scope().alive; }

UncountedGpuWork::UncountedGpuWork()
    : counts_(counting_scope().alive ? counting_scope().counts : nullptr) {
  if (counts_) counts_->pause_statistics();
}

UncountedGpuWork::~UncountedGpuWork() {
  if (counts_) counts_->resume_statistics();
}

}  // namespace ldm
