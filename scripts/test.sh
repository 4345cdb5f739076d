#!/usr/bin/env bash
# Install what is missing, build with warnings as errors, and run every test; then every test
# but the browser's and the front's again under AddressSanitizer and UBSan; the server tests under
# ThreadSanitizer; then the libFuzzer targets (clang) for a fixed number of inputs from a fixed
# seed.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
jobs=$(nproc)
# A compiler cache (Debian's ccache) under the four builds below: a second run on one machine
# recompiles only what changed, also from another clone (paths relative to the repository).
# Cold, on a new machine, the run takes its full time (docs/performance.md, "CI's time").
if command -v ccache > /dev/null; then
  export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
fi
started=$SECONDS
stage() { echo "test.sh: $1 at +$((SECONDS - started)) s"; }  # where CI's time goes

# The web UI's lint, formatting and types (web/eslint.config.js, .prettierrc.json, jsconfig.json:
# tsc checks every module's JSDoc types under // @ts-check): about 6 s of CPU.
stage "web lint (ESLint, Prettier, tsc)"
(cd web && npm run -s lint)
# The C++ format (.clang-format, Debian's clang-format): every tracked source as clang-format
# writes it (about 3 s). Fix with: git ls-files '*.cpp' '*.h' | xargs clang-format -i
stage "C++ format (clang-format)"
git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run --Werror

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSPINFOLD_WERROR=ON > /dev/null
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"

# The golden frames again as two other CPUs would render them: llvmpipe compiling for AVX without
# AVX2, then for SSE4.1, and glibc's libm without its FMA variants (the physics behind the frames).
# Proves the tolerance holds beyond this machine (docs/performance.md, "Across CPUs").
stage "golden frames with other CPUs' code"
for caps in avx sse4.1; do
  GALLIUM_OVERRIDE_CPU_CAPS=$caps GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-AVX \
    build/tests/render_tests --gtest_filter='Views/GoldenFrame.*' --gtest_brief=1
done
# The golden frames through the other GL backend: auto picks EGL (surfaceless llvmpipe) on a machine
# without a GPU, so the ctest run above checked EGL's frames; OSMesa's once more (README, "GL backends").
if build/spinfold --version | grep -q '^GL backends built in:.*osmesa'; then
  stage "golden frames through OSMesa"
  SPINFOLD_GL=osmesa build/tests/render_tests --gtest_filter='Views/GoldenFrame.*' --gtest_brief=1
fi

# The sanitizer and ThreadSanitizer runs render through OSMesa, as before EGL came: EGL's GLVND
# dispatch and driver are uninstrumented libraries whose start-up allocations and threads would be
# reported as ours. The release run above covers EGL (and gl_backend_test makes an EGL context in
# every build).
export SPINFOLD_GL=osmesa
stage "AddressSanitizer + UBSan build"
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSPINFOLD_WERROR=ON \
  -DSPINFOLD_SANITIZE=ON > /dev/null
cmake --build build-sanitize -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0" \
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
# ThreadSanitizer over the server tests: HTTP workers, the player and the render thread share
# sessions (the other tests are single-threaded).
stage "ThreadSanitizer build"
# Without EGL: GLVND's libEGL, loaded even when OSMesa draws, trips TSan's mutex checks in its own
# (uninstrumented) start-up ("unlock of an unlocked mutex" in libEGL.so.1).
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSPINFOLD_WERROR=ON \
  -DSPINFOLD_TSAN=ON -DSPINFOLD_EGL=OFF > /dev/null
cmake --build build-tsan -j "$jobs" --target server_tests
# Two shards side by side (one per core), then the timing tests alone, as ctest runs them.
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/tests/tsan.supp"
GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=0 build-tsan/tests/server_tests --gtest_filter=-HardeningIdle.* \
  > build-tsan/server_tests_0.log 2>&1 & shard0=$!
GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=1 build-tsan/tests/server_tests --gtest_filter=-HardeningIdle.* \
  > build-tsan/server_tests_1.log 2>&1 & shard1=$!
tsan_failed=0
wait "$shard0" || tsan_failed=1
wait "$shard1" || tsan_failed=1
tail -n 3 build-tsan/server_tests_0.log build-tsan/server_tests_1.log
if ((tsan_failed)); then cat build-tsan/server_tests_0.log build-tsan/server_tests_1.log; exit 1; fi
build-tsan/tests/server_tests --gtest_filter=HardeningIdle.*
unset TSAN_OPTIONS
stage "fuzz build"
# The fuzzers render through OSMesa as before EGL came (the sanitizer runs above say why).
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release -DSPINFOLD_WERROR=ON \
  -DSPINFOLD_FUZZ=ON -DSPINFOLD_EGL=OFF > /dev/null
cmake --build build-fuzz -j "$jobs"
ctest --test-dir build-fuzz --output-on-failure -j "$jobs"
stage "done"
echo "test.sh: all tests passed"
