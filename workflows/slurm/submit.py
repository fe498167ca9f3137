#!/usr/bin/python3
"""Submits the aniso campaign to SLURM as jobs with dependencies.

usage: submit.py --config FILE.toml --out RUN_DIR --bin BUILD_DIR [--ranks N]
                 [--launcher 'srun --mpi=pmix'] [--sbatch-arg=ARG ...] [--dry-run] [--wait]
       submit.py --paper --out PAPER_DIR --bin BUILD_DIR [--realisations N] [--paper-configs DIR]
                 [--paper-shapes 'spheres ovoids-0.5'] [other options as above]

--paper submits `make paper` (workflows/paper.mk): for every shape and realisation the
campaign below into PAPER_DIR/<shape>/r<k>, with the config campaign.py realisation writes
into PAPER_DIR/configs/, then one serial job, after all their report jobs, that draws the
paper's figures and writes PAPER_DIR/comparison.md (`make paper-figures`).

The jobs are the steps of workflows/Makefile (its `slurm-plan` target lists
them): prepare -> load -> per checkpoint {the seven probe forks (reference and
six increments) as a 7-task array -> probe collect; voxel -> the LBM's three
flow directions as a 3-task array -> LBM collect (or one LBM job when aniso-lbm
runs all directions at once)}, fabric after the load, the fabric series after
every analysis, and the figures and report last. Each job runs
`make <its targets>` (slurm/make-step.sh), so a job's output is exactly what a
local `make campaign` writes, and resubmitting after a failure or a kill
submits only the steps whose files are missing or out of date, and of a job
array only the tasks whose files are (--array=3 when one probe fork is lost).

Stages whose executables are missing or lack the workflow's options are left out, one line each on stderr.
MPI steps get --ntasks=N (--ranks, default 1), serial ones 1 task. Each kind
of job can have its own resources in the config (time, mem, ranks,
cpus_per_task under [workflow.resources.<kind>], `campaign.py` documents
them); they override --ranks. Cluster settings (partition, account...) go
through --sbatch-arg or sbatch's own environment variables (SBATCH_PARTITION,
SBATCH_ACCOUNT, ...).

Every job is a script in RUN_DIR/slurm/jobs/<step>.sh with its #SBATCH lines
(written also by --dry-run): read it, or rerun one step by hand with
`sbatch RUN_DIR/slurm/jobs/<step>.sh` (an array step: add --array=...). Only
the array indices and the dependencies on this submission's jobs are on the
sbatch command line. Logs: RUN_DIR/slurm/<step>-<job>[_<task>].log; the job
ids: RUN_DIR/slurm/jobs.tsv. --wait blocks until every job has ended and
exits 0 only if all completed, polling SLURM every 0.5 s at first and at
most every 30 s later (gentle on the controller for a long campaign).
"""
import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import time

WORKFLOWS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STEP_SCRIPT = os.path.join(WORKFLOWS, "slurm", "make-step.sh")
ENDED_OK = {"COMPLETED"}
STILL_RUNNING = {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "REQUEUED", "RESIZING", "SUSPENDED",
                 "STAGE_OUT", "SIGNALING"}


def say(message):
    print(f"submit: {message}", file=sys.stderr, flush=True)


def fail(message):
    say(f"error: {message}")
    sys.exit(1)


class Step:
    def __init__(self, line):
        fields = line.split()
        if len(fields) < 5 or fields[2] not in ("mpi", "serial"):
            fail(f"bad slurm-plan line from the Makefile: '{line}'")
        self.name, self.mpi = fields[0], fields[2] == "mpi"
        self.kind = re.sub(r"-load_\d+$", "", self.name)  # probe-load_003 -> probe
        self.tasks = int(fields[1])
        self.after = [] if fields[3] == "-" else fields[3].split(",")
        self.targets = fields[4:]
        self.job_id = None

        self.indices = list(range(self.tasks))  # the array tasks to submit

    def task_targets(self, k):
        return [t.replace("{task}", str(k)) for t in self.targets]

    def expanded_targets(self):
        """The files of every array task."""
        return [t for k in range(self.tasks) for t in self.task_targets(k)] if self.tasks > 1 else list(self.targets)


def campaign_facts(args):
    def ask(*words):
        result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "campaign.py"), *words],
                                stdout=subprocess.PIPE, text=True)  # its skip lines go to our stderr
        if result.returncode != 0:
            fail(f"campaign.py {' '.join(words)} failed")
        return result.stdout.strip()

    # Every stage's section, before any job is submitted; each stage's effective settings go to the
    # run's settings/ folder, which the jobs' make compares its targets with (workflows/Makefile).
    ask("check", args.config, args.bin, os.path.join(args.out, "settings"))
    facts = {"CHECKPOINTS": ask("checkpoints", args.config, args.bin), "STAGES": ask("stages", args.bin)}
    for stage in ("probe", "voxel", "lbm"):  # the checkpoints the config's [workflow] gives each stage
        facts[f"{stage.upper()}_CHECKPOINTS"] = ask("checkpoints", args.config, args.bin, stage)
    resources = json.loads(ask("resources", args.config))
    return facts, resources


def make_variables(args, facts):
    # Passing the checkpoint and stage lists keeps every job on the plan submitted here.
    return [f"CONFIG={args.config}", f"OUT={args.out}", f"BIN={args.bin}"] + [f"{k}={v}" for k, v in facts.items()]


def read_plan(variables):
    result = subprocess.run(["make", "-s", "-C", WORKFLOWS, "slurm-plan", *variables], capture_output=True,
                            text=True)
    if result.returncode != 0:
        fail(f"make slurm-plan failed:\n{result.stderr}")
    steps = [Step(line) for line in result.stdout.splitlines() if line.strip()]
    names = {s.name for s in steps}
    for step in steps:
        for name in step.after:
            if name != "*" and name not in names:
                fail(f"step {step.name} waits for unknown step {name}")
    return steps


def up_to_date(targets, variables):
    return subprocess.run(["make", "-q", "-C", WORKFLOWS, *variables, *targets],
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0


def upstream(step, earlier):
    return earlier if "*" in step.after else [s for s in earlier if s.name in step.after]


def job_script(step, waits_for, args, variables, resources, log_dir):
    """Writes RUN_DIR/slurm/jobs/<step>.sh: the job's sbatch options and its make-step.sh call."""
    log = os.path.join(log_dir, f"{step.name}-%A_%a.log" if step.tasks > 1 else f"{step.name}-%j.log")
    options = {"--job-name": f"aniso-{step.name}", "--output": log, "--ntasks": str(args.ranks if step.mpi else 1)}
    options.update(resources.get(step.kind, {}))
    upstream_files = [f"--upstream={path}" for s in waits_for for path in s.expanded_targets()]
    body = [STEP_SCRIPT, WORKFLOWS, *variables, *upstream_files, *step.targets]
    lines = ["#!/bin/bash", f"# aniso campaign step {step.name}, written by workflows/slurm/submit.py"]
    lines += [f"#SBATCH {key}={value}" for key, value in options.items()]
    lines += [f"#SBATCH {argument}" for argument in args.sbatch_arg]
    lines += [f"export ANISO_SLURM_LAUNCHER=${{ANISO_SLURM_LAUNCHER:-{shlex.quote(args.launcher)}}}",
              "exec " + " \\\n  ".join(shlex.quote(word) for word in body), ""]
    path = os.path.join(log_dir, "jobs", f"{step.name}.sh")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as script:
        script.write("\n".join(lines))
    os.chmod(path + ".tmp", 0o755)
    os.replace(path + ".tmp", path)
    return path


def sbatch_command(step, waits_for, script):
    command = ["sbatch", "--parsable"]
    if step.tasks > 1:
        whole = step.indices == list(range(step.tasks))
        command.append(f"--array=0-{step.tasks - 1}" if whole else "--array=" + ",".join(map(str, step.indices)))
    job_ids = [s.job_id for s in waits_for if s.job_id]
    if job_ids:
        # --kill-on-invalid-dep: a failed upstream job cancels this one instead of leaving it pending
        command += ["--dependency=afterok:" + ":".join(job_ids), "--kill-on-invalid-dep=yes"]
    return command + [script]


def submit(steps, args, variables, resources):
    log_dir = os.path.join(args.out, "slurm")
    os.makedirs(log_dir, exist_ok=True)
    submitted = []
    for index, step in enumerate(steps):
        waits_for = upstream(step, steps[:index])
        if not any(s.job_id for s in waits_for):
            # Nothing upstream reruns: only the array tasks whose files are missing or stale go again
            # (one deleted probe fork resubmits that fork, not all seven).
            step.indices = [k for k in range(step.tasks) if not up_to_date(step.task_targets(k), variables)]
            if not step.indices:
                say(f"{step.name}: up to date, not submitted")
                continue
        command = sbatch_command(step, waits_for, job_script(step, waits_for, args, variables, resources, log_dir))
        if args.dry_run:
            print(shlex.join(command))
            step.job_id = f"<{step.name}>"
            submitted.append(step)  # a later step's dependency names it (make paper's figures job)
            continue
        env = dict(os.environ, ANISO_SLURM_LAUNCHER=args.launcher)
        result = subprocess.run(command, capture_output=True, text=True, env=env)
        if result.returncode != 0:
            queued = " ".join(s.job_id for s in submitted)
            fail(f"sbatch refused step {step.name}: {result.stderr.strip()}"
                 + (f"; already queued: {queued} (scancel them, or fix the cause and submit again)" if queued else ""))
        step.job_id = result.stdout.strip().split(";")[0]
        submitted.append(step)
        with open(os.path.join(log_dir, "jobs.tsv"), "a") as table:  # at once: a later refusal keeps it
            table.write(f"{step.name}\t{step.job_id}\t{step.tasks}\t{' '.join(step.targets)}\n")
        say(f"{step.name}: job {step.job_id}"
            + (f" (array of {step.tasks})" if step.tasks > 1 and len(step.indices) == step.tasks else "")
            + (f" (tasks {','.join(map(str, step.indices))} of {step.tasks})" if len(step.indices) < step.tasks else "")
            + (f", after {','.join(s.job_id for s in waits_for if s.job_id)}"
               if any(s.job_id for s in waits_for) else ""))
    return submitted


def job_states(job_id):
    """{array task id ("" for a plain job): state} of a job; {} once SLURM has forgotten it."""
    result = subprocess.run(["scontrol", "-o", "show", "job", job_id], capture_output=True, text=True)
    if result.returncode != 0 and "Invalid job id" not in result.stderr:
        fail(f"cannot ask SLURM about job {job_id}: {result.stderr.strip()} (the jobs go on; watch them with squeue)")
    states = {}
    for line in result.stdout.splitlines():
        fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
        states[fields.get("ArrayTaskId", "")] = fields.get("JobState", "UNKNOWN")
    return states


def report_end(step, states, log_dir):
    """Says how a finished job ended; True when every task completed."""
    bad = {task: state for task, state in states.items() if state not in ENDED_OK}
    if not bad:
        say(f"{step.name}: job {step.job_id} completed")
        return True
    if set(bad.values()) == {"CANCELLED"} and len(bad) == len(states):
        say(f"{step.name}: job {step.job_id} ended CANCELLED (a job it waits for failed, or scancel)")
        return False
    for task, state in sorted(bad.items()):
        log = os.path.join(log_dir, f"{step.name}-{step.job_id}_{task}.log" if task else
                           f"{step.name}-{step.job_id}.log")
        say(f"{step.name}: job {step.job_id}{' task ' + task if task else ''} ended {state}; log: {log}")
    return False


def wait(steps, log_dir):
    """Polls after 0.5 s, then 1.5 times longer each round up to 30 s (a short test campaign ends
    quickly; a day-long one asks SLURM about twice a minute). True when all completed."""
    pending = {s.job_id: s for s in steps}
    ok = True
    interval = 0.5
    while pending:
        for job_id, step in list(pending.items()):
            states = job_states(job_id)
            if not states:
                say(f"{step.name}: job {job_id} is no longer known to SLURM")
                ok = False
            elif set(states.values()) & STILL_RUNNING:
                continue
            else:
                ok = report_end(step, states, log_dir) and ok
            del pending[job_id]
        if pending:
            time.sleep(interval)
            interval = min(30.0, 1.5 * interval)
    return ok


def submit_campaign(args):
    """Submits one campaign (args.config into args.out); returns its submitted steps."""
    if not os.path.isfile(args.config):
        fail(f"config file {args.config} not found")
    facts, resources = campaign_facts(args)
    variables = make_variables(args, facts)
    return submit(read_plan(variables), args, variables, resources)


def paper_runs(args):
    """[(config, run folder)] of make paper: PAPER_DIR/<shape>/r<k>, its config written now."""
    runs = []
    for shape in args.paper_shapes.split():
        source = os.path.join(args.paper_configs, f"paper-{shape}.toml")
        if not os.path.isfile(source):
            fail(f"--paper-shapes names '{shape}', but {source} does not exist")
        for k in range(1, args.realisations + 1):
            config = os.path.join(args.out, "configs", f"{shape}-r{k}.toml")
            result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "campaign.py"), "realisation", source,
                                     str(k), config])
            if result.returncode != 0:
                fail(f"campaign.py realisation {source} {k} failed")
            runs.append((config, os.path.join(args.out, shape, f"r{k}")))
    return runs


def submit_paper(args):
    """Every run's campaign, then the figures after all of them (one serial job)."""
    paper_out = args.out
    submitted, reports = [], []
    for config, out in paper_runs(args):
        args.config, args.out = config, out
        steps = submit_campaign(args)
        submitted += steps
        reports += [s for s in steps if s.name == "report"]
    args.out = paper_out
    variables = [f"PAPER_OUT={paper_out}", f"BIN={args.bin}", f"PAPER_CONFIGS={args.paper_configs}",
                 f"PAPER_SHAPES={args.paper_shapes}", f"REALISATIONS={args.realisations}"]
    figures = Step(f"paper-figures 1 serial {','.join(s.name for s in reports) or '-'} "
                   f"{os.path.join(paper_out, 'comparison.md')}")
    figures.kind = "report"  # its resources: [workflow.resources.report] does not apply (no config here)
    if not reports and up_to_date(figures.targets, variables):
        say("paper-figures: up to date, not submitted")
        return submitted
    log_dir = os.path.join(paper_out, "slurm")
    # No --upstream files: the figures' make rule itself needs every run's report.md.
    script = job_script(figures, [], args, variables + ["paper-figures"], {}, log_dir)
    command = sbatch_command(figures, reports, script)
    if args.dry_run:
        print(shlex.join(command))
        return submitted
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        fail(f"sbatch refused step paper-figures: {result.stderr.strip()}")
    figures.job_id = result.stdout.strip().split(";")[0]
    say(f"paper-figures: job {figures.job_id}" + (f", after {len(reports)} report jobs" if reports else ""))
    return submitted + [figures]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--config", help="campaign configuration (TOML); not with --paper")
    parser.add_argument("--paper", action="store_true", help="submit make paper's campaigns and figures")
    parser.add_argument("--realisations", type=int, default=1, help="with --paper: seeds per shape [1]")
    parser.add_argument("--paper-configs", default=os.path.join(WORKFLOWS, "configs"),
                        help="with --paper: the folder of paper-<shape>.toml [workflows/configs]")
    parser.add_argument("--paper-shapes", default="spheres ovoids-0.8 ovoids-0.625 ovoids-0.5",
                        help="with --paper: the shapes [all four]")
    parser.add_argument("--out", required=True, help="run folder (shared by all nodes)")
    parser.add_argument("--bin", required=True, help="build folder holding <stage>/aniso-<stage>")
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks of each MPI step [1]")
    parser.add_argument("--launcher", default="srun", help="starts the stages inside a job [srun]")
    parser.add_argument("--sbatch-arg", action="append", default=[], help="extra sbatch option (repeatable)")
    parser.add_argument("--dry-run", action="store_true", help="print the sbatch commands, submit nothing")
    parser.add_argument("--wait", action="store_true", help="wait for the jobs; exit 1 if any did not complete")
    args = parser.parse_args()
    if args.ranks < 1:
        fail("--ranks must be at least 1")
    if args.paper == (args.config is not None):
        fail("give either --config (one campaign) or --paper (the paper's study)")
    if args.realisations < 1:
        fail("--realisations must be at least 1")
    for name in ("config", "out", "bin", "paper_configs"):
        if getattr(args, name) is not None:
            setattr(args, name, os.path.abspath(getattr(args, name)))
    steps = submit_paper(args) if args.paper else submit_campaign(args)
    if args.dry_run:
        return
    if not steps:
        say("nothing to submit: the campaign is up to date")
    elif args.wait and not wait(steps, os.path.join(args.out, "slurm")):
        sys.exit(1)


if __name__ == "__main__":
    main()
