#!/usr/bin/python3
"""The named loading behaviours (dem.load.behaviour; docs/methods/dem.md, "Loading behaviours") on the
same prepared assemblies: each assembly loaded with its paper config to FINAL strain as
  inertial      continuous at I = 1e-3, contact damping on sticking contacts (the engine's default)
  oval          DEMPLA/OVAL's body damping of translation (0.071) and spin (x6), no contact damping
  quasi_static  increments of 3e-5, each minimised to 1e-3
  increments    the paper configs' setting before the behaviours: OVAL's increments of 1e-4 relaxed to 1e-2
with checkpoints at 2%, 10% and FINAL written unrelaxed: a loading with relaxed copies as checkpoints
(dem.equilibrium.fork_checkpoints, the oval behaviour's) has the same history to the bit
(tests/dem/fork_checkpoints.sh), and the ovoids' copies can take longer than the loading.

A BEHAVIOUR may also be NAME:KEY=VALUE[,KEY=VALUE...], a loading of its own settings, and an assembly
NAME=:PREPARED.h5 (no config) loads with the config stored in the prepared file.

Each run loads into WORK/<assembly>_<behaviour>/ (history, checkpoints, its log and run record; runner.py)
and writes WORK/results/<assembly>_<behaviour>.csv (strain, q13, q23, p, eps_v, void_ratio, coordination,
tests/dem/peer/dempla_io.py's columns), which chart_dem_behaviours.py draws. A finished run is not redone.

usage: load_behaviours.py BUILD WORK FINAL NAME=CONFIG:PREPARED.h5 ... [-- BEHAVIOUR ...]
"""
import os
import sys

from runner import StudyError, main_guarded, run_cached, settings_arguments, stage
from readers import checkpoint_particle_count

BEHAVIOURS = {
    "inertial": ["dem.load.behaviour=inertial"],
    "oval": ["dem.load.behaviour=oval"],
    "quasi_static": ["dem.load.behaviour=quasi_static"],
    "increments": ["dem.load.behaviour=inertial", "dem.load.increment=1e-4", "dem.load.increment_tolerance=1e-2"],
}
DEMPLA_IO = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "dem", "peer", "dempla_io.py")


def behaviour_settings(behaviour):
    """(name, settings) of a named behaviour or of NAME:KEY=VALUE,..."""
    name, _, pairs = behaviour.partition(":")
    if pairs:
        return name, pairs.split(",")
    if name not in BEHAVIOURS:
        raise StudyError(f"unknown behaviour '{name}' (known: {', '.join(BEHAVIOURS)}, or NAME:KEY=VALUE,...)")
    return name, BEHAVIOURS[name]


def load(build, work, final, name, config, prepared, behaviour):
    behaviour, extra = behaviour_settings(behaviour)
    run = f"{name}_{behaviour}"
    folder, result = os.path.join(work, run), os.path.join(work, "results", f"{run}.csv")
    checkpoints = ", ".join(str(s) for s in sorted({s for s in (0.02, 0.1) if s < float(final)} | {float(final)}))
    settings = [f"dem.output_dir={folder}", f"dem.load.final_strain={final}",
                f"dem.load.checkpoint_strains=[{checkpoints}]", "dem.load.history_interval=5e-4", *extra,
                "dem.equilibrium.at_checkpoints=false", "dem.equilibrium.fork_checkpoints=false"]
    config_options = []
    if config:
        # The config's particle count is the paper's; the assembly's own is what the load uses.
        config_options = ["--config", config]
        settings.append(f"dem.particles.count={checkpoint_particle_count(prepared)}")
    print(f"{run}: loading to {final} (load average {os.getloadavg()[0]:.2f})", flush=True)
    done = run_cached([stage(build, "dem"), "load", *config_options, "--input", prepared, "--overwrite",
                       *settings_arguments(settings)], folder, outputs=[os.path.join(folder, "history.csv")])
    run_cached([sys.executable, DEMPLA_IO, "aniso", os.path.join(folder, "history.csv"), result], folder,
               outputs=[result], log="results.log")
    print(f"{run}: {done.wall:.0f} s", flush=True)


def main(build, work, final, arguments):
    assemblies, behaviours = arguments, list(BEHAVIOURS)
    if "--" in arguments:
        split = arguments.index("--")
        assemblies, behaviours = arguments[:split], arguments[split + 1:]
    for behaviour in behaviours:
        behaviour_settings(behaviour)  # an unknown name stops the study before any run
    if not assemblies:
        raise StudyError(__doc__)
    os.makedirs(os.path.join(work, "results"), exist_ok=True)
    for assembly in assemblies:
        name, spec = assembly.split("=", 1)
        config, prepared = spec.split(":", 1)
        for behaviour in behaviours:
            load(os.path.abspath(build), work, final, name, config and os.path.abspath(config), prepared, behaviour)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
