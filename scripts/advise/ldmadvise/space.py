"""The search space of `ldmbench advise`: a space file (or the default) expanded into
candidates, and the sweep files that measure a subset of them at one precision.

A space file is a sweep file's `axes` restricted to what advise may choose:
  {"axes": {"structures": ["psppsll", "ppfla"], "views": [8, 16, 32], "r_ldm": [64, 128],
            "ppfla:k": [4, 8, 16], "trace": "plane"}}
The scene, the passes and the image size are the question's (advise's options), not the
space's. A parameter OWNER:KEY applies to the candidates of its owner (a structure, or a
pass) only, so `ppfla:k` multiplies ppfla's candidates and no other's.

The method is an axis too: `--pass ao,gtao,hbao,rtao_gpu` puts the LDM AO pass (every
structure, N, R_LDM) beside the peers, each a candidate per value of its own parameters
(no structure, no N or R_LDM: each its own lattice of one point), all scored against the
same AO reference, so "the best AO under 5 ms" is one question. Passes of one kind only:
the AO passes together, or the indirect pass alone (its error is against another reference).
"""
import itertools
import json

from .search import Candidate

CHOSEN = ("structures", "views", "r_ldm", "trace", "sizing", "sizing_initial_per_pixel")
FIXED = ("scenes", "passes", "image_size", "frames", "warmup", "d_max", "visibility",
         "normal_offset", "ao_estimator", "sizing_budget_mib")
FIXED_ARRAYS = ("ppfla", "psppfla")

# Passes that read LDMs (structures, N, R_LDM are their axes); the others are peers.
LDM_PASSES = ("ao", "indirect")
AO_PASSES = ("ao", "hbao", "gtao", "rtao", "rtao_gpu")

DEFAULT_SPACE = {
    "ao": {"views": [8, 16, 32], "r_ldm": [64, 128], "ppfla:k": [4, 8, 16], "psppfla:k": [4, 8, 16]},
    # indirect:r_light (the light map's resolution: photons emitted) trades time for error too.
    "indirect": {"views": [8, 16], "r_ldm": [32, 64], "ppfla:k": [4, 8, 16], "psppfla:k": [4, 8, 16],
                 "indirect:r_light": [32, 64]},
    # The peers' own speed/accuracy knobs: GTAO's and HBAO's sampling, GPU RTAO's rays per pixel.
    "gtao": {"gtao:slices": [2, 4, 8], "gtao:steps": [4, 8, 16]},
    "hbao": {"hbao:directions": [4, 8, 16], "hbao:steps": [4, 8, 16]},
    "rtao_gpu": {"rtao_gpu:spp": [1, 2, 4, 8, 16]},
    "rtao": {"rtao:spp": [1, 4, 16]},
}


def check_passes(passes, registry_passes):
    """The question's passes: known, each once, of one kind. Raises SpaceError."""
    if not passes:
        raise SpaceError("--pass: no pass given")
    unknown = [p for p in passes if p not in registry_passes]
    if unknown:
        raise SpaceError(f"--pass: unknown pass{'es' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))} "
                         f"(known: {', '.join(registry_passes)})")
    if len(set(passes)) != len(passes):
        raise SpaceError("--pass: a pass is given twice")
    if len(passes) > 1 and not all(p in AO_PASSES for p in passes):
        raise SpaceError(f"--pass {','.join(passes)}: only the AO passes ({', '.join(AO_PASSES)}) can be "
                         "compared in one question (they share a reference); ask about indirect alone")
    return passes


class SpaceError(Exception):
    """A space the search cannot use; the message names the file and the axis."""


def as_list(value):
    return value if isinstance(value, list) else [value]


def load_space(path, passes, structures, registry_structures, registry_passes):
    """The space's axes: the file's, or the defaults of the passes; --structures narrows."""
    passes = [passes] if isinstance(passes, str) else list(passes)
    if path:
        try:
            with open(path, encoding="utf-8") as f:
                root = json.load(f)
        except OSError as e:
            raise SpaceError(f"{path}: cannot read: {e.strerror}")
        except json.JSONDecodeError as e:
            raise SpaceError(f"{path}: line {e.lineno} column {e.colno}: {e.msg}")
        if not isinstance(root, dict) or not isinstance(root.get("axes"), dict):
            raise SpaceError(f"{path}: expected an object with \"axes\" (an object of axis -> values)")
        for key in root:
            if key not in ("axes", "description", "comment"):
                raise SpaceError(f"{path}: {key}: unknown key (known: axes, description, comment)")
        axes = dict(root["axes"])
        where = path
    else:
        axes = {}
        for p in passes:
            axes.update(json.loads(json.dumps(DEFAULT_SPACE.get(p, {}))))
        where = "the default space"
    for key, values in axes.items():
        if key in FIXED:
            raise SpaceError(f"{where}: axes.{key}: fixed by the question (advise's options), "
                             "not a choice of the search")
        if ":" in key:
            owner = key.split(":", 1)[0]
            if owner not in registry_structures and owner not in registry_passes:
                raise SpaceError(f"{where}: axes.{key}: unknown owner {owner!r}")
        elif key not in CHOSEN:
            raise SpaceError(f"{where}: axes.{key}: not an axis advise can choose "
                             f"(known: {', '.join(CHOSEN)}, OWNER:KEY)")
        if as_list(values) == []:
            raise SpaceError(f"{where}: axes.{key}: no values (an empty axis leaves an empty space)")
    space_structures = as_list(axes.get("structures", "all"))
    if space_structures == ["all"]:
        space_structures = list(registry_structures)
    if structures:
        space_structures = [s for s in space_structures if s in structures]
        if not space_structures:
            raise SpaceError(f"{where}: none of --structures {','.join(structures)} is in the space")
    axes["structures"] = space_structures
    return axes


def candidate_assignments(axes, passes):
    """Every configuration of the space, each {axis: value} with its pass, in a stable order
    (the passes in the order given). Parameters of other structures or passes are left out
    (they would not change the configuration); a peer pass takes only its own."""
    passes = [passes] if isinstance(passes, str) else list(passes)
    general = [k for k in CHOSEN if k in axes and k != "structures"]
    out = []
    for pass_name in passes:
        if pass_name not in LDM_PASSES:
            params = [k for k in sorted(axes) if ":" in k and k.split(":", 1)[0] == pass_name]
            for values in itertools.product(*(as_list(axes[k]) for k in params)):
                a = {"passes": pass_name}
                a.update(dict(zip(params, values)))
                out.append(a)
            continue
        for structure in axes["structures"]:
            params = [k for k in sorted(axes) if ":" in k and k.split(":", 1)[0] in (structure, pass_name)]
            keys = general + params
            for values in itertools.product(*(as_list(axes[k]) for k in keys)):
                a = {"passes": pass_name, "structures": structure}
                a.update(dict(zip(keys, values)))
                out.append(a)
    return out


def group_of(assignment):
    """The lattice a configuration lies on: every value but N and R_LDM."""
    rest = {k: v for k, v in assignment.items() if k not in ("views", "r_ldm")}
    return json.dumps(rest, sort_keys=True)


def candidate_of(key, assignment, defaults):
    structure = assignment.get("structures")
    k = assignment.get(f"{structure}:k") if structure in FIXED_ARRAYS else None
    return Candidate(key=key, group=group_of(assignment),
                     views=int(assignment.get("views", defaults["views"])),
                     r_ldm=int(assignment.get("r_ldm", defaults["r_ldm"])), k=k)


def sweep_file(question, assignments, precision, description):
    """A sweep measuring exactly `assignments` (the first as the main product, each other
    an include block naming every axis it sets) at `precision`."""
    # The pass is each assignment's own (the method is an axis of the search).
    fixed = {"scenes": question["scene"],
             "image_size": question["image_size"],
             "frames": precision["frames"], "warmup": precision["warmup"]}
    main = dict(fixed)
    main.update(assignments[0])
    reference = {"enabled": precision.get("reference", True)}
    if reference["enabled"]:
        if precision.get("spp"):
            reference["spp"] = precision["spp"]
        if question.get("reference_max_spp"):
            reference["max_spp"] = question["reference_max_spp"]
            if "spp" in reference:
                reference["spp"] = min(reference["spp"], reference["max_spp"])
    timing = {"target": precision["target"]}
    if "cap_s" in precision:
        timing["cap_s"] = precision["cap_s"]
    if precision.get("repetitions", 1) > 1:
        timing["repetitions"] = precision["repetitions"]
    if precision.get("isolation"):
        timing["isolation"] = precision["isolation"]
    settings = {"reference": reference, "images": precision.get("images", False), "timing": timing}
    if not precision.get("work", True):
        settings["work"] = False  # no counting replay (docs/reference/work-counters.md)
    return {
        "description": description,
        "axes": main,
        "include": [dict(a) for a in assignments[1:]],
        "settings": settings,
    } if len(assignments) > 1 else {
        "description": description, "axes": main, "settings": settings,
    }
