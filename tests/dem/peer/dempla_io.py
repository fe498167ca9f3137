"""DEMPLA 0.2.5 (Kuhn's OVAL successor, github.com/mrkuhn53/dempla, branch master) files for
tests/dem/peer/dempla_biaxial.sh: RunFiles in, A-file histories out. Written from DEMPLA's manual
(doc/dempla_0_2_5.tex, "RunFile" and "A-files") and its reader readit2; no DEMPLA code.

  dempla_io.py runfile OUT key=value ... seg=SEGMENT [seg=SEGMENT ...]
      SEGMENT = icontr,icontp,r11,r22,r33,r12,r13,r23,r8,igoal,finalv,ipts,idump,defdot
  dempla_io.py history AFILE OUT.csv
      strain (x1 compressive, engineering), q13 = (s11 - s33)/p, q23 = (s22 - s33)/p, p [Pa],
      eps_v (V/V0 - 1, dilation positive), void_ratio, coordination (2 contacts / N, rattlers
      included: DEMPLA does not write a count without them), chi1 (its unbalanced-force measure)
  dempla_io.py aniso HISTORY.csv OUT.csv
      an aniso-dem load history (history.csv) as the same columns, and Z without rattlers
  dempla_io.py agreement WORK_DIR
      the two codes on the same start (dempla_biaxial.sh's files): p of the start's overlaps
      (DEMPLA's first step against aniso's import) within 1e-4, and the void ratio after each
      code's consolidation to 100 kPa within 1e-3; exit 1 otherwise
  dempla_io.py stresses AFILE
      the first row's s11 s22 s33 [Pa, compression negative]: where a consolidation ramp starts
"""
import re
import sys

import numpy as np

# The RunFile's general part: 62 lines, one value in the first 16 columns each (readit2 formats
# 203-209). imodel 6 is Jager's full Mindlin-Deresiewicz history (5 has a sign defect);
# rho = dt = -1 asks for DEMPLA's automatic mass scaling (time unit = one step); idamp 1 with
# pcrit 0.03 / 0.05 / 0 are the body damping of translation and rotation and the contact
# damping, as in every sample RunFile of the repository.
DEFAULTS = dict(
    title="aniso peer run (tests/dem/peer/dempla_biaxial.sh)",
    algori=1, ivers=6, ncownt=0, iout2=0, iout3=0, istart=1, iend=0, idef=0,
    iupdtm=500, icirct=0, imodel=6, nplatn=0, nloop1=5,
    iexact=0, isub=0, idamp=1, iheat=0, icoef=0, iporo=0,
    kn="29.d9", kratio="0.15", frict="0.50", frictw="0.", rho="-1.", sep="0.250",
    pcrit1="0.03", pcrit2="0.05", pcrit3="0.", xseed="0.64", rmsvel="0.",
    pdif="0.10", tmax="0.", A_1="0.", dt="-1.", palpha="1.5")
INT_KEYS = ["algori", "ivers", "ncownt", "iout2", "iout3", "istart", "iend", "idef", "iupdtm", "icirct",
            "imodel", "nplatn", "nloop1", "iexact", "isub", "idamp", "iheat", "icoef", "iporo"]
REAL_KEYS = ["kn", "kratio", "frict", "frictw", "rho", "sep", "pcrit1", "pcrit2", "pcrit3", "xseed",
             "rmsvel", "pdif", "tmax", "A_1", "dt"]
UNUSED_REALS = ["gravty(1)", "gravty(2)", "gravty(3)", "p_o", "K_s", "K_f", "S_o", "p_atm", "Hcc", "gamm",
                "D_o", "N_o", "p_vap", "p_wcav", "rfree(15)", "rfree(16)", "rfree(17)", "rfree(18)"]


def f9(x):
    """x in at most 9 columns with a decimal point: Fortran reads a pointless f9.6 field as
    digits x 1e-6. Exact where a candidate is, else the closest."""
    x = float(x)
    candidates = [f"{x:9.{k}f}" for k in range(6, 0, -1)] + [f"{x:#9.0f}"]
    candidates += [f"{x:9.{k}e}" for k in range(3, 0, -1)] + [f"{x:#9.0e}"]
    candidates = [c for c in candidates if len(c) <= 9 and "." in c]
    if not candidates:
        raise SystemExit(f"dempla_io.py: {x} does not fit a 9-column field")
    exact = [c for c in candidates if float(c) == x]
    return exact[0] if exact else min(candidates, key=lambda c: abs(float(c) - x))


def segment_line(spec):
    """One deformation-stress segment in readit2's format 212."""
    v = spec.split(",")
    if len(v) != 14 or len(v[0]) != 6:
        raise SystemExit(f"dempla_io.py: segment '{spec}': expected 14 fields, icontr of 6 digits")
    rates = " ".join(f9(r) for r in v[2:9])
    igoal, finalv, ipts, idump, defdot = int(v[9]), f9(v[10]), int(v[11]), int(v[12]), float(v[13])
    if not 0 < ipts <= 9999:
        raise SystemExit(f"dempla_io.py: output interval {ipts} outside 1..9999")
    friction = f"{defdot:6.4f}" if defdot else "    0."
    return (f"{v[0]:>6s} {int(v[1]):1d} {rates} {igoal:2d} 0 {finalv} {ipts:4d} {idump:1d}  0 0  0 "
            f"{friction}    0  0")


def write_runfile(path, settings, segments):
    p = dict(DEFAULTS)
    p.update(settings)
    lines = [p["title"][:72]]
    lines += [f"{p[k]:>8}         : {k}" for k in INT_KEYS]
    lines += [f"{0:>8}         : ifree({i})" for i in range(11, 19)]
    lines += [f"{p[k]:>12}     : {k}" for k in REAL_KEYS]
    lines += [f"{'0.':>12}     : {name}" for name in UNUSED_REALS]
    lines += [f"{p['palpha']:>12}     : palpha"]
    assert len(lines) == 62
    lines += ["       ************  Deformation-Stress Path Segments  **********"] + ["-"] * 4
    lines += [segment_line(s) for s in segments]
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")


def read_afile(path):
    """(particle count, rows): the numeric rows of a 3D A-file (tab-separated, 41-42 columns)."""
    count, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("Number of particles:"):
                count = int(line.split("\t")[1])
            elif line[:1] == " " and line.count("\t") > 30:
                rows.append([float(v) for v in line.rstrip("\n").split("\t")])
    a = np.array(rows)
    if count is None or a.ndim != 2 or a.shape[1] < 41:
        raise SystemExit(f"dempla_io.py: {path} is not a 3D DEMPLA A-file (no particle count or rows)")
    return count, a


def write_history(afile, out):
    count, a = read_afile(afile)
    a = a[np.r_[np.diff(a[:, 0]) != 0, True]]  # a segment's last row is repeated at the next's start
    stretch = 1.0 + a[:, 1:4]  # Def(i,i) = F_ii / F0_ii - 1
    stretch /= stretch[0]
    s = -a[:, 7:10]  # Cauchy stress, tension positive in DEMPLA
    p = s.mean(axis=1)
    table = np.column_stack([1.0 - stretch[:, 0], (s[:, 0] - s[:, 2]) / p, (s[:, 1] - s[:, 2]) / p, p,
                             stretch.prod(axis=1) - 1.0, a[:, 30], 2.0 * a[:, 16] / count, a[:, 13]])
    np.savetxt(out, table, delimiter=",", header="strain,q13,q23,p,eps_v,void_ratio,coordination,chi1",
               comments="", fmt=["%.8e", "%.6f", "%.6f", "%.2f", "%.8e", "%.7f", "%.5f", "%.3e"])


def write_aniso_history(history, out):
    h = np.genfromtxt(history, delimiter=",", names=True)
    s = -np.column_stack([h["stress_11"], h["stress_22"], h["stress_33"]])
    p = s.mean(axis=1)
    table = np.column_stack([-h["strain_11"], (s[:, 0] - s[:, 2]) / p, (s[:, 1] - s[:, 2]) / p, p,
                             h["volumetric_strain"], h["void_ratio"], h["coordination"],
                             h["coordination_no_rattlers"]])
    np.savetxt(out, table, delimiter=",", comments="",
               header="strain,q13,q23,p,eps_v,void_ratio,coordination,coordination_no_rattlers",
               fmt=["%.8e", "%.6f", "%.6f", "%.2f", "%.8e", "%.7f", "%.5f", "%.5f"])


def agreement(work):
    start_dempla = -read_afile(f"{work}/dempla_consolidation/ARprobe.txt")[1][0, 7:10].mean()
    start_aniso = float(re.search(r"p = ([0-9.e+-]+) Pa", open(f"{work}/import.log").read()).group(1))
    a_rows = read_afile(f"{work}/dempla_consolidation/ARcons.txt")[1]
    e_dempla, p_dempla = a_rows[-1, 30], -a_rows[-1, 7:10].mean()
    e_aniso = float(re.search(r"e [0-9.]+ -> ([0-9.]+)", open(f"{work}/consolidate.log").read()).group(1))
    checks = {
        f"p of the start's overlaps: DEMPLA {start_dempla:.1f} Pa, aniso {start_aniso:.1f} Pa (within 1e-4)":
        abs(start_aniso / start_dempla - 1) <= 1e-4,
        f"consolidated to 100 kPa (DEMPLA {p_dempla:.1f} Pa): e DEMPLA {e_dempla:.5f}, aniso {e_aniso:.5f} "
        f"(within 1e-3)": abs(e_aniso - e_dempla) <= 1e-3 and abs(p_dempla / 1e5 - 1) <= 1e-3,
    }
    for name, ok in checks.items():
        print(("ok: " if ok else "FAIL: ") + name)
    return all(checks.values())


def main(argv):
    if len(argv) >= 3 and argv[1] == "runfile":
        settings, segments = {}, []
        for arg in argv[3:]:
            key, value = arg.split("=", 1)
            if key == "seg":
                segments.append(value)
            elif key in DEFAULTS:
                settings[key] = value
            else:
                raise SystemExit(f"dempla_io.py: unknown RunFile key '{key}'")
        write_runfile(argv[2], settings, segments)
    elif len(argv) == 4 and argv[1] == "history":
        write_history(argv[2], argv[3])
    elif len(argv) == 3 and argv[1] == "agreement":
        raise SystemExit(0 if agreement(argv[2]) else 1)
    elif len(argv) == 4 and argv[1] == "aniso":
        write_aniso_history(argv[2], argv[3])
    elif len(argv) == 3 and argv[1] == "stresses":
        print(" ".join(repr(v) for v in read_afile(argv[2])[1][0, 7:10]))
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
