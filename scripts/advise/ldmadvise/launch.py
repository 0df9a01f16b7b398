"""How a stage's sweep file is measured: in one `ldmbench sweep` process, in shards run one
after another here (`--shards N`), or in shards as a Slurm job array (`--launcher slurm`,
through scripts/slurm-sweep.sh: every shard on a GPU node of its own, then `ldmbench merge`).
Each launcher returns the folder whose records.csv holds the stage's records, and runs the
census's memory plan (`ldmbench sweep --memory-plan`) where the stages run.

Sharded stages keep their shards in STAGE/shards-N/ (shard-I, merged, slurm-logs), N the
shards actually used (never more than the stage's configurations), so a rerun with another
--shards starts that stage's shards afresh instead of mixing two deals. A rerun resumes
like a sweep: every shard skips what it recorded. Under Slurm the journal keeps each
submission's job ids; a rerun while they are still queued or running waits for them
(reattaches) instead of submitting the stage twice.
"""
import json
import os
import subprocess
import sys
import time

# The one records reader (scripts/ldmrecords, installed beside the advise folder).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import ldmrecords  # noqa: E402

SWEEP_FINISHED = (0, 3)  # ok; finished with some records failed (those are pruned)


class LaunchError(Exception):
    pass


def complete(records_csv, keys):
    """Whether records_csv holds every key (a config_id column)."""
    if not os.path.isfile(records_csv):
        return False
    have = ldmrecords.by_config_id(records_csv)
    return all(k in have for k in keys)


class SingleProcess:
    """The stage as one `ldmbench sweep` into STAGE/run (the default)."""

    def __init__(self, ldmbench, cache_dir):
        self.ldmbench, self.cache_dir = ldmbench, cache_dir

    def sweep_argv(self, sweep_path, out, shard=None):
        argv = [self.ldmbench, "sweep", sweep_path, "--out", out]
        if shard:
            argv += ["--shard", shard]
        if self.cache_dir:
            argv += ["--cache-dir", self.cache_dir]
        return argv

    def call(self, argv, log_path, what, env=None):
        with open(log_path, "a", encoding="utf-8") as log:
            status = subprocess.call(argv, stdout=log, stderr=subprocess.STDOUT, env=env)
        if status not in SWEEP_FINISHED:
            raise LaunchError(f"{what}: `{' '.join(argv)}` exited {status} (its output: {log_path})")

    def run(self, folder, sweep_path, keys, stage, log):
        run = os.path.join(folder, "run")
        self.call(self.sweep_argv(sweep_path, run), os.path.join(folder, "sweep.log"), f"stage {stage}")
        return run

    def plan_argv(self, sweep_path, folder):
        return [self.ldmbench, "sweep", sweep_path, "--memory-plan", "--out", os.path.join(folder, "plan")]

    def plan(self, folder, sweep_path, keys, stage, log):
        """The stage's memory plan (`ldmbench sweep --memory-plan`: census and storage, nothing
        built or timed) in STAGE/plan/memory-plan.csv; kept when a rerun finds it whole."""
        csv_path = os.path.join(folder, "plan", "memory-plan.csv")
        if not complete(csv_path, keys):
            self.run_plan(folder, sweep_path, stage)
        if not complete(csv_path, keys):
            raise LaunchError(f"stage {stage}: {csv_path} lacks configurations "
                              f"(see {os.path.join(folder, 'plan.log')})")
        return csv_path

    def run_plan(self, folder, sweep_path, stage):
        self.call(self.plan_argv(sweep_path, folder), os.path.join(folder, "plan.log"), f"stage {stage}")


def shard_count(wanted, keys):
    return max(1, min(wanted, len(keys)))


class LocalShards(SingleProcess):
    """The stage in N shards, one process after another on this machine, then merged: what a
    sweep's shards do, without a scheduler (one GPU times one shard at a time)."""

    def __init__(self, ldmbench, cache_dir, shards):
        super().__init__(ldmbench, cache_dir)
        self.shards = shards

    def run(self, folder, sweep_path, keys, stage, log):
        n = shard_count(self.shards, keys)
        base = os.path.join(folder, f"shards-{n}")
        merged = os.path.join(base, "merged")
        if complete(os.path.join(merged, "records.csv"), keys):
            return merged
        os.makedirs(base, exist_ok=True)
        log_path = os.path.join(folder, "sweep.log")
        for i in range(n):
            self.call(self.sweep_argv(sweep_path, os.path.join(base, f"shard-{i}"), f"{i}/{n}"), log_path,
                      f"stage {stage}, shard {i}/{n}")
        self.call([self.ldmbench, "merge", "--overwrite", merged] + [os.path.join(base, f"shard-{i}") for i in range(n)],
                  log_path, f"stage {stage}, merge")
        log({"event": "shards_merged", "stage": stage, "folder": folder, "shards": n})
        return merged


class SlurmShards(SingleProcess):
    """The stage as a Slurm job array of N shards plus the merge job (scripts/slurm-sweep.sh),
    waited for here. The environment's LDM_SLURM_GPUS, LDM_SLURM_GPU_ARGS and SBATCH_ARGS
    reach the jobs as they reach slurm-sweep.sh; LDM_SWEEP_ARGS gets --cache-dir added."""
    RESUBMISSIONS = 2   # a failed shard is resubmitted (it resumes) this often, then the stage fails

    def __init__(self, ldmbench, cache_dir, shards, script, journal, poll_s=2.0):
        super().__init__(ldmbench, cache_dir)
        self.shards, self.script, self.poll_s = shards, script, poll_s
        self.journal = journal  # the events of earlier calls: submissions to reattach to

    def submit(self, sweep_path, n, base, tasks=None):
        env = dict(os.environ, LDMBENCH=self.ldmbench)
        jobs_file = os.path.join(base, "jobs.json.tmp")
        env["LDM_SLURM_JOBS_FILE"] = jobs_file
        if self.cache_dir:
            env["LDM_SWEEP_ARGS"] = (env.get("LDM_SWEEP_ARGS", "") + " --cache-dir " + self.cache_dir).strip()
        if tasks:
            env["LDM_SLURM_TASKS"] = ",".join(str(t) for t in tasks)
        else:
            env.pop("LDM_SLURM_TASKS", None)
        r = subprocess.run([self.script, sweep_path, str(n), base], env=env, capture_output=True, text=True)
        if r.returncode != 0 or not os.path.isfile(jobs_file):
            raise LaunchError(f"{self.script} {sweep_path} {n} {base} exited {r.returncode}: "
                              f"{(r.stderr or r.stdout).strip()}")
        with open(jobs_file, encoding="utf-8") as f:
            jobs = json.load(f)
        os.remove(jobs_file)
        return jobs

    def queued(self, job_ids):
        """The ids of job_ids still pending or running (squeue; a job it no longer knows has ended)."""
        r = subprocess.run(["squeue", "-h", "-o", "%F", "-j", ",".join(job_ids)], capture_output=True, text=True)
        if r.returncode != 0:
            if "Invalid job id" in r.stderr:
                return set()
            raise LaunchError(f"squeue -j {','.join(job_ids)} exited {r.returncode}: {r.stderr.strip()}")
        return {line.strip() for line in r.stdout.splitlines() if line.strip()} & set(job_ids)

    def wait(self, jobs):
        """Until neither job is pending or running (however long the queue takes: a killed
        advise reattaches when rerun)."""
        ids = [str(jobs["array"]), str(jobs["merge"])]
        while self.queued(ids):
            time.sleep(self.poll_s)

    def run_plan(self, folder, sweep_path, stage):
        """On a GPU node too (the storage block that refuses a buffer is the GPU's): one job
        through slurm-sweep.sh (LDM_SLURM_PLAN=1), with the shards' GPU and sbatch options,
        waited for; its log in STAGE/plan/slurm-logs/."""
        env = dict(os.environ, LDMBENCH=self.ldmbench, LDM_SLURM_PLAN="1")
        self.call([self.script, os.path.abspath(sweep_path), "1", os.path.abspath(os.path.join(folder, "plan"))],
                  os.path.join(folder, "plan.log"), f"stage {stage} (the memory plan as a Slurm job)", env)

    def earlier_submission(self, folder):
        for event in reversed(self.journal):
            if event.get("event") in ("submitted", "resubmitted") and event.get("folder") == folder:
                return event
        return None

    def run(self, folder, sweep_path, keys, stage, log):
        n = shard_count(self.shards, keys)
        base = os.path.abspath(os.path.join(folder, f"shards-{n}"))
        merged = os.path.join(base, "merged")
        records = os.path.join(merged, "records.csv")
        earlier = self.earlier_submission(folder)
        if earlier and earlier.get("shards") == n and self.queued([str(earlier["array"]), str(earlier["merge"])]):
            log({"event": "reattached", "stage": stage, "folder": folder, "array": earlier["array"],
                 "merge": earlier["merge"]})
            self.wait(earlier)
        for attempt in range(self.RESUBMISSIONS + 1):
            if complete(records, keys):
                return merged
            os.makedirs(base, exist_ok=True)
            missing = self.unfinished_shards(sweep_path, base, n) if attempt else None
            jobs = self.submit(os.path.abspath(sweep_path), n, base, missing)
            event = {"event": "submitted" if not attempt else "resubmitted", "stage": stage, "folder": folder,
                     "shards": n, "tasks": missing, **jobs}
            self.journal.append(event)
            log(event)
            self.wait(jobs)
        if complete(records, keys):
            return merged
        raise LaunchError(f"stage {stage}: {records} still lacks configurations after {self.RESUBMISSIONS} "
                          f"resubmissions; the jobs' logs are in {os.path.join(base, 'slurm-logs')}")

    def unfinished_shards(self, sweep_path, base, n):
        """The shards whose folder lacks one of their configurations (`sweep --dry-run --shard`)."""
        out = []
        for i in range(n):
            r = subprocess.run([self.ldmbench, "sweep", sweep_path, "--dry-run", "--shard", f"{i}/{n}"],
                               capture_output=True, text=True)
            ids = [line.split("\t")[1] for line in r.stdout.splitlines() if "\t" in line]
            if not complete(os.path.join(base, f"shard-{i}", "records.csv"), ids):
                out.append(i)
        return out or list(range(n))
