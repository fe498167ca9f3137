#!/usr/bin/env bash
# Two checks of `aniso-dem load` through the executable, on one small run:
# 1. A load whose checkpoints are not relaxed (equilibrium.at_checkpoints = false) logs,
#    at each checkpoint, the unbalanced-force ratio stored in that file (the log once printed
#    the last relaxation's ratio instead: a stale 8.75e-5 beside a state at 3.8e-2).
# 2. `load --resume` with a loading setting that differs from the checkpoint's (which the
#    resumed run would silently ignore) stops with exit 2 naming the key, and leaves the
#    files already written untouched.
# 3. A fresh load applies the configured time step (it once kept the prepared file's).
# 4. A run resumed under another default time step is refused, and resumes when given back
#    the stored step exactly as the refusal prints it (a run begun before the defaults changed).
# 5. A mean stress of 1e-300 Pa (a rate of 1e-151 /s) is refused before anything runs, where
#    it once ran forever; an inertial number of 0.9 runs with a warning that it is not
#    quasi-static.
# 6. Keys that the checkpoint fixes (particle count, shear modulus, explosion overlap, ...) given
#    with other values are refused naming each; the values used are the file's, and provenance
#    records them (it once recorded the configured 500 particles for a 200-particle file).
#
# usage: load_cli_checks.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
settings=(--set dem.particles.count=200 --set dem.seed=5 --set dem.prepare.cycles=1
          --set dem.prepare.void_ratio_tolerance=1
          --set dem.equilibrium.tolerance=1e-3 --set dem.equilibrium.verify_steps=2000
          --set dem.prepare.inertial_number=0.05 --set dem.prepare.initial_solid_fraction=0.35
          --set dem.load.final_strain=0.002 --set 'dem.load.checkpoint_strains=[0.001, 0.002]'
          --set dem.load.history_interval=2e-4 --set dem.output_dir="$work"
          --set dem.integration.time_step_fraction=0.2 --set dem.integration.control_interval=10)
"$build/dem/aniso-dem" prepare "${settings[@]}" --log-level warn
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false \
  --input "$work/prepared.h5" > "$work/load.log" 2>&1

# The stored attribute, printed as the log prints it (%.2e).
stored_ratio() {
  h5dump -a /unbalanced_force_ratio "$1" | awk '/\(0\):/ { printf "%.2e\n", $2 }'
}
status=0
prepared=$(stored_ratio "$work/prepared.h5")
for index in 000 001; do
  file="$work/load_$index.h5"
  logged=$(grep "checkpoint .*load_$index.h5" "$work/load.log" |
           sed -n 's/.*unbalanced-force ratio \([^,]*\),.*/\1/p')
  stored=$(stored_ratio "$file")
  if [ -z "$logged" ] || [ -z "$stored" ]; then
    echo "FAIL: load_$index.h5: logged ratio '$logged', stored '$stored'"; status=1
  elif [ "$logged" != "$stored" ]; then
    echo "FAIL: load_$index.h5: the log says $logged, the file stores $stored"; status=1
  elif [ "$logged" = "$prepared" ]; then
    echo "FAIL: load_$index.h5: ratio $logged equals the prepared state's: the check cannot tell stale from fresh"
    status=1
  else
    echo "load_$index.h5: logged $logged = stored $stored (prepared state: $prepared)"
  fi
done

# 2. Resume from checkpoint 0 at another rate: refused, nothing rewritten.
before=$(cd "$work" && md5sum load_001.h5 history.h5)
set +e
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false \
  --set dem.load.inertial_number=1e-4 --input "$work/load_000.h5" --resume > "$work/resume.log" 2>&1
code=$?
set -e
after=$(cd "$work" && md5sum load_001.h5 history.h5)
if [ $code != 2 ]; then
  echo "FAIL: resume at another rate exited $code, expected 2:"; tail -3 "$work/resume.log"; status=1
elif ! grep -q "dem.load.inertial_number = 0.0001, the checkpoint's loading has 0.001" "$work/resume.log"; then
  echo "FAIL: the refusal does not name the rate:"; tail -3 "$work/resume.log"; status=1
elif [ "$before" != "$after" ]; then
  echo "FAIL: the refused resume changed files already written"; status=1
else
  echo "resume at another rate: exit 2, rate named, files untouched"
fi

# 3. A fresh load at 0.4 of the Rayleigh step runs at twice the prepared step (0.2).
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false \
  --set dem.output_dir="$work/step" --set dem.integration.time_step_fraction=0.4 \
  --set dem.integration.control_interval=5 --input "$work/prepared.h5" --log-level warn
step_of() { h5dump -a /time_step "$1" | awk '/\(0\):/ { print $2 }'; }
ratio=$(awk -v a="$(step_of "$work/step/load_000.h5")" -v b="$(step_of "$work/prepared.h5")" 'BEGIN { print a / b }')
if awk -v r="$ratio" 'BEGIN { exit !(r > 1.9999 && r < 2.0001) }'; then
  echo "fresh load at 0.4 t_R: time step ratio $ratio to the prepared 0.2 t_R"
else
  echo "FAIL: fresh load at 0.4 t_R ran at $ratio times the prepared step, expected 2"; status=1
fi
# 4. The 0.4 t_R run resumed with the configured 0.2: refused, naming the stored step; resumed
#    with that step (and interval) given back, it ends where it ended before.
set +e
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false \
  --set dem.output_dir="$work/step" --input "$work/step/load_000.h5" --resume > "$work/step/resume.log" 2>&1
code=$?
set -e
stored=$(sed -n 's/.*a time step of \([0-9.e+-]*\) s.*/\1/p' "$work/step/resume.log")
if [ $code != 2 ] || [ -z "$stored" ]; then
  echo "FAIL: resume at another time step exited $code, stored step '$stored':"; tail -3 "$work/step/resume.log"
  status=1
else
  cp "$work/step/load_001.h5" "$work/step/uninterrupted_001.h5"
  "$build/dem/aniso-dem" load "${settings[@]}" --set dem.equilibrium.at_checkpoints=false \
    --set dem.output_dir="$work/step" --set dem.integration.time_step="$stored" \
    --set dem.integration.control_interval=5 --input "$work/step/load_000.h5" --resume --log-level warn
  same=1
  for group in /particles /contacts /cell; do
    h5diff "$work/step/uninterrupted_001.h5" "$work/step/load_001.h5" "$group" "$group" > /dev/null || same=0
  done
  if [ $same = 1 ]; then
    echo "resume with the stored step $stored s given back: the same final checkpoint (h5diff)"
  else
    echo "FAIL: resumed with the stored step $stored s, the final checkpoint differs"; status=1
  fi
fi
# 5. Loadings that would never end are refused; a non-quasi-static one is warned about.
set +e
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.output_dir="$work/tiny" --set dem.load.mean_stress=1e-300 \
  --input "$work/prepared.h5" > "$work/tiny.log" 2>&1
code=$?
set -e
if [ $code != 2 ] || ! grep -q "takes .* steps (more than 1e+09)" "$work/tiny.log" || [ -e "$work/tiny/history.h5" ]; then
  echo "FAIL: a load at 1e-300 Pa exited $code:"; tail -3 "$work/tiny.log"; status=1
else
  echo "load at 1e-300 Pa: refused with exit 2 before running"
fi
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.output_dir="$work/fast" --set dem.load.inertial_number=0.9 \
  --set dem.load.final_strain=0.001 --set 'dem.load.checkpoint_strains=[0.001]' --input "$work/prepared.h5" \
  > "$work/fast.log" 2>&1
if ! grep -q "warning dem.load.inertial_number = 0.9 is above 0.01: the loading is not quasi-static" "$work/fast.log"; then
  echo "FAIL: no warning for an inertial number of 0.9:"; tail -3 "$work/fast.log"; status=1
else
  echo "load at I = 0.9: warned that it is not quasi-static"
fi
# 6. Keys fixed by the checkpoint.
set +e
"$build/dem/aniso-dem" load "${settings[@]}" --set dem.output_dir="$work/fixed" --set dem.particles.count=500 \
  --set dem.material.shear_modulus=1e9 --set dem.integration.explosion_overlap=0.1 --input "$work/prepared.h5" \
  > "$work/fixed.log" 2>&1
code=$?
set -e
if [ $code != 2 ] || ! grep -q "dem.particles.count = 500, the checkpoint has 200 particles" "$work/fixed.log" ||
   ! grep -q "dem.material.shear_modulus = 1e+09 Pa, the checkpoint has 2.9e+10 Pa" "$work/fixed.log" ||
   ! grep -q "dem.integration.explosion_overlap = 0.1, the checkpoint has 0.05" "$work/fixed.log"; then
  echo "FAIL: keys fixed by the checkpoint, given other values: exit $code:"; cat "$work/fixed.log"; status=1
else
  echo "keys fixed by the checkpoint: refused with exit 2, each named"
fi
recorded=$(h5dump -a /provenance/config "$work/load_000.h5")
if ! grep -q "count = 200  # from the input checkpoint" <<<"$recorded"; then
  echo "FAIL: provenance does not record the checkpoint's particle count"; status=1
fi
exit $status
