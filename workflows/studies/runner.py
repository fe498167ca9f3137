"""The one runner of the studies (workflows/studies/README.md): every stage run of every study goes
through run_cached, which

- skips a run whose outputs and record are already there, so an interrupted study resumes where it
  stopped (delete the run's folder, or its record, to redo it);
- keeps the run's output in its own log file and its record beside it (log.run.json for log.txt): the command, the
  exit status, the wall and CPU seconds, the host's load average when it started;
- stops the study with StudyError, naming the command, the exit status and the log with its last
  lines, when a stage fails (exit statuses a study expects, such as aniso-dem's 5 for a target it
  missed, are accepted and recorded instead).

RunTable keeps a study's measured rows in a CSV as they come, and cached_load the DEM loadings the
convergence studies compare. Importing this module also puts workflows/plots on the path, so that the
studies read every stage file with the plotting library's readers (readers.py)."""
import csv
import json
import os
import resource
import subprocess
import sys
import time
from dataclasses import dataclass

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "plots"))

from readers import read_history  # noqa: E402

TAIL_LINES = 15


class StudyError(RuntimeError):
    """A stage run failed: the message names the command, its exit status and its log."""


@dataclass
class Run:
    code: int
    wall: float
    cpu: float


def stage(build, name):
    """The executable of a stage in a build folder: stage(build, 'dem') is BUILD/dem/aniso-dem."""
    return os.path.join(build, name, f"aniso-{name}")


def settings_arguments(settings):
    """['--set', 'k=v', ...] for key=value strings."""
    return [arg for setting in settings for arg in ("--set", setting)]


def record_path(folder, log="log.txt"):
    """The record of the run logged to FOLDER/LOG: FOLDER/log.run.json for log.txt."""
    return os.path.join(folder, os.path.splitext(log)[0] + ".run.json")


def log_tail(path, lines=TAIL_LINES):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


def run_cached(command, folder, outputs=(), log="log.txt", accept=(0,), env=None):
    """Runs `command` with its output in FOLDER/LOG unless its record (record_path) and every path of
    `outputs` exist already; returns the Run (exit code, wall and CPU seconds) either way. A run whose
    exit code is not in `accept` raises StudyError and leaves no record, so it is redone next time."""
    os.makedirs(folder, exist_ok=True)
    record = record_path(folder, log)
    if os.path.exists(record) and all(os.path.exists(p) for p in outputs):
        with open(record) as f:
            done = json.load(f)
        return Run(done["code"], done["wall_seconds"], done["cpu_seconds"])
    log_path = os.path.join(folder, log)
    load_average = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with open(log_path, "w") as out:
        try:
            code = subprocess.run([str(c) for c in command], stdout=out, stderr=subprocess.STDOUT,
                                  env=None if env is None else {**os.environ, **env}).returncode
        except OSError as error:  # no such executable (a stage not built), not executable
            raise StudyError(f"{' '.join(str(c) for c in command)}\ncould not start: {error}") from None
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if code not in accept:
        raise StudyError(f"{' '.join(str(c) for c in command)}\nfailed with exit {code}; its log, {log_path}, "
                         f"ends:\n{log_tail(log_path)}")
    missing = [p for p in outputs if not os.path.exists(p)]
    if code == 0 and missing:
        raise StudyError(f"{' '.join(str(c) for c in command)}\nexited 0 but did not write {', '.join(missing)} "
                         f"(log: {log_path})")
    with open(record, "w") as f:
        json.dump({"command": [str(c) for c in command], "code": code, "wall_seconds": wall, "cpu_seconds": cpu,
                   "load_average": load_average}, f, indent=1)
    return Run(code, wall, cpu)


def read_record(folder, log="log.txt"):
    """The record run_cached kept of the run logged to FOLDER/LOG ({command, code, wall_seconds,
    cpu_seconds, load_average}), or None where there is none (not run, running, or failed)."""
    try:
        with open(record_path(folder, log)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def main_guarded(main, *args):
    """Calls main(*args); a StudyError ends the study with its message and exit status 1."""
    try:
        return main(*args)
    except StudyError as error:
        sys.exit(f"{os.path.basename(sys.argv[0])}: {error}")


class RunTable:
    """A CSV of measured runs that a study fills as it goes: runs already listed are reused, and each new
    row is written at once, so an interrupted study resumes where it stopped (delete the CSV to redo
    every run)."""

    def __init__(self, path, fields):
        self.path = path
        self.fields = fields
        self.rows = []
        if os.path.exists(path):
            with open(path) as f:
                self.rows = list(csv.DictReader(f))

    def find(self, matches):
        """The first row for which matches(row) is true, or None."""
        return next((row for row in self.rows if matches(row)), None)

    def add(self, row):
        """Appends a row (values kept as text, as read back) and rewrites the CSV; returns the stored row."""
        self.rows.append({k: str(v) for k, v in row.items()})
        with open(self.path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=self.fields)
            writer.writeheader()
            writer.writerows(self.rows)
        return self.rows[-1]


def finished_load(folder, final_strain):
    """(history, wall seconds) of a load in `folder` that reached `final_strain` and has its record, else None."""
    record = read_record(folder)
    try:
        h = read_history(os.path.join(folder, "history.h5"))
    except (OSError, KeyError):
        return None
    if record is None:
        return None
    wall = record["wall_seconds"]
    if abs(-h["strain_11"][-1] - final_strain) < 1e-3 * final_strain:
        return h, wall
    return None


def cached_load(binary, prepared, folder, settings, final_strain):
    """Runs `aniso-dem load` of `prepared` with `settings` (key=value strings) into `folder`, to
    `final_strain` with 200 history rows, unless a finished run is there. Returns (history, wall seconds)."""
    if (done := finished_load(folder, final_strain)) is not None:
        return done
    command = [binary, "load", "--input", prepared, "--overwrite",
               *settings_arguments([f"dem.output_dir={folder}", f"dem.load.final_strain={final_strain}",
                                    f"dem.load.history_interval={final_strain / 200}", *settings])]
    if os.path.exists(record_path(folder)):
        os.remove(record_path(folder))  # the record of a run to another strain: redo it
    run = run_cached(command, folder, outputs=[os.path.join(folder, "history.h5")])
    return read_history(os.path.join(folder, "history.h5")), run.wall
