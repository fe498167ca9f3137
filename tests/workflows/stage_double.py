#!/usr/bin/python3
"""A test double of an analysis stage's command line, for testing the
workflow's job plumbing (arrays, dependencies, file names) before the real
stage exists. It computes nothing: each "result" is a text file saying which
command and which SLURM job and array task wrote it, and from which inputs.
Only the workflow tests use it, from a throw-away BIN folder. --print-config prints the
stage's section of the config, as a real stage prints its effective settings (campaign.py check
keeps them in the run's settings/ folder).

usage: stage_double.py STAGE [fork|collect|series] --config F --set STAGE.output_dir=OUT --input FILE...
                       [--fork K] [--direction D] [--probe FILE...] [--voids FILE...] [--permeability FILE...]
"""
import argparse
import json
import os
import sys
import tomllib


def stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def record(path, args, inputs):
    if os.environ.get("STAGE_DOUBLE_FAIL") == stem(path):  # a stage failure, for the failure tests
        sys.exit(f"stage_double: failing on purpose instead of writing {path}")
    job = {k: os.environ.get(k, "") for k in ("SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID")}
    for needed in inputs:
        if not os.path.exists(needed):
            sys.exit(f"stage_double: input {needed} missing when writing {path}")
    os.makedirs(os.path.dirname(path), exist_ok=True)  # as the stages make their output_dir
    with open(path + ".part", "w") as f:
        f.write(" ".join(f"{k}={v}" for k, v in job.items()) + "\n")
        f.write(f"stage={args.stage} command={args.command or '-'} fork={args.fork} direction={args.direction}\n")
        f.write("inputs=" + " ".join(inputs) + "\n")
    os.replace(path + ".part", path)


def print_table(name, table):
    """TOML of a table of scalars, lists and tables (JSON writes their values as TOML does)."""
    print(f"[{name}]")
    for key, value in table.items():
        if not isinstance(value, dict):
            print(f"{key} = {json.dumps(value)}")
    for key, value in table.items():
        if isinstance(value, dict):
            print_table(f"{name}.{key}", value)


def main():
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("stage", choices=["fabric", "probe", "voxel", "lbm"])
    parser.add_argument("command", nargs="?", choices=["fork", "collect", "series"])
    parser.add_argument("--config")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--input", nargs="+", default=[])
    parser.add_argument("--fork", type=int)
    parser.add_argument("--direction", type=int)
    for results in ("--probe", "--voids", "--permeability"):
        parser.add_argument(results, nargs="+", default=[])
    parser.add_argument("--print-config", action="store_true")
    parser.add_argument("--log-level")
    args = parser.parse_args()
    if args.print_config:  # campaign.py check: accepts any config
        section = {}
        if args.config:
            with open(args.config, "rb") as f:
                section = tomllib.load(f).get(args.stage, {})
        print_table(args.stage, section)
        return
    settings = dict(s.split("=", 1) for s in args.set)
    out = settings[f"{args.stage}.output_dir"]
    source = args.input[0]
    if args.stage == "fabric" and args.command == "series":
        record(f"{out}/fabric_series.h5", args, args.input + args.probe + args.voids + args.permeability)
    elif args.stage == "fabric":
        record(f"{out}/fabric.h5", args, args.input)
    elif args.stage == "probe" and args.command == "fork":
        record(f"{out}/probe_{stem(source)}_fork{args.fork}.h5", args, [source])
    elif args.stage == "probe" and args.command == "collect":
        forks = [f"{out}/probe_{stem(source)}_fork{k}.h5" for k in range(7)]
        record(f"{out}/probe_{stem(source)}.h5", args, forks)
    elif args.stage == "voxel":
        record(f"{out}/image_{stem(source)}.h5", args, [source])
        record(f"{out}/voids_{stem(source)}.h5", args, [source])
    elif args.stage == "lbm" and args.direction is not None:
        record(f"{out}/permeability_{stem(source)}_direction{args.direction}.h5", args, [source])
    elif args.stage == "lbm" and args.command == "collect":
        directions = [f"{out}/permeability_{stem(source)}_direction{d}.h5" for d in range(3)]
        record(f"{out}/permeability_{stem(source)}.h5", args, directions)
    else:
        sys.exit(f"stage_double: unexpected command line {sys.argv[1:]}")


if __name__ == "__main__":
    main()
