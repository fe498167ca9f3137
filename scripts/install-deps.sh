#!/usr/bin/env bash
# Installs the Debian packages aniso needs, and only those that are missing.
#
#   scripts/install-deps.sh [test|demo]
#
# Nothing missing: exits 0 without a word. Something missing: as root, runs
# `apt-get update` and installs it; otherwise prints the exact apt-get line to
# run and exits 1. Every package below exists in Debian 12 (bookworm).
set -euo pipefail

purpose=${1:-test}
case "$purpose" in
  test | demo) ;;
  -h | --help)
    sed -n '2,8s/^# \{0,1\}//p' "$0"
    exit 0
    ;;
  *)
    echo "install-deps.sh: unknown purpose '$purpose' (expected 'test' or 'demo')" >&2
    exit 2
    ;;
esac

# One list serves both purposes: the demo builds and runs the same programs
# the tests do, and its plots need the same Python packages.
packages=(
  # build tools
  cmake make g++ pkg-config git ca-certificates
  # MPI, parallel HDF5 (h5dump), PETSc, METIS, Eigen
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools petsc-dev libmetis-dev libeigen3-dev
  # command line, config, logging
  libcli11-dev libtomlplusplus-dev libspdlog-dev libfmt-dev
  # tests and the format check
  libgtest-dev libgmock-dev clang-format
  # the SLURM path's test: a single-node cluster on localhost (workflows/slurm/local-cluster.sh)
  slurm-wlm munge libpmix2
  # plots and reports
  python3 python3-numpy python3-h5py python3-scipy python3-matplotlib
  # the voxel benchmark's scikit-image peer (tests/perf/bench_voxel_peer.py --skimage)
  python3-skimage
  # a peer DEM code: the import test settles a packing with LIGGGHTS (tests/dem/peer/liggghts_import.sh)
  liggghts
  # the LBM step's x86-64 levels checked on emulated CPUs without AVX-512 and AVX (tests/lbm)
  qemu-user
  # ParaView reads the XDMF outputs: the e2e test renders one with pvpython, headless under Xvfb
  python3-paraview xvfb xauth libgl1-mesa-dri
)

command -v dpkg-query >/dev/null || {
  echo "install-deps.sh: dpkg-query not found; this script is for Debian/Ubuntu." >&2
  echo "On other systems install the equivalents of: ${packages[*]}" >&2
  echo "(or use the Spack environment in workflows/spack.yaml)." >&2
  exit 1
}

# A machine with no /etc/hosts (a bare debootstrap chroot; every installed Debian
# has one) resolves "localhost" through DNS, and Open MPI asks for it at every
# start. A resolver that drops one of glibc's two parallel queries then costs a
# 5-s timeout per MPI program, --help included: in the fresh-machine chroot it
# doubled the test time. Write Debian's default file when there is none; never
# touch one that exists.
if [ ! -e /etc/hosts ]; then
  if [ "$(id -u)" -eq 0 ]; then
    host=$(uname -n)
    printf '127.0.0.1\tlocalhost\n127.0.1.1\t%s\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' "$host" >/etc/hosts
    echo "install-deps.sh: /etc/hosts was missing; wrote Debian's default (localhost, $host)"
  else
    echo "install-deps.sh: warning: /etc/hosts is missing, so every MPI start waits 5 s for DNS;" >&2
    echo "  as root: printf '127.0.0.1\\tlocalhost\\n' > /etc/hosts" >&2
  fi
fi

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
  [ "$status" = installed ] || missing+=("$package")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps.sh: missing Debian packages for '$purpose': ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "Not root: install them with"
  echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends ${missing[*]}"
  exit 1
fi

started=$SECONDS
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends "${missing[@]}"
echo "install-deps.sh: installed ${#missing[@]} packages in $((SECONDS - started)) s"
