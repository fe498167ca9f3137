#!/bin/bash
# Fabric benchmark against its peers in one invocation, on one checkpoint (spheres):
#   aniso: bench_fabric (every measure of measure_fabric), median of REPEATS;
#   numpy: bench_fabric_numpy.py (contact stress, F, G, H and strong, J, W3, Z), median of REPEATS;
#   LAMMPS: `compute fabric radius contact branch force/normal` on the same packing (data file by
#           dem_peer/checkpoint_to_data.py), evaluated every step of a 200-step run without time
#           integration; its cost per evaluation is the loop time with it minus the loop time
#           without it, over 200, median of REPEATS pairs of runs.
# usage: bench_fabric_peer.sh CHECKPOINT.h5 BUILD_DIR WORK_DIR [REPEATS=7]
set -eu
checkpoint=$1 build=$2 work=$3 repeats=${4:-7}
[[ -x $build/tests/perf/bench_fabric ]] || { echo "missing $build/tests/perf/bench_fabric: cmake --build $build --target benchmarks" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
command -v lmp > /dev/null || { echo "installing lammps (apt-get)" >&2; DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends lammps > /dev/null; }
/usr/bin/python3 "$here/dem_peer/checkpoint_to_data.py" "$checkpoint" "$work/peer.data" --info "$work/peer.info"
"$build/fabric/aniso-fabric" --input "$checkpoint" --output "$work/fabric.h5" --log-level warn
steps=200
for with in 0 1; do
  {
    echo "units si"
    echo "atom_style sphere"
    echo "boundary p p p"
    echo "comm_modify vel yes"
    echo "read_data $work/peer.data"
    echo "pair_style gran/hooke 1e3 NULL 0 NULL 0.5 0"
    echo "pair_coeff * *"
    echo "neighbor 1e-6 bin"
    echo "timestep 1e-9"
    if [ $with = 1 ]; then
      echo "compute fab all fabric radius contact branch force/normal"
      echo "thermo_style custom step c_fab[1] c_fab[7] c_fab[13]"
    else
      echo "thermo_style custom step"
    fi
    echo "thermo 1"
    echo "run $steps"
  } > "$work/lammps_$with.in"
done
echo "== aniso (bench_fabric)"
"$build/tests/perf/bench_fabric" "$checkpoint" "$repeats"
echo "== numpy peer"
/usr/bin/python3 "$here/bench_fabric_numpy.py" "$checkpoint" "$work/fabric.h5" "$repeats"
echo "== LAMMPS compute fabric"
for r in $(seq "$repeats"); do
  for with in 0 1; do
    lmp -in "$work/lammps_$with.in" -log none -nocite -screen "$work/lammps_${with}_$r.out" > /dev/null
  done
done
/usr/bin/python3 - "$work" "$repeats" "$steps" << 'PY'
import re, statistics, sys
work, repeats, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def loop(path):
    return float(re.search(r"Loop time of ([0-9.e+-]+)", open(path).read()).group(1))
costs = [(loop(f"{work}/lammps_1_{r}.out") - loop(f"{work}/lammps_0_{r}.out")) / steps for r in range(1, repeats + 1)]
print(f"LAMMPS compute fabric (contact, branch, force/normal): median {statistics.median(costs):.5f} s per evaluation "
      f"(min {min(costs):.5f}, max {max(costs):.5f}) over {repeats} run pairs")
PY
