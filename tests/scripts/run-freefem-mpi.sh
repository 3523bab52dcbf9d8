#!/usr/bin/env bash
# run-freefem.sh on MPI ranks: a FreeFEM script run by FreeFem++-mpi on <np>
# ranks (mpirun --oversubscribe -np <np>), with the freshly built plugin, the
# repo's .idp files and those of the script's folder.
#   run-freefem-mpi.sh <build-dir> <repo-dir> <np> <script.edp> [script args...]
# The job is killed after NBM_MPIRUN_LIMIT seconds (default 600; exit 124),
# so that a hung job ends the test. NBM_MPI_TIMEOUT (the plugin's wait for
# ranks that stopped) and OPENBLAS_NUM_THREADS reach the ranks when set.
set -u
build=$1 repo=$2 np=$3 script=$4
shift 4
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch 2>/dev/null)
export FF_LOADPATH="$build/plugin;/usr/lib/freefem++${multiarch:+;/usr/lib/$multiarch/freefem++}"
export FF_INCLUDEPATH="$repo/edp;$repo/tests/scripts;$(dirname "$script");/usr/include/freefem++/idp"
flags=(--oversubscribe -np "$np" -x FF_LOADPATH -x FF_INCLUDEPATH)
[ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)  # OpenMPI refuses root unless told; CI runs as root
for var in NBM_MPI_TIMEOUT OPENBLAS_NUM_THREADS OMP_NUM_THREADS; do
  [ -n "${!var+set}" ] && flags+=(-x "$var")
done
exec timeout "${NBM_MPIRUN_LIMIT:-600}" mpirun "${flags[@]}" \
  FreeFem++-mpi -nw -ne -v 0 "$script" -geodir "$repo/geo" "$@"
