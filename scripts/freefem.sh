#!/usr/bin/env bash
# Runs a FreeFEM script with the built plugin: scripts/freefem.sh script.edp [-arg value ...]
repo=$(cd "$(dirname "$0")/.." && pwd)
exec bash "$repo/tests/scripts/run-freefem.sh" "$repo/build" "$repo" "$@"
