#pragma once
// Where a record was measured: this machine's host name, and, when a Slurm job measured it
// (scripts/slurm-sweep.sh), which job, array task, node and GPUs, read from the variables
// Slurm sets in a job's environment. Every record carries them, since a merged sweep joins
// records of several jobs and nodes (docs/guide/sweeps.md#shards-merge-and-slurm).
#include <string>
#include <utility>
#include <vector>

#include "harness/records/record.h"

namespace ldm {

// The record columns of the Slurm job this process runs in, in a fixed order, each only
// when its variable is set and not empty (none outside Slurm): slurm_job_id (SLURM_JOB_ID),
// slurm_array_job_id, slurm_array_task_id, slurm_node (SLURMD_NODENAME), slurm_gpus
// (SLURM_JOB_GPUS, the node's GPU indices allocated to the job).
std::vector<std::pair<std::string, std::string>> slurm_job_columns();

// Sets host (gethostname) and the slurm_job_columns() on the record.
void describe_host(Record& record);

}  // namespace ldm
