#!/bin/bash
# Command-line checks of aniso-fabric on synthetic inputs (tests/fabric/write_inputs.cpp):
#   series on 1 and 2 ranks gives identical results files; correlations equal numpy's;
#   a checkpoint without /contacts/force is refused with exit 3 naming the file and dataset,
#   and the results file already there is left untouched; a linked result from a checkpoint
#   outside the series is refused naming that file; too few checkpoints and clashing names are
#   refused as bad input.
# usage: cli_checks.sh WRITE_INPUTS ANISO_FABRIC SOURCE_DIR WORK_DIR
set -u
write_inputs=$1 fabric=$2 source=$3 work=$4
mpiexec=${MPIEXEC:-mpiexec}
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"$write_inputs" in || fail "write_inputs"
linked=(--probe in/probe_*.h5 --permeability in/permeability_*.h5 --voids in/voids_*.h5)
"$fabric" series --input in/load_*.h5 "${linked[@]}" --output np1/fabric_series.h5 > np1.log 2>&1 \
  || { cat np1.log; fail "series on 1 rank"; }
"$mpiexec" --oversubscribe -n 2 "$fabric" series --input in/load_*.h5 "${linked[@]}" \
  --output np2/fabric_series.h5 > np2.log 2>&1 || { cat np2.log; fail "series on 2 ranks"; }
h5diff --exclude-path /provenance np1/fabric_series.h5 np2/fabric_series.h5 || fail "1 and 2 ranks differ (HDF5)"
cmp np1/fabric_series.csv np2/fabric_series.csv || fail "1 and 2 ranks differ (series CSV)"
cmp np1/fabric_series_correlations.csv np2/fabric_series_correlations.csv || fail "1 and 2 ranks differ (correlations)"
/usr/bin/python3 "$source/check_series.py" in np1 || fail "correlations differ from numpy's"

# Missing contact dataset: clear error, exit 3, the earlier results file survives.
"$fabric" --input in/load_000.h5 --output keep/fabric.h5 > keep.log 2>&1 || { cat keep.log; fail "single checkpoint"; }
before=$(md5sum keep/fabric.h5 keep/fabric.csv)
"$fabric" --input in/load_000.h5 in/broken.h5 --output keep/fabric.h5 > broken.log 2>&1
code=$?
cat broken.log
[ $code -eq 3 ] || fail "broken checkpoint: exit $code, expected 3 (file error)"
grep -q "broken.h5" broken.log && grep -q "contacts/force" broken.log || fail "message does not name the file and dataset"
[ "$before" == "$(md5sum keep/fabric.h5 keep/fabric.csv)" ] || fail "the earlier results were changed"

# A probe result of a checkpoint that is not in the series.
"$fabric" series --input in/load_000.h5 in/load_001.h5 in/load_002.h5 --probe in/probe_load_005.h5 \
  --output stray/fabric_series.h5 > stray.log 2>&1
code=$?
[ $code -eq 3 ] || { cat stray.log; fail "stray probe: exit $code, expected 3"; }
grep -q "probe_load_005.h5" stray.log || fail "stray probe message does not name the file"
[ ! -e stray/fabric_series.h5 ] || fail "a results file was written despite the error"
# Too few checkpoints for a correlation, and two inputs with one name: bad input (exit 2).
"$fabric" series --input in/load_000.h5 in/load_001.h5 > few.log 2>&1
code=$?
[ $code -eq 2 ] && grep -q "at least 3 checkpoints" few.log || { cat few.log; fail "series of 2: exit $code"; }
mkdir -p copy && cp in/load_000.h5 copy/
"$fabric" --input in/load_000.h5 copy/load_000.h5 --output same/fabric.h5 > same.log 2>&1
code=$?
[ $code -eq 2 ] && grep -q "share the name 'load_000'" same.log || { cat same.log; fail "same stems: exit $code"; }
echo "all fabric command-line checks passed"
