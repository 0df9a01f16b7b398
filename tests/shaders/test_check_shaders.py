#!/usr/bin/env python3
"""scripts/check_shaders.py can fail: fake dumps (the format of LDM_SHADER_DUMP,
harness/gl/shader_dump.h) of a fake shaders/ folder, each broken in one way, must each fail
the check with a message naming what is wrong, and the clean one must pass.

  tests/shaders/test_check_shaders.py LDMBENCH     (run by ctest: shaders.CheckShaders.*)
"""
import json
import re
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "check_shaders.py"
sys.path.insert(0, str(SCRIPT.parent))
import check_shaders  # noqa: E402

LDMBENCH = sys.argv.pop(1) if len(sys.argv) > 1 else str(ROOT / "build" / "ldmbench")

# A fake shaders/ folder: an include with an include guard, an #if/#elif whose #else is only
# #error, an #ifdef without #else; a compute shader taking preludes (a query family).
SHADERS = {
    "fake/common.glsl": """#ifndef FAKE_COMMON_GLSL
#define FAKE_COMMON_GLSL
#if MODE == 1
float mode_value() { return 1.0; }
#elif MODE == 2
float mode_value() { return 2.0; }
#else
#error MODE must be 1 or 2
#endif
#endif
""",
    "fake/draw.vert": """#include "fake/common.glsl"
out float v;
void main() {
  v = mode_value();
#ifdef EXTRA
  v += 1.0;
#endif
  gl_Position = vec4(v);
}
""",
    "fake/draw.frag": """in float v;
out vec4 colour;
void main() { colour = vec4(v); }
""",
    "fake/query_a.glsl": "float query() { return 1.0; }\n",
    "fake/query_b.glsl": "float query() { return 2.0; }\n",
    "fake/grid.comp": """layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { float result[]; };
void main() { result[gl_GlobalInvocationID.x] = query(); }
""",
    "fake/other.comp": """layout(local_size_x = 1) in;
layout(binding = 0) uniform atomic_uint counter;
void main() { if (query() > 0.0) atomicCounterIncrement(counter); }
""",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"\s*$')


def preprocess(shaders, file, defines, preludes):
    """What harness/gl/shader_program.cpp's preprocess_shader() writes: #version, the
    defines, then the preludes and the file with includes expanded once, each with #line."""
    table, included, out = ["<defines>"], set(), ["#version 450 core"]
    out += [f"#define {k} {v}" for k, v in defines.items()]

    def expand(name):
        if name in included:
            return
        included.add(name)
        if name not in table:
            table.append(name)
        sid = table.index(name)
        out.append(f"#line 1 {sid}")
        for number, line in enumerate(shaders[name].rstrip("\n").split("\n"), 1):
            m = INCLUDE.match(line)
            if m:
                expand(m.group(1))
                out.append(f"#line {number + 1} {sid}")
            else:
                out.append(line)

    for p in preludes:
        expand(p)
    expand(file)
    return "\n".join(out) + "\n", table


class FakeDump:
    def __init__(self, root, shaders):
        self.shaders_dir = root / "shaders"
        self.dump = root / "dump"
        self.dump.mkdir()
        self.shaders = shaders
        for name, text in shaders.items():
            path = self.shaders_dir / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        self.count = 0

    def program(self, *stages):
        """stages: (file, defines, preludes); writes each source, sidecar and the program."""
        names = []
        for file, defines, preludes in stages:
            text, table = preprocess(self.shaders, file, defines, preludes)
            stage = file.rsplit(".", 1)[1]
            self.count += 1
            name = f"{self.count:016x}.{stage}"
            (self.dump / (name + ".json")).write_text(json.dumps(
                {"stage": stage, "file": file, "preludes": preludes, "source_strings": table}))
            (self.dump / name).write_text(text)
            names.append(name)
        (self.dump / f"{self.count:016x}.program.json").write_text(json.dumps({"stages": names}))
        return names

    def check(self):
        out = subprocess.run([sys.executable, str(SCRIPT), "--dump", str(self.dump),
                              "--shaders", str(self.shaders_dir), "--jobs", "2"],
                             capture_output=True, text=True)
        return out.returncode, out.stdout + out.stderr


def clean_programs(fake, modes=(1, 2), extra=(True, False)):
    for mode, with_extra in zip(modes, extra):
        defines = {"MODE": mode, **({"EXTRA": 1} if with_extra else {})}
        fake.program(("fake/draw.vert", defines, []), ("fake/draw.frag", defines, []))
    for query in ("fake/query_a.glsl", "fake/query_b.glsl"):
        fake.program(("fake/grid.comp", {}, [query]))
        fake.program(("fake/other.comp", {}, [query]))


class CheckShadersTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="ldm-test-check-shaders-")
        self.root = Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def fake(self, folder="first", **changes):
        """A fake dump (empty) in its own folder, of SHADERS with `changes`."""
        shaders = dict(SHADERS)
        shaders.update(changes)
        (self.root / folder).mkdir()
        return FakeDump(self.root / folder, shaders)

    def assert_fails(self, fake, *needles):
        status, output = fake.check()
        self.assertEqual(status, 1, output)
        self.assertIn("FAILED", output)
        for needle in needles:
            self.assertIn(needle, output)
        return output

    def test_clean_dump_passes_with_its_summary(self):
        fake = self.fake()
        clean_programs(fake)
        status, output = fake.check()
        self.assertEqual(status, 0, output)
        self.assertIn("8 sources in 6 programs (2 of several stages, linked) from 7 shader files", output)
        # The include guard, MODE's two branches, EXTRA's #ifdef and its implicit #else; the
        # #error branch and the include guard's implicit #else are exempt.
        self.assertIn("5 preprocessor branches, each compiled", output)
        self.assertIn("fake/grid.comp <- fake/query_b.glsl", output)
        self.assertIn("MODE: 1, 2", output)

    def test_a_source_glslang_rejects_fails_naming_the_dumped_and_the_shader_file(self):
        fake = self.fake(**{"fake/draw.frag": "in float v;\nout vec4 colour;\n"
                            "void main() { int i = v; colour = vec4(i); }\n"})
        clean_programs(fake)
        self.assert_fails(fake, "cannot convert", "fake/draw.frag:3", str(fake.dump))

    def test_a_warning_fails_too(self):
        # Mesa compiles this without a word; glslang warns: reserved by the specification. (A
        # compute shader: a program of one stage, which only the compile, not -l, sees.)
        fake = self.fake(**{"fake/grid.comp": SHADERS["fake/grid.comp"].replace(
            "void main() {", "void main() { float a__b = 1.0;")})
        clean_programs(fake)
        self.assert_fails(fake, "WARNING", "consecutive underscores", "fake/grid.comp:3")

    def test_stages_whose_interfaces_differ_fail_when_linked(self):
        fake = self.fake(**{"fake/draw.frag": "in vec2 v;\nout vec4 colour;\n"
                            "void main() { colour = vec4(v, 0.0, 1.0); }\n"})
        clean_programs(fake)
        self.assert_fails(fake, "Linking", "fake/draw.vert + fake/draw.frag")

    def test_a_branch_no_source_compiled_fails_naming_its_line(self):
        fake = self.fake()
        clean_programs(fake, modes=(1, 1))
        self.assert_fails(fake, "shaders/fake/common.glsl:5: #elif MODE == 2")

    def test_an_ifdef_never_taken_fails_and_so_does_its_implicit_else(self):
        fake = self.fake()
        clean_programs(fake, extra=(False, False))
        self.assert_fails(fake, "shaders/fake/draw.vert:5: #ifdef EXTRA")
        fake = self.fake("again")
        clean_programs(fake, extra=(True, True))
        self.assert_fails(fake, "shaders/fake/draw.vert:7: (no #if branch taken: implicit #else)")

    def test_a_shader_file_no_run_built_fails(self):
        fake = self.fake(**{"fake/unused.comp": "layout(local_size_x = 1) in;\nvoid main() {}\n"})
        clean_programs(fake)
        self.assert_fails(fake, "shader files no covering run built", "shaders/fake/unused.comp")

    def test_a_prelude_one_file_of_a_family_missed_fails(self):
        fake = self.fake()
        clean_programs(fake)
        for p in fake.dump.glob("*.json"):
            if '"fake/other.comp"' in p.read_text() and "query_b" in p.read_text():
                name = p.name[:-len(".json")]
                p.unlink()
                (fake.dump / name).unlink()
                for program in fake.dump.glob("*.program.json"):
                    if name in program.read_text():
                        program.unlink()
        self.assert_fails(fake, "shaders/fake/other.comp never compiled with fake/query_b.glsl")

    def test_a_dump_that_is_not_whole_fails(self):
        fake = self.fake()
        clean_programs(fake)
        next(fake.dump.glob("*.frag.json")).unlink()
        self.assert_fails(fake, "no sidecar")
        fake = self.fake("orphan")
        clean_programs(fake)
        (fake.dump / "ffffffffffffffff.program.json").write_text(json.dumps({"stages": ["0.comp"]}))
        self.assert_fails(fake, "which the dump does not hold")
        self.assert_fails(self.fake("empty"), "no dumped source")

    def test_preprocessor_marks_nested_and_continued_directives(self):
        source = check_shaders.Source.__new__(check_shaders.Source)
        source.path, source.stage = Path("x.comp"), "comp"
        source.strings = ["<defines>", "a.glsl"]
        source.text = ("#version 450 core\n#define A 1\n#line 1 1\n#if A\n#if \\\n  B\nint x;\n"
                       "#endif\n#else\nint y;\n#endif\n")
        branches, index = {}, []
        text = check_shaders.instrument(source, branches, index)
        keys = sorted((f, line, t) for f, line, t in branches)
        self.assertEqual([(line, t) for _, line, t in keys],
                         [(1, "#if A"), (2, "#if B"), (5, "(no #if branch taken: implicit #else)"),
                          (6, "#else")])
        self.assertEqual(len(index), 4)
        self.assertIn("LDM_BRANCH_MARKER_0", text)

    def test_records_a_configuration_failed_under_both_drivers_fails(self):
        ok = {"config_id": "a", "status": "ok"}
        failed = {"config_id": "a", "status": "failed", "status_detail": "needs 64-bit atomics"}
        self.assertEqual(check_shaders.check_records({"llvmpipe": [failed], "zink": [ok]}), 1)
        with self.assertRaises(check_shaders.CheckFailed) as e:
            check_shaders.check_records({"llvmpipe": [failed], "zink": [dict(failed)]})
        self.assertIn("needs 64-bit atomics", str(e.exception))

    def test_covering_sweep_holds_every_value_the_registry_lists(self):
        axes = check_shaders.registry_axes(LDMBENCH)
        with tempfile.TemporaryDirectory() as scratch:
            sweep, refused = check_shaders.covering_sweep(axes, LDMBENCH, Path(scratch))
        blocks = [sweep["axes"], *sweep["include"]]

        def listed(name, value):
            return any(value in (b[name] if isinstance(b.get(name), list) else [b.get(name)])
                       for b in blocks if name in b)

        for axis in axes:
            if axis["kind"] == "choice" and axis["name"] != "scenes":
                for value in axis["choices"]:
                    if value != axis.get("default"):
                        self.assertTrue(listed(axis["name"], value), f"{axis['name']}={value}")
            if axis["kind"] == "bool":
                self.assertTrue(listed(axis["name"], axis.get("default") != "true"), axis["name"])
        self.assertEqual(sweep["axes"]["structures"],
                         next(a for a in axes if a["name"] == "structures")["choices"])


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
