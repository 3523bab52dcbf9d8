#!/usr/bin/env bash
# Configures and builds nbm (plugin, core, tests, benchmarks) in ./build.
#   bash scripts/build.sh [-D<option>=<value>...]
# The options go to cmake after the defaults below, so they win; a later run
# without them goes back to these defaults (scripts/test.sh builds without the
# unit tests, which it compiles and runs in the sanitized build only).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
cmake -S "$repo" -B "$repo/build" -DCMAKE_BUILD_TYPE=Release -DNBM_BUILD_UNIT_TESTS=ON "$@" >/dev/null
cmake --build "$repo/build" -j "$(nproc)"
