#!/usr/bin/python3
"""Facts about a campaign that the Makefile and the SLURM submitter both need.

usage:
  campaign.py checkpoints CONFIG BIN   the load checkpoints' stems (load_000 ...), from the effective config
  campaign.py stages BIN               the analysis stages built with the command line the workflow calls
  campaign.py load-input OUT CONFIG    the arguments of `aniso-dem load` that continue an interrupted run

`stages` prints one word per usable stage, then the optional command lines
they offer (lbm-directions: one LBM run per flow direction); for every other
stage it writes one line to stderr saying why it is skipped. A stage counts as built when its
executable exists, is no longer the stub of common/stage_stub.cpp (which only
validates its input) and its --help shows the options the workflow passes.

`load-input` resumes from the newest checkpoint of this run that history.h5
already covers (history.h5 is rewritten just after each checkpoint, so a kill
between the two leaves the newer checkpoint uncovered) and that is newer than
prepared.h5 and the config; otherwise it starts from prepared.h5.
"""
import os
import subprocess
import sys
import tomllib

# stage -> (executable under BIN, [(arguments for --help, text that help must contain)]): the
# command lines workflows/Makefile uses.
STAGE_INTERFACES = {
    "fabric": ("fabric/aniso-fabric", [([], "--input"), (["series"], "--probe")]),
    "probe": ("probe/aniso-probe", [(["fork"], "--fork"), (["collect"], "--input")]),
    "voxel": ("voxel/aniso-voxel", [([], "--input")]),
    "lbm": ("lbm/aniso-lbm", [([], "--input")]),
}
# Optional command lines of a usable stage: feature -> (stage, checks as above).
# lbm-directions: one flow direction per run (--direction D), then `collect`, for job arrays.
STAGE_FEATURES = {
    "lbm-directions": ("lbm", [([], "--direction"), (["collect"], "--input")]),
}
# The message of common/stage_stub.cpp: an executable that still links the stub holds it.
STUB_MARK = b"this stage is not built yet"


def fail(message):
    sys.exit(f"campaign.py: {message}")


def checkpoint_stems(config, bin_dir):
    dem = os.path.join(bin_dir, "dem", "aniso-dem")
    if not os.access(dem, os.X_OK):
        fail(f"{dem} not found: build it first (make build)")
    printed = subprocess.run([dem, "prepare", "--config", config, "--print-config", "--log-level", "error"],
                             capture_output=True, text=True)
    if printed.returncode != 0:
        fail(f"'{dem} load --config {config} --print-config' failed:\n{printed.stderr}")
    strains = tomllib.loads(printed.stdout)["dem"]["load"]["checkpoint_strains"]
    return [f"load_{index:03d}" for index in range(len(strains))]


def help_text(executable, arguments):
    result = subprocess.run([executable, *arguments, "--help"], capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def missing_options(executable, interface):
    missing = []
    for arguments, needle in interface:
        code, text = help_text(executable, arguments)
        if code != 0 or needle not in text:
            missing.append(" ".join([*arguments, needle]))
    return missing


def usable_stages(bin_dir):
    """The usable stages, then the optional features they offer."""
    usable = []
    for stage, (relative, interface) in STAGE_INTERFACES.items():
        executable = os.path.join(bin_dir, relative)
        if not os.access(executable, os.X_OK):
            print(f"campaign: skipping {stage}: {executable} not found", file=sys.stderr)
            continue
        missing = missing_options(executable, interface)
        with open(executable, "rb") as binary:
            if STUB_MARK in binary.read():
                missing.append("a computation (it is the stage stub)")
        if missing:
            print(f"campaign: skipping {stage}: {os.path.basename(executable)} is not built yet "
                  f"(it lacks: {', '.join(missing)}); no {stage} results are written", file=sys.stderr)
        else:
            usable.append(stage)
    for feature, (stage, interface) in STAGE_FEATURES.items():
        if stage in usable and not missing_options(os.path.join(bin_dir, STAGE_INTERFACES[stage][0]), interface):
            usable.append(feature)
    return usable


def load_input(out, config):
    prepared = os.path.join(out, "prepared.h5")
    history = os.path.join(out, "history.h5")
    start = ["--input", prepared]
    if not os.path.exists(history):
        return start
    oldest_allowed = max(os.path.getmtime(prepared), os.path.getmtime(config))
    history_time = os.path.getmtime(history)
    newest = None
    index = 0
    while True:
        path = os.path.join(out, f"load_{index:03d}.h5")
        if not os.path.exists(path):
            break
        written = os.path.getmtime(path)
        if written < oldest_allowed or written > history_time:
            break
        newest = path
        index += 1
    if newest is None:
        return start
    print(f"campaign: resuming the interrupted load from {newest}", file=sys.stderr)
    return ["--input", newest, "--resume"]


def main(argv):
    if len(argv) == 4 and argv[1] == "checkpoints":
        print(" ".join(checkpoint_stems(argv[2], argv[3])))
    elif len(argv) == 3 and argv[1] == "stages":
        print(" ".join(usable_stages(argv[2])))
    elif len(argv) == 4 and argv[1] == "load-input":
        print(" ".join(load_input(argv[2], argv[3])))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
