#!/bin/bash
# The preparation as a lever of its own (issue 45, item 4; docs/methods/dem.md, "The preparation
# study"): assemblies of the same void ratio made in different ways, each then loaded the same way.
# Every variant is its config (the paper's, at COUNT particles, default 1000) with the settings it
# names, prepared with `aniso-dem prepare` and loaded with the config's own loading (the paper
# configs: the oval behaviour) to FINAL strain without checkpoints. A variant whose prepare stops
# with exit 5 (its e missed the target band) is recorded as failed and the study goes on.
#
# usage: workflows/preparation_study.sh BUILD WORK FINAL NAME=CONFIG[:KEY=VALUE[,KEY=VALUE...]] ...
#   e.g. spheres_mu0=configs/paper-spheres.toml:dem.material.friction_prepare=0,dem.prepare.compaction_stop_void_ratio=0.57
# Writes WORK/NAME/prepare/ (prepared.h5, log), WORK/NAME/load/ (history.h5, log) and
# WORK/NAME/wall.txt (seconds to prepare, to load); a stage whose output exists is skipped, so a
# killed study continues where it stopped. Then summarise with plots/chart_preparation_study.py WORK.
set -euo pipefail
build=$(cd "$1" && pwd) work=$2 final=$3
shift 3
count=${COUNT:-1000}
mkdir -p "$work"
for variant in "$@"; do
  name=${variant%%=*} spec=${variant#*=}
  config=${spec%%:*} settings=()
  if [ "$spec" != "$config" ]; then
    IFS=, read -r -a pairs <<<"${spec#*:}"
    for pair in "${pairs[@]}"; do settings+=(--set "$pair"); done
  fi
  run=$work/$name
  mkdir -p "$run"
  printf '%s\n' "$config" "${settings[@]}" >"$run/variant.txt"
  if [ -e "$run/failed.txt" ]; then
    echo "$name: failed before ($(cat "$run/failed.txt"))"
    continue
  fi
  if [ ! -s "$run/prepare/prepared.h5" ]; then
    echo "$name: preparing ($(uptime | sed 's/.*load/load/'))"
    start=$SECONDS rc=0
    resume=()
    ls "$run"/prepare/prepare_*.h5 >/dev/null 2>&1 && resume=(--resume)
    "$build/dem/aniso-dem" prepare --config "$config" --set dem.particles.count="$count" "${settings[@]}" \
      --set dem.output_dir="$run/prepare" "${resume[@]}" >"$run/prepare.log" 2>&1 || rc=$?
    echo "prepare $((SECONDS - start))" >"$run/wall.txt"
    if [ $rc -eq 5 ]; then
      echo "prepare exit 5: the target band missed, see prepare.log" >"$run/failed.txt"
      echo "$name: $(cat "$run/failed.txt")"
      continue
    fi
    [ $rc -eq 0 ] || { echo "$name: prepare failed with exit $rc (see $run/prepare.log)"; exit $rc; }
  fi
  if [ ! -s "$run/load/history.h5" ] || [ ! -e "$run/load.done" ]; then
    echo "$name: loading to $final ($(uptime | sed 's/.*load/load/'))"
    start=$SECONDS
    "$build/dem/aniso-dem" load --config "$config" --input "$run/prepare/prepared.h5" \
      --set dem.particles.count="$count" --set dem.output_dir="$run/load" --set dem.load.final_strain="$final" \
      --set "dem.load.checkpoint_strains=[]" --set dem.load.history_interval=5e-4 \
      --set dem.equilibrium.at_checkpoints=false --set dem.equilibrium.fork_checkpoints=false \
      --overwrite >"$run/load.log" 2>&1
    echo "load $((SECONDS - start))" >>"$run/wall.txt"
    touch "$run/load.done"
  fi
done
