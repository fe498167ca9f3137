#!/usr/bin/python3
"""The preparation as a lever of its own (issue 45, item 4; docs/methods/dem.md, "The preparation
study"): assemblies of the same void ratio made in different ways, each then loaded the same way.
Every variant is its config (the paper's, at COUNT particles, default 1000) with the settings it
names, prepared with `aniso-dem prepare` and loaded with the config's own loading (the paper configs:
the oval behaviour) to FINAL strain without checkpoints. A variant whose prepare stops with exit 5 (its
e missed the target band) is recorded as such and the study goes on.

usage: preparation_study.py BUILD WORK FINAL NAME=CONFIG[:KEY=VALUE[,KEY=VALUE...]] ...
  e.g. spheres_mu0=configs/paper-spheres.toml:dem.material.friction_prepare=0,dem.prepare.compaction_stop_void_ratio=0.57
Writes WORK/NAME/variant.txt (the config, then its settings, one a line), WORK/NAME/prepare/ (prepared.h5, its log
prepare.log and record prepare.run.json; runner.py) and WORK/NAME/load/ (history.h5, load.log,
load.run.json); a stage with its outputs and record is not redone, so a killed study continues where
it stopped (a killed prepare resumes from its pieces). Then summarise with chart_preparation_study.py WORK.
"""
import glob
import os
import sys

from runner import main_guarded, run_cached, settings_arguments, stage

MISSED_TARGET = 5  # aniso-dem prepare's exit status when e ends outside the target band


def variant(build, work, final, count, name, spec):
    config, _, pairs = spec.partition(":")
    settings = [f"dem.particles.count={count}", *(pair for pair in pairs.split(",") if pair)]
    run = os.path.join(work, name)
    os.makedirs(run, exist_ok=True)
    with open(os.path.join(run, "variant.txt"), "w") as f:
        f.write("\n".join([config, *settings[1:]]) + "\n")
    prepare_folder = os.path.join(run, "prepare")
    prepared = os.path.join(prepare_folder, "prepared.h5")
    resume = ["--resume"] if glob.glob(os.path.join(prepare_folder, "prepare_*.h5")) else []
    print(f"{name}: preparing (load average {os.getloadavg()[0]:.2f})", flush=True)
    prepare = run_cached([stage(build, "dem"), "prepare", "--config", config, *resume,
                          *settings_arguments([*settings, f"dem.output_dir={prepare_folder}"])],
                         prepare_folder, outputs=[prepared], log="prepare.log", accept=(0, MISSED_TARGET))
    if prepare.code == MISSED_TARGET:
        print(f"{name}: prepare missed the target band (exit 5), see {prepare_folder}/prepare.log", flush=True)
        return
    load_folder = os.path.join(run, "load")
    print(f"{name}: loading to {final} (load average {os.getloadavg()[0]:.2f})", flush=True)
    run_cached([stage(build, "dem"), "load", "--config", config, "--input", prepared, "--overwrite",
                *settings_arguments([*settings, f"dem.output_dir={load_folder}", f"dem.load.final_strain={final}",
                                     "dem.load.checkpoint_strains=[]", "dem.load.history_interval=5e-4",
                                     "dem.equilibrium.at_checkpoints=false", "dem.equilibrium.fork_checkpoints=false"])],
               load_folder, outputs=[os.path.join(load_folder, "history.h5")], log="load.log")


def main(build, work, final, variants):
    count = int(os.environ.get("COUNT", "1000"))
    for v in variants:
        name, spec = v.split("=", 1)
        variant(os.path.abspath(build), work, final, count, name, spec)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main_guarded(main, sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
