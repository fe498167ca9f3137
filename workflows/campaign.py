#!/usr/bin/python3
"""Facts about a campaign that the Makefile and the SLURM submitter both need.

usage:
  campaign.py checkpoints CONFIG BIN [STAGE]
                                       the load checkpoints' stems (load_000 ...), from the effective config;
                                       with STAGE (probe, voxel or lbm) only those [workflow] gives that stage
  campaign.py stages BIN               the analysis stages built with the command line the workflow calls
  campaign.py load-input OUT SETTINGS  the arguments of `aniso-dem load` that continue an interrupted run
  campaign.py check CONFIG BIN [SETTINGS]
                                       validates the whole config before any stage runs: every built stage
                                       reads its own section (`--print-config`, the stage's own validator)
                                       and the [workflow] section is checked against the checkpoints; with
                                       SETTINGS (a run's settings/ folder), each stage's effective settings are
                                       written there as <stage>.json, rewritten only when they change
  campaign.py resources CONFIG         the SLURM resources of [workflow.resources] as JSON, validated
  campaign.py status OUT N             what the run OUT has written so far, per kind of step: reads the job
                                       plan (`make slurm-plan` lines) on stdin; N is the number of checkpoints;
                                       an unfinished prepare lists its kept pieces, an unfinished load the
                                       strain its history reaches
  campaign.py realisation CONFIG K OUT writes OUT, the config of realisation K (1, 2, ...) of CONFIG:
                                       CONFIG itself for K = 1, else with dem.seed raised by K - 1
                                       (make paper REALISATIONS=N); rewritten only when it changes

`stages` prints one word per built stage (its executable exists under BIN), then the optional
command lines they offer (lbm-directions: one LBM run per flow direction); for every other stage
it writes one line to stderr saying why it is skipped. BIN is one build of this source tree
(make build-stages), so a built stage offers every command line the workflow calls.

The campaign's own section of the config, all keys optional:

  [workflow]
  probe_strains = [...]   checkpoint strains that get the probes (default: every checkpoint)
  voxel_strains = [...]   checkpoint strains that get the voxel image and void morphology (default: every)
  lbm_strains = [...]     checkpoint strains that get the permeability; each must be in voxel_strains
                          (default: voxel_strains)

Every strain named must be one of dem.load.checkpoint_strains (relative 1e-9); an
unknown key, a value that is not a list of numbers, or a strain that is not a
checkpoint stops with a message naming the key and the value.

The SLURM resources of each kind of job (slurm/submit.py), all optional:

  [workflow.resources.load]      one table per kind: prepare, load, fabric, probe,
  time = "12:00:00"              probe-collect, voxel, lbm, lbm-collect, series, report
  mem = "4G"                     sbatch --time (D-HH:MM:SS, HH:MM:SS, MM:SS or minutes), --mem
  ranks = 2                      (a number with K, M, G or T), --ntasks of an MPI job (the
  cpus_per_task = 1              collect, series and report jobs are serial), --cpus-per-task

A run folder keeps each stage's files in a folder of its own (docs/user-guide.md, "The run
folder"): dem/ (prepared.h5, load_NNN.h5, history), fabric/, probe/, voxel/, lbm/, beside
figures/, logs/, slurm/ and report.md.

The Makefile's stages depend on their own SETTINGS/<stage>.json (the values the stage's
--print-config gives, comments left out), not on the config file: editing
[lbm] reruns the flows, not the DEM, and a comment or a [workflow] change reruns nothing but
what it selects anew. A settings file that is new (the first run, or a run folder older than
these files) is dated as the config file, so that results newer than the config stay valid
(the run folder's settings/ also records what each stage ran with).

`load-input OUT SETTINGS` (OUT the DEM's folder, SETTINGS the DEM's settings file, or the config)
resumes from the newest checkpoint of this run that history.h5 already covers (history.h5 is
rewritten just after each checkpoint, so a kill between the two leaves the newer checkpoint
uncovered) and that is newer than prepared.h5 and SETTINGS; where the checkpoints are relaxed copies
(dem.equilibrium.fork_checkpoints), from load_resume.h5, the loading's own state at the
newest of them; otherwise it starts from prepared.h5, with --overwrite
when files of an earlier (stale) loading run are there.
"""
import csv
import json
import os
import re
import subprocess
import sys
import tomllib

# stage -> its executable under BIN.
STAGE_EXECUTABLES = {
    "fabric": "fabric/aniso-fabric",
    "probe": "probe/aniso-probe",
    "voxel": "voxel/aniso-voxel",
    "lbm": "lbm/aniso-lbm",
}
# Optional command lines of a built stage: feature -> stage. lbm-directions: one flow direction
# per run (--direction D), then `collect`, for job arrays.
STAGE_FEATURES = {"lbm-directions": "lbm"}


# The exit codes and kinds of common/error.hpp (docs/user-guide.md, "Exit codes").
BAD_INPUT, FILE_ERROR = 2, 3
ERROR_KINDS = {BAD_INPUT: "bad input", FILE_ERROR: "file error"}


def fail(message, code=BAD_INPUT):
    """Stops as the programs do: 'campaign.py: error (kind): message' and the kind's exit code."""
    print(f"campaign.py: error ({ERROR_KINDS[code]}): {message}", file=sys.stderr)
    sys.exit(code)


# [workflow] keys: the stage they select checkpoints for, and the key whose strains bound them.
WORKFLOW_KEYS = {"probe_strains": None, "voxel_strains": None, "lbm_strains": "voxel_strains"}
# The kinds of SLURM job (slurm/submit.py; workflows/Makefile's slurm-plan) and whether they run MPI.
JOB_KINDS = {"prepare": True, "load": True, "fabric": True, "probe": True, "probe-collect": False,
             "voxel": True, "lbm": True, "lbm-collect": False, "series": False, "report": False}
# [workflow.resources.KIND] keys: sbatch option, and the check of the value with what it expects.
RESOURCE_KEYS = {
    "time": ("--time", lambda v: isinstance(v, str) and re.fullmatch(r"(\d+-)?\d+(:\d\d){0,2}", v),
             'a SLURM time such as "12:00:00" or "1-00:00:00"'),
    "mem": ("--mem", lambda v: isinstance(v, str) and re.fullmatch(r"\d+[KMGT]?", v), 'a size such as "4G"'),
    "ranks": ("--ntasks", lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= 1,
              "an integer >= 1"),
    "cpus_per_task": ("--cpus-per-task", lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= 1,
                      "an integer >= 1"),
}
SELECTING_STAGES = {"probe": "probe_strains", "voxel": "voxel_strains", "lbm": "lbm_strains"}


def checkpoint_strains(config, bin_dir):
    dem = os.path.join(bin_dir, "dem", "aniso-dem")
    if not os.access(dem, os.X_OK):
        fail(f"{dem} not found: build it first (make build)", FILE_ERROR)
    printed = subprocess.run([dem, "--config", config, "--print-config", "--log-level", "error"],
                             capture_output=True, text=True)
    if printed.returncode != 0:
        fail(f"'{dem} prepare --config {config} --print-config' failed:\n{printed.stderr.rstrip()}",
             printed.returncode if printed.returncode in ERROR_KINDS else BAD_INPUT)
    return tomllib.loads(printed.stdout)["dem"]["load"]["checkpoint_strains"]


def workflow_section(config):
    try:
        with open(config, "rb") as f:
            section = tomllib.load(f).get("workflow", {})
    except OSError as error:
        fail(f"{config}: cannot read the config: {error.strerror}", FILE_ERROR)
    except tomllib.TOMLDecodeError as error:
        fail(f"{config}: not valid TOML: {error}")
    if not isinstance(section, dict):
        fail(f"{config}: [workflow] must be a table, not {section!r}")
    for key in section:
        if key not in WORKFLOW_KEYS and key != "resources":
            fail(f"{config}: unknown key workflow.{key}; allowed: {', '.join(WORKFLOW_KEYS)}, resources")
    check_resources(config, section.get("resources", {}))
    return section


def check_resources(config, resources):
    """[workflow.resources]: a table of job kinds, each a table of known keys with valid values."""
    if not isinstance(resources, dict):
        fail(f"{config}: workflow.resources must be a table of job kinds, not {resources!r}")
    for kind, table in resources.items():
        if kind not in JOB_KINDS:
            fail(f"{config}: unknown job kind workflow.resources.{kind}; allowed: {', '.join(JOB_KINDS)}")
        if not isinstance(table, dict):
            fail(f"{config}: workflow.resources.{kind} must be a table, not {table!r}")
        for key, value in table.items():
            if key not in RESOURCE_KEYS:
                fail(f"{config}: unknown key workflow.resources.{kind}.{key}; allowed: {', '.join(RESOURCE_KEYS)}")
            if not RESOURCE_KEYS[key][1](value):
                fail(f"{config}: workflow.resources.{kind}.{key} = {value!r}: expected {RESOURCE_KEYS[key][2]}")
        if table.get("ranks", 1) > 1 and not JOB_KINDS[kind]:
            fail(f"{config}: workflow.resources.{kind}.ranks = {table['ranks']}: the {kind} job is serial")


def sbatch_resources(config):
    """{kind: {sbatch option: value}} of [workflow.resources]."""
    resources = workflow_section(config).get("resources", {})
    return {kind: {RESOURCE_KEYS[key][0]: str(value) for key, value in table.items()}
            for kind, table in resources.items()}


def strain_indices(config, key, values, strains):
    """Indices into `strains` of the strains listed under workflow.`key`."""
    if not isinstance(values, list) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                               for v in values):
        fail(f"{config}: workflow.{key} = {values!r}: expected a list of checkpoint strains")
    indices = []
    for value in values:
        matches = [k for k, s in enumerate(strains) if abs(s - value) <= 1e-9 * max(abs(s), abs(value))]
        if not matches:
            fail(f"{config}: workflow.{key} = {values!r}: {value!r} is not one of "
                 f"dem.load.checkpoint_strains {strains}")
        indices.append(matches[0])
    return sorted(set(indices))


def selected_indices(config, strains):
    """For each [workflow] key, the checkpoint indices it selects (validated)."""
    section = workflow_section(config)
    selected = {}
    for key, bound in WORKFLOW_KEYS.items():  # a key's bound comes before it
        default = selected[bound] if bound else list(range(len(strains)))
        selected[key] = strain_indices(config, key, section[key], strains) if key in section else default
        if bound and not set(selected[key]) <= set(selected[bound]):
            fail(f"{config}: workflow.{key} = {section[key]!r}: every strain must also be in workflow.{bound}")
    return selected


def checkpoint_stems(config, bin_dir, stage=None):
    strains = checkpoint_strains(config, bin_dir)
    indices = range(len(strains))
    if stage is not None:
        if stage not in SELECTING_STAGES:
            fail(f"no checkpoint selection for stage {stage!r}; allowed: {', '.join(SELECTING_STAGES)}")
        indices = selected_indices(config, strains)[SELECTING_STAGES[stage]]
    return [f"load_{index:03d}" for index in indices]


def write_settings(path, text, dated_as):
    """PATH holds TEXT, rewritten only when it differs, so that its time is when the stage's settings
    last changed; a new file gets the time of DATED_AS (the config file)."""
    try:
        with open(path) as f:
            if f.read() == text:
                return
        new = False
    except FileNotFoundError:
        new = True
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path + ".tmp", "w") as f:
        f.write(text)
    if new:
        when = os.path.getmtime(dated_as)
        os.utime(path + ".tmp", (when, when))
    os.replace(path + ".tmp", path)


def canonical_settings(stage, printed):
    """The values of a stage's --print-config, without its comments (help texts change between
    versions; the values are what the results depend on), as sorted JSON."""
    try:
        values = tomllib.loads(printed)
    except tomllib.TOMLDecodeError as error:
        fail(f"the {stage} stage's --print-config is not valid TOML ({error}):\n{printed}", FILE_ERROR)
    return json.dumps(values, sort_keys=True, indent=1) + "\n"


def check_config(config, bin_dir, settings_dir=None):
    """Every built stage validates its section of CONFIG, so that a misspelt [lbm] key stops the
    campaign before hours of DEM rather than when the LBM job starts. With SETTINGS_DIR, what each
    stage printed (its effective settings) is kept there as <stage>.json for the Makefile."""
    executables = [("dem", "dem/aniso-dem")] + list(STAGE_EXECUTABLES.items())
    checked = []
    printed_settings = {}
    for stage, relative in executables:
        executable = os.path.join(bin_dir, relative)
        if not os.access(executable, os.X_OK):
            continue  # `stages` says why it is skipped
        printed = subprocess.run([executable, "--config", config, "--print-config", "--log-level", "error"],
                                 capture_output=True, text=True)
        if printed.returncode != 0:
            fail(f"the [{stage}] section of {config} is refused by {os.path.basename(executable)}, "
                 f"before any stage runs:\n{printed.stderr.rstrip()}",
                 printed.returncode if printed.returncode in ERROR_KINDS else BAD_INPUT)
        checked.append(stage)
        printed_settings[stage] = printed.stdout
    selected_indices(config, checkpoint_strains(config, bin_dir))
    if settings_dir is not None:
        for stage, text in printed_settings.items():
            write_settings(os.path.join(settings_dir, f"{stage}.json"), canonical_settings(stage, text), config)
    print(f"campaign: {config} is valid for {', '.join(checked)} and [workflow]", file=sys.stderr)


def usable_stages(bin_dir):
    """The built stages, then the optional features they offer."""
    usable = []
    for stage, relative in STAGE_EXECUTABLES.items():
        executable = os.path.join(bin_dir, relative)
        if os.access(executable, os.X_OK):
            usable.append(stage)
        else:
            print(f"campaign: skipping {stage}: {executable} not found", file=sys.stderr)
    usable += [feature for feature, stage in STAGE_FEATURES.items() if stage in usable]
    return usable


def loading_run_files(out):
    """The files of a loading run in OUT (what `aniso-dem load` refuses to replace without --overwrite)."""
    names = os.listdir(out) if os.path.isdir(out) else []
    return sorted(n for n in names if re.fullmatch(r"history\.(h5|csv)|load_(\d{3,}|interrupted|resume)\.h5", n))


def relaxed_copy(path):
    """A checkpoint that is a relaxed copy of the loading's state (dem.equilibrium.fork_checkpoints):
    not a state the loading passed through, so not a point to resume from."""
    import h5py  # only here: the rest of campaign.py runs without it

    try:
        with h5py.File(path, "r") as f:
            return "relaxed_copy_of_step" in f.attrs
    except OSError:  # not HDF5: aniso-dem load names the file when it cannot read it
        return False


def load_input(out, settings):
    prepared = os.path.join(out, "prepared.h5")
    history = os.path.join(out, "history.h5")
    start = ["--input", prepared]
    stale = loading_run_files(out)
    if stale:
        # make reruns the load because its inputs changed or it never got far: the run there is
        # stale, and the new one replaces it (aniso-dem refuses that without --overwrite).
        start = start + ["--overwrite"]
    if not os.path.exists(history):
        if stale:
            print(f"campaign: starting the load afresh, replacing {', '.join(stale)}", file=sys.stderr)
        return start
    oldest_allowed = max(os.path.getmtime(prepared), os.path.getmtime(settings))
    history_time = os.path.getmtime(history)
    newest = None
    index = 0
    while True:
        path = os.path.join(out, f"load_{index:03d}.h5")
        if not os.path.exists(path):
            break
        written = os.path.getmtime(path)
        if written < oldest_allowed or written > history_time or relaxed_copy(path):
            break
        newest = path
        index += 1
    # Where the checkpoints are relaxed copies, the loading's own state at the newest of them:
    # written just after the history, which always reaches it (aniso-dem load checks the steps).
    resume = os.path.join(out, "load_resume.h5")
    if os.path.exists(resume) and os.path.getmtime(resume) >= oldest_allowed:
        newest = resume
    # A load stopped by SIGTERM (a SLURM time limit) wrote load_interrupted.h5 and then history.h5:
    # it is the resume point when newer than every numbered checkpoint.
    interrupted = os.path.join(out, "load_interrupted.h5")
    if os.path.exists(interrupted):
        written = os.path.getmtime(interrupted)
        if oldest_allowed <= written <= history_time and (newest is None or written > os.path.getmtime(newest)):
            newest = interrupted
    if newest is None:
        print(f"campaign: starting the load afresh, replacing {', '.join(stale)}", file=sys.stderr)
        return start
    print(f"campaign: resuming the interrupted load from {newest}", file=sys.stderr)
    return ["--input", newest, "--resume"]


DEM_HEADER = re.compile(r"^\s*\[\s*dem\s*\]\s*(#.*)?$")
TABLE_HEADER = re.compile(r"^\s*\[")
SEED_LINE = re.compile(r"^\s*seed\s*=")


def with_seed(text, seed):
    """TOML text with dem.seed set to `seed`, every other line (comments included) as it was."""
    lines = text.splitlines(keepends=True)
    header = next((k for k, line in enumerate(lines) if DEM_HEADER.match(line)), None)
    if header is None:
        return text + ("" if text.endswith("\n") or not text else "\n") + f"\n[dem]\nseed = {seed}\n"
    end = next((k for k in range(header + 1, len(lines)) if TABLE_HEADER.match(lines[k])), len(lines))
    for k in range(header + 1, end):
        if SEED_LINE.match(lines[k]):
            lines[k] = f"seed = {seed}\n"
            return "".join(lines)
    lines.insert(header + 1, f"seed = {seed}\n")
    return "".join(lines)


def write_realisation(config, index, out):
    try:
        k = int(index)
    except ValueError:
        k = 0
    if k < 1:
        fail(f"realisation {index!r}: expected an integer >= 1")
    try:
        with open(config) as f:
            text = f.read()
        source = tomllib.loads(text)
    except OSError as error:
        fail(f"{config}: cannot read the config: {error.strerror}", FILE_ERROR)
    except tomllib.TOMLDecodeError as error:
        fail(f"{config}: not valid TOML: {error}")
    seed = source.get("dem", {}).get("seed", 1) + k - 1  # 1: aniso-dem's default seed
    written = text if k == 1 else with_seed(text, seed)
    if tomllib.loads(written).get("dem", {}).get("seed", 1) != seed:
        fail(f"{config}: could not set dem.seed = {seed} for realisation {k}")
    if os.path.exists(out):
        with open(out) as f:
            if f.read() == written:
                return
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    with open(out + ".tmp", "w") as f:
        f.write(written)
    os.replace(out + ".tmp", out)
    print(f"campaign: {out} is realisation {k} of {config} (dem.seed = {seed})", file=sys.stderr)


def run_status(out, n_checkpoints, plan_lines):
    """Lines saying, per kind of step of the plan (prepare, load, probe, ...), how many steps (and
    array tasks) have all their files: what is there, not whether it is up to date (make -q says that)."""
    kinds = {}
    for line in plan_lines:
        words = line.split()
        if len(words) < 5:
            continue
        name, tasks, targets = words[0], int(words[1]), words[4:]
        kind = re.sub(r"-load_\d+$", "", name)
        files_of_task = [[t.replace("{task}", str(k)) for t in targets] for k in range(tasks)]
        done_tasks = sum(all(os.path.exists(f) for f in files) for files in files_of_task)
        counts = kinds.setdefault(kind, [0, 0, 0, 0])  # steps done, steps, tasks done, tasks
        counts[0] += done_tasks == tasks
        counts[1] += 1
        counts[2] += done_tasks
        counts[3] += tasks
    dem = os.path.join(out, "dem")
    names = os.listdir(dem) if os.path.isdir(dem) else []
    written = [n for n in names if re.fullmatch(r"load_\d{3,}\.h5", n)]
    lines = [f"{out}:"]
    for kind, (done, steps, tasks_done, tasks) in kinds.items():
        detail = f" ({tasks_done}/{tasks} tasks)" if tasks > steps else ""
        if kind == "load":
            detail = f" ({len(written)} of {n_checkpoints} checkpoints written)"
            strain = history_strain(dem) if done < steps else None
            if strain is not None:
                detail = detail[:-1] + f", the history at strain {100 * strain:.3g}%)"
        if kind == "prepare" and done < steps:
            detail = prepare_pieces(names)
        lines.append(f"  {kind:<14} {done}/{steps}{detail}")
    return lines


def history_strain(dem):
    """The compressive strain -eps11 of the last row of a load's history.csv (written with history.h5,
    at every checkpoint and kept state), or None when there is none."""
    try:
        with open(os.path.join(dem, "history.csv")) as f:
            last = None
            for last in csv.DictReader(f):
                pass
    except OSError:
        return None
    try:
        return 0.0 - float(last["strain_11"]) if last else None  # 0 - x: no "-0%" at the start
    except (KeyError, ValueError):
        return None


def prepare_pieces(names):
    """What an unfinished prepare has kept (its prepare_*.h5 pieces), as ' (kept: ...)' or ''."""
    pieces = [re.fullmatch(r"prepare_(seized|consolidated)_(\d+)_(\d+)(_interrupted)?\.h5", n) for n in names]
    pieces = [m for m in pieces if m]
    if not pieces:
        return ""
    finished = [m for m in pieces if not m.group(4)]
    cycles = {int(m.group(2)) for m in finished if m.group(1) == "seized" and m.group(3) == "0"}
    refinements = sum(1 for m in finished if m.group(1) == "seized" and m.group(3) != "0")
    consolidated = sum(1 for m in finished if m.group(1) == "consolidated")
    parts = [f"{len(cycles)} cycles seized"]
    if refinements:
        parts.append(f"{refinements} refinements")
    parts.append(f"{consolidated} consolidated")
    in_progress = [m for m in pieces if m.group(4)]
    for m in in_progress:
        what = "compaction" if m.group(1) == "seized" else "consolidation"
        parts.append(f"{what} of cycle {m.group(2)}{'' if m.group(3) == '0' else f' refinement {m.group(3)}'} in progress")
    return f" (kept: {', '.join(parts)})"


def main(argv):
    if len(argv) in (4, 5) and argv[1] == "checkpoints":
        print(" ".join(checkpoint_stems(*argv[2:])))
    elif len(argv) == 3 and argv[1] == "stages":
        print(" ".join(usable_stages(argv[2])))
    elif len(argv) in (4, 5) and argv[1] == "check":
        check_config(*argv[2:])
    elif len(argv) == 3 and argv[1] == "resources":
        print(json.dumps(sbatch_resources(argv[2])))
    elif len(argv) == 4 and argv[1] == "status":
        print("\n".join(run_status(argv[2], int(argv[3]), sys.stdin.read().splitlines())))
    elif len(argv) == 5 and argv[1] == "realisation":
        write_realisation(*argv[2:])
    elif len(argv) == 4 and argv[1] == "load-input":
        print(" ".join(load_input(argv[2], argv[3])))
    else:
        fail(f"unknown command line {' '.join(argv[1:]) or '(none)'}\n{__doc__}")


if __name__ == "__main__":
    main(sys.argv)
