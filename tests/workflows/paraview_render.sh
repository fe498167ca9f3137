#!/usr/bin/env bash
# ParaView reads aniso's XDMF output: renders a voxel image of the e2e campaign
# with pvpython, headless (xvfb-run: Debian's ParaView renders through X), and
# checks that the PNG shows the solid (not a blank frame). Also checks that
# h5dump reads every HDF5 file the campaign wrote. Given the build folder, also
# exports the particles and force chains of the last load checkpoint
# (aniso-dem export --format xdmf, docs/formats/particle-xdmf.md) and renders them.
#
# usage: paraview_render.sh SOURCE_DIR RUN_DIR WORK_DIR [BINARY_DIR]
set -euo pipefail
source_dir=$1 run=$2 work=$3 binary_dir=${4:-}
fail() { echo "paraview_render: FAIL: $*" >&2; exit 1; }
for tool in pvpython xvfb-run h5dump; do
  command -v "$tool" > /dev/null || fail "$tool not found: run scripts/install-deps.sh test (python3-paraview, xvfb, hdf5-tools)"
done
rm -rf "$work"
mkdir -p "$work"

count=0
for file in "$run"/*/*.h5; do  # every stage folder of the run
  h5dump -H "$file" > /dev/null || fail "h5dump -H cannot read $file"
  count=$((count + 1))
done
[ "$count" -ge 10 ] || fail "only $count HDF5 files in $run: did the e2e campaign run?"
echo "paraview_render: h5dump -H reads all $count HDF5 files of $run"

# render SCRIPT INPUT.xmf OUTPUT.png: pvpython under xvfb-run, its output in OUTPUT.log.
# xvfb-run can hand pvpython the display before Xvfb accepts connections (about one run in
# three here: "bad X server connection"); only that start-up failure is tried again.
render() {
  local script=$1 input=$2 png=$3 log=${3%.png}.log
  for attempt in 1 2 3 4; do
    xvfb-run -a -s "-screen 0 1024x768x24" pvpython "$source_dir/tests/workflows/$script" "$input" "$png" \
      > "$log" 2>&1 && break
    grep -q "bad X server connection" "$log" && [ "$attempt" -lt 4 ] ||
      fail "pvpython could not render $input: $(grep -m3 -E 'ERR|Error|error' "$log") $(tail -3 "$log")"
    echo "paraview_render: the X server was not ready (attempt $attempt), starting it again"
  done
  grep "$script:" "$log"
}

# not_blank PNG: more than 5% of the pixels differ from the corner's and more than 10 colours.
not_blank() {
  /usr/bin/python3 - "$1" <<'PY' || fail "the rendered PNG $1 is blank"
import sys
import matplotlib.image
import numpy as np
rgb = matplotlib.image.imread(sys.argv[1])[..., :3]
background = rgb[0, 0]
drawn = np.any(np.abs(rgb - background) > 0.05, axis=-1).mean()
colours = len(np.unique((rgb * 255).astype(np.uint8).reshape(-1, 3), axis=0))
print(f"paraview_render: {sys.argv[1]}: {rgb.shape[1]}x{rgb.shape[0]}, {100 * drawn:.1f}% of the pixels drawn, "
      f"{colours} colours")
assert drawn > 0.05 and colours > 10, "blank or flat frame"
PY
}

image=$(ls "$run"/voxel/image_*.xmf | tail -1)
render render_xdmf.py "$image" "$work/render.png"
not_blank "$work/render.png"

if [ -n "$binary_dir" ]; then
  checkpoint=$(ls "$run"/dem/load_[0-9]*.h5 | sort | tail -1)
  xmf="$work/particles_$(basename "$checkpoint" .h5).xmf"
  "$binary_dir/dem/aniso-dem" export --input "$checkpoint" --format xdmf --output "$xmf" > "$work/export.log" 2>&1 ||
    fail "aniso-dem export --format xdmf failed on $checkpoint: $(tail -3 "$work/export.log")"
  [ -s "${xmf%.xmf}.vis.h5" ] || fail "aniso-dem export wrote no ${xmf%.xmf}.vis.h5"
  h5dump -H "${xmf%.xmf}.vis.h5" > /dev/null || fail "h5dump -H cannot read ${xmf%.xmf}.vis.h5"
  render render_particles.py "$xmf" "$work/particles.png"
  not_blank "$work/particles.png"
fi
echo "paraview_render: all checks passed"
