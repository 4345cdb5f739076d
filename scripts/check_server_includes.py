#!/usr/bin/env python3
"""server/'s includes point down (docs/architecture.md, "The server's rooms").

server/ is a row of rooms, lowest first:

    options.h < http/ < store/ < sessions/ < frames/ < jobs/ < context.{h,cpp} < routes/ < api.{h,cpp}

A file may include files of its own room and of the rooms below it, never one above it. Every
`#include "server/..."` of every file under server/ is checked; so is the room of every file (a file
in no room is an error: place it), and an include without a folder (`#include "frames.h"`), which
would slip past the check. Run with --self-test to see the rule refuse a bad include.
Exit status 1 and one line per problem when anything is wrong."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
ROOMS = ["options", "http", "store", "sessions", "frames", "jobs", "context", "routes", "api"]
TOP_FILES = {"options.h": "options", "context.h": "context", "context.cpp": "context",
             "api.h": "api", "api.cpp": "api"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def room_of(path):
    """The room of a path relative to the repository ("server/jobs/recordings.h"), or None."""
    parts = path.split("/")
    if len(parts) < 2 or parts[0] != "server":
        return None
    if len(parts) == 2:
        return TOP_FILES.get(parts[1])
    return parts[1] if parts[1] in ROOMS and parts[1] not in TOP_FILES.values() else None


def problems_of(source, includes):
    """The problems of one file of server/ (its path and its quoted includes as (line, text))."""
    problems = []
    room = room_of(source)
    if room is None:
        problems.append(f"{source}: in no room of server/ (rooms: {', '.join(ROOMS)})")
        return problems
    for number, target in includes:
        if "/" not in target:
            problems.append(f'{source}:{number}: #include "{target}" names no folder (write "server/<room>/...")')
            continue
        if not target.startswith("server/"):
            continue
        to = room_of(target)
        if to is None:
            problems.append(f'{source}:{number}: #include "{target}" is in no room of server/')
        elif ROOMS.index(to) > ROOMS.index(room):
            problems.append(f'{source}:{number}: #include "{target}" points up: {room} may include only '
                            f"{', '.join(ROOMS[: ROOMS.index(room) + 1])}")
    return problems


def includes_of(path):
    found = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        m = INCLUDE.match(line)
        if m:
            found.append((number, m.group(1)))
    return found


def self_test():
    bad = problems_of("server/http/route_table.cpp", [(3, "server/context.h")])
    sideways = problems_of("server/store/store.cpp", [(5, "server/sessions/session.h")])
    good = problems_of("server/routes/live.cpp", [(1, "server/context.h"), (2, "server/http/problem.h"),
                                                    (3, "server/routes/routes.h"), (4, "server/options.h")])
    stray = problems_of("server/frames/frames.cpp", [(2, "render_pool.h")])
    homeless = problems_of("server/misc.cpp", [])
    ok = bool(bad) and bool(sideways) and not good and bool(stray) and bool(homeless)
    for p in bad + sideways + stray + homeless:
        print("  (expected) " + p)
    print("self-test " + ("passed" if ok else "FAILED"))
    return 0 if ok else 1


def main(argv):
    if "--self-test" in argv:
        return self_test()
    root = pathlib.Path(argv[1]).resolve() if len(argv) > 1 else ROOT
    problems = []
    files = sorted(p for p in (root / "server").rglob("*") if p.suffix in (".h", ".cpp"))
    for path in files:
        problems += problems_of(path.relative_to(root).as_posix(), includes_of(path))
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{len(files)} files of server/ in {len(ROOMS)} rooms, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
