#!/usr/bin/env bash
# `aniso-dem relax`: a checkpoint written at OVAL's increment tolerance
# (1e-2, no verified relaxation) loses about a fifth of p when its cell is held still; relaxed
# with its own loading control it holds p within 1e-3 over the same hold, at the same strain and
# a mean stress within the servo's tolerance, with the same bits on 1 and 2 ranks; a hold as long
# as its verification window replays that window; a relaxation ended on max_windows records the
# steps it held (static_held_steps, static_verified = 0). Writing over
# the input is refused and the input is kept.
#
# usage: relax_checkpoint.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
small_prepared_assembly "$build" dem
"$dem" load --input dem/prepared.h5 --set dem.output_dir=load --set dem.particles.count=200 \
  --set dem.load.final_strain=0.01 --set 'dem.load.checkpoint_strains=[0.01]' \
  --set dem.equilibrium.at_checkpoints=false --set dem.load.increment=1e-3 --log-level warn

# The loosely relaxed checkpoint is not static: the same hold that the relaxed state passes fails.
expect_exit 5 hold_loose "above --max-drift" "$dem" hold --input load/load_000.h5 --steps 10000 --max-drift 1e-3
expect_exit 0 relax "relax of 'load/load_000.h5'" "$dem" relax --input load/load_000.h5 \
  --output relaxed/load_000.h5 --set dem.equilibrium.tolerance=1e-3
expect_exit 0 hold_relaxed "hold of" "$dem" hold --input relaxed/load_000.h5 --steps 10000 --max-drift 1e-3
# The written state is the one the verification window began from: a hold as long as the window
# replays it, to the drift the relaxation logged (a hold of the window's end state drifts otherwise).
window=$(sed -n 's/.*static through the 20000-step verification at a fixed cell (p drift \([^,]*\),.*/\1/p' relax.log)
expect_exit 0 hold_window "hold of" "$dem" hold --input relaxed/load_000.h5 --steps 20000
replayed=$(sed -n 's/.*hold of .* (drift \([^,]*\),.*/\1/p' hold_window.log)
[ -n "$window" ] && [ "$window" = "$replayed" ] ||
  { echo "FAIL: the window's p drift '$window' is not replayed by a 20000-step hold ('$replayed')"; status=1; }

# Same strain along the loading axis, p at the servo's target, the equilibrium ratios recorded.
/usr/bin/python3 - load/load_000.h5 relaxed/load_000.h5 relax.log <<'PY' || status=1
import re
import sys
import h5py

def state(path):
    with h5py.File(path, "r") as f:
        return f["/cell/lengths"][()], f.attrs["unbalanced_force_ratio"], f.attrs["run_id"]

loose_cell, loose_ratio, loose_id = state(sys.argv[1])
cell, ratio, run_id = state(sys.argv[2])
p = float(re.search(r"p [0-9.e+-]+ -> ([0-9.e+-]+) Pa", open(sys.argv[3]).read()).group(1))
checks = {
    "the loading axis keeps its length (rel. 1e-12)": abs(cell[0] / loose_cell[0] - 1) < 1e-12,
    "the plane-strain axis keeps its length (rel. 1e-12)": abs(cell[1] / loose_cell[1] - 1) < 1e-12,
    f"p = {p:.6g} Pa within 1e-3 of 100 kPa": abs(p / 100e3 - 1) < 1e-3,
    f"unbalanced-force ratio {ratio:.3g} below 1e-3 (was {loose_ratio:.3g})": ratio < 1e-3 < loose_ratio,
    "the run id is kept": run_id == loose_id,
}
for name, ok in checks.items():
    print(("ok: " if ok else "FAIL: ") + name)
sys.exit(0 if all(checks.values()) else 1)
PY

# Two ranks relax to the same bits as one (the relaxation's sums are exact).
mpiexec --oversubscribe -n 2 "$dem" relax --input load/load_000.h5 --output relaxed_np2/load_000.h5 \
  --set dem.equilibrium.tolerance=1e-3 --log-level warn
for group in /particles /contacts /cell; do
  h5diff relaxed/load_000.h5 relaxed_np2/load_000.h5 "$group" "$group" >diff.txt \
    || { echo "FAIL: 2 ranks: relaxed $group differs from 1 rank:"; head -5 diff.txt; status=1; }
done

# A verified relaxation records its whole window; one that leaves dem.equilibrium.max_windows
# windows (a stress tolerance of 1e-5 that its balance cannot keep) ends unverified at the balance
# the last window began from, with the steps it held, which a hold that long replays.
expect_exit 0 relax_windows "left the verification 2 times (dem.equilibrium.max_windows): ends unverified" \
  "$dem" relax --input load/load_000.h5 --output unverified.h5 --set dem.equilibrium.tolerance=1e-3 \
  --set dem.equilibrium.verify_steps=2000 --set dem.equilibrium.stress_tolerance=1e-5 --set dem.equilibrium.max_windows=2
attribute() { h5dump -a "/$2" "$1" | sed -n 's/.*(0): \([0-9]*\).*/\1/p'; }
held=$(attribute unverified.h5 static_held_steps)
[ "$(attribute unverified.h5 static_verified)" = 0 ] && [ "$held" -gt 0 ] && [ "$held" -lt 2000 ] ||
  { echo "FAIL: unverified.h5 records static_verified $(attribute unverified.h5 static_verified), held '$held'"; status=1; }
[ "$(attribute relaxed/load_000.h5 static_verified)" = 1 ] && [ "$(attribute relaxed/load_000.h5 static_held_steps)" = 20000 ] ||
  { echo "FAIL: relaxed/load_000.h5 does not record its verified 20000-step window"; status=1; }
expect_exit 0 hold_unverified "hold of" "$dem" hold --input unverified.h5 --steps $((held - 4)) --max-drift 1e-5
expect_exit 5 hold_unverified_longer "above --max-drift" "$dem" hold --input unverified.h5 --steps 2000 --max-drift 1e-5

# The loaded state is never overwritten.
before=$(md5sum load/load_000.h5)
expect_exit 2 relax_onto_input "is the input" "$dem" relax --input load/load_000.h5 --output ./load/../load/load_000.h5
[ "$(md5sum load/load_000.h5)" = "$before" ] || { echo "FAIL: the input changed"; status=1; }
exit $status
