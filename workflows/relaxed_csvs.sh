#!/bin/bash
# Issue 21, section 4: the committed CSVs of a shape's relaxed checkpoints, from what
# workflows/relax_and_probe.sh has finished so far: the fabric series of the relaxed checkpoints with
# their probe results (aniso-fabric series) and each probe's CSV. Rerun as more checkpoints finish.
# usage: workflows/relaxed_csvs.sh SHAPE   (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)
#   reads runs/paper-SHAPE/relaxed/, writes docs/paper-size/<folder>/relaxed/{fabric_series*.csv,probes/}
#   (<folder>: spheres or ovoids-0.8 ...); BIN=<build dir> (default build)
set -euo pipefail
cd "$(dirname "$0")/.."  # the repository root
shape=${1:?usage: workflows/relaxed_csvs.sh SHAPE (spheres, ovoids-0.8, ovoids-0.625, ovoids-0.5)}
relaxed=runs/paper-$shape/relaxed
config=workflows/configs/paper-$shape.toml
out=docs/paper-size/$shape/relaxed
bin=${BIN:-build}
[ -f "$config" ] || { echo "relaxed_csvs.sh: no config $config" >&2; exit 2; }
compgen -G "$relaxed/load_0*.h5" > /dev/null ||
  { echo "relaxed_csvs.sh: no relaxed checkpoints $relaxed/load_0*.h5 (run workflows/relax_and_probe.sh $shape)" >&2; exit 2; }
compgen -G "$relaxed/probe_load_0*.h5" > /dev/null || { echo "relaxed_csvs.sh: no probe results in $relaxed" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/fabric/aniso-fabric" series --config "$config" --input "$relaxed"/load_0*.h5 \
  --probe "$relaxed"/probe_load_0*.h5 --output "$work/fabric_series.h5" --log-level warn
mkdir -p "$out/probes"
cp "$work/fabric_series.csv" "$work/fabric_series_correlations.csv" "$out/"
cp "$relaxed"/probe_load_0*.csv "$out/probes/"
echo "relaxed_csvs.sh: $(ls "$relaxed"/load_0*.h5 | wc -l) relaxed checkpoints, $(ls "$out"/probes/*.csv | wc -l) probes -> $out"
