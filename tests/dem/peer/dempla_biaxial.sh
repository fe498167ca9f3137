#!/usr/bin/env bash
# aniso beside DEMPLA, Kuhn's successor of OVAL (the code that made the paper's material), on the
# same assembly. The start is DEMPLA's sample StartFiles/Dsphere_1800 (1800 spheres made
# frictionless), scaled to D50 = 0.17 mm by `aniso-dem import --d50`, or with START=FILE.h5 an aniso
# checkpoint (spheres or ovoids, e.g. a prepared paper-config assembly); `aniso-dem export --format
# dempla` writes it for DEMPLA, so that both codes start from the same positions (and axes). Each
# code consolidates it to p0 = 100 kPa with mu = 0.5 and loads it in biaxial plane strain at
# constant p (x1 shortened, x2 fixed, x3 servoed) to FINAL_STRAIN, with the paper's material
# (G = 29 GPa, nu = 0.15). aniso's ovoids take DEMPLA's Hertz radius (dem.material.hertz_radius =
# mean_semi_axis, a (2 + alpha) / 3) unless HERTZ_RADIUS names another; for spheres every choice is
# the sphere's radius.
#
# Runs (each skipped when its CSV exists, so an interrupted comparison continues):
#   dempla_default   DEMPLA as its samples run: algori 1, strain 1e-6 per step (I = 8.1e-4 in
#                    its mass-scaled time), body damping 3% / 5% of critical on the fluctuating
#                    translation / rotation, no contact damping, Jager's tangential law (imodel 6)
#   dempla_no_body   DEMPLA set as aniso is: no body damping, contact damping pcrit3 = 0.05
#   dempla_no_spin_damping  dempla_default without the body damping of rotation (pcrit2 = 0);
#                    DEMPLA gives every grain the mean mass and a moment of 2.0 m r^2 (iexact 0),
#                    five times a solid sphere's, so its rotational damping torque is about six
#                    times aniso_body's at the same spin
#   aniso_default    aniso's own loading at DEMPLA's inertial number (8.1e-4 on Dsphere_1800: 1e-6 a step
#                    with DEMPLA's scaled mass, which the script reads from DEMPLA's output)
#   aniso_oval       aniso with the paper configs' increments (1e-4, relaxed to 1e-2)
#   aniso_qs         aniso's quasi-static mode (increments of 3e-5, each minimised to 1e-3)
#   dempla_slow      dempla_default at a tenth of the rate (1e-7 a step; I = 8.1e-5 on Dsphere_1800)
#   aniso_slow       aniso_default at a tenth of DEMPLA's inertial number
#   aniso_body       aniso set as DEMPLA is: global damping of the fluctuating motion (0.071 of
#                    aniso's critical = DEMPLA's 0.03 of its own, see docs/validation.md), no
#                    contact damping
#   aniso_body_spin  aniso_body with the spin damped 6 times as fast (global_damping_spin_factor 6): the
#                    damping torque of DEMPLA's samples (moment 5x a sphere's, spin rate 1.18x)
#   aniso_halfwidth  aniso_default with the paper configs' Hertz radius of ovoids (halfwidth: a_i a_j /
#                    (a_i + a_j); the same overlap gives 1.03-1.10 times DEMPLA's force for alpha 0.8-0.5),
#                    from its own consolidation of the same start
#   aniso_body_spin_slow  aniso_body_spin at a tenth of the rate (the damping rate unchanged)
# Every run writes WORK_DIR/results/<run>.csv (strain, q13, q23, p, eps_v, void_ratio,
# coordination); workflows/studies/chart_dem_dempla.py charts them.
#
# usage: dempla_biaxial.sh BUILD_DIR WORK_DIR DEMPLA_REPO [FINAL_STRAIN [RUN...]]
#   DEMPLA_REPO: a local copy of github.com/mrkuhn53/dempla, branch master (source/, StartFiles/),
#   or - for the environment variable DEMPLA_REPO;
#   exit 77 (skipped) without it or without gfortran. FINAL_STRAIN defaults to 0.20 (about 30 min
#   of DEMPLA and 10 min of aniso per run on one core).
set -euo pipefail
build=$(cd "$1" && pwd) work=$2 repo=${3:--} final=${4:-0.20}
[ "$repo" = - ] && repo=${DEMPLA_REPO:-}
shift $(($# < 4 ? $# : 4))
runs=${*:-dempla_default aniso_default aniso_oval dempla_no_body aniso_body}
[ -n "$repo" ] && [ -f "$repo/source/dempla-0.2.5.f" ] ||
  { echo "no DEMPLA repository given (a local copy of github.com/mrkuhn53/dempla, branch master)"; exit 77; }
command -v gfortran >/dev/null || { echo "gfortran not found (apt-get install gfortran)"; exit 77; }
here=$(cd "$(dirname "$0")" && pwd)
dem=$build/dem/aniso-dem
io="/usr/bin/python3 $here/dempla_io.py"
mkdir -p "$work/results"
cd "$work"

# DEMPLA as its reference (shared/reference/dempla.md) builds it, with the list of near pairs
# (mlist2) four times its stock length: without body damping the stock list overflowed at 5.7%
# ("array listf0() is too short"), with it the stock list reached 20%.
if [ ! -x dempla ]; then
  rm -rf dempla-source
  cp -r "$repo/source" dempla-source
  sed -i 's/mlist2=20\*mp\/2,mholes=20\*mp\/2,mconvx=10/mlist2=80*mp\/2,mholes=80*mp\/2,mconvx=10/' \
    dempla-source/param-dempla-0.2.5.f
  grep -q "mlist2=80\*mp" dempla-source/param-dempla-0.2.5.f ||
    { echo "FAIL: could not raise mlist2 in DEMPLA's param-dempla-0.2.5.f"; exit 1; }
  (cd dempla-source && gfortran -std=gnu -O2 -mcmodel=large -w -o ../dempla.new dempla-0.2.5.f)
  mv dempla.new dempla
fi

# The same start for both codes: Dsphere_1800 at D50 = 0.17 mm (its volume median is 1.27, not 1),
# or the given checkpoint through a D-file (what DEMPLA reads is what aniso imports).
hertz=${HERTZ_RADIUS:-mean_semi_axis}
if [ ! -f start.h5 ]; then
  if [ -n "${START:-}" ]; then
    "$dem" export --input "$START" --format dempla --output DGiven --log-level warn
    "$dem" import --format dempla --input DGiven --output start.h5 --set dem.material.hertz_radius="$hertz" \
      >import.log 2>&1
  else
    "$dem" import --format dempla --input "$repo/StartFiles/Dsphere_1800" --d50 0.17e-3 --output start.h5 \
      --set dem.material.hertz_radius="$hertz" >import.log 2>&1
  fi
  "$dem" export --input start.h5 --format dempla --output DStart --log-level warn
fi
[ -f aniso_prepared.h5 ] || "$dem" consolidate --input start.h5 --output aniso_prepared.h5 >consolidate.log 2>&1

dempla_failed() { # DEMPLA stops with status 0 after its own errors: read what it printed
  grep -qE '\*\*\*\* Error|runtime error|too short|Insufficient space|singular|Segmentation|NaN' "$1"
}

# DEMPLA's consolidation, once, with its samples' damping: one step to read the start's stresses,
# a ramp of s11, s22, s33 to -p0 at no more than 25 Pa a step (each at its own rate, arriving
# together), 2000 steps at p0; every DEMPLA loading restarts from its restart file CRcons.
dempla_consolidate() {
  mkdir -p dempla_consolidation
  (
    cd dempla_consolidation
    [ -s CRcons ] && exit 0
    ln -sf ../DStart DStart
    $io runfile Rprobe "seg=111000,0,0,0,0,0,0,0,0,70,1,1,0,0"
    ../dempla <<<$'1\nRprobe\nDStart' >probe.out 2>&1
    dempla_failed probe.out && { echo "FAIL: DEMPLA probe:"; tail probe.out; exit 1; }
    read -r ramp hold < <(/usr/bin/python3 - $($io stresses ARprobe.txt) <<'PY'
import math
import sys
start = [float(v) for v in sys.argv[1:4]]
steps = max(1000, math.ceil(max(abs(-1e5 - s) for s in start) / 25))
rates = ",".join(f"{(-1e5 - s) / steps:.6g}" for s in start)
print(f"111000,0,{rates},0,0,0,0,70,{steps},100,0,0 111000,0,0,0,0,0,0,0,0,70,2000,100,0,0")
PY
    )
    $io runfile Rcons iend=3 "seg=$ramp" "seg=$hold"
    ../dempla <<<$'1\nRcons\nDStart' >cons.out 2>&1
    dempla_failed cons.out && { echo "FAIL: DEMPLA consolidation:"; tail cons.out; exit 1; }
    [ -s CRcons ] || { echo "FAIL: DEMPLA wrote no restart file CRcons"; exit 1; }
  )
  # One step from the consolidated state: the reference mass DEMPLA's loadings start with.
  (
    cd dempla_consolidation
    [ -s mass.out ] && grep -q "reference particle mass" mass.out && exit 0
    $io runfile Rmass istart=3 "seg=111000,0,0,0,0,0,0,0,0,70,1,1,0,0"
    ../dempla <<<$'1\nRmass\nCRcons' >mass.out 2>&1
    grep -q "reference particle mass" mass.out || { echo "FAIL: DEMPLA printed no reference mass:"; tail mass.out; exit 1; }
  )
}

# DEMPLA's loading: F11 at -1e-6 a step, F22 fixed, F33 servoed for constant p (icontr 002000),
# to F11 = 1 - FINAL_STRAIN; strains from the start of loading (idef 1, from the restart file).
dempla_load() { # RUN STRAIN_PER_STEP [KEY=VALUE...]: RunFile settings (pcrit1=0 ...)
  local run=$1 rate=$2
  shift 2
  dempla_consolidate
  mkdir -p "$run"
  (
    cd "$run"
    cp ../dempla_consolidation/CRcons .
    $io runfile Rload "$@" istart=3 idef=1 \
      "seg=002000,0,-$rate,0,0,0,0,0,0,10,$(/usr/bin/python3 -c "print(1 - $final)"),100,0,0"
    start=$SECONDS
    ../dempla <<<$'1\nRload\nCRcons' >load.out 2>&1
    dempla_failed load.out && { echo "FAIL: DEMPLA loading:"; tail load.out; exit 1; }
    echo $((SECONDS - start)) >wall.txt
    $io history ARload.txt "../results/$run.csv"
  )
}

# DEMPLA's inertial number at STRAIN_PER_STEP: its automatic mass scaling gives every grain the
# reference mass it prints (time unit one step; it grows with the contact stiffness, so it is read
# at the consolidated state), i.e. a density of that mass over the mean grain volume;
# I = rate d50 sqrt(rho / p0) with aniso's D50 and grain volumes of the same start.
dempla_inertial_number() { # STRAIN_PER_STEP
  /usr/bin/python3 - "$1" "$(grep -m1 "reference particle mass" dempla_consolidation/mass.out | awk '{print $NF}')" \
    <<'PY'
import sys
import h5py
import numpy as np
rate, mass = float(sys.argv[1]), float(sys.argv[2])
with h5py.File("start.h5", "r") as f:
    d = np.sort(f["particles/diameter"][:])
    volume = (f["particles/mass"][:] / f["parameters"].attrs["density"]).mean()
cumulative = np.cumsum(d**3)
d50 = d[np.searchsorted(cumulative, 0.5 * cumulative[-1])]
print(f"{rate * d50 * np.sqrt(mass / volume / 1e5):.2g}")
PY
}

# aniso's loading from its own consolidation of the same start, as a CSV of the same columns.
aniso_load() { # RUN SETTINGS... (PREPARED=file overrides aniso_prepared.h5)
  local run=$1
  shift
  local settings=()
  for s in "$@"; do settings+=(--set "$s"); done
  local start=$SECONDS
  "$dem" load --input "${PREPARED:-aniso_prepared.h5}" --set dem.output_dir="$run" --set dem.load.final_strain="$final" \
    --set dem.load.checkpoint_strains="[$final]" --set dem.equilibrium.at_checkpoints=false \
    --set dem.load.history_interval=5e-4 "${settings[@]}" --overwrite >"$run.log" 2>&1
  echo $((SECONDS - start)) >"$run/wall.txt"
  $io aniso "$run/history.csv" "results/$run.csv"
}

# The same start and the same consolidation: the codes' Hertz laws and geometry agree.
dempla_consolidate
$io agreement .
fast=$(dempla_inertial_number 1e-6) slow=$(dempla_inertial_number 1e-7)
echo "DEMPLA's inertial number: $fast at 1e-6 a step, $slow at 1e-7"

for run in $runs; do
  [ -s "results/$run.csv" ] && { echo "$run: done before (results/$run.csv)"; continue; }
  echo "$run: running to strain $final"
  case $run in
    dempla_default) dempla_load "$run" 1e-6 ;;
    dempla_no_body) dempla_load "$run" 1e-6 pcrit1=0. pcrit2=0. pcrit3=0.05 ;;
    dempla_no_spin_damping) dempla_load "$run" 1e-6 pcrit2=0. ;;
    dempla_slow) dempla_load "$run" 1e-7 ;;
    aniso_default) aniso_load "$run" dem.load.inertial_number="$fast" ;;
    aniso_halfwidth)
      if [ ! -f aniso_prepared_halfwidth.h5 ]; then
        "$dem" import --format dempla --input DStart --output start_halfwidth.h5 \
          --set dem.material.hertz_radius=halfwidth >import_halfwidth.log 2>&1
        "$dem" consolidate --input start_halfwidth.h5 --output aniso_prepared_halfwidth.h5 \
          >consolidate_halfwidth.log 2>&1
      fi
      PREPARED=aniso_prepared_halfwidth.h5 aniso_load "$run" dem.load.inertial_number="$fast" ;;
    aniso_slow) aniso_load "$run" dem.load.inertial_number="$slow" ;;
    aniso_qs) aniso_load "$run" dem.load.quasi_static=true dem.load.increment=3e-5 dem.load.increment_tolerance=1e-3 ;;
    aniso_oval) aniso_load "$run" dem.load.increment=1e-4 dem.load.increment_tolerance=1e-2 ;;
    aniso_body) aniso_load "$run" dem.load.inertial_number="$fast" dem.integration.global_damping=0.071 \
      dem.integration.damping=0 ;;
    aniso_body_spin) aniso_load "$run" dem.load.inertial_number="$fast" dem.integration.global_damping=0.071 \
      dem.integration.global_damping_spin_factor=6 dem.integration.damping=0 ;;
    aniso_body_spin_slow) aniso_load "$run" dem.load.inertial_number="$slow" dem.integration.global_damping=0.071 \
      dem.integration.global_damping_spin_factor=6 dem.integration.damping=0 ;;
    *) echo "unknown run '$run'"; exit 2 ;;
  esac
done
echo "dempla_biaxial: results in $work/results"
