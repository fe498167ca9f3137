#!/bin/bash
# Builds the Palabos peer benchmark against the Debian package (libplb-dev, Palabos 1.5).
# The Debian headers are copied to the build folder and one line that GCC 12 rejects is fixed
# there (multiGrid/coarseGridProcessors3D.hh calls indices.assign with three iterators; the first
# argument is dropped). /usr/include is never modified and no Palabos code is kept in this repository.
#
# usage: build.sh [BUILD_DIR=/tmp/aniso-lbm-peer]   -> BUILD_DIR/palabos_bench
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-/tmp/aniso-lbm-peer}
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
mpic++ -O3 -DNDEBUG -DPLB_MPI_PARALLEL -DPLB_USE_POSIX -I"$build/palabos" -I/usr/include/eigen3 \
  -w -o "$build/palabos_bench" "$here/palabos_bench.cpp" -lplb
echo "$build/palabos_bench"
