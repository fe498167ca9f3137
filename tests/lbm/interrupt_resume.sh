#!/bin/bash
# SIGTERM to a running `aniso-lbm` (what SLURM sends at a time limit): it stops at the next
# convergence check, keeps the directions it finished as direction files, writes no tensor, names
# what is done and left and the command that continues, and exits 143; the same command then runs
# only the directions left and writes the tensor of an uninterrupted run to the last bit. The
# signal is sent once the log shows the flow along x1 converged, so that x2's is in progress.
# A temporary of the result left by a process killed on this host (kill -9) is removed by the
# resumed run; those of a live process or of another host are left alone.
# usage: interrupt_resume.sh ANISO_LBM MAKE_LBM_IMAGE
set -euo pipefail
lbm=$1 make_image=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/../tools/cli_lib.sh"
fail() { echo "interrupt_resume.sh: $*" >&2; exit 1; }
# About a second per direction: a 32^3 sphere array converged to 1e-9.
"$make_image" sphere_array "$work/cell.h5" --side 32 --solid-fraction 0.2 --voxel-size 1e-4
run=("$lbm" --input "$work/cell.h5" --set lbm.convergence.tolerance=1e-9)
"${run[@]}" --set lbm.output_dir="\"$work/whole\"" > "$work/whole.log" 2>&1 ||
  { cat "$work/whole.log"; fail "the uninterrupted run failed"; }

# The interrupted run: SIGTERM once it logs "flow along x1 .*converged".
stop_when_logged "flow along x1 .*converged" "$work/stopped.log" "${run[@]}" --set lbm.output_dir="\"$work/stopped\""
code=$stopped_code
cat "$work/stopped.log"
[ "$code" = 143 ] || fail "the stopped run exited $code, expected 143"
grep -q "stopped on SIGTERM: directions done: x1.* (kept as .*/permeability_cell_direction<D>.h5); directions left: .*x3; continue with the same command, which runs only the directions left: .*aniso-lbm --input $work/cell.h5" \
  "$work/stopped.log" || fail "the stop message does not say what is done, what is left and how to continue"
[ ! -e "$work/stopped/permeability_cell.h5" ] || fail "a stopped run wrote a tensor"
[ -z "$(find "$work/stopped" -name '.*.tmp-*')" ] || fail "a temporary file was left behind"
[ -f "$work/stopped/permeability_cell_direction0.h5" ] || fail "the flow along x1 was not kept"
[ ! -e "$work/stopped/permeability_cell_direction2.h5" ] || fail "the flow along x3 was kept: the signal came too late"
/usr/bin/python3 - "$work/stopped/permeability_cell_direction0.h5" "$work/whole/permeability_cell.h5" <<'PY' ||
import sys, h5py, numpy as np
with h5py.File(sys.argv[1]) as d, h5py.File(sys.argv[2]) as w:
    assert np.array_equal(d["direction/runs/mean_momentum"][0], w["permeability/runs/mean_momentum"][0])
    assert d["direction/runs/steps"][0] == w["permeability/runs/steps"][0]
PY
  fail "the kept direction 0 differs from the uninterrupted run's flow along x1"

# Temporaries of the tensor: one of a process killed on this host, one of a live process (this
# shell), one of another host. Only the first goes.
sh -c 'exit 0' &
dead=$!
wait "$dead"
host=$(hostname)
for tag in "$host-$dead" "$host-$$" "another-host-$dead"; do
  echo partial > "$work/stopped/.permeability_cell.h5.tmp-$tag-AbC123"
done

"${run[@]}" --set lbm.output_dir="\"$work/stopped\"" > "$work/resumed.log" 2>&1 || { cat "$work/resumed.log"; fail "the resumed run failed"; }
grep -q "directions already done by an earlier run: x1" "$work/resumed.log" ||
  { cat "$work/resumed.log"; fail "the resumed run did not reuse the kept direction"; }
grep -q "flow along x1 .*converged" "$work/resumed.log" && { cat "$work/resumed.log"; fail "the resumed run ran x1 again"; }
for dataset in K K_lattice runs/mean_momentum runs/steps runs/reynolds runs/pressure_gradient; do
  h5diff "$work/whole/permeability_cell.h5" "$work/stopped/permeability_cell.h5" \
    "/permeability/$dataset" "/permeability/$dataset" ||
    fail "/permeability/$dataset of the resumed run differs from the uninterrupted run"
done
[ -z "$(ls "$work/stopped" | grep "_direction[0-2].h5$")" ] || fail "the direction files were not removed after the tensor"
[ ! -e "$work/stopped/.permeability_cell.h5.tmp-$host-$dead-AbC123" ] ||
  fail "the temporary of a dead process of this host was left"
[ -e "$work/stopped/.permeability_cell.h5.tmp-$host-$$-AbC123" ] || fail "the temporary of a live process was removed"
[ -e "$work/stopped/.permeability_cell.h5.tmp-another-host-$dead-AbC123" ] ||
  fail "the temporary of another host was removed"
echo "interrupt_resume.sh: all checks passed"
