#!/usr/bin/env bash
# Installs the Debian packages nbm needs, only those missing (idempotent).
# Runs as root (CI) or through sudo when available.
set -eu
packages=(
  build-essential cmake pkg-config
  freefem++ libfreefem++-dev gmsh gnuplot-nox
  libeigen3-dev libsuitesparse-dev
  libspectra-dev                # Lanczos (shift-invert) for the reduced bases' modes
  libmumps-dev libopenmpi-dev openmpi-bin   # MUMPS on MPI: the iteration
                                # matrix on several ranks under FreeFem++-mpi / ff-mpirun
  libopenblas0-pthread          # optimised BLAS/LAPACK for CHOLMOD and the core's
  libblas-dev liblapack-dev     # dense kernels, see below; -lblas -llapack to link
  libgtest-dev libbenchmark-dev
  clang-14 libclang-rt-14-dev   # libFuzzer (tests/fuzz/run.sh); gcc's ASan/UBSan
                                # runtimes (tests/sanitize.sh) come with build-essential
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
else
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# CHOLMOD (libsuitesparse) loads libblas.so.3 and liblapack.so.3, which Debian
# resolves through the alternatives system: point both at OpenBLAS (pthread
# variant), whatever an administrator selected before. The reference BLAS stays
# installed (libsuitesparse depends on a BLAS) but unused. bench/bench_step.cpp
# reports which BLAS was loaded and with how many threads.
multiarch=$(gcc -print-multiarch)
for lib in libblas.so.3 liblapack.so.3; do
  name="$lib-$multiarch"
  want="/usr/lib/$multiarch/openblas-pthread/$lib"
  current=$(readlink -f "/etc/alternatives/$name" || true)
  if [ "$current" != "$want" ]; then
    echo "install-deps: $lib -> $want"
    $sudo update-alternatives --set "$name" "$want"
  fi
done
