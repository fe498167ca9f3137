#!/usr/bin/env bash
# A write that fails part-way (disk full, quota, file-size limit) ends with exit 3 and the file
# named, leaves no temporary behind and keeps the file written before under the same name.
# The failure is made with a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored so that write()
# returns EFBIG), which fails every write past the limit as a full disk does.
#
# usage: disk_full.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
settings=(--set dem.particles.count=200 --set dem.seed=3 --set dem.prepare.cycles=1
          --set dem.prepare.void_ratio_tolerance=1 --set dem.equilibrium.tolerance=1e-3
          --set dem.prepare.initial_solid_fraction=0.35 --set dem.output_dir="$work/dem")
"$build/dem/aniso-dem" prepare "${settings[@]}" --log-level warn
before=$(md5sum <"$work/dem/prepared.h5")
status=0

# Runs a command under a 60 KiB file-size limit; expects exit 3 and a message naming the file.
expect_write_failure() {
  local what=$1 pattern=$2
  shift 2
  set +e
  (trap '' XFSZ; ulimit -f 60; "$@") >"$work/$what.log" 2>&1
  local code=$?
  set -e
  if [ "$code" != 3 ]; then
    echo "FAIL: $what under a full disk ended with exit $code, expected 3 (file error)"
    cat "$work/$what.log"
    status=1
  elif ! grep -q "error (file error): .*$pattern.*write failed" "$work/$what.log"; then
    echo "FAIL: $what: no file error naming $pattern"
    cat "$work/$what.log"
    status=1
  fi
}

# prepare's first write is the piece it keeps for a resume (prepare_seized_1_0.h5).
expect_write_failure dem "prepare_seized_1_0.h5" "$build/dem/aniso-dem" prepare "${settings[@]}" --log-level warn
expect_write_failure voxel image_prepared.h5 "$build/voxel/aniso-voxel" --input "$work/dem/prepared.h5" \
  --set voxel.output_dir="$work/voxel" --log-level warn

leftover=$(find "$work" -name '.*.tmp-*')
if [ -n "$leftover" ]; then
  echo "FAIL: temporaries left behind: $leftover"
  status=1
fi
if [ "$(md5sum <"$work/dem/prepared.h5")" != "$before" ]; then
  echo "FAIL: the prepared.h5 written before the failure changed"
  status=1
fi
[ "$status" = 0 ] && echo "disk full: exit 3 with the file named, no temporary left, earlier file intact"
exit "$status"
