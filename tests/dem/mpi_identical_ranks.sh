#!/usr/bin/env bash
# The DEM on 1, 2 and 4 ranks: prepare and load must write identical
# particles, contacts, cell state and history (h5diff finds no difference).
# 4 ranks on a 2-core machine spin 4x slower, so with 4 ranks only the load runs,
# from the 1-rank packing (prepare is compared on 1 and 2 ranks).
#
# usage: mpi_identical_ranks.sh BUILD_DIR WORK_DIR ["RANKS"] [--set key=value ...]
#   RANKS defaults to "1 2 4"; further arguments are extra settings (an ovoid assembly, say).
set -euo pipefail
build=$1 work=$2
ranks=${3:-1 2 4}
shift $(($# < 3 ? $# : 3))
rm -rf "$work"
mkdir -p "$work"
# Ranks above the core count wait by yielding instead of spinning.
export OMPI_MCA_mpi_yield_when_idle=1
# Two compaction cycles (the second restarts from the first) at a fast rate from a dense start.
settings=(--set dem.particles.count=200 --set dem.seed=5 --set dem.prepare.cycles=2
          --set dem.prepare.void_ratio_tolerance=1
          --set dem.equilibrium.tolerance=1e-3 --set dem.equilibrium.verify_steps=2000
          --set dem.prepare.inertial_number=0.05 --set dem.prepare.initial_solid_fraction=0.35
          --set dem.load.final_strain=0.002 --set 'dem.load.checkpoint_strains=[0.001, 0.002]'
          --set dem.load.history_interval=2e-4 --log-level warn "$@")
for n in $ranks; do
  out="$work/np$n"
  mkdir -p "$out"
  if [ "$n" -le 2 ]; then
    mpiexec --oversubscribe -n "$n" "$build/dem/aniso-dem" prepare "${settings[@]}" --set dem.output_dir="$out"
  else
    cp "$work/np1/prepared.h5" "$out/"
  fi
  mpiexec --oversubscribe -n "$n" "$build/dem/aniso-dem" load "${settings[@]}" --set dem.output_dir="$out" \
    --input "$out/prepared.h5"
done
status=0
for n in $ranks; do
  [ "$n" = 1 ] && continue
  files="load_000.h5 load_001.h5"
  [ "$n" -le 2 ] && files="prepared.h5 $files"
  for file in $files; do
    for group in /particles /contacts /cell; do
      if ! h5diff "$work/np1/$file" "$work/np$n/$file" "$group" "$group" > "$work/diff.txt"; then
        echo "FAIL: $n ranks: $file $group differs from 1 rank:"; head -5 "$work/diff.txt"; status=1
      fi
    done
  done
  if ! h5diff "$work/np1/history.h5" "$work/np$n/history.h5" /history /history > "$work/diff.txt"; then
    echo "FAIL: $n ranks: history differs from 1 rank:"; head -5 "$work/diff.txt"; status=1
  fi
done
# The halo volume under the timing table: none on 1 rank; on 2 ranks what one rank sends is the
# other's ghosts, so the kB a refresh sends per rank are the ghosts per rank times 13 doubles.
if [[ " $ranks " == *" 2 "* ]]; then
  one=$("$build/dem/aniso-dem" hold --input "$work/np1/prepared.h5" --steps 1 2>&1)
  two=$(mpiexec --oversubscribe -n 2 "$build/dem/aniso-dem" hold --input "$work/np1/prepared.h5" --steps 1 2>&1)
  line=$(grep -m1 " halo: " <<<"$two" || true)
  if grep -q " halo: " <<<"$one"; then echo "FAIL: a halo line on 1 rank"; status=1; fi
  if ! /usr/bin/python3 - "$line" "$work/np1/prepared.h5" <<'PY'; then status=1; fi
import re, sys
import h5py
line = sys.argv[1]
with h5py.File(sys.argv[2], "r") as f:
    half = len(f["particles/diameter"]) / 2  # owned per rank, on average
m = re.search(r"halo: (\d+) ghosts per rank \(min (\d+), max (\d+)\), ([\d.]+)% of the owned; a refresh "
              r"sends ([\d.]+) kB per rank per step \(max ([\d.]+) kB\) to at most (\d+) rank", line)
if not m:
    sys.exit(f"FAIL: no halo line on 2 ranks: {line!r}")
ghosts, low, high, share, sent, _, partners = (float(v) for v in m.groups())
# On 2 ranks a rank's ghosts are some of the other rank's owned particles.
checks = [(0 < low <= ghosts <= high and ghosts <= half, "ghosts per rank within (0, N/2]"),
          (abs(sent - ghosts * 13 * 8 / 1e3) <= 0.05 + 1e-9 * sent, "sent kB = ghosts x 104 B"),
          (abs(share - 100 * ghosts / half) <= 0.05 + 50 / half, "share of the N/2 owned per rank"),
          (partners == 1, "one partner rank")]
failed = [what for ok, what in checks if not ok]
if failed:
    sys.exit(f"FAIL: halo line {line!r}: {failed}")
print(f"halo line on 2 ranks: {int(ghosts)} ghosts per rank, {sent} kB a refresh")
PY
fi
[ $status = 0 ] && echo "identical bits on ranks $ranks: prepared.h5 (ranks 1 and 2), 2 load checkpoints, history"
exit $status
