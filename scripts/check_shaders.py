#!/usr/bin/env python3
"""Every shader program ldmbench builds, compiled again by a second GLSL front end: glslang
(glslangValidator, the Khronos reference compiler), as OpenGL GLSL 4.50 with the extensions
the sources enable. llvmpipe and zink share Mesa's GLSL compiler; the GPUs users run on
(NVIDIA's, AMD's) have their own, and glslang is the one that follows the specification.

  scripts/check_shaders.py [--build DIR] [--keep DIR]     the CI step (scripts/check-shaders.sh)
  scripts/check_shaders.py --dump DIR [--shaders DIR]     check a dump only (no runs)

The full check, in four parts:

1. Covering runs, with LDM_SHADER_DUMP set (harness/gl/shader_dump.h: every stage's exact
   source and every program's stages, deduplicated by content hash). Their values come from
   the registries, read from `ldmbench axes --json`, never listed here: one sweep
   (`ldmbench sweep`) of every structure x every pass, plus, one axis at a time, every other
   value of every choice and boolean axis (the trace variant, the sizing policy, the AO
   visibility and estimator, each structure's and pass's own choices: key width, atomic
   reads, jitter, emission ...) with every structure and pass it applies to, and every
   integer parameter of a structure or pass at its lower bound, or one above where that is
   its default (k = 0, an array of no entry; blur 1, a program only a nonzero radius
   builds); not reals, which
   change a value in the code, not the code. A pass that refuses a value it declares (the
   indirect pass takes only the default AO visibility) runs without it, as
   `ldmbench sweep --dry-run` says; a value no pass takes fails. Tiny sizes: the runs only
   need each program built once. Under llvmpipe, in shards run at once (one per core), with
   the test binaries that build programs no run does (the synthetic fragment source that
   runs fragment shaders as compute shaders, the driver self-test's failing variant, the
   indirect pass's probes) and `ldmbench view`'s point cloud on a virtual X server. Then
   under zink (over lavapipe) the configurations llvmpipe could not build: its
   GL_NV_shader_atomic_int64 builds the HA-buffer's 64-bit keys. The rest is the same code
   under zink (its sources differ only in sizes from the storage limits).
2. The runs' records: every configuration of the covering sweep built (a status other than
   failed) under at least one of the two drivers, so that no value the registry lists goes
   unchecked because its run failed.
3. Coverage of the dump (`--dump` checks this too): every shader file under shaders/ is in
   some dumped source, and every branch of every preprocessor conditional in them
   (#if/#ifdef/#ifndef/#elif/#else, and the implicit empty #else of an #if without one) was
   the active one in some dumped source, as glslang's own preprocessor decides (-E on a copy
   with a marker after each branch). Exempt: include guards' implicit #else, and branches
   holding only #error. A define value no run sets -- a new axis value, or a new define --
   fails here, naming the file and line of the branch no run compiled. And a file compiled
   with some of a family of preludes (the query API's users, each with a structure's query
   implementation) must have been compiled with all of them.
4. glslang on every dumped program: each stage with its stage (-S vert/frag/comp/geom), all
   stages of a program linked together (-l: the interfaces between stages must match).
   Flags: none beyond -S and -l. Without -V or -G, glslangValidator checks GLSL for OpenGL
   (client API OpenGL, no SPIR-V rules: default uniforms, atomic counters and std430 blocks
   are what the OpenGL GLSL specification says); the version and the extensions are the
   source's own (`#version 450 core`, its `#extension` lines), as every GL driver reads
   them. Warnings count as failures: a driver may reject what glslang only warns about.

Prints a summary (sources, programs, variants per shader file and prelude, branches, the
values each code-selecting define took) and exits 0 when everything was accepted; 1 with
each distinct glslang message once (its source strings named as shader files and lines),
the dumped files it came from and the command that reproduces it, or naming what the
covering runs missed; 2 when the check itself could not run (no glslangValidator, no zink,
a run that crashed). On a failure the dump, the generated sweep and every run's log are
kept (the folder is printed).
"""
import argparse
import concurrent.futures
import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import ldmrecords
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GLSLANG = "glslangValidator"
STAGES = ("vert", "tesc", "tese", "geom", "frag", "comp")
# The tiny configuration every covering run starts from: the programs depend on what a
# structure, pass or parameter selects, not on these sizes (4 views of 8x8, a 16x16 image,
# one frame, no warm-up, no reference).
TINY_AXES = {"views": 4, "r_ldm": 8, "image_size": "16x16", "frames": 1, "warmup": 0}
# Values a registry value cannot run without. The budget sizing policy needs a budget (its
# axis has no default); 1 MiB is enough for the tiny configuration.
COMPANIONS = {("sizing", "budget"): {"sizing_budget_mib": [1]}}
# Test binaries (build/tests/...) and the tests in them that build programs no run builds:
# the synthetic fragment source (fragment shaders run as compute shaders, every structure),
# the driver self-test's variant that drops invocations on purpose, the indirect pass's
# probes. Each pattern must match a test that ran.
TEST_PROGRAMS = [
    ("test_structures", "*/Contention.*:ContentionSource.*"),
    ("test_context", "DriverProbe.CatchesInvocationsThatNeverFinish"),
    ("test_indirect", "IndirectDegenerate.DifferentialFunctionsReportEveryDegenerateCase:"
                      "IndirectAudit.TheDepthTestHoldsAtItsThreshold"),
]
# `ldmbench view`: its display and point cloud programs (llvmpipe, under xvfb-run), the
# point cloud for every structure (the key s steps to the next one each frame).
VIEWER_ARGS = ["view", "--scene", "cornell", "-N", "4", "-R", "8", "--width", "16",
               "--height", "16", "--no-reference", "--layout", "points", "--hide-panel",
               "--window", "64x64", "--print-status"]


def viewer_command(ldmbench, structures):
    steps = ",".join(f"{frame}:s" for frame in range(1, len(structures)))
    return [ldmbench, *VIEWER_ARGS, "--structure", structures[0],
            "--frames", str(len(structures) + 1), *(["--script", steps] if steps else [])]


class CheckFailed(Exception):
    """A finding: the check ran and something failed it (exit 1)."""


class CannotCheck(Exception):
    """The check could not run (exit 2)."""


def log(message):
    print(f"check-shaders: {message}", flush=True)


# ---------------------------------------------------------------------------------------------
# 1. The covering runs.

def registry_axes(ldmbench):
    out = subprocess.run([ldmbench, "axes", "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        raise CannotCheck(f"{ldmbench} axes --json failed:\n{out.stderr}")
    return json.loads(out.stdout)["axes"]


def lower_values(axis):
    """An integer parameter's value to cover besides its default: its lower bound (a size of
    0 or 1, a loop of one turn), or one above it where the default is the bound (a radius
    that switches a program on)."""
    low = int(axis["min"])
    value = low if str(low) != axis.get("default") else low + 1
    return [value] if value <= axis["max"] else []


def other_values(axis):
    """An axis's values besides its default, as a sweep file writes them."""
    if axis["kind"] == "choice":
        return [c for c in axis["choices"] if c != axis.get("default")]
    if axis["kind"] == "bool":
        return [v for v in (False, True) if str(v).lower() != axis.get("default")]
    if axis["kind"] == "uint" and axis["owner"] != "harness":
        return lower_values(axis)
    # Text (scenes), image sizes and the harness's sizes (pinned tiny above), and reals: a real
    # changes a value in the code (a uniform, a constant), not the code.
    return []


def dry_run(ldmbench, sweep, scratch):
    """Whether `ldmbench sweep --dry-run` accepts the sweep, and its message when not."""
    path = scratch / "dry-run.json"
    path.write_text(json.dumps(sweep))
    out = subprocess.run([ldmbench, "sweep", path, "--dry-run"], capture_output=True, text=True)
    return out.returncode == 0, (out.stderr.strip().splitlines() or [""])[-1]


def covering_sweep(axes, ldmbench, scratch):
    """The sweep of part 1, and the values a pass refuses (pass -> [(axis value, why)])."""
    by_name = {a["name"]: a for a in axes}
    for name in ("passes", "structures", *TINY_AXES):
        if name not in by_name:
            raise CannotCheck(f"ldmbench axes has no axis '{name}' (the covering sweep needs it)")
    passes = by_name["passes"]["choices"]
    main = {"scenes": by_name["scenes"]["default"], "passes": passes,
            "structures": by_name["structures"]["choices"], **TINY_AXES}
    blocks = []
    for axis in axes:
        name = axis["name"]
        if name in main or name in ("passes", "structures"):
            continue
        values = other_values(axis)
        scope = {}
        if axis["owner"] != "harness":
            # A structure's parameter with that structure (every pass); a pass's with that
            # pass (every structure).
            scope = {"structures" if axis["owner_kind"] == "structure" else "passes": [axis["owner"]]}
        plain = [v for v in values if (name, v) not in COMPANIONS]
        if plain:
            blocks.append((f"{name}: {', '.join(map(str, plain))}", {**scope, name: plain}))
        for v in values:
            if (name, v) in COMPANIONS:
                blocks.append((f"{name}: {v}", {**scope, name: [v], **COMPANIONS[(name, v)]}))
    # A pass may refuse an axis value it declares (the indirect pass takes only the default
    # AO visibility and estimator): each block runs with the passes that accept it, asked of
    # `ldmbench sweep --dry-run`; a value no pass accepts fails the check.
    include, refused = [], defaultdict(list)
    for comment, block in blocks:
        accepted = []
        for p in block.get("passes", passes):
            ok, why = dry_run(ldmbench, {"axes": {**main, **block, "passes": [p]}}, scratch)
            if ok:
                accepted.append(p)
            else:
                refused[p].append((comment, why.split("}: ")[-1]))
        if not accepted:
            raise CheckFailed(f"no pass accepts {comment}:\n  " +
                              "\n  ".join(f"{p}: {w}" for p in refused for c, w in refused[p] if c == comment))
        include.append({"comment": comment, **block, "passes": accepted})
    sweep = {
        "description": "Generated by scripts/check_shaders.py from `ldmbench axes --json`: every "
                       "structure x pass, then every other value of every choice axis and the "
                       "lower bounds of every integer parameter, one axis at a time, at tiny "
                       "sizes; builds every shader program once.",
        "axes": main,
        "include": include,
        "settings": {"reference": {"enabled": False}, "images": False, "timing": {"target": 0}},
    }
    ok, why = dry_run(ldmbench, sweep, scratch)
    if not ok:
        raise CannotCheck(f"ldmbench refuses the covering sweep: {why}")
    return sweep, refused


def driver_env(driver, scratch):
    env = dict(os.environ)
    for name in ("MESA_LOADER_DRIVER_OVERRIDE", "LIBGL_ALWAYS_SOFTWARE", "GALLIUM_DRIVER"):
        env.pop(name, None)
    if driver == "zink":
        runtime = scratch / "xdg-runtime"
        runtime.mkdir(mode=0o700, exist_ok=True)
        env.update(XDG_RUNTIME_DIR=str(runtime), MESA_LOADER_DRIVER_OVERRIDE="zink",
                   LIBGL_ALWAYS_SOFTWARE="1")
    return env


def run_logged(command, env, log_path, ok_codes=(0,)):
    with open(log_path, "w") as out:
        status = subprocess.run(command, env=env, stdout=out, stderr=subprocess.STDOUT).returncode
    if status not in ok_codes:
        tail = Path(log_path).read_text(errors="replace").splitlines()[-30:]
        raise CannotCheck(f"{' '.join(map(str, command))} exited {status} (log {log_path}):\n" +
                          "\n".join(tail))
    return status


def renderer_check(ldmbench, driver, env):
    info = subprocess.run([ldmbench, "info"], env=env, capture_output=True, text=True)
    renderer = re.search(r"^renderer: (.*)$", info.stdout, re.M)
    if info.returncode != 0 or not renderer or not renderer.group(1).startswith(driver):
        raise CannotCheck(f"ldmbench info under {driver} opened "
                          f"{renderer.group(1) if renderer else 'nothing'}, not {driver} (zink: are "
                          "mesa-vulkan-drivers and libvulkan1 installed? scripts/setup.sh)\n" +
                          info.stdout + info.stderr)


def run_tests(binary, tests, build, env, log_path):
    """One of TEST_PROGRAMS; every pattern must match a test that ran."""
    run_logged([build / "tests" / binary, f"--gtest_filter={tests}"], env, log_path)
    ran = re.findall(r"^\[ RUN +\] (\S+)", Path(log_path).read_text(), re.M)
    for pattern in tests.split(":"):
        if not any(fnmatch.fnmatchcase(name, pattern) for name in ran):
            raise CannotCheck(f"{binary} --gtest_filter={tests}: no test matches {pattern} "
                              "(renamed? scripts/check_shaders.py names the tests that build "
                              "programs no run builds)")


def covering_runs_llvmpipe(build, sweep, sweep_file, dump, scratch, jobs):
    """Part 1 under llvmpipe: the covering sweep as `jobs` shards, the test binaries and the
    viewer, all at once (each process compiles on one core: compiling is most of the time).
    Returns the sweep's records."""
    work = scratch / "llvmpipe"
    work.mkdir()
    env = driver_env("llvmpipe", work)
    env["LDM_SHADER_DUMP"] = str(dump)
    ldmbench = build / "ldmbench"
    t0 = time.monotonic()
    renderer_check(ldmbench, "llvmpipe", env)
    if not shutil.which("xvfb-run"):
        raise CannotCheck("xvfb-run is not installed (scripts/setup.sh installs xvfb): "
                          "`ldmbench view`'s programs need a window")
    shards = max(1, jobs)
    # Exit 3: some configurations failed (key_bits=64 on llvmpipe): zink builds them below.
    tasks = [lambda i=i: run_logged(
                 [ldmbench, "sweep", sweep_file, "--shard", f"{i}/{shards}", "--out",
                  work / f"run-{i}", "--cache-dir", work / "cache"],
                 env, work / f"sweep-{i}.log", ok_codes=(0, 3)) for i in range(shards)]
    tasks += [lambda b=b, t=t: run_tests(b, t, build, env, work / f"{b}.log")
              for b, t in TEST_PROGRAMS]
    tasks.append(lambda: run_logged(["xvfb-run", "-a", "-s", "-screen 0 640x480x24",
                                     *viewer_command(ldmbench, sweep["axes"]["structures"])],
                                    env, work / "view.log"))
    with concurrent.futures.ThreadPoolExecutor(shards) as pool:
        for f in [pool.submit(t) for t in tasks]:
            f.result()
    records = [r for i in range(shards) for r in ldmrecords.read(work / f"run-{i}")]
    log(f"llvmpipe: {len(records)} configurations in {shards} shards, {len(TEST_PROGRAMS)} test "
        f"binaries and the viewer in {time.monotonic() - t0:.0f} s")
    return records


def covering_runs_zink(build, sweep_file, ids, dump, scratch):
    """Part 1 under zink: the configurations llvmpipe could not build (its
    GL_NV_shader_atomic_int64 builds the HA-buffer's 64-bit keys), and nothing else: every
    other program is the same source under both drivers (zink-tests.sh compiles them through
    zink). Returns their records."""
    work = scratch / "zink"
    work.mkdir()
    if not ids:
        log("zink: nothing to build (llvmpipe built every configuration)")
        return []
    env = driver_env("zink", work)
    env["LDM_SHADER_DUMP"] = str(dump)
    ldmbench = build / "ldmbench"
    t0 = time.monotonic()
    renderer_check(ldmbench, "zink", env)
    run_logged([ldmbench, "sweep", sweep_file, "--step", ",".join(ids), "--out", work / "run",
                "--cache-dir", work / "cache"], env, work / "sweep.log", ok_codes=(0, 3))
    records = ldmrecords.read(work / "run")
    log(f"zink: the {len(records)} configurations llvmpipe could not build in "
        f"{time.monotonic() - t0:.0f} s")
    return records


# ---------------------------------------------------------------------------------------------
# 2. The records: every configuration built under at least one driver.

def check_records(records_by_driver):
    built, failed = set(), defaultdict(list)
    ids = set()
    for driver, records in records_by_driver.items():
        for r in records:
            ids.add(r["config_id"])
            if r["status"] == "failed":
                failed[r["config_id"]].append(f"{driver}: {r.get('status_detail', '')}")
            else:
                built.add(r["config_id"])
    missing = sorted(ids - built)
    if missing:
        raise CheckFailed("configurations of the covering sweep that built under neither driver "
                          "(their programs went unchecked):\n" +
                          "\n".join(f"  {c}\n    " + "\n    ".join(failed[c]) for c in missing))
    return len(ids)


# ---------------------------------------------------------------------------------------------
# 3. Coverage of the dump.

class Source:
    """One dumped stage: DIR/<hash>.<stage> and its sidecar <hash>.<stage>.json."""

    def __init__(self, path):
        self.path = path
        self.stage = path.suffix[1:]
        sidecar = path.with_name(path.name + ".json")
        if not sidecar.exists():
            raise CheckFailed(f"{path}: no sidecar {sidecar.name} (a dump written by something "
                              "other than LDM_SHADER_DUMP?)")
        meta = json.loads(sidecar.read_text())
        self.file = meta["file"]
        self.preludes = meta.get("preludes", [])
        self.strings = meta["source_strings"]
        self.text = path.read_text()
        # The define block: string 0, before the first #line.
        self.defines = {}
        for line in self.text.split("\n"):
            d = DIRECTIVE.match(line)
            if d and d.group(1) == "line":
                break
            if d and d.group(1) == "define":
                name, _, value = d.group(2).partition(" ")
                self.defines[name] = value.strip()

    def variant_of(self):
        """What the summary counts variants of: the file, with the files injected before it."""
        return self.file + "".join(f" <- {p}" for p in self.preludes)

    def where(self, string, line):
        s = int(string)
        name = self.strings[s] if 0 <= s < len(self.strings) else f"string {string}"
        return f"{name}:{line}"


def read_dump(dump):
    sources = {p.name: Source(p) for p in sorted(dump.iterdir())
               if p.is_file() and p.suffix[1:] in STAGES and not p.name.startswith(".")}
    programs = []
    for p in sorted(dump.glob("*.program.json")):
        stages = json.loads(p.read_text())["stages"]
        for s in stages:
            if s not in sources:
                raise CheckFailed(f"{p}: names {s}, which the dump does not hold")
        programs.append((p, stages))
    if not sources:
        raise CheckFailed(f"{dump}: no dumped source (was LDM_SHADER_DUMP set for the runs?)")
    if not programs:
        raise CheckFailed(f"{dump}: no dumped program")
    return sources, programs


DIRECTIVE = re.compile(r"^\s*#\s*(\w+)\s*(.*?)\s*$")


class Branch:
    def __init__(self, file, line, text, required=True):
        self.file, self.line, self.text, self.required = file, line, text, required

    def name(self):
        return f"{self.file}:{self.line}: {self.text}"


def instrument(source, branches, index):
    """The source with a marker line after each conditional branch's directive (and an
    explicit #else with a marker where an #if has none); `branches` maps (file, line, text)
    to Branch, `index` each marker number to its key (shared by all sources). Lines keep their text; the markers
    only add lines, which -E passes through when their branch is active."""
    out = []
    string, line = 0, 1
    stack = []  # per open #if: {"else": bool, "guard": name or None, "branch": key}
    lines = source.text.split("\n")
    i = 0

    def marker(key):
        index.append(key)
        return f"LDM_BRANCH_MARKER_{len(index) - 1}"

    def branch(kind_text, required=True):
        key = (source.strings[string] if string < len(source.strings) else str(string), line,
               kind_text)
        if key not in branches:
            branches[key] = Branch(*key, required=required)
        return key

    while i < len(lines):
        text = lines[i]
        # A directive continues over lines ending in a backslash.
        full, n = text, 1
        while full.endswith("\\") and i + n < len(lines):
            full = full[:-1] + lines[i + n]
            n += 1
        m = DIRECTIVE.match(full)
        word = m.group(1) if m else ""
        if word == "line":
            out.extend(lines[i:i + n])
            parts = m.group(2).split()
            line, string = int(parts[0]), (int(parts[1]) if len(parts) > 1 else string)
            i += n
            continue
        if word in ("if", "ifdef", "ifndef", "elif", "else", "endif"):
            if word in ("if", "ifdef", "ifndef"):
                guard = None
                if word == "ifndef":
                    following = lines[i + n] if i + n < len(lines) else ""
                    d = DIRECTIVE.match(following)
                    if d and d.group(1) == "define" and d.group(2).split()[:1] == [m.group(2)]:
                        guard = m.group(2)
                stack.append({"else": False, "guard": guard})
            elif not stack:
                raise CheckFailed(f"{source.path}: #{word} without #if at {source.where(string, line)}")
            if word == "endif":
                group = stack.pop()
                if not group["else"]:
                    # The implicit empty #else: the condition false. An include guard's is never
                    # compiled (includes are expanded once) and needs no coverage.
                    key = branch("(no #if branch taken: implicit #else)", group["guard"] is None)
                    out.extend(["#else", marker(key)])
                out.extend(lines[i:i + n])
            else:
                if word == "else":
                    stack[-1]["else"] = True
                out.extend(lines[i:i + n])
                # A branch whose body is only #error (and comments) must never be taken.
                body = []
                for following in lines[i + n:]:
                    d = DIRECTIVE.match(following)
                    if d and d.group(1) in ("if", "ifdef", "ifndef", "elif", "else", "endif"):
                        break
                    body.append(following.strip())
                errors = [b for b in body if DIRECTIVE.match(b) and DIRECTIVE.match(b).group(1) == "error"]
                only_error = bool(errors) and all(
                    not b or b.startswith("//") or b in errors for b in body)
                key = branch(f"#{word} {m.group(2)}".strip(), not only_error)
                out.append(marker(key))
            i += n
            line += n
            continue
        out.extend(lines[i:i + n])
        i += n
        line += n
    return "\n".join(out)


def glslang_batches(paths_by_stage, jobs, *options):
    """glslangValidator over many files: one process per stage and share of the files (its
    built-in symbol tables take ~0.1 s to set up; then a file takes a few ms), each file again
    alone where its process reported anything. Returns ({path: [glslang's messages]} for the
    files it rejected or warned about, the processes' joined output)."""
    chunks = []
    for stage, paths in sorted(paths_by_stage.items()):
        size = max(1, -(-len(paths) // jobs))
        chunks += [(stage, paths[i:i + size]) for i in range(0, len(paths), size)]
    preprocess = "-E" in options

    def run(stage, paths):
        return subprocess.run([GLSLANG, *options, "-S", stage, *map(str, paths)],
                              capture_output=True, text=True)

    def findings(out, paths):
        # Without -E, glslang prints each file's name and then its messages; with -E, the
        # preprocessed text (a message there means it failed).
        if preprocess:
            return [] if out.returncode == 0 else (
                [l for l in (out.stdout + "\n" + out.stderr).splitlines()
                 if l.startswith(("ERROR", "WARNING"))] or [f"exit {out.returncode}"])
        names = {str(p) for p in paths}
        lines = [l for l in (out.stdout + "\n" + out.stderr).splitlines()
                 if l.strip() and l.strip() not in names]
        return lines or ([f"exit {out.returncode}"] if out.returncode else [])

    def check(chunk):
        stage, paths = chunk
        out = run(stage, paths)
        if not findings(out, paths):
            return out.stdout, {}
        alone = {p: findings(run(stage, [p]), [p]) for p in paths}
        return out.stdout, {p: m for p, m in alone.items() if m}

    messages, output = {}, []
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        for text, found in pool.map(check, chunks):
            output.append(text)
            messages.update(found)
    return messages, "\n".join(output)


def shader_files(shaders):
    return sorted(str(p.relative_to(shaders)) for p in shaders.rglob("*")
                  if p.is_file() and p.suffix[1:] in ("glsl", *STAGES))


def prelude_gaps(sources):
    """Files compiled with injected preludes (the query API's users: AO, the photon trace, the
    inspector, the point cloud, each with a structure's query implementation) that missed a
    prelude another of them was compiled with: a file that takes some of a family of
    preludes must take all of them."""
    seen = defaultdict(set)
    for s in sources.values():
        if s.preludes:
            seen[s.file].add(tuple(s.preludes))
    problems = []
    for file, preludes in sorted(seen.items()):
        family, grown = set(preludes), True
        while grown:
            grown = False
            for other in seen.values():
                if other & family and not other <= family:
                    family |= other
                    grown = True
        for missing in sorted(family - preludes):
            problems.append(f"  shaders/{file} never compiled with {' + '.join(missing)}")
    if problems:
        return ["files never compiled with a prelude that files of the same family were (add "
                "the run or test that builds it):\n" + "\n".join(problems)]
    return []


def check_coverage(sources, shaders, scratch, jobs):
    seen_files = {f for s in sources.values() for f in s.strings[1:]}
    unseen = [f for f in shader_files(shaders) if f not in seen_files]
    # Every source instrumented, its markers numbered across all of them, and preprocessed
    # by glslang (-E): the markers in the output are the branches taken.
    branches, index = {}, []
    by_stage, origin = defaultdict(list), {}
    for source in sources.values():
        path = scratch / source.path.name
        path.write_text(instrument(source, branches, index))
        by_stage[source.stage].append(path)
        origin[path] = source
    errors, text = glslang_batches(by_stage, jobs, "-E")
    if errors:
        raise CheckFailed("glslang's preprocessor rejects dumped sources:\n" + "\n".join(
            f"{origin[p].path} ({origin[p].file}):\n  " +
            "\n  ".join(annotate(origin[p], l) for l in m) for p, m in errors.items()))
    taken = {index[int(n)] for n in re.findall(r"\bLDM_BRANCH_MARKER_(\d+)\b", text)}
    never = [b for k, b in sorted(branches.items()) if b.required and k not in taken]
    problems = prelude_gaps(sources)
    if unseen:
        problems.append("shader files no covering run built (add a run or test that builds them "
                        "to scripts/check_shaders.py):\n" + "\n".join(f"  shaders/{f}" for f in unseen))
    if never:
        problems.append("preprocessor branches no dumped source compiled (a define value no "
                        "covering run sets: add the axis value or test that sets it):\n" +
                        "\n".join(f"  shaders/{b.name()}" for b in never))
    if problems:
        raise CheckFailed("\n".join(problems))
    return len(seen_files & set(shader_files(shaders))), branches


# ---------------------------------------------------------------------------------------------
# 4. glslang on every program.

GLSLANG_WHERE = re.compile(r"\b(ERROR|WARNING): (?:[^\s:]+:)?(\d+):(\d+):")


def annotate(source, message):
    """glslang's "ERROR: <file>:S:L:" with source string S named as the shader file."""
    return GLSLANG_WHERE.sub(lambda m: f"{m.group(1)}: {source.where(m.group(2), m.group(3))}:",
                             message)


def link_program(program, stages, sources):
    """glslang -l on a program of several stages (the interfaces between them must match):
    None, or (glslang's messages, which program, the command)."""
    by_path = {str(sources[s].path): sources[s] for s in stages}
    out = subprocess.run([GLSLANG, "-l", *by_path], capture_output=True, text=True)
    # glslang names each file before its messages; the link's messages come last.
    lines, current = [], None
    for line in (out.stdout + "\n" + out.stderr).splitlines():
        if line.strip() in by_path:
            current = by_path[line.strip()]
        elif line.strip():
            lines.append(annotate(current, line).rstrip() if current else line.rstrip())
    if out.returncode == 0 and not lines:
        return None
    return ("\n".join(lines or [f"exit {out.returncode}"]),
            f"program {program} ({' + '.join(sources[s].file for s in stages)})",
            f"glslangValidator -l {' '.join(by_path)}")


def grouped(findings, limit=3):
    """Findings (message, where, command) with one message, as one paragraph: the message,
    how many had it, a few of them and the command that reproduces the first."""
    by_message = defaultdict(list)
    for message, where, command in findings:
        by_message[message].append((where, command))
    paragraphs = []
    for message, places in by_message.items():
        shown = "\n".join(f"  in {w}" for w, _ in places[:limit])
        more = f"\n  and {len(places) - limit} more" if len(places) > limit else ""
        paragraphs.append(f"{message}\n{shown}{more}\n  reproduce: {places[0][1]}")
    return paragraphs


def check_glslang(sources, programs, jobs):
    """Every source compiled by glslang with its stage; every program of several stages
    linked. Warnings are findings too."""
    in_program = {s for _, stages in programs for s in stages}
    problems = []
    orphans = sorted(set(sources) - in_program)
    if orphans:
        problems.append("dumped sources that no dumped program names: " + ", ".join(orphans))
    by_stage = defaultdict(list)
    for source in sources.values():
        by_stage[source.stage].append(source.path)
    origin = {s.path: s for s in sources.values()}
    rejected, _ = glslang_batches(by_stage, jobs)
    compiled = [("\n".join(annotate(origin[path], l).rstrip() for l in lines),
                 f"{path} ({origin[path].file})",
                 f"glslangValidator -S {origin[path].stage} {path}")
                for path, lines in sorted(rejected.items(), key=lambda item: str(item[0]))]
    linked = [(p.name, stages) for p, stages in programs if len(stages) > 1]
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        links = [r for r in pool.map(lambda p: link_program(*p, sources), linked) if r]
    if compiled:
        problems.append(f"glslang rejected {len(compiled)} of {len(sources)} sources:\n\n" +
                        "\n\n".join(grouped(compiled)))
    if links:
        problems.append(f"glslang rejected {len(links)} of {len(linked)} programs linked:\n\n" +
                        "\n\n".join(grouped(links)))
    if problems:
        raise CheckFailed("\n\n".join(problems))
    return len(linked)


def summary(sources, branches):
    """Variants per shader file (and prelude), and the values each macro that selects code
    took in the define blocks."""
    per_file = defaultdict(int)
    for s in sources.values():
        per_file[s.variant_of()] += 1
    width = max(len(f) for f in per_file)
    lines = [f"  {f:<{width}}  {n:4d}" for f, n in sorted(per_file.items())]
    selecting = {name for b in branches.values() if b.required
                 for name in re.findall(r"\b[A-Za-z_]\w*\b", b.text.partition(" ")[2])
                 if name != "defined"}
    values = defaultdict(set)
    for s in sources.values():
        for name in selecting:
            if name in s.defines:
                values[name].add(s.defines[name])
    lines.append("  define values that select code, as the runs set them:")
    lines += [f"    {name}: {', '.join(sorted(v))}" for name, v in sorted(values.items())]
    return "\n".join(lines)


def check_dump(dump, shaders, jobs):
    if not shutil.which(GLSLANG):
        raise CannotCheck(f"{GLSLANG} is not installed (Debian glslang-tools; scripts/setup.sh)")
    t0 = time.monotonic()
    sources, programs = read_dump(dump)
    problems = []
    try:
        linked = check_glslang(sources, programs, jobs)
    except CheckFailed as e:
        problems.append(str(e))
    try:
        with tempfile.TemporaryDirectory(prefix="ldm-check-shaders-") as scratch:
            files, branches = check_coverage(sources, shaders, Path(scratch), jobs)
    except CheckFailed as e:
        problems.append(str(e))
    if problems:
        raise CheckFailed("\n\n".join(problems))
    version = subprocess.run([GLSLANG, "--version"], capture_output=True, text=True).stdout.split("\n")[0]
    required = sum(b.required for b in branches.values())
    log(f"{len(sources)} sources in {len(programs)} programs ({linked} of several stages, "
        f"linked) from {files} shader files; {required} preprocessor branches, each compiled; "
        f"all accepted by {version} ({time.monotonic() - t0:.0f} s). Variants per shader "
        f"file:\n" + summary(sources, branches))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=str(ROOT / "build"), help="build folder (default build/)")
    parser.add_argument("--dump", help="check this dump folder only (no covering runs)")
    parser.add_argument("--keep", help="dump and run folder to keep (default: a temporary one)")
    parser.add_argument("--shaders", default=str(ROOT / "shaders"), help="the shader sources")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    args = parser.parse_args()
    try:
        if args.dump:
            check_dump(Path(args.dump), Path(args.shaders), args.jobs)
            return 0
        build = Path(args.build)
        needed = [build / "ldmbench", *(build / "tests" / b for b, _ in TEST_PROGRAMS)]
        absent = [str(p) for p in needed if not os.access(p, os.X_OK)]
        if absent:
            raise CannotCheck("not built: " + ", ".join(absent) + " (scripts/test.sh builds "
                              "them; or --build DIR)")
        scratch = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="ldm-check-shaders-"))
        keep = bool(args.keep)
        try:
            if args.keep and scratch.exists() and any(scratch.iterdir()):
                raise CannotCheck(f"--keep {scratch}: not empty")
            scratch.mkdir(parents=True, exist_ok=True)
            dump = scratch / "dump"
            dump.mkdir()
            sweep, refused = covering_sweep(registry_axes(build / "ldmbench"), build / "ldmbench", scratch)
            sweep_file = scratch / "covering-sweep.json"
            sweep_file.write_text(json.dumps(sweep, indent=1) + "\n")
            log(f"covering sweep {sweep_file}: every structure x pass, and {len(sweep['include'])} "
                "axis values one at a time")
            for p, values in sorted(refused.items()):
                log(f"  {p} refuses " + "; ".join(c for c, _ in values) + f" ({values[0][1]})")
            records = {"llvmpipe": covering_runs_llvmpipe(build, sweep, sweep_file, dump,
                                                          scratch, args.jobs)}
            unbuilt = [r["config_id"] for r in records["llvmpipe"] if r["status"] == "failed"]
            records["zink"] = covering_runs_zink(build, sweep_file, unbuilt, dump, scratch)
            configurations = check_records(records)
            log(f"{configurations} configurations, each built under at least one driver")
            check_dump(dump, Path(args.shaders), args.jobs)
        except (CheckFailed, CannotCheck):
            keep = True  # the dumped files and logs the message names
            log(f"kept the dump, the covering sweep and the runs' logs in {scratch}")
            raise
        finally:
            if not keep:
                shutil.rmtree(scratch, ignore_errors=True)
        return 0
    except CheckFailed as e:
        print(f"check-shaders: FAILED: {e}", file=sys.stderr)
        return 1
    except CannotCheck as e:
        print(f"check-shaders: cannot check: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
