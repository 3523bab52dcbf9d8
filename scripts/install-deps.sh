#!/usr/bin/env bash
# Installs the Debian packages nbm needs, only those missing (idempotent).
# Runs as root (CI) or through sudo when available.
set -eu
packages=(
  build-essential cmake pkg-config
  freefem++ libfreefem++-dev gmsh gnuplot-nox
  libeigen3-dev libsuitesparse-dev
  libgtest-dev libbenchmark-dev
  clang-14 libclang-rt-14-dev   # libFuzzer (tests/fuzz/run.sh); gcc's ASan/UBSan
                                # runtimes (tests/sanitize.sh) come with build-essential
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
