#!/usr/bin/env bash
# DEMPLA beside aniso on ovoids, at test size: 300 alpha = 0.625 ovoids prepared by aniso in one
# compaction cycle, written as a DEMPLA D-file by dempla_biaxial.sh (START=...), which checks that
# both codes give the same p from the same overlaps (1e-4) and consolidate to the same e (1e-3), then
# loads both to 0.2%. Exit 77 (skipped) without a DEMPLA repository, as dempla_biaxial.sh.
#
# usage: dempla_ovoids.sh BUILD_DIR WORK_DIR DEMPLA_REPO   (DEMPLA_REPO: a path, or - for $DEMPLA_REPO)
set -euo pipefail
build=$(cd "$1" && pwd) work=$2 repo=${3:--}
[ "$repo" = - ] && repo=${DEMPLA_REPO:-}
[ -n "$repo" ] && [ -f "$repo/source/dempla-0.2.5.f" ] ||
  { echo "no DEMPLA repository given (a local copy of github.com/mrkuhn53/dempla, branch master)"; exit 77; }
mkdir -p "$work"
work=$(cd "$work" && pwd)
[ -f "$work/prepared/prepared.h5" ] ||
  "$build/dem/aniso-dem" prepare --set dem.particles.count=300 --set dem.seed=3 --set dem.prepare.cycles=1 \
    --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3 \
    --set dem.prepare.initial_solid_fraction=0.35 --set dem.particles.aspect_ratio=0.625 \
    --set dem.prepare.global_damping=0.05 --set "dem.prepare.cell_aspect=[1,1,1]" \
    --set dem.output_dir="$work/prepared" --log-level warn
START=$work/prepared/prepared.h5 "$(dirname "$0")/dempla_biaxial.sh" "$build" "$work/compare" "$repo" 0.002 \
  dempla_default aniso_default
