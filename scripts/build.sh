#!/usr/bin/env bash
# Configures and builds nbm (plugin, core, tests) in ./build.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
cmake -S "$repo" -B "$repo/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$repo/build" -j "$(nproc)"
