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
3. No C++ source branches on a surface kind outside the surface catalog: `== SurfaceKind::`,
   `!= SurfaceKind::`, `case SurfaceKind::` and a set of kinds `surface_bit(SurfaceKind::…)` are
   written only in the catalog (engine/surface.h), the kinds' own files (engine/surface.cpp for the
   three of constant curvature, engine/surface_<name>.cpp, engine/revolution.*,
   engine/formula_surface.*) and the vocabulary (engine/scene_fields.h: a kind's own parameters).
   Elsewhere code asks what the surface offers (`offers(surface, Offer::…)`).
4. docs/architecture.md's "Adding a surface kind" is counted from the code: it names every product
   file that writes a surface of revolution's enumerator (`SurfaceKind::<name>`), and the number of
   files it says a new one takes is the number that write one of theirs.

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
# Rule 3's catalog: the places that may say which kind a surface is.
CATALOG = ("engine/surface.h", "engine/surface.cpp", "engine/revolution.h", "engine/revolution.cpp",
           "engine/formula_surface.h", "engine/formula_surface.cpp", "engine/scene_fields.h")
KIND_FILE = re.compile(r"^engine/surface_(\w+)\.cpp$")  # a kind's own file (not surface_model.cpp)
KIND_BRANCH = re.compile(r"(?:[=!]=\s*|\bcase\s+|surface_bit\(\s*)SurfaceKind::(\w+)")
# Rule 4: where a kind's enumerator may be written in the product (the oracle is separate code).
NOT_PRODUCT = FREE + ("oracle/",)
NUMBER_WORDS = {"one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8,
                "nine": 9, "ten": 10}


def in_catalog(path, kinds):
    m = KIND_FILE.match(path)
    return path in CATALOG or bool(m and m.group(1) in kinds)


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
    if path.endswith((".cpp", ".h")) and not in_catalog(path, kinds):
        for n, line in enumerate(lines, 1):
            for kind in KIND_BRANCH.findall(line):
                problems.append(f"{path}:{n}: branches on the surface kind SurfaceKind::{kind}: ask "
                                "what the surface offers (offers(surface, Offer::…), engine/surface.h)")
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


def recipe_problems(sources, kinds, recipe_text):
    """Rule 4: the recipe names every product file that writes a kind's enumerator, and its count of
    the files a new surface of revolution takes is the count of the files that write one of theirs."""
    problems = []
    start = recipe_text.find("## Adding a surface kind")
    if start < 0:
        return ["docs/architecture.md: no section \"## Adding a surface kind\""]
    section = recipe_text[start:]
    section = section[:section.find("\n## ", 3) if "\n## " in section[3:] else len(section)]
    writers = {}
    for rel, text in sources:
        if rel.startswith(NOT_PRODUCT) or not rel.endswith((".cpp", ".h")):
            continue
        for kind in kinds:
            if re.search(r"\bSurfaceKind::%s\b" % kind, text):
                writers.setdefault(kind, set()).add(rel)
    profile_kinds = [k for k in kinds if f"engine/surface_{k}.cpp" in writers.get(k, set())]
    for kind in profile_kinds:
        for rel in sorted(writers[kind]):
            m = KIND_FILE.match(rel)
            named = f"`{rel}`" in section or (m and "`engine/surface_<name>.cpp`" in section)
            if not named:
                problems.append(f"docs/architecture.md: \"Adding a surface kind\" does not name {rel}, "
                                f"which writes SurfaceKind::{kind}")
    said = re.search(r"is (\w+) product files", section)
    counted = min((len(writers[k]) for k in profile_kinds), default=0)  # the default kind has one more
    if not said:
        problems.append("docs/architecture.md: \"Adding a surface kind\" does not say \"is N product "
                        "files\"")
    else:
        word = said.group(1)
        n = NUMBER_WORDS.get(word, int(word) if word.isdigit() else -1)
        if n != counted:
            problems.append(f"docs/architecture.md: \"Adding a surface kind\" says {word} product files; "
                            f"counted from the code, a surface of revolution's enumerator is in {counted}")
    return problems


def self_test(kinds):
    """Each rule refuses its bad line, and neither refuses the places that may say it."""
    cases = [
        ("render/figure.cpp", "  if (view.kind == ViewKind::disk) return;", 1),
        ("render/views/disk.cpp", "  return ViewKind::disk;", 0),
        ("tests/render/figure_test.cpp", "  view.kind = ViewKind::disk;", 0),
        ("web/physical.js", f'  if (kind === "{kinds[-1]}") rows.push(x);', 1),
        ("web/surface.js", '  return K > 0 ? "sphere" : "plane";', 0),
        ("server/routes/catalog.cpp", f'  // e.g. "{kinds[-1]}"', 0),
        ("render/figure.cpp", "  if (surface.kind == SurfaceKind::sphere) return;", 1),
        ("engine/invariants.cpp", "    case SurfaceKind::plane: return 0.0;", 1),
        ("render/view_table.cpp", "constexpr unsigned kS = surface_bit(SurfaceKind::sphere);", 1),
        ("engine/surface.cpp", "    case SurfaceKind::plane: return r;", 0),
        (f"engine/surface_{kinds[3]}.cpp", f"  if (s.kind != SurfaceKind::{kinds[3]}) return;", 0),
        ("engine/surface_model.cpp", "  if (s.kind == SurfaceKind::graph) return;", 1),
        ("tests/engine/surface_test.cpp", "  if (s.kind == SurfaceKind::plane) return;", 0),
    ]
    failed = 0
    for path, line, expected in cases:
        got = len(problems_of(path, line, kinds))
        if got != expected:
            print(f"self-test: {path}: {line.strip()!r} gave {got} problems, expected {expected}")
            failed += 1
    kind = kinds[3]
    sources = [("engine/surface.h", f"SurfaceKind::{kind}"), (f"engine/surface_{kind}.cpp", f"SurfaceKind::{kind}")]
    recipe_cases = [
        (f"## Adding a surface kind\nis two product files: `engine/surface.h`, `engine/surface_<name>.cpp`.", 0),
        (f"## Adding a surface kind\nis three product files: `engine/surface.h`, `engine/surface_<name>.cpp`.", 1),
        (f"## Adding a surface kind\nis two product files: `engine/surface_<name>.cpp`.", 1),
    ]
    for text, expected in recipe_cases:
        got = len(recipe_problems(sources, kinds, text))
        if got != expected:
            print(f"self-test: recipe {text!r} gave {got} problems, expected {expected}")
            failed += 1
    cases += recipe_cases
    print("self-test: " + ("failed" if failed else f"{len(cases)} cases as expected"))
    return 1 if failed else 0


def main():
    kinds = surface_kinds()
    if len(kinds) < 3:
        print("engine/scene_fields.h: could not read the surface table")
        return 1
    if "--self-test" in sys.argv:
        return self_test(kinds)
    sources = list(tracked_sources())
    problems = [p for rel, text in sources for p in problems_of(rel, text, kinds)]
    problems += recipe_problems(sources, kinds, (ROOT / "docs/architecture.md").read_text())
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
