#!/usr/bin/env python3
"""A view and a surface kind are each named in one place (docs/architecture.md, "Adding a view",
"Adding a surface kind").

1. `ViewKind::<name>` is written only where a view is defined: its enumerator (render/view.h), its
   row (render/view_table.cpp), its file (render/views/), and default_view (render/view.cpp, which
   view a surface opens in); tests, benchmarks and fuzzers may pick one. Anywhere else a switch on
   views has come back (the figure's captions and scale bars once were one).
2. The front doors (web/, cli/, server/, python/, sweep/, record/, workprecision/) write no surface
   kind's name as a string literal, except the three of constant curvature, which the curvature
   dial reaches by the sign of K (web/surface.js). They read the kinds, their menu words and
   whether K varies from the scene's schema, which engine/scene_fields.h's table makes.

Exit status 1 and one line per problem. --self-test shows both rules refusing a bad line."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
VIEW_PLACES = ("render/view.h", "render/view.cpp", "render/view_table.cpp", "render/views/")
FREE = ("tests/", "bench/", "fuzz/")
FRONT_DOORS = ("web/", "cli/", "server/", "python/", "sweep/", "record/", "workprecision/")
DIAL_KINDS = {"sphere", "pseudosphere", "plane"}  # K > 0, K < 0, K = 0: the dial's family
VIEW_KIND = re.compile(r"\bViewKind::(\w+)")
SOURCE = (".cpp", ".h", ".js", ".mjs", ".py")


def surface_kinds():
    """The names of engine/scene_fields.h's surface table, in its order."""
    text = (ROOT / "engine/scene_fields.h").read_text()
    table = text[text.index("kSurfaceKindNames[] = {"):]
    table = table[:table.index("};")]
    return re.findall(r'\{"(\w+)", SurfaceKind::', table)


def problems_of(path, text, kinds):
    """The problems of one file (its path relative to the repository, its text)."""
    problems = []
    if path.startswith(FREE) or "node_modules" in path:
        return problems
    lines = text.splitlines()
    if path.endswith((".cpp", ".h")) and not path.startswith(VIEW_PLACES):
        for n, line in enumerate(lines, 1):
            for view in VIEW_KIND.findall(line):
                problems.append(f"{path}:{n}: names the view ViewKind::{view}: ask the view "
                                "(render/views/view_model.h) instead")
    if path.startswith(FRONT_DOORS):
        names = [k for k in kinds if k not in DIAL_KINDS]
        literal = re.compile(r"""["'](%s)["']""" % "|".join(map(re.escape, names))) if names else None
        for n, line in enumerate(lines, 1):
            stripped = line.strip()
            if stripped.startswith(("//", "*", "/*", "#")):
                continue  # a comment may give an example
            for kind in literal.findall(line) if literal else []:
                problems.append(f'{path}:{n}: writes the surface kind "{kind}": read it from the '
                                "scene's schema (surface.kind) instead")
    return problems


def tracked_sources():
    for path in sorted(ROOT.rglob("*")):
        rel = path.relative_to(ROOT).as_posix()
        if path.is_file() and path.suffix in SOURCE and not rel.startswith(("build", ".")) \
                and "node_modules" not in rel:
            yield rel, path.read_text(errors="replace")


def self_test(kinds):
    """Each rule refuses its bad line, and neither refuses the places that may say it."""
    cases = [
        ("render/figure.cpp", "  if (view.kind == ViewKind::disk) return;", 1),
        ("render/views/disk.cpp", "  return ViewKind::disk;", 0),
        ("tests/render/figure_test.cpp", "  view.kind = ViewKind::disk;", 0),
        ("web/physical.js", f'  if (kind === "{kinds[-1]}") rows.push(x);', 1),
        ("web/surface.js", '  return K > 0 ? "sphere" : "plane";', 0),
        ("server/routes/catalog.cpp", f'  // e.g. "{kinds[-1]}"', 0),
    ]
    failed = 0
    for path, line, expected in cases:
        got = len(problems_of(path, line, kinds))
        if got != expected:
            print(f"self-test: {path}: {line.strip()!r} gave {got} problems, expected {expected}")
            failed += 1
    print("self-test: " + ("failed" if failed else f"{len(cases)} cases as expected"))
    return 1 if failed else 0


def main():
    kinds = surface_kinds()
    if len(kinds) < 3:
        print("engine/scene_fields.h: could not read the surface table")
        return 1
    if "--self-test" in sys.argv:
        return self_test(kinds)
    problems = [p for rel, text in tracked_sources() for p in problems_of(rel, text, kinds)]
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
