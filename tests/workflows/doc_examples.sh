#!/usr/bin/env bash
# The Python examples of docs/formats/ ("Reading it elsewhere") run as written against files the
# programs wrote: one was left reading a parameter name that does not exist.
#
# usage: doc_examples.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source "$1/tests/tools/cli_lib.sh"
docs=$1/docs/formats build=$2
enter_fresh_folder "$3"
small_prepared_assembly "$build" dem
cp dem/prepared.h5 checkpoint.h5
"$build/dem/aniso-dem" load --set dem.output_dir=dem --input dem/prepared.h5 --set dem.equilibrium.at_checkpoints=false \
  --set dem.load.final_strain=0.003 --set 'dem.load.checkpoint_strains=[0.001, 0.002, 0.003]' --log-level warn
"$build/fabric/aniso-fabric" series --input dem/load_00{0,1,2}.h5 --output fabric_series.h5 --log-level warn
status=0
for page in checkpoint fabric; do
  awk '/^```python/{inside=1; next} /^```/{inside=0} inside' "$docs/$page.md" > "$page.py"
  [ -s "$page.py" ] || { echo "FAIL: no python example in $page.md"; status=1; continue; }
  /usr/bin/python3 "$page.py" || { echo "FAIL: the python example of docs/formats/$page.md"; status=1; }
done
[ "$status" = 0 ] && echo "the python examples of docs/formats run as written"
exit "$status"
