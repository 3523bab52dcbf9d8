#!/usr/bin/env bash
# Runs a FreeFEM script with the freshly built plugin and the repo's .idp files.
#   run-freefem.sh <build-dir> <repo-dir> <script.edp> [script args...]
# Exits with FreeFem++'s code; output goes to stdout/stderr as usual. Scripts
# get `-geodir <repo>/geo` first (the folder of the gmsh geometries; a later
# -geodir of the caller wins, getARGV takes the last one).
set -u
build=$1 repo=$2 script=$3
shift 3
# FreeFEM's stock plugins: /usr/lib/freefem++ on Debian, or the multiarch
# folder /usr/lib/<triplet>/freefem++ of this machine on other layouts.
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch 2>/dev/null)
export FF_LOADPATH="$build/plugin;/usr/lib/freefem++${multiarch:+;/usr/lib/$multiarch/freefem++}"
export FF_INCLUDEPATH="$repo/edp;$repo/tests/scripts;/usr/include/freefem++/idp"
exec FreeFem++ -nw -ne -v 0 "$script" -geodir "$repo/geo" "$@"
