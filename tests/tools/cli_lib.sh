# Helpers of the shell tests of bad input and faults; source it after setting `status=0`.

# small_prepared_assembly BUILD FOLDER [SEED]: 200 particles prepared in seconds into FOLDER.
small_prepared_assembly() {
  "$1/dem/aniso-dem" prepare --set dem.particles.count=200 --set dem.seed="${3:-3}" --set dem.prepare.cycles=1 \
    --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 \
    --set dem.prepare.initial_solid_fraction=0.35 --set dem.output_dir="$2" --log-level warn
}

# small_relaxing_load: the array `settings` (--set options) of 200 spheres prepared in one fast
# cycle and loaded to 0.4% with checkpoints at 0.2% and 0.4%, relaxations to 1e-3 verified over
# 2000 steps: the tests of relaxations inside a load.
small_relaxing_load() {
  settings=(--set dem.particles.count=200 --set dem.seed=5 --set dem.prepare.cycles=1
            --set dem.prepare.void_ratio_tolerance=1
            --set dem.equilibrium.tolerance=1e-3 --set dem.equilibrium.verify_steps=2000
            --set dem.prepare.inertial_number=0.05 --set dem.prepare.initial_solid_fraction=0.35
            --set dem.load.final_strain=0.004 --set 'dem.load.checkpoint_strains=[0.002, 0.004]'
            --set dem.load.history_interval=1e-3)
}

# two_cycle_prepare: the array `settings` of 200 spheres prepared in two cycles (the first seizes
# above the target) and one consolidation (the tolerance takes it): the tests of a stopped or
# killed prepare.
two_cycle_prepare() {
  settings=(--set dem.particles.count=200 --set dem.seed=3 --set dem.prepare.cycles=2
            --set dem.prepare.target_void_ratio=0.3 --set dem.prepare.void_ratio_tolerance=1
            --set dem.equilibrium.tolerance=1e-3 --set dem.prepare.initial_solid_fraction=0.35)
}

# small_continuous_load [--set key=value ...]: the array `settings` of 200 spheres prepared in one
# fast cycle and loaded to 5% without relaxed checkpoints (at 0.2% and 5%), history every 0.1%:
# the tests of a stopped or killed load; further arguments are appended.
small_continuous_load() {
  settings=(--set dem.particles.count=200 --set dem.seed=5 --set dem.prepare.cycles=1
            --set dem.prepare.void_ratio_tolerance=1
            --set dem.equilibrium.tolerance=1e-3 --set dem.equilibrium.verify_steps=2000
            --set dem.prepare.inertial_number=0.05 --set dem.prepare.initial_solid_fraction=0.35
            --set dem.equilibrium.at_checkpoints=false
            --set dem.load.final_strain=0.05 --set 'dem.load.checkpoint_strains=[0.002, 0.05]'
            --set dem.load.history_interval=1e-3 "$@")
}

# expect_exit CODE NAME PATTERN COMMAND...: runs COMMAND with its output in NAME.log; unless it
# exits CODE with a line matching PATTERN (grep basic regex), prints the log and sets status=1.
expect_exit() {
  local expected=$1 name=$2 pattern=$3
  shift 3
  set +e
  "$@" >"$name.log" 2>&1
  local code=$?
  set -e
  if [ "$code" != "$expected" ] || ! grep -q -- "$pattern" "$name.log"; then
    echo "FAIL: $name: exit $code (expected $expected) or no '$pattern' in:"
    cat "$name.log"
    status=1
  fi
}

# enter_fresh_folder DIR: empties DIR (made if missing) and makes it the working directory.
enter_fresh_folder() {
  rm -rf "$1"
  mkdir -p "$1"
  cd "$1"
}

# small_checkpoint_and_image BUILD: dem/prepared.h5 (200 particles) and its voxel image
# voxel/image_prepared.h5, in the working directory.
small_checkpoint_and_image() {
  small_prepared_assembly "$1" dem
  "$1/voxel/aniso-voxel" --input dem/prepared.h5 --set voxel.output_dir=voxel --log-level warn
}

# stop_when_logged PATTERN LOG COMMAND...: runs COMMAND in the background (its own pid, not a
# subshell's) with its output in LOG, sends it SIGTERM once LOG matches PATTERN (at once if it has
# ended before), and sets stopped_code to its exit code. 143 is also what the shell reports for a
# death by SIGTERM: the caller tells the two apart by the program's own stop message.
stop_when_logged() {
  local pattern=$1 log=$2
  shift 2
  "$@" >"$log" 2>&1 &
  local pid=$!
  for _ in $(seq 1 1200); do
    grep -q -- "$pattern" "$log" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  kill -TERM "$pid" 2>/dev/null || true # already ended: its exit code tells
  set +e
  wait "$pid"
  stopped_code=$?
  set -e
}

# expect_same_state LABEL A.h5 B.h5: the two checkpoints hold the same particles, contacts and cell
# to the bit (h5diff); otherwise prints the first differences and sets status=1.
expect_same_state() {
  local label=$1 a=$2 b=$3 group
  for group in /particles /contacts /cell; do
    h5diff "$a" "$b" "$group" "$group" >"$b.diff" 2>&1 ||
      { echo "FAIL: $label: $group of $b differs from $a:"; head -5 "$b.diff"; status=1; }
  done
}

# expect_same_history LABEL A B: two loading runs' history.h5 hold the same rows to the bit.
expect_same_history() {
  local label=$1 a=$2 b=$3
  h5diff "$a" "$b" /history /history >"$b.diff" 2>&1 ||
    { echo "FAIL: $label: the history $b differs from $a:"; head -5 "$b.diff"; status=1; }
}

# kill_when_written FILE LOG COMMAND...: starts COMMAND in a process group of its own (output to
# LOG), waits until FILE exists and kills the whole group with SIGKILL, as a lost node would.
# Fails, naming LOG's last lines, when COMMAND ends before FILE appears.
kill_when_written() {
  local file=$1 log=$2
  shift 2
  setsid "$@" >"$log" 2>&1 &
  local group=$!
  until [ -e "$file" ]; do
    kill -0 "$group" 2>/dev/null || { echo "FAIL: '$*' ended before $file was written: $(tail -3 "$log")" >&2; exit 1; }
    sleep 0.02
  done
  kill -KILL -- "-$group"
  wait "$group" 2>/dev/null || true
}
