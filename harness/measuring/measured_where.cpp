#include "harness/measuring/measured_where.h"
#include "harness/records/harness_columns.h"

#include <unistd.h>

#include <cstdlib>

namespace ldm {

std::vector<std::pair<std::string, std::string>> slurm_job_columns() {
  static const std::pair<const char*, const char*> kVariables[] = {
      {"slurm_job_id", "SLURM_JOB_ID"},
      {"slurm_array_job_id", "SLURM_ARRAY_JOB_ID"},
      {"slurm_array_task_id", "SLURM_ARRAY_TASK_ID"},
      {"slurm_node", "SLURMD_NODENAME"},
      {"slurm_gpus", "SLURM_JOB_GPUS"},
  };
  std::vector<std::pair<std::string, std::string>> columns;
  for (const auto& [column, variable] : kVariables)
    if (const char* value = std::getenv(variable); value && *value) columns.emplace_back(column, value);
  return columns;
}

void describe_host(Record& record) {
  char name[256] = {};
  record.set(columns::kHost, ::gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string());
  for (const auto& [column, value] : slurm_job_columns()) record.set(column, value);
}

}  // namespace ldm
