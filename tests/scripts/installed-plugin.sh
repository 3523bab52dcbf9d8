#!/usr/bin/env bash
# The install step: `cmake --install` into a scratch DESTDIR, then the README's
# minimal example runs with FreeFEM finding nbm.so and nbm.idp only where the
# install put them (no build tree, no repo folders on the search paths), and
# so does a P4L space from the installed Element_PkL.so.
#   installed-plugin.sh <build-dir> <repo-dir>
set -eu
build=$1 repo=$2
dest=$(mktemp -d)
trap 'rm -rf "$dest"' EXIT
DESTDIR="$dest" cmake --install "$build" >/dev/null
plugin_dir=$(grep '^NBM_FREEFEM_PLUGIN_DIR:' "$build/CMakeCache.txt" | cut -d= -f2)
idp_dir=$(grep '^NBM_FREEFEM_IDP_DIR:' "$build/CMakeCache.txt" | cut -d= -f2)
test -f "$dest$plugin_dir/nbm.so" || { echo "FAIL: nbm.so not installed in $plugin_dir"; exit 1; }
test -f "$dest$plugin_dir/Element_PkL.so" || { echo "FAIL: Element_PkL.so not installed in $plugin_dir"; exit 1; }
test -f "$dest$idp_dir/nbm.idp" || { echo "FAIL: nbm.idp not installed in $idp_dir"; exit 1; }
cp "$repo/edp/minimal.edp" "$dest/"
cd "$dest"
export FF_LOADPATH="$dest$plugin_dir;/usr/lib/freefem++"
export FF_INCLUDEPATH="$dest$idp_dir;/usr/include/freefem++/idp"
FreeFem++ -nw -ne -v 0 minimal.edp | tee out.log
grep -q "min gap" out.log || { echo "FAIL: the minimal example printed no result"; exit 1; }
printf 'load "msh3"\nload "Element_PkL"\nmeshL Th = segment(3, [x]);\nfespace Vh(Th, P4L);\ncout << "P4L ndof " << Vh.ndof << endl;\n' > p4l.edp
FreeFem++ -nw -ne -v 0 p4l.edp | tee -a out.log
grep -q "P4L ndof 13" out.log || { echo "FAIL: the installed Element_PkL gave no P4L space"; exit 1; }
echo "OK: the installed plugin and helpers run the minimal example; the installed Element_PkL gives P4L"
