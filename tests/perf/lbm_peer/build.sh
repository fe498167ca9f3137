#!/bin/bash
# Builds the Palabos peer benchmark against the Debian package (libplb-dev, Palabos 1.5).
# The Debian headers are copied to the build folder and one line that GCC 12 rejects is fixed
# there (multiGrid/coarseGridProcessors3D.hh calls indices.assign with three iterators; the first
# argument is dropped). /usr/include is never modified and no Palabos code is kept in this repository.
#
# usage: build.sh [BUILD_DIR=/tmp/aniso-lbm-peer] [SOURCE.cpp ...]   -> BUILD_DIR/<source stem> for each
#   (default: palabos_bench.cpp beside this script; tests/lbm/peer/palabos_permeability.cpp is the other)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-/tmp/aniso-lbm-peer}
shift || true
sources=("$@")
[ ${#sources[@]} -gt 0 ] || sources=("$here/palabos_bench.cpp")
if [ ! -f /usr/include/palabos/palabos3D.h ]; then
  echo "installing libplb-dev (apt-get)" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y libplb-dev > /dev/null
fi
mkdir -p "$build"
rm -rf "$build/palabos"
cp -r /usr/include/palabos "$build/palabos"
header=$build/palabos/multiGrid/coarseGridProcessors3D.hh
# indices.assign(a, b, c) -> indices.assign(b, c)
sed -i -E 's/indices\.assign\(\s*[^,]+,\s*([^,]+),\s*([^)]+)\)/indices.assign(\1, \2)/' "$header"
for source in "${sources[@]}"; do
  binary=$build/$(basename "$source" .cpp)
  mpic++ -O3 -DNDEBUG -DPLB_MPI_PARALLEL -DPLB_USE_POSIX -I"$build/palabos" -I/usr/include/eigen3 \
    -w -o "$binary" "$source" -lplb
  echo "$binary"
done
