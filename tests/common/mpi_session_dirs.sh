#!/usr/bin/env bash
# Open MPI singletons' session directories (common/mpi.cpp, own_session_base): every aniso program
# started without a launcher puts Open MPI's session directory under a base of its own in $TMPDIR
# (aniso-mpi-XXXXXX), so that two stages started at once by make -j cannot race on the shared
# <tmp>/ompi.<host>.<uid>/jf.0, and removes it when it ends. Checked: two concurrent preparations
# use two distinct bases while they run and leave $TMPDIR empty; a user's own orte_tmpdir_base
# is used instead; under mpiexec nothing is made.
#
# usage: mpi_session_dirs.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
dem=$build/dem/aniso-dem
fail() {
  echo "mpi_session_dirs: FAIL: $*" >&2
  exit 1
}
rm -rf "$work"
mkdir -p "$work/tmp" "$work/own"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
settings=(--set dem.particles.count=200 --set dem.prepare.cycles=2 --set dem.prepare.void_ratio_tolerance=1
          --set dem.prepare.inertial_number=0.05 --set dem.prepare.initial_solid_fraction=0.35 --log-level warn)

# Two singletons at once: each has its own base while it runs.
TMPDIR=$work/tmp "$dem" prepare "${settings[@]}" --set dem.output_dir="$work/a" &
first=$!
TMPDIR=$work/tmp "$dem" prepare "${settings[@]}" --set dem.output_dir="$work/b" &
second=$!
most=0
while kill -0 "$first" 2>/dev/null || kill -0 "$second" 2>/dev/null; do
  seen=$(find "$work/tmp" -mindepth 3 -maxdepth 3 -path "$work/tmp/aniso-mpi-*/ompi.*/jf.*" | wc -l)
  stray=$(find "$work/tmp" -mindepth 1 -maxdepth 1 ! -name 'aniso-mpi-*' | wc -l)
  [[ $stray -eq 0 ]] || fail "a session directory outside a private base: $(ls "$work/tmp")"
  ((seen > most)) && most=$seen
  sleep 0.1
done
wait "$first" || fail "the first preparation failed"
wait "$second" || fail "the second preparation failed"
[[ $most -eq 2 ]] || fail "expected 2 private session bases at once, saw at most $most"
[[ -z $(ls -A "$work/tmp") ]] || fail "left behind in TMPDIR: $(ls -A "$work/tmp")"

# The user's own base wins.
OMPI_MCA_orte_tmpdir_base=$work/own TMPDIR=$work/tmp "$dem" prepare "${settings[@]}" \
  --set dem.output_dir="$work/c" &
own=$!
used=0
while kill -0 "$own" 2>/dev/null; do
  [[ -z $(ls -A "$work/tmp") ]] || fail "a private base despite OMPI_MCA_orte_tmpdir_base: $(ls -A "$work/tmp")"
  [[ -n $(find "$work/own" -mindepth 2 -maxdepth 2 -path "$work/own/ompi.*/jf.*") ]] && used=1
  sleep 0.1
done
wait "$own" || fail "the preparation with the user's base failed"
[[ $used -eq 1 ]] || fail "OMPI_MCA_orte_tmpdir_base was not used"

# Under mpiexec the launcher's session directory stands: no private base.
TMPDIR=$work/tmp mpiexec --oversubscribe -n 2 "$dem" hold --input "$work/a/prepared.h5" --steps 200 --log-level warn
[[ -z $(ls -A "$work/tmp") ]] || fail "a private base under mpiexec: $(ls -A "$work/tmp")"
echo "mpi_session_dirs: 2 concurrent singletons in 2 private bases, removed at the end; the user's base wins; none under mpiexec"
