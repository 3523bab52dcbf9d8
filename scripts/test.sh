#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (unit and script).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
bash "$repo/scripts/install-deps.sh"
bash "$repo/scripts/build.sh"
cd "$repo/build"
ctest --output-on-failure -j "$(nproc)" "$@"
