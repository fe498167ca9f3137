# YADE (Debian package `yade`) runs the loading aniso-dem runs, from an aniso checkpoint, as an
# independent check of the DEM's physics (docs/validation.md, "DEM against YADE").
#
#   yade -x -n tests/dem/peer/yade_biaxial.py CHECKPOINT.h5 MODE INERTIAL_NUMBER FINAL_STRAIN OUT.csv
#
# MODE: `drained`   biaxial plane strain at constant mean stress (x1 shortened at the rate of the
#                   inertial number, x2 fixed, x3 servoed as aniso servoes it: stiffness-scaled,
#                   gain 0.2 every 4 steps, integral over 20 updates, capped at 20x the rate);
#       `undrained` the same at constant volume (x3 lengthened at the rate x1 is shortened).
# The material, density, time step, contact damping and friction are the checkpoint's loading
# settings; the spheres, cell and the elastic tangential forces of its contacts are imported.
# YADE's Law2_ScGeom_MindlinPhys_Mindlin has the same Hertz and Mindlin stiffnesses as aniso
# (k_n = 2 E* a, k_t = 8 G* a), viscous damping 2 beta sqrt(m* k) on sticking contacts only, and
# the incremental tangential force turned with the contact. OUT.csv gets one row per 0.5% of the
# final strain: step, strain (-eps11), p, q, (s11 - s33)/p, YADE's unbalancedForce(), eps_v.
import math
import sys
import time

import h5py
import numpy as np

path, mode, inertial, final, out = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
if mode not in ("drained", "undrained"):
    sys.exit(f"yade_biaxial.py: unknown mode '{mode}' (drained or undrained)")
with h5py.File(path, "r") as f:
    lengths = f["cell/lengths"][:]
    position = f["particles/position"][:]
    diameter = f["particles/diameter"][:]
    ids = f["particles/id"][:]
    contact_ids = f["contacts/particles"][:]
    tangential = f["contacts/tangential_force"][:]
    parameters = f["parameters"].attrs
    shear_modulus = float(parameters["shear_modulus"])
    poisson = float(parameters["poisson_ratio"])
    friction = float(parameters["friction"])
    density = float(parameters["density"])
    damping = float(parameters["damping_ratio"])
    d50 = float(parameters["d50"])
    time_step = float(f.attrs["time_step"])
    mean_stress = float(f["cell/mean_stress_target"][()]) if "mean_stress_target" in f["cell"] else 100e3
if mean_stress <= 0:
    mean_stress = 100e3

O.periodic = True
O.cell.hSize = Matrix3(lengths[0], 0, 0, 0, lengths[1], 0, 0, 0, lengths[2])
material = O.materials.append(FrictMat(young=2 * shear_modulus * (1 + poisson), poisson=poisson,
                                       density=density, frictionAngle=math.atan(friction)))
body_of = {}
for k in range(len(ids)):
    body_of[int(ids[k])] = O.bodies.append(sphere(Vector3(*position[k]), 0.5 * diameter[k], material=material))

rate = inertial / (d50 * math.sqrt(density / mean_stress))
interval, gain, integral_updates, max_rate = 4, 0.2, 20.0, 20.0 * rate
servo = {"integral": 0.0, "next_row": 0.0}
rows = []


def stress_tensor():
    s = getStress()  # tension positive, as aniso's
    return np.array([[s[i, j] for j in range(3)] for i in range(3)])


def axial_stiffness_3():
    """(1/V) sum k_n n3^2 d3^2: what aniso's servo divides by."""
    total = 0.0
    for interaction in O.interactions:
        if not interaction.isReal:
            continue
        n = interaction.geom.normal
        d3 = (O.bodies[interaction.id2].state.pos[2] - O.bodies[interaction.id1].state.pos[2]
              + (O.cell.hSize * interaction.cellDist)[2])
        total += interaction.phys.kn * n[2] ** 2 * d3 ** 2
    return total / O.cell.volume


def control():
    sigma = stress_tensor()
    p = -np.trace(sigma) / 3
    rate_3 = rate
    if mode == "drained":
        proportional = gain * 3 * (p - mean_stress) / max(axial_stiffness_3(), 1e-12) / (interval * O.dt)
        servo["integral"] = min(max(servo["integral"] + proportional / integral_updates, -max_rate), max_rate)
        rate_3 = min(max(proportional + servo["integral"], -max_rate), max_rate)
    O.cell.velGrad = Matrix3(-rate, 0, 0, 0, 0, 0, 0, 0, rate_3)
    h = O.cell.hSize
    strain = 1 - h[0, 0] / lengths[0]
    if strain >= servo["next_row"]:
        deviator = sigma + p * np.eye(3)
        rows.append((O.iter, strain, p, math.sqrt(1.5 * np.sum(deviator * deviator)),
                     (-sigma[0, 0] + sigma[2, 2]) / p, unbalancedForce(),
                     h[0, 0] * h[1, 1] * h[2, 2] / lengths.prod() - 1))
        servo["next_row"] += final / 200
    if strain >= final:
        np.savetxt(out, np.array(rows), delimiter=",", comments="",
                   header="step,strain,p,q,stress_ratio,unbalanced_force,volumetric_strain")
        O.pause()


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=0.1 * d50),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys(betan=damping, betas=damping)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0),
    PyRunner(command="control()", iterPeriod=interval),
]
O.dt = time_step
O.step()  # creates the interactions; then the checkpoint's elastic tangential forces are set on them
# aniso stores the tangential force on the lower id i; YADE applies -shearForce to its id1.
for (a, b), force in zip(contact_ids, tangential):
    interaction = O.interactions[body_of[int(a)], body_of[int(b)]]
    if interaction is None or not interaction.isReal:
        continue
    sign = -1.0 if interaction.id1 == body_of[int(a)] else 1.0
    interaction.phys.shearElastic = Vector3(*(sign * force))
    interaction.phys.shearForce = Vector3(*(sign * force))
start = time.time()
O.run()
O.wait()
print(f"yade_biaxial: {mode} to {final} at I = {inertial} in {O.iter} steps, {time.time() - start:.0f} s")
