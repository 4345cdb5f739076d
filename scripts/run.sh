#!/usr/bin/env bash
# The main job: install what is missing, build, and serve the HTTP API with a session on the
# embedded default scene (it prints the URLs to open). Extra arguments replace the default, e.g.
#   scripts/run.sh simulate --scene pole_crossing_sphere
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build --target spinfold

if (($#)); then
  exec build/spinfold "$@"
fi
exec build/spinfold serve
