#!/usr/bin/env bash
# `aniso-dem replicate`: a prepared assembly of 200 spheres and one of 150 ovoids (alpha = 0.625)
# tiled 2 x 2 x 2 and 1 x 2 x 3 is the same state in a larger cell (replicate_checks.py: counts
# times the copies, every particle and contact carried, the contact stress, void ratio and the
# contact fabric equal to 1e-12, the stored forces reproduced by the first force passes of a
# hold, the loading path followed, relax accepted); 1 x 1 x 1 gives the input's datasets; 2 ranks
# replicate and load a replicated file to the bits of 1; bad --copies, a missing input, an
# existing output, a file it cannot tile and a mismatched image shift are refused by name, and
# `load --resume` refuses a replicated file.
#
# usage: replicate.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
source "$(dirname "$0")/../tools/cli_lib.sh"
checks=$(cd "$(dirname "$0")" && pwd)/replicate_checks.py
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
export OMPI_MCA_mpi_yield_when_idle=1

small_prepared_assembly "$build" spheres
# The ovoid assembly of the 2-rank identity test (tests/dem/CMakeLists.txt), prepared in seconds.
"$dem" prepare --set dem.particles.count=150 --set dem.seed=3 --set dem.particles.aspect_ratio=0.625 \
  --set dem.particles.diameter_min=0.1e-3 --set dem.particles.d50=0.15e-3 --set dem.particles.diameter_max=0.2e-3 \
  --set dem.prepare.initial_solid_fraction=0.35 --set dem.prepare.inertial_number=0.05 --set dem.prepare.cycles=1 \
  --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 --set dem.equilibrium.verify_steps=0 \
  --set dem.output_dir=ovoids --log-level warn

# A short biaxial loading (0.1%, about 1400 steps, no relaxations).
loading=(--set dem.load.final_strain=1e-3 --set 'dem.load.checkpoint_strains=[1e-3]'
         --set dem.equilibrium.at_checkpoints=false --set dem.load.history_interval=1e-4 --log-level warn)
for shape in spheres ovoids; do
  cd "$work/$shape"
  for copies in 2,2,2 1,2,3 1,1,1; do
    name=x${copies//,/}
    expect_exit 0 "replicate_$name" "replicate of 'prepared.h5' ${copies//,/ x }" \
      "$dem" replicate --input prepared.h5 --output "$name.h5" --copies "$copies"
  done
  mpiexec --oversubscribe -n 2 "$dem" replicate --input prepared.h5 --output x222_np2.h5 --copies 2,2,2 \
    --log-level warn
  expect_same_state "$shape: replicate on 2 ranks" x222.h5 x222_np2.h5
  "$build/fabric/aniso-fabric" --input prepared.h5 x222.h5 x123.h5 --output fabric.h5 --log-level warn
  for name in prepared x222 x123; do
    "$dem" hold --input "$name.h5" --steps 200 --csv "hold_$name.csv" --log-level warn
  done
  for name in prepared x222; do
    "$dem" load --input "$name.h5" --set dem.output_dir="load_$name" "${loading[@]}"
    "$dem" relax --input "$name.h5" --output "relaxed_$name.h5" --set dem.equilibrium.tolerance=1e-3 \
      --set dem.equilibrium.verify_steps=0 --log-level warn
  done
  mpiexec --oversubscribe -n 2 "$dem" load --input x222.h5 --set dem.output_dir=load_x222_np2 "${loading[@]}"
  expect_same_state "$shape: load of the copies on 2 ranks" load_x222/load_000.h5 load_x222_np2/load_000.h5
  expect_same_history "$shape: load of the copies on 2 ranks" load_x222/history.h5 load_x222_np2/history.h5
  /usr/bin/python3 "$checks" "$shape" || status=1
done

# Refusals: exit 2 for a bad request (3 for a file that is missing or inconsistent), naming the
# problem, and no output written.
cd "$work/spheres"
refuse() { # NAME EXIT PATTERN ARGS...: replicate to NAME.h5, which must not appear
  local name=$1 code=$2 pattern=$3
  shift 3
  expect_exit "$code" "$name" "$pattern" "$dem" replicate --output "$name.h5" "$@"
  [ ! -e "$name.h5" ] || { echo "FAIL: $name: a checkpoint was written"; status=1; }
}
# (test_replicate.cpp parses more malformed counts; these reach it through the command line.)
for bad in 0,2,2 2,2 2,x,2 -1,2,2; do
  refuse "copies_$bad" 2 "replicate: --copies '$bad': expected three whole numbers n1,n2,n3, each >= 1" \
    --input prepared.h5 --copies "$bad"
done
refuse missing 3 "missing.h5: file not found" --input missing.h5 --copies 2,2,2
/usr/bin/python3 - <<'PY'
import shutil
import h5py
for name in ("interrupted", "unknown_attribute", "wrong_shift"):
    shutil.copy("prepared.h5", f"{name}.h5")
with h5py.File("interrupted.h5", "r+") as f:
    f.create_group("relaxation").attrs["command"] = "relax"
with h5py.File("unknown_attribute.h5", "r+") as f:
    f.attrs["cell_volume"] = 1.0
with h5py.File("wrong_shift.h5", "r+") as f:
    f["contacts/image_shift"][0, 0] += 1
PY
refuse from_interrupted 2 "replicate: 'interrupted.h5' holds a relaxation stopped on SIGTERM" \
  --input interrupted.h5 --copies 2,2,2
refuse from_unknown 2 "has the root attribute 'cell_volume', which replicate does not know" \
  --input unknown_attribute.h5 --copies 2,2,2
refuse from_wrong_shift 3 "wrong_shift.h5: /contacts/image_shift: contact .*the image shift does not match" \
  --input wrong_shift.h5 --copies 2,2,2
# An existing output is kept without --overwrite and replaced with it; the input never.
sum=$(md5sum x123.h5)
expect_exit 2 exists "replicate: --output 'x123.h5' exists: give a new file, or --overwrite" \
  "$dem" replicate --input prepared.h5 --output x123.h5 --copies 2,1,1
[ "$(md5sum x123.h5)" = "$sum" ] || { echo "FAIL: exists: x123.h5 was changed"; status=1; }
expect_exit 0 overwrite "wrote x123.h5" "$dem" replicate --input prepared.h5 --output x123.h5 --copies 2,1,1 --overwrite
[ "$(h5dump -a /replicate_copies x123.h5 | sed -n 's/.*(0): "\(.*\)"/\1/p')" = 2,1,1 ] ||
  { echo "FAIL: overwrite: x123.h5 does not hold the 2 x 1 x 1 copies"; status=1; }
sum=$(md5sum prepared.h5)
expect_exit 2 onto_input "replicate: --output './prepared.h5' is the input" \
  "$dem" replicate --input prepared.h5 --output ./prepared.h5 --copies 2,2,2 --overwrite
[ "$(md5sum prepared.h5)" = "$sum" ] || { echo "FAIL: onto_input: prepared.h5 was changed"; status=1; }
# The copies are no state a loading passed through.
expect_exit 2 resume_copies "load --resume: 'x222.h5' was written by aniso-dem replicate" \
  "$dem" load --resume --input x222.h5 --set dem.output_dir=load_x222

[ "$status" = 0 ] && echo "replicate: all checks passed"
exit "$status"
