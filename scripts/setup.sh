#!/usr/bin/env bash
# Installs every Debian package Spinfold needs, and nothing else. Idempotent and non-interactive:
# packages already present are skipped, so a second run does no network work.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  ccache                                          # compiler cache: scripts/test.sh's four builds
  libeigen3-dev                                   # engine
  libosmesa6-dev libegl-dev libegl-mesa0 libglm-dev libimgui-dev libpng-dev  # renderer (OSMesa, EGL)
  libdeflate-dev libturbojpeg0-dev                # frames: PNG compression, JPEG
  libcpp-httplib-dev nlohmann-json3-dev           # server and JSON codec
  libsqlite3-dev                                  # the durable session store
  libpq-dev postgresql iproute2                   # the PostgreSQL store, its tests, several hosts (netns)
  libgif-dev libzip-dev                           # recordings: GIF (giflib), a zip of PNGs (libzip)
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev  # recordings: WebM/VP9 and MP4/H.264
                                                  # (FFmpeg; its libavcodec brings libvpx and libx264)
  libcli11-dev                                    # command line
  libgtest-dev libgmock-dev libbenchmark-dev      # tests and benchmarks
  clang libclang-rt-14-dev                        # fuzzing (libFuzzer) and sanitizer runtimes
  libboost-dev                                    # reference integrators (Boost.Odeint)
  python3-sympy                                   # docs/physics_inertia_check.py (a ctest)
  wrk curl                                        # HTTP load benchmark
  stress-ng clang-format                          # flake hunts under load (scripts/flake_hunt.sh); C++ format check
  chromium                                        # browser tests of the web UI (playwright-core)
  nginx                                           # the front of the shared server (scripts/front.sh)
  slurm-wlm munge                                 # the Slurm job array test (scripts/slurm_sweep_test.sh)
  pybind11-dev python3-dev python3-numpy          # the Python package (python/): pybind11, NumPy
  python3-pytest                                  # its tests (tests/python)
  python3-pandas                                  # the CSV files read as they are by pandas (tests/python)
  python3-yaml gettext-base                       # the Kubernetes recipe's test: PyYAML, envsubst
  python3-setuptools python3-pip                  # pip install --no-build-isolation of the package
  jupyter-nbconvert python3-nbconvert python3-ipykernel python3-matplotlib  # the notebook (examples/)
  libopenvdb-dev                                  # meshes of formula surfaces (OpenVDB's volume-to-mesh)
  libcairo2-dev fonts-dejavu-core               # vector figures (SVG, PDF): cairo, Debian-packaged and
                                                  # mature, one API for both, text in DejaVu Sans
  libxml2-utils poppler-utils librsvg2-bin        # the figures' checks: xmllint, pdfinfo/pdftoppm, rsvg-convert
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi

# The web UI's npm packages (uPlot, served to the browser; playwright-core and @axe-core/playwright,
# for the browser tests; @seriousme/openapi-schema-validator and ajv, for the OpenAPI check; eslint,
# @eslint/js, globals, prettier and typescript, for the UI's lint stage in scripts/test.sh), from
# the npm registry, pinned by web/package-lock.json. Installed again when any of them is missing.
root=$(cd "$(dirname "$0")/.." && pwd)
missing=""
for package in uplot playwright-core @axe-core/playwright @seriousme/openapi-schema-validator ajv eslint @eslint/js \
               globals prettier typescript; do
  [[ -d "$root/web/node_modules/$package" ]] || missing="$missing $package"
done
if [[ -n "$missing" ]]; then
  echo "setup: installing the web UI's npm packages (missing:$missing)"
  (cd "$root/web" && npm ci --no-audit --no-fund)
fi
