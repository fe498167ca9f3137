#!/usr/bin/env bash
# Test fixture: prepares tests/probe/tiny.toml's assembly (isotropic, prepared.h5) and
# loads it to 1% strain along x1 (load_000.h5), in WORK_DIR. Seconds on one core.
#
# usage: make_assembly.sh BUILD_DIR CONFIG WORK_DIR
set -euo pipefail
build=$1 config=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
"$build/dem/aniso-dem" prepare --config "$config" --set dem.output_dir="$work" --log-level warn
"$build/dem/aniso-dem" load --config "$config" --set dem.output_dir="$work" --input "$work/prepared.h5" \
  --log-level warn
test -f "$work/load_000.h5"
