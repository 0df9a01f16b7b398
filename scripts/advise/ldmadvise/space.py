"""The search space of `ldmbench advise`: a space file (or the default) expanded into
candidates, and the sweep files that measure a subset of them at one precision.

A space file is a sweep file's `axes` restricted to what advise may choose:
  {"axes": {"structures": ["psppsll", "ppfla"], "views": [8, 16, 32], "r_ldm": [64, 128],
            "ppfla:k": [4, 8, 16], "trace": "plane"}}
The scene, the pass and the image size are the question's (advise's options), not the
space's. A parameter OWNER:KEY applies to the candidates of its owner (a structure, or the
pass) only, so `ppfla:k` multiplies ppfla's candidates and no other's.
"""
import itertools
import json

from .search import Candidate

CHOSEN = ("structures", "views", "r_ldm", "trace", "sizing", "sizing_initial_per_pixel")
FIXED = ("scenes", "passes", "image_size", "frames", "warmup", "d_max", "visibility",
         "normal_offset", "ao_estimator", "sizing_budget_mib")
FIXED_ARRAYS = ("ppfla", "psppfla")

DEFAULT_SPACE = {
    "ao": {"views": [8, 16, 32], "r_ldm": [64, 128], "ppfla:k": [4, 8, 16], "psppfla:k": [4, 8, 16]},
    # indirect:r_light (the light map's resolution: photons emitted) trades time for error too.
    "indirect": {"views": [8, 16], "r_ldm": [32, 64], "ppfla:k": [4, 8, 16], "psppfla:k": [4, 8, 16],
                 "indirect:r_light": [32, 64]},
}


class SpaceError(Exception):
    """A space the search cannot use; the message names the file and the axis."""


def as_list(value):
    return value if isinstance(value, list) else [value]


def load_space(path, pass_name, structures, registry_structures, registry_passes):
    """The space's axes: the file's, or the default for the pass; --structures narrows."""
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
        axes = json.loads(json.dumps(DEFAULT_SPACE[pass_name]))
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


def candidate_assignments(axes, pass_name):
    """Every configuration of the space, each {axis: value}, in a stable order. Parameters
    of other structures or passes are left out (they would not change the configuration)."""
    general = [k for k in CHOSEN if k in axes and k != "structures"]
    out = []
    for structure in axes["structures"]:
        params = [k for k in sorted(axes) if ":" in k and k.split(":", 1)[0] in (structure, pass_name)]
        keys = general + params
        for values in itertools.product(*(as_list(axes[k]) for k in keys)):
            a = {"structures": structure}
            a.update(dict(zip(keys, values)))
            out.append(a)
    return out


def group_of(assignment):
    """The lattice a configuration lies on: every value but N and R_LDM."""
    rest = {k: v for k, v in assignment.items() if k not in ("views", "r_ldm")}
    return json.dumps(rest, sort_keys=True)


def candidate_of(key, assignment, defaults):
    structure = assignment["structures"]
    k = assignment.get(f"{structure}:k") if structure in FIXED_ARRAYS else None
    return Candidate(key=key, group=group_of(assignment),
                     views=int(assignment.get("views", defaults["views"])),
                     r_ldm=int(assignment.get("r_ldm", defaults["r_ldm"])), k=k)


def sweep_file(question, assignments, precision, description):
    """A sweep measuring exactly `assignments` (the first as the main product, each other
    an include block naming every axis it sets) at `precision`."""
    fixed = {"scenes": question["scene"], "passes": question["pass"],
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
    return {
        "description": description,
        "axes": main,
        "include": [dict(a) for a in assignments[1:]],
        "settings": {"reference": reference, "images": precision.get("images", False), "timing": timing},
    } if len(assignments) > 1 else {
        "description": description, "axes": main,
        "settings": {"reference": reference, "images": precision.get("images", False), "timing": timing},
    }
