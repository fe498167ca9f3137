#!/bin/bash
# DEM at scale (issue 47, item 4): one prepared assembly tiled by `aniso-dem replicate` into larger
# cells, and at each size, on each rank count: the memory (largest resident set of any rank), the
# particle-steps per second per core of a fixed-cell hold (`aniso-dem hold`, its own timing of the
# step loop: force pass, integration, list updates, halo and control sums; its "other" time, the
# start-up from the read checkpoint, left out), the
# checkpoint's size and its read (a hold of 1 step, start-up included) and read-and-write time
# (`replicate --copies 1,1,1`), and the fabric and voxel stages' wall time and memory. The copies are
# one assembly repeated (docs/user-guide.md, "A larger cell from copies of a checkpoint"), static,
# so every size integrates the same state per particle.
#
# usage: run.sh PREPARED.h5 [WORK=/tmp/aniso-dem-scale]
# environment: ANISO_BUILD (default /work/build), COPIES (default "1,1,1 2,2,2 4,4,4 6,5,5"),
#   RANKS (default "1 2"), STEPS (default 500), REPEATS (default 3), VOXEL_MAX (largest particle
#   count voxelized, default 500000), VOXEL_RESOLUTION (voxels per d50, default 20)
# Prints a Markdown table; the raw numbers are in WORK/results.csv, from which project.py projects
# the weak scaling to many ranks. Quote it with the machine, the
# date and the load average it prints.
set -euo pipefail
prepared=${1:?usage: run.sh PREPARED.h5 [WORK]}
work=${2:-/tmp/aniso-dem-scale}
build=${ANISO_BUILD:-/work/build}
copies_list=${COPIES:-"1,1,1 2,2,2 4,4,4 6,5,5"}
ranks_list=${RANKS:-"1 2"}
steps=${STEPS:-500}
repeats=${REPEATS:-3}
voxel_max=${VOXEL_MAX:-500000}
resolution=${VOXEL_RESOLUTION:-20}
dem=$build/dem/aniso-dem
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
[ -f "$prepared" ] || { echo "run.sh: no checkpoint $prepared" >&2; exit 2; }
for binary in "$dem" "$build/fabric/aniso-fabric" "$build/voxel/aniso-voxel"; do
  [ -x "$binary" ] || { echo "run.sh: $binary is missing: build it first" >&2; exit 2; }
done
mkdir -p "$work"
results=$work/results.csv
echo "particles,copies,ranks,measure,value" >"$results"
record() { echo "$1,${2//,/x},$3,$4,$5" >>"$results"; }
# wall seconds and the largest RSS [kB] of any rank of a command, from /usr/bin/time on each rank
timed() {
  local ranks=$1 tag=$2
  shift 2
  rm -f "$work/$tag.time".*
  # each rank writes its own file (OMPI_COMM_WORLD_RANK), so that their lines cannot interleave
  mpirun --oversubscribe -np "$ranks" sh -c 'exec /usr/bin/time -f "rss_kb %M wall %e" -o "$0.$OMPI_COMM_WORLD_RANK" "$@"' \
    "$work/$tag.time" "$@" >"$work/$tag.log" 2>&1 || { echo "run.sh: '$*' failed; see $work/$tag.log" >&2; exit 1; }
  cat "$work/$tag.time".* | awk '/^rss_kb/ { if ($2 > rss) rss = $2; if ($4 > wall) wall = $4 } END { print wall, rss }'
}
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); $(lscpu | sed -n 's/^Model name: *//p'); $(date -u +%FT%TZ)"
for copies in $copies_list; do
  file=$work/tiled_${copies//,/x}.h5
  [ -s "$file" ] || "$dem" replicate --input "$prepared" --output "$file" --copies "$copies" --log-level warn
  n=$(h5dump -H -d /particles/diameter "$file" | sed -n 's/.*SIMPLE { ( \([0-9]*\) ).*/\1/p')
  record "$n" "$copies" 1 file_bytes "$(stat -c %s "$file")"
  read -r wall rss < <(timed 1 "read_$n" "$dem" hold --input "$file" --steps 1 --log-level warn)
  record "$n" "$copies" 1 read_s "$wall"
  read -r wall rss < <(timed 1 "io_$n" "$dem" replicate --input "$file" --output "$work/io.h5" --copies 1,1,1 \
    --overwrite --log-level warn)
  record "$n" "$copies" 1 read_write_s "$wall"
  for ranks in $ranks_list; do
    for ((r = 1; r <= repeats; ++r)); do
      read -r wall rss < <(timed "$ranks" "hold_${n}_${ranks}_$r" "$dem" hold --input "$file" --steps "$steps")
      # the step loop: the hold's wall time less its "other" (the start-up from the read checkpoint)
      loop=$(awk '/info timing:/ { wall = $4 } /info   other / { other = $5 } END { print wall - other }' \
        "$work/hold_${n}_${ranks}_$r.log")
      record "$n" "$copies" "$ranks" hold_loop_s "$loop"
      # the halo exchange's share (the timing table's max over ranks): the time in MPI of a step
      halo=$(awk '/info   halo / { print $5; exit }' "$work/hold_${n}_${ranks}_$r.log")
      record "$n" "$copies" "$ranks" halo_s "$halo"
      # the halo volume: ghosts per rank, from the line under the timing table (none on 1 rank)
      ghosts=$(sed -n 's/.*halo: \([0-9]*\) ghosts per rank.*/\1/p' "$work/hold_${n}_${ranks}_$r.log")
      [ -z "$ghosts" ] || record "$n" "$copies" "$ranks" ghosts_per_rank "$ghosts"
      record "$n" "$copies" "$ranks" rss_kb "$rss"
    done
  done
  read -r wall rss < <(timed 1 "fabric_$n" "$build/fabric/aniso-fabric" --input "$file" \
    --set "fabric.output_dir='$work/fabric_$n'" --log-level warn)
  record "$n" "$copies" 1 fabric_s "$wall"
  record "$n" "$copies" 1 fabric_rss_kb "$rss"
  if [ "$n" -le "$voxel_max" ]; then
    read -r wall rss < <(timed 1 "voxel_$n" "$build/voxel/aniso-voxel" --input "$file" \
      --set "voxel.output_dir='$work/voxel_$n'" --set voxel.resolution="$resolution" --set voxel.write_image=false \
      --set voxel.threads=1 --log-level warn)
    record "$n" "$copies" 1 voxel_s "$wall"
    record "$n" "$copies" 1 voxel_rss_kb "$rss"
  fi
  rm -f "$work/io.h5"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$results" "$steps" <<'PY'
import collections, csv, statistics, sys
steps = int(sys.argv[2])
values = collections.defaultdict(list)
for row in csv.DictReader(open(sys.argv[1])):
    values[(int(row["particles"]), int(row["ranks"]), row["measure"])].append(float(row["value"]))
sizes = sorted({n for n, _, _ in values})
ranks = sorted({r for _, r, m in values if m == "hold_loop_s"})
base = {r: None for r in ranks}
print("| particles | file [MB] | read [s] | read+write [s] | "
      + " | ".join(f"{r} rank(s): particle-steps/s/core (vs smallest; halo share) | RSS/rank [MB] (B/particle)"
                 for r in ranks)
      + " | fabric [s] | voxel [s] (RSS MB) |")
print("|" + " --- |" * (6 + 2 * len(ranks)))
for n in sizes:
    cells = [f"{n}", f"{values[(n, 1, 'file_bytes')][0] / 1e6:.1f}", f"{values[(n, 1, 'read_s')][0]:.2f}",
             f"{values[(n, 1, 'read_write_s')][0]:.2f}"]
    for r in ranks:
        rate = n * steps / statistics.median(values[(n, r, "hold_loop_s")]) / r
        base[r] = base[r] or rate
        rss = max(values[(n, r, "rss_kb")]) / 1e3
        halo = statistics.median(values[(n, r, "halo_s")]) / statistics.median(values[(n, r, "hold_loop_s")])
        cells += [f"{rate:.3g} ({rate / base[r]:.2f}; halo {100 * halo:.0f}%)", f"{rss:.0f} ({rss * 1e6 * r / n:.0f})"]
    cells.append(f"{values[(n, 1, 'fabric_s')][0]:.2f}")
    voxel = values.get((n, 1, "voxel_s"))
    cells.append(f"{voxel[0]:.1f} ({values[(n, 1, 'voxel_rss_kb')][0] / 1e3:.0f})" if voxel else "not run")
    print("| " + " | ".join(cells) + " |")
PY
