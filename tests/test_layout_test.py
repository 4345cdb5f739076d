#!/usr/bin/env python3
"""Tests mirror sources file by file (docs/style.md): every <dir>/<name>.cpp of the C++ sources has
tests/<dir>/<name>_test.cpp, or an entry in tests/mirror_exemptions.txt saying in one line where it
is tested instead. Fails on a source with neither, on an entry without a reason, and on an entry
that no longer applies (its source gone, or its mirror written), so the list stays true."""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE_DIRS = ["cli", "codec", "engine", "record", "render", "server", "sweep", "workprecision"]
EXEMPTIONS = ROOT / "tests" / "mirror_exemptions.txt"


def sources():
    for directory in SOURCE_DIRS:
        for path in sorted((ROOT / directory).rglob("*.cpp")):
            yield path.relative_to(ROOT).as_posix()


def mirror_of(source):
    return ROOT / "tests" / (source[: -len(".cpp")] + "_test.cpp")


def read_exemptions(problems):
    exempt = {}
    for number, line in enumerate(EXEMPTIONS.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        source, _, reason = line.partition(":")
        source, reason = source.strip(), reason.strip()
        if not reason:
            problems.append(f"{EXEMPTIONS.name}:{number}: '{source}' has no reason (write '<source>: <where it is tested>')")
        if source in exempt:
            problems.append(f"{EXEMPTIONS.name}:{number}: '{source}' is listed twice")
        exempt[source] = reason
    return exempt


def main():
    problems = []
    exempt = read_exemptions(problems)
    all_sources = set(sources())
    for source in sorted(all_sources):
        has_mirror = mirror_of(source).is_file()
        if not has_mirror and source not in exempt:
            problems.append(f"{source}: no tests/{source[:-4]}_test.cpp and no entry in {EXEMPTIONS.name}")
        if has_mirror and source in exempt:
            problems.append(f"{source}: has its mirror test now; remove its entry from {EXEMPTIONS.name}")
    for source in sorted(set(exempt) - all_sources):
        problems.append(f"{EXEMPTIONS.name}: '{source}' is not a source file (renamed or removed?)")
    for problem in problems:
        print(problem, file=sys.stderr)
    mirrored = sum(mirror_of(s).is_file() for s in all_sources)
    print(f"{mirrored} sources mirrored, {len(exempt)} exempt, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
