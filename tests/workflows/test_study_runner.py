#!/usr/bin/python3
"""workflows/studies/runner.py, the studies' one runner, on small commands whose effects are known:
a run writes its log and record and is not run again while its outputs and record are there; a
run without its record (killed) or with an output missing is run again; an exit status outside
`accept` stops with StudyError naming the command, the status and the log's last lines, and leaves
no record; an accepted non-zero status is recorded; an exit 0 that did not write its outputs is an
error; RunTable keeps rows across instances; cached_load's record check; and a study script stops
with exit 1 and the runner's message when its stage fails (load_behaviours.py on a missing build).

usage: test_study_runner.py SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
STUDIES = os.path.join(SOURCE, "workflows", "studies")
sys.path.insert(0, STUDIES)

import runner  # noqa: E402

PYTHON = "/usr/bin/python3"


def counting_command(counter, output, code=0, message="ran"):
    """A command that appends a line to COUNTER, prints MESSAGE, writes OUTPUT (unless None), exits CODE."""
    write = f"open({output!r}, 'w').write('x')" if output else "None"
    return [PYTHON, "-c", f"open({counter!r}, 'a').write('1\\n'); print({message!r}); {write}; raise SystemExit({code})"]


def runs(counter):
    if not os.path.exists(counter):
        return 0
    with open(counter) as f:
        return len(f.read().split())


class RunCached(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.folder = os.path.join(self.tmp.name, "run")
        self.counter = os.path.join(self.tmp.name, "count")
        self.output = os.path.join(self.folder, "out.h5")

    def tearDown(self):
        self.tmp.cleanup()

    def test_runs_once_and_records(self):
        first = runner.run_cached(counting_command(self.counter, self.output), self.folder, outputs=[self.output])
        self.assertEqual(first.code, 0)
        self.assertGreaterEqual(first.wall, 0.0)
        second = runner.run_cached(counting_command(self.counter, self.output), self.folder, outputs=[self.output])
        self.assertEqual(runs(self.counter), 1)
        self.assertEqual(second, first)
        with open(os.path.join(self.folder, "log.txt")) as log:
            self.assertIn("ran", log.read())
        record = runner.read_record(self.folder)
        self.assertEqual(record["code"], 0)
        self.assertEqual(record["command"][0], PYTHON)
        self.assertIn("load_average", record)

    def test_reruns_without_record_or_output(self):
        runner.run_cached(counting_command(self.counter, self.output), self.folder, outputs=[self.output])
        os.remove(runner.record_path(self.folder))  # as if killed before the record was written
        runner.run_cached(counting_command(self.counter, self.output), self.folder, outputs=[self.output])
        os.remove(self.output)
        runner.run_cached(counting_command(self.counter, self.output), self.folder, outputs=[self.output])
        self.assertEqual(runs(self.counter), 3)

    def test_failure_names_command_status_and_log(self):
        with self.assertRaises(runner.StudyError) as caught:
            runner.run_cached(counting_command(self.counter, None, code=3, message="the stage's last words"),
                              self.folder, outputs=[self.output])
        text = str(caught.exception)
        self.assertIn("exit 3", text)
        self.assertIn("the stage's last words", text)
        self.assertIn(os.path.join(self.folder, "log.txt"), text)
        self.assertIsNone(runner.read_record(self.folder))

    def test_accepted_status_is_recorded_once(self):
        for _ in range(2):
            done = runner.run_cached(counting_command(self.counter, None, code=5), self.folder, log="prepare.log",
                                     accept=(0, 5))
            self.assertEqual(done.code, 5)
        self.assertEqual(runs(self.counter), 1)
        self.assertEqual(runner.read_record(self.folder, "prepare.log")["code"], 5)
        self.assertTrue(os.path.exists(os.path.join(self.folder, "prepare.run.json")))

    def test_exit_zero_without_outputs_is_an_error(self):
        with self.assertRaises(runner.StudyError) as caught:
            runner.run_cached(counting_command(self.counter, None), self.folder, outputs=[self.output])
        self.assertIn("did not write", str(caught.exception))
        self.assertIn(self.output, str(caught.exception))


class Tables(unittest.TestCase):
    def test_run_table_keeps_rows(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "t.csv")
            table = runner.RunTable(path, ["a", "b"])
            table.add({"a": 1, "b": 2.5})
            again = runner.RunTable(path, ["a", "b"])
            self.assertEqual(again.find(lambda r: r["a"] == "1"), {"a": "1", "b": "2.5"})
            self.assertIsNone(again.find(lambda r: r["a"] == "2"))

    def test_finished_load_needs_record(self):
        with tempfile.TemporaryDirectory() as tmp:
            self.assertIsNone(runner.finished_load(tmp, 0.01))
            with open(runner.record_path(tmp), "w") as f:
                json.dump({"code": 0, "wall_seconds": 1.0, "cpu_seconds": 1.0}, f)
            self.assertIsNone(runner.finished_load(tmp, 0.01))  # no history.h5


class StudyScript(unittest.TestCase):
    def test_failed_stage_stops_the_study(self):
        with tempfile.TemporaryDirectory() as tmp:
            prepared = os.path.join(tmp, "prepared.h5")
            import h5py
            with h5py.File(prepared, "w") as f:
                f["particles/diameter"] = [1.0, 2.0]
            done = subprocess.run([PYTHON, os.path.join(STUDIES, "load_behaviours.py"), os.path.join(tmp, "nobuild"),
                                   os.path.join(tmp, "work"), "0.01", f"a=:{prepared}", "--", "oval"],
                                  capture_output=True, text=True)
            self.assertEqual(done.returncode, 1, done.stderr)
            self.assertIn("load_behaviours.py:", done.stderr)
            self.assertIn("could not start", done.stderr)
            self.assertIn("aniso-dem", done.stderr)

    def test_unknown_behaviour_is_refused_before_any_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run([PYTHON, os.path.join(STUDIES, "load_behaviours.py"), tmp, os.path.join(tmp, "work"),
                                   "0.01", "a=:x.h5", "--", "sideways"], capture_output=True, text=True)
            self.assertEqual(done.returncode, 1)
            self.assertIn("unknown behaviour 'sideways'", done.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "work", "a_sideways")))


if __name__ == "__main__":
    unittest.main()
