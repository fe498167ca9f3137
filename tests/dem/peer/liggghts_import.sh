#!/usr/bin/env bash
# A static state made by LIGGGHTS 3.8 (Debian package) comes into aniso static.
# An aniso assembly, exported, is settled by LIGGGHTS with its own Hertz-Mindlin contacts (they
# start without tangential history, so it finds its own static state, at a lower p); LIGGGHTS
# writes it with `write_data` and its tangential forces with `compute pair/gran/local id
# force_tangential`. `aniso-dem import --contact-columns 1,2,4` must give LIGGGHTS' p (to the 6
# digits of its dump), a balanced state and a hold that keeps p within 1e-6. The same import
# with the sign turned (1,2,-4) or without the dump is not static: the check can fail.
#
# usage: liggghts_import.sh BUILD_DIR WORK_DIR   (exit 77, skipped, without liggghts)
set -euo pipefail
build=$1 work=$2
command -v liggghts >/dev/null || { echo "liggghts not found (scripts/install-deps.sh test installs it)"; exit 77; }
source "$(dirname "$0")/../../tools/cli_lib.sh"
status=0
enter_fresh_folder "$work"
dem=$build/dem/aniso-dem
small_prepared_assembly "$build" dem
"$dem" export --input dem/prepared.h5 --output aniso.data --log-level warn

# LIGGGHTS' material from the checkpoint's: E = 2 G (1 + nu); the restitution coefficient of
# aniso's damping ratio beta on the normal spring (beta_L = beta / sqrt(5/6)).
read -r young nu mu restitution dt < <(/usr/bin/python3 - dem/prepared.h5 <<'PY'
import math
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    q = f["parameters"].attrs
    beta = q["damping_ratio"] / math.sqrt(5 / 6)
    print(2 * q["shear_modulus"] * (1 + q["poisson_ratio"]), q["poisson_ratio"], q["friction"],
          math.exp(-math.pi * beta / math.sqrt(1 - beta * beta)), f.attrs["time_step"])
PY
)
cat >settle.in <<EOF
atom_style granular
atom_modify map array
boundary p p p
newton off
communicate single vel yes
units si
hard_particles yes
read_data aniso.data
neighbor 1.6e-5 bin
neigh_modify delay 0 every 1 check yes
fix m1 all property/global youngsModulus peratomtype $young
fix m2 all property/global poissonsRatio peratomtype $nu
fix m3 all property/global coefficientRestitution peratomtypepair 1 $restitution
fix m4 all property/global coefficientFriction peratomtypepair 1 $mu
pair_style gran model hertz tangential history
pair_coeff * *
timestep $dt
fix integr all nve/sphere
compute contacts all pair/gran/local id force_tangential
compute sa all stress/atom
compute ss all reduce sum c_sa[1] c_sa[2] c_sa[3]
variable p equal -(c_ss[1]+c_ss[2]+c_ss[3])/(3*vol)
thermo_style custom step v_p
thermo_modify format float %.10g
thermo 10000
fix drag all viscous 0.002
run 20000
unfix drag
run 10000
dump local all local 1 liggghts.dump c_contacts[1] c_contacts[2] c_contacts[3] c_contacts[4] c_contacts[5] c_contacts[6]
run 0
write_data liggghts.data
EOF
liggghts -in settle.in -log none -nocite >liggghts.log 2>&1 || { echo "FAIL: LIGGGHTS failed:"; tail liggghts.log; exit 1; }
p_liggghts=$(awk '$1 == 30000 && NF == 2 { p = $2 } END { print p }' liggghts.log)
echo "LIGGGHTS settled at p = $p_liggghts Pa"

expect_exit 0 import "tangential forces adopted" "$dem" import --input liggghts.data --contacts liggghts.dump \
  --contact-columns 1,2,4 --output liggghts.h5
expect_exit 0 hold "hold of" "$dem" hold --input liggghts.h5 --steps 20000 --max-drift 1e-6
expect_exit 0 import_turned "tangential forces adopted" "$dem" import --input liggghts.data \
  --contacts liggghts.dump --contact-columns 1,2,-4 --output turned.h5
expect_exit 5 hold_turned "above --max-drift" "$dem" hold --input turned.h5 --steps 20000 --max-drift 1e-2
expect_exit 0 import_bare "contacts by aniso" "$dem" import --input liggghts.data --output bare.h5
expect_exit 5 hold_bare "above --max-drift" "$dem" hold --input bare.h5 --steps 20000 --max-drift 1e-2

/usr/bin/python3 - "$p_liggghts" <<'PY' || status=1
import re
import sys
log = open("import.log").read()
p, ratio = (float(v) for v in re.search(r"p = ([0-9.e+-]+) Pa, unbalanced-force ratio ([0-9.e+-]+)", log).groups())
matched = re.search(r"(\d+) dumped pairs are apart in aniso; (\d+) aniso contacts have no dumped row", log).groups()
p_peer = float(sys.argv[1])
checks = {
    f"p {p:.8g} Pa is LIGGGHTS' {p_peer:.8g} Pa (rel. 1e-5)": abs(p / p_peer - 1) < 1e-5,
    f"unbalanced-force ratio {ratio:.2e} below 1e-5": ratio < 1e-5,
    f"every contact matched (apart / without a dumped row: {matched})": matched == ("0", "0"),
    "LIGGGHTS settled below aniso's 100 kPa (its own static state, not aniso's)": p_peer < 99.9e3,
}
for name, ok in checks.items():
    print(("ok: " if ok else "FAIL: ") + name)
raise SystemExit(0 if all(checks.values()) else 1)
PY
if [ "$status" = 0 ]; then echo "liggghts_import: all checks passed"; fi
exit "$status"
