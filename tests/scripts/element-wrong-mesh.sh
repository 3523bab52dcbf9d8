#!/usr/bin/env bash
# P4L on a mesh that is not a meshL must be refused by FreeFEM when the script
# is compiled (exit 1, "Compile error" with Element_PkL's message naming the
# mesh type), never a crash or a run.
#   element-wrong-mesh.sh <build-dir> <repo-dir>
# The same script on a meshL must run: the refusal comes from the mesh type.
set -u
build=$1 repo=$2
run="$(dirname "$0")/run-freefem.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
ok=1
check() {  # <name> <expected exit code> <mesh declaration>
  printf 'load "msh3"\nload "Element_PkL"\n%s\nfespace Vh(Th, P4L);\nVh u = x;\ncout << "ndof " << Vh.ndof << endl;\n' \
    "$3" > "$dir/$1.edp"
  out=$(cd "$dir" && timeout 60 bash "$run" "$build" "$repo" "$dir/$1.edp" 2>&1)
  code=$?
  if [ "$2" -eq 0 ]; then
    if [ $code -eq 0 ] && printf '%s\n' "$out" | grep -q '^ndof 9$'; then
      echo "OK: P4L on a $1 runs (9 dofs)"
    else
      printf '%s\n' "$out" | tail -n 5; echo "FAIL: P4L on a $1: exit $code"; ok=0
    fi
  elif [ $code -eq 1 ] && printf '%s\n' "$out" | grep -q 'Compile error' \
      && printf '%s\n' "$out" | grep -q "Compile error : fespace: a finite element of curve meshes (P1L ... P4L) on a $4; these elements need a meshL"; then
    echo "OK: P4L on a $1 refused at compile time: $(printf '%s\n' "$out" | grep -m1 'Compile error')"
  else
    printf '%s\n' "$out" | tail -n 5; echo "FAIL: P4L on a $1: exit $code, expected a compile error"; ok=0
  fi
}
check meshL 0 'meshL Th = segment(2, [x]);'
check mesh 1 'mesh Th = square(2, 2);' 'mesh (2d)'
check mesh3 1 'mesh3 Th = cube(2, 2, 2);' 'mesh3'
check meshS 1 'meshS Th = square3(2, 2, [x, y, 0]);' 'meshS'
[ $ok -eq 1 ]
