#!/usr/bin/python3
"""Unit tests of workflows/campaign.py (resume point, stage detection) and of
workflows/slurm/submit.py --dry-run (the job plan, without a SLURM cluster).

usage: test_campaign.py SOURCE_DIR BUILD_DIR
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

SOURCE, BUILD = sys.argv[1], sys.argv[2]
WORKFLOWS = os.path.join(SOURCE, "workflows")
DOUBLE = os.path.join(SOURCE, "tests", "workflows", "stage_double.py")


def campaign(*words):
    return subprocess.run([sys.executable, os.path.join(WORKFLOWS, "campaign.py"), *words], capture_output=True,
                          text=True)


def touch(path, when):
    open(path, "a").close()
    os.utime(path, (when, when))


def fake_bin(folder, doubles):
    """A BIN folder: the real aniso-dem and command-line doubles for `doubles`."""
    os.symlink(os.path.join(BUILD, "dem"), os.path.join(folder, "dem"))
    for stage in doubles:
        os.makedirs(os.path.join(folder, stage))
        path = os.path.join(folder, stage, f"aniso-{stage}")
        with open(path, "w") as f:
            f.write(f'#!/bin/sh\nexec /usr/bin/python3 {DOUBLE} {stage} "$@"\n')
        os.chmod(path, 0o755)
    return folder


class LoadInput(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.out = self.dir.name
        self.config = os.path.join(self.out, "c.toml")
        touch(self.config, 1000)
        touch(os.path.join(self.out, "prepared.h5"), 1100)

    def tearDown(self):
        self.dir.cleanup()

    def load_input(self):
        result = campaign("load-input", self.out, self.config)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout.split(), result.stderr

    def test_fresh_run_starts_from_the_prepared_assembly(self):
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/prepared.h5"])

    def test_resumes_from_the_newest_checkpoint_the_history_covers(self):
        touch(f"{self.out}/load_000.h5", 1200)
        touch(f"{self.out}/load_001.h5", 1300)
        touch(f"{self.out}/history.h5", 1301)
        touch(f"{self.out}/load_002.h5", 1400)  # killed before the history was rewritten
        arguments, log = self.load_input()
        self.assertEqual(arguments, ["--input", f"{self.out}/load_001.h5", "--resume"])
        self.assertIn("resuming the interrupted load from", log)

    def test_resumes_from_the_checkpoint_a_sigterm_wrote(self):
        touch(f"{self.out}/load_000.h5", 1200)
        touch(f"{self.out}/load_interrupted.h5", 1250)  # SIGTERM: checkpoint, then the history
        touch(f"{self.out}/history.h5", 1251)
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/load_interrupted.h5", "--resume"])

    def test_a_stale_interrupted_checkpoint_yields_to_newer_numbered_ones(self):
        touch(f"{self.out}/load_interrupted.h5", 1150)  # resumed since, and checkpointed on
        touch(f"{self.out}/load_000.h5", 1200)
        touch(f"{self.out}/history.h5", 1201)
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/load_000.h5", "--resume"])

    def test_checkpoints_older_than_the_config_are_not_resumed(self):
        touch(f"{self.out}/load_000.h5", 900)
        touch(f"{self.out}/history.h5", 950)
        touch(self.config, 1000)
        arguments, log = self.load_input()
        self.assertEqual(arguments, ["--input", f"{self.out}/prepared.h5", "--overwrite"])
        self.assertIn("replacing history.h5, load_000.h5", log)

    def test_checkpoints_older_than_the_prepared_assembly_are_not_resumed(self):
        touch(f"{self.out}/load_000.h5", 1050)
        touch(f"{self.out}/history.h5", 1060)
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/prepared.h5", "--overwrite"])

    def test_a_load_killed_before_its_first_history_is_replaced(self):
        touch(f"{self.out}/load_000.h5", 1200)  # no history.h5 yet: nothing to resume
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/prepared.h5", "--overwrite"])


    def relaxed_copy(self, name, when):
        """A checkpoint written as a relaxed copy (dem.equilibrium.fork_checkpoints)."""
        import h5py

        with h5py.File(f"{self.out}/{name}", "w") as f:
            f.attrs["relaxed_copy_of_step"] = 1000
        os.utime(f"{self.out}/{name}", (when, when))

    def test_relaxed_copies_resume_from_the_loading_state(self):
        self.relaxed_copy("load_000.h5", 1200)
        touch(f"{self.out}/history.h5", 1201)
        touch(f"{self.out}/load_resume.h5", 1202)  # written just after the history
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/load_resume.h5", "--resume"])

    def test_a_relaxed_copy_is_never_the_resume_point(self):
        self.relaxed_copy("load_000.h5", 1200)  # killed before load_resume.h5 was written
        touch(f"{self.out}/history.h5", 1201)
        arguments, log = self.load_input()
        self.assertEqual(arguments, ["--input", f"{self.out}/prepared.h5", "--overwrite"])
        self.assertIn("replacing history.h5, load_000.h5", log)

    def test_a_sigterm_after_the_loading_state_resumes_from_its_file(self):
        self.relaxed_copy("load_000.h5", 1200)
        touch(f"{self.out}/history.h5", 1201)
        touch(f"{self.out}/load_resume.h5", 1202)
        touch(f"{self.out}/load_interrupted.h5", 1300)  # SIGTERM in checkpoint 1's copy
        touch(f"{self.out}/history.h5", 1301)
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/load_interrupted.h5", "--resume"])

    def test_a_loading_state_older_than_the_config_is_not_resumed(self):
        touch(f"{self.out}/load_resume.h5", 900)
        touch(f"{self.out}/history.h5", 950)
        self.assertEqual(self.load_input()[0], ["--input", f"{self.out}/prepared.h5", "--overwrite"])


class Realisation(unittest.TestCase):
    """campaign.py realisation: make paper's config of realisation K (REALISATIONS=N)."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.source = os.path.join(SOURCE, "workflows", "configs", "paper-spheres.toml")

    def tearDown(self):
        self.dir.cleanup()

    def realise(self, source, k):
        out = os.path.join(self.dir.name, f"r{k}.toml")
        return campaign("realisation", source, str(k), out), out

    def test_the_first_is_the_config_itself_and_later_ones_raise_the_seed(self):
        import tomllib

        done, first = self.realise(self.source, 1)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(first) as f, open(self.source) as g:
            self.assertEqual(f.read(), g.read())
        done, third = self.realise(self.source, 3)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(third, "rb") as f, open(self.source, "rb") as g:
            realised, shipped = tomllib.load(f), tomllib.load(g)
        self.assertEqual(realised["dem"]["seed"], shipped["dem"]["seed"] + 2)
        realised["dem"]["seed"] = shipped["dem"]["seed"]
        self.assertEqual(realised, shipped)

    def test_a_config_without_a_seed_gets_one(self):
        source = os.path.join(self.dir.name, "noseed.toml")
        with open(source, "w") as f:
            f.write("[dem.particles]\ncount = 5\n")
        done, out = self.realise(source, 2)
        self.assertEqual(done.returncode, 0, done.stderr)
        import tomllib

        with open(out, "rb") as f:
            self.assertEqual(tomllib.load(f)["dem"], {"seed": 2, "particles": {"count": 5}})

    def test_an_unchanged_config_is_not_rewritten(self):
        _, out = self.realise(self.source, 2)
        os.utime(out, (1000, 1000))
        done, _ = self.realise(self.source, 2)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(os.path.getmtime(out), 1000)

    def test_a_bad_index_is_refused(self):
        done, out = self.realise(self.source, 0)
        self.assertEqual(done.returncode, 2)
        self.assertIn("realisation '0': expected an integer >= 1", done.stderr)
        self.assertFalse(os.path.exists(out))


class Stages(unittest.TestCase):
    def test_only_built_stages_are_used(self):
        with tempfile.TemporaryDirectory() as folder:
            fake_bin(folder, doubles=["probe", "lbm"])
            result = campaign("stages", folder)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertEqual(result.stdout.split(), ["probe", "lbm", "lbm-directions"])
            self.assertRegex(result.stderr, r"skipping fabric: .*aniso-fabric not found")
            self.assertRegex(result.stderr, r"skipping voxel: .*aniso-voxel not found")

    def test_checkpoint_names_come_from_the_effective_config(self):
        result = campaign("checkpoints", os.path.join(WORKFLOWS, "configs", "demo.toml"), BUILD)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout.split(), [f"load_{k:03d}" for k in range(12)])

    def test_every_shipped_config_is_valid(self):
        configs = sorted(glob.glob(os.path.join(WORKFLOWS, "configs", "*.toml")))
        self.assertGreaterEqual(len(configs), 6)  # demo, e2e, paper spheres and three ovoid shapes
        for config in configs:
            dry = subprocess.run([os.path.join(BUILD, "dem", "aniso-dem"), "prepare", "--config", config, "--dry-run",
                                  "--log-level", "error"], capture_output=True, text=True)
            self.assertEqual(dry.returncode, 0, f"{config}: {dry.stderr}")
            checked = campaign("check", config, BUILD)  # every stage's section
            self.assertEqual(checked.returncode, 0, f"{config}: {checked.stderr}")
            for stage in ("probe", "voxel", "lbm"):
                result = campaign("checkpoints", config, BUILD, stage)
                self.assertEqual(result.returncode, 0, f"{config}: {result.stderr}")

    def test_missing_dem_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            result = campaign("checkpoints", os.path.join(WORKFLOWS, "configs", "e2e.toml"), folder)
            self.assertEqual(result.returncode, 3)
            self.assertRegex(result.stderr, r"^campaign.py: error \(file error\): .*aniso-dem not found")

    def test_a_bad_command_line_is_bad_input(self):
        result = campaign("no-such-command")
        self.assertEqual(result.returncode, 2)
        self.assertRegex(result.stderr, r"^campaign.py: error \(bad input\): unknown command line no-such-command")


def e2e_with_workflow(folder, section):
    """The e2e config (checkpoints at strains 1e-4, 5e-3, 0.01) plus a [workflow] section."""
    with open(os.path.join(WORKFLOWS, "configs", "e2e.toml")) as f:
        text = f.read()
    path = os.path.join(folder, "c.toml")
    with open(path, "w") as f:
        f.write(text + "\n[workflow]\n" + section + "\n")
    return path


class CheckpointSelection(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def stems(self, section, stage):
        result = campaign("checkpoints", e2e_with_workflow(self.dir.name, section), BUILD, stage)
        return result.returncode, result.stdout.split(), result.stderr

    def test_every_checkpoint_by_default(self):
        for stage in ("probe", "voxel", "lbm"):
            self.assertEqual(self.stems("", stage)[1], ["load_000", "load_001", "load_002"])

    def test_strains_select_checkpoints_and_lbm_follows_voxel(self):
        section = "probe_strains = [0.01, 1e-4]\nvoxel_strains = [5e-3, 0.01]"
        self.assertEqual(self.stems(section, "probe")[1], ["load_000", "load_002"])
        self.assertEqual(self.stems(section, "voxel")[1], ["load_001", "load_002"])
        self.assertEqual(self.stems(section, "lbm")[1], ["load_001", "load_002"])
        self.assertEqual(self.stems(section + "\nlbm_strains = [0.01]", "lbm")[1], ["load_002"])
        self.assertEqual(self.stems("probe_strains = []", "probe")[1], [])

    def test_bad_sections_are_refused_with_the_key_named(self):
        cases = {
            "probe_strains = [0.02]": "workflow.probe_strains = [0.02]: 0.02 is not one of dem.load.checkpoint_strains",
            "voxel_strains = 0.01": "workflow.voxel_strains = 0.01: expected a list of checkpoint strains",
            "probe_strain = [0.01]": "unknown key workflow.probe_strain",
            "voxel_strains = [0.01]\nlbm_strains = [5e-3]": "every strain must also be in workflow.voxel_strains",
        }
        for section, message in cases.items():
            code, _, log = self.stems(section, "lbm" if "lbm" in section else "probe")
            self.assertEqual(code, 2, section)
            self.assertIn(message, log, section)
            self.assertRegex(log, r"^campaign.py: error \(bad input\): ", section)

    def test_dry_run_plans_only_the_selected_analyses(self):
        bin_dir = os.path.join(self.dir.name, "bin")
        os.mkdir(bin_dir)
        fake_bin(bin_dir, doubles=["fabric", "probe", "voxel", "lbm"])
        config = e2e_with_workflow(self.dir.name, "probe_strains = [0.01]\nvoxel_strains = [1e-4, 0.01]\n"
                                                   "lbm_strains = [0.01]")
        result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config", config,
                                 "--out", os.path.join(self.dir.name, "run"), "--bin", bin_dir, "--dry-run"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        names = [name for name, _ in submitted_plan(result.stdout)]
        self.assertEqual(names, ["prepare", "load", "fabric", "voxel-load_000", "probe-load_002",
                                 "probe-collect-load_002", "voxel-load_002", "lbm-load_002", "lbm-collect-load_002",
                                 "series", "report"])


def submitted_plan(stdout):
    """[(step name, the sbatch command line and the job script it submits)] of a --dry-run."""
    plan = []
    for line in stdout.splitlines():
        script = line.split()[-1]
        with open(script) as f:
            plan.append((re.search(r"jobs/(\S+)\.sh$", script).group(1), line + "\n" + f.read()))
    return plan


class WholeConfigCheck(unittest.TestCase):
    """A misspelt key of a later stage stops the campaign before the DEM starts."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        with open(os.path.join(WORKFLOWS, "configs", "e2e.toml")) as f:
            text = f.read()
        self.config = os.path.join(self.dir.name, "c.toml")
        with open(self.config, "w") as f:
            f.write(text + "\n[lbm]\ntua = 1.0\n")
        self.out = os.path.join(self.dir.name, "run")

    def tearDown(self):
        self.dir.cleanup()

    def assert_refused(self, result):
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        self.assertIn(f"the [lbm] section of {self.config} is refused by aniso-lbm", result.stderr)
        self.assertIn("unknown config key 'lbm.tua'", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.out, "dem", "prepared.h5")), "the DEM ran")

    def test_check_names_the_stage_and_the_key(self):
        self.assert_refused(campaign("check", self.config, BUILD))
        valid = campaign("check", os.path.join(WORKFLOWS, "configs", "e2e.toml"), BUILD)
        self.assertEqual(valid.returncode, 0, valid.stderr)
        self.assertIn("is valid for dem, fabric, probe, voxel, lbm and [workflow]", valid.stderr)

    def test_make_stops_before_the_dem(self):
        result = subprocess.run(["make", "-s", "-C", WORKFLOWS, "campaign", f"CONFIG={self.config}",
                                 f"OUT={self.out}", f"BIN={BUILD}"], capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("unknown config key 'lbm.tua'", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.out, "dem", "prepared.h5")), "the DEM ran")

    def test_submit_stops_before_submitting(self):
        result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config",
                                 self.config, "--out", self.out, "--bin", BUILD, "--dry-run"],
                                capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("unknown config key 'lbm.tua'", result.stderr)
        self.assertNotIn("sbatch", result.stdout)

    def test_every_stage_prints_its_config_without_an_input(self):
        for stage in ("dem", "fabric", "probe", "voxel", "lbm"):
            printed = subprocess.run([os.path.join(BUILD, stage, f"aniso-{stage}"), "--print-config"],
                                     capture_output=True, text=True)
            self.assertEqual(printed.returncode, 0, f"{stage}: {printed.stderr}")
            self.assertIn(f"[{stage}", printed.stdout, stage)


class StageSettings(unittest.TestCase):
    """Each stage's targets depend on its own effective settings (the run's settings/<stage>.json),
    not on the config file: editing [lbm] reruns the flows and what reads them, never the DEM."""

    @classmethod
    def setUpClass(cls):
        # A finished run, made once: every file of the job plan, written in the plan's (dependency)
        # order. Each test works on a copy (copytree keeps the files' times).
        cls.template = tempfile.TemporaryDirectory()
        folder = cls.template.name
        os.mkdir(os.path.join(folder, "bin"))
        fake_bin(os.path.join(folder, "bin"), doubles=["fabric", "probe", "voxel", "lbm"])
        with open(os.path.join(WORKFLOWS, "configs", "e2e.toml")) as f:
            cls.text = f.read()
        config = os.path.join(folder, "c.toml")
        with open(config, "w") as f:
            f.write(cls.text)
        os.utime(config, (1000, 1000))
        plan = subprocess.run(["make", "-s", "-C", WORKFLOWS, "slurm-plan", f"CONFIG={config}",
                               f"OUT={os.path.join(folder, 'run')}", f"BIN={os.path.join(folder, 'bin')}"],
                              capture_output=True, text=True)
        if plan.returncode != 0:
            raise RuntimeError(plan.stderr)
        when = 2000
        for line in plan.stdout.splitlines():
            _, tasks, _, _, *targets = line.split()
            for k in range(int(tasks)):
                for target in targets:
                    os.makedirs(os.path.dirname(target), exist_ok=True)
                    touch(target.replace("{task}", str(k)), when)
                    when += 1

    @classmethod
    def tearDownClass(cls):
        cls.template.cleanup()

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        folder = os.path.join(self.dir.name, "t")
        self.out = os.path.join(folder, "run")
        # Nothing the run holds names its folder, so a copy is the same finished run.
        shutil.copytree(self.template.name, folder, symlinks=True)
        self.bin = os.path.join(folder, "bin")
        self.config = os.path.join(folder, "c.toml")
        self.variables = [f"CONFIG={self.config}", f"OUT={self.out}", f"BIN={self.bin}"]

    def tearDown(self):
        self.dir.cleanup()

    def edit(self, addition, when):
        with open(self.config, "w") as f:
            f.write(self.text + addition)
        os.utime(self.config, (when, when))

    def steps(self):
        """The kinds of step that submit.py --dry-run finds out of date (it asks make -q of each step's
        files; the report, whose figures this run lacks, is always among them and left out)."""
        result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config",
                                 self.config, "--out", self.out, "--bin", self.bin, "--dry-run"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        kinds = {re.sub(r"-load_\d+$", "", name) for name, _ in submitted_plan(result.stdout)}
        return sorted(kinds - {"report"})

    def settings(self, stage):
        with open(os.path.join(self.out, "settings", f"{stage}.json")) as f:
            return json.load(f)

    def test_a_finished_run_is_up_to_date(self):
        self.assertEqual(self.steps(), [])
        self.assertEqual(self.settings("lbm"), {"lbm": {}})  # what the stage printed for the config
        dem = self.settings("dem")["dem"]  # the real aniso-dem's values, defaults included, no help texts
        self.assertEqual((dem["seed"], dem["particles"]["count"], dem["material"]["friction"]), (3, 200, 0.5))
        self.assertEqual(os.path.getmtime(os.path.join(self.out, "settings", "dem.json")), 1000)

    def test_status_counts_what_the_run_has_written(self):
        os.remove(os.path.join(self.out, "probe", "probe_load_001_fork3.h5"))
        for k in range(2):  # a load stopped after its second checkpoint (load.done is a plan file)
            touch(os.path.join(self.out, "dem", f"load_00{k}.h5"), 2500)
        status = subprocess.run(["make", "-s", "-C", WORKFLOWS, "status", *self.variables], capture_output=True,
                                text=True)
        self.assertEqual(status.returncode, 0, status.stderr)
        lines = {line.split()[0]: line.split(None, 1)[1] for line in status.stdout.splitlines()[1:]}
        self.assertEqual(status.stdout.splitlines()[0], f"{self.out}:")
        self.assertEqual(lines["prepare"], "1/1")
        self.assertEqual(lines["load"], "1/1 (2 of 3 checkpoints written)")
        self.assertEqual(lines["probe"], "2/3 (20/21 tasks)")
        self.assertEqual(lines["lbm"], "3/3 (9/9 tasks)")
        self.assertEqual(lines["report"], "1/1")

    def test_status_says_where_an_unfinished_prepare_and_load_stand(self):
        dem = os.path.join(self.out, "dem")
        os.remove(os.path.join(dem, "prepared.h5"))
        for name in ["prepare_seized_1_0.h5", "prepare_seized_2_0.h5", "prepare_seized_3_1.h5",
                     "prepare_consolidated_2_0.h5", "prepare_consolidated_3_0_interrupted.h5"]:
            touch(os.path.join(dem, name), 2500)
        os.remove(os.path.join(dem, "load.done"))
        touch(os.path.join(dem, "load_000.h5"), 2500)
        with open(os.path.join(dem, "history.csv"), "w") as f:
            f.write("step,strain_11,p\n0,0,1e5\n10,-0.0012,1e5\n20,-0.00481,1e5\n")
        status = subprocess.run(["make", "-s", "-C", WORKFLOWS, "status", *self.variables], capture_output=True,
                                text=True)
        self.assertEqual(status.returncode, 0, status.stderr)
        lines = {line.split()[0]: line.split(None, 1)[1] for line in status.stdout.splitlines()[1:]}
        self.assertEqual(lines["prepare"], "0/1 (kept: 2 cycles seized, 1 refinements, 1 consolidated, "
                                           "consolidation of cycle 3 in progress)")
        self.assertEqual(lines["load"], "0/1 (1 of 3 checkpoints written, the history at strain 0.481%)")

    def test_a_comment_reruns_nothing(self):
        self.edit("\n# a note on this run\n", 3000)
        self.assertEqual(self.steps(), [])

    def test_lbm_settings_rerun_the_flows_and_their_readers_only(self):
        self.edit("\n[lbm]\ntau = 0.8\n", 3000)
        self.assertEqual(self.steps(), ["lbm", "lbm-collect", "series"])
        self.assertEqual(self.settings("lbm"), {"lbm": {"tau": 0.8}})
        self.assertEqual(os.path.getmtime(os.path.join(self.out, "settings", "voxel.json")), 1000)

    def test_dem_settings_rerun_everything(self):
        self.edit("\n".join(["", "[dem.material]", "friction = 0.45", ""]), 3000)
        self.assertEqual(self.steps(), ["fabric", "lbm", "lbm-collect", "load", "prepare", "probe", "probe-collect",
                                        "series", "voxel"])


class SubmitDryRun(unittest.TestCase):
    def test_only_the_missing_array_tasks_are_resubmitted(self):
        # A finished load whose probe fork 3 of load_001 was deleted: that one task goes again, not
        # the whole 7-task array.
        with tempfile.TemporaryDirectory() as folder:
            bin_dir, out = os.path.join(folder, "bin"), os.path.join(folder, "run")
            os.mkdir(bin_dir)
            os.makedirs(os.path.join(out, "dem"))
            os.makedirs(os.path.join(out, "probe"))
            fake_bin(bin_dir, doubles=["fabric", "probe", "voxel", "lbm"])
            config = os.path.join(folder, "c.toml")
            with open(os.path.join(WORKFLOWS, "configs", "e2e.toml")) as f, open(config, "w") as g:
                g.write(f.read())
            start = os.path.getmtime(config)
            for name, age in [("prepared.h5", 10), ("load.done", 20)] + [(f"load_00{k}.h5", 20) for k in range(3)]:
                touch(os.path.join(out, "dem", name), start + age)
            for k in range(7):
                if k != 3:
                    touch(os.path.join(out, "probe", f"probe_load_001_fork{k}.h5"), start + 30)
            result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config", config,
                                     "--out", out, "--bin", bin_dir, "--dry-run"], capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            plan = dict(submitted_plan(result.stdout))
            self.assertNotIn("prepare", plan)
            self.assertNotIn("load", plan)
            self.assertIn("--array=3 ", plan["probe-load_001"])
            self.assertIn("--array=0-6 ", plan["probe-load_000"])
            self.assertIn("--dependency=afterok:<probe-load_001>", plan["probe-collect-load_001"])


    def test_resources_per_kind_go_into_the_job_scripts(self):
        # [workflow.resources.<kind>] sets each kind's sbatch options; they override --ranks.
        with tempfile.TemporaryDirectory() as folder:
            bin_dir = os.path.join(folder, "bin")
            os.mkdir(bin_dir)
            fake_bin(bin_dir, doubles=["fabric", "probe", "voxel", "lbm"])
            config = e2e_with_workflow(folder, '[workflow.resources.load]\ntime = "1-12:00:00"\nmem = "6G"\n'
                                               'ranks = 3\n[workflow.resources.voxel]\ncpus_per_task = 4\n')
            result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config", config,
                                     "--out", os.path.join(folder, "run"), "--bin", bin_dir, "--ranks", "2",
                                     "--dry-run"], capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            plan = dict(submitted_plan(result.stdout))
            for option in ("#SBATCH --time=1-12:00:00", "#SBATCH --mem=6G", "#SBATCH --ntasks=3"):
                self.assertIn(option, plan["load"])
            self.assertIn("#SBATCH --ntasks=2", plan["prepare"])
            self.assertNotIn("--time", plan["prepare"])
            self.assertIn("#SBATCH --cpus-per-task=4", plan["voxel-load_001"])
            script = os.path.join(folder, "run", "slurm", "jobs", "load.sh")
            self.assertTrue(os.access(script, os.X_OK), "the job script can be rerun by hand")
            self.assertEqual(subprocess.run(["bash", "-n", script]).returncode, 0)

    def test_bad_resources_are_refused_before_submitting(self):
        for section, message in [('[workflow.resources.report]\nranks = 2', "the report job is serial"),
                                 ('[workflow.resources.load]\ntime = "12h"', "expected a SLURM time"),
                                 ('[workflow.resources.laod]\ntime = "1:00:00"', "unknown job kind"),
                                 ('[workflow.resources.load]\nmemory = "4G"', "unknown key workflow.resources.load")]:
            with tempfile.TemporaryDirectory() as folder:
                config = e2e_with_workflow(folder, section)
                result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config",
                                         config, "--out", os.path.join(folder, "run"), "--bin", BUILD, "--dry-run"],
                                        capture_output=True, text=True)
                self.assertNotEqual(result.returncode, 0, section)
                self.assertIn(message, result.stderr, section)
                self.assertEqual(result.stdout, "", section)

    def test_plan_has_arrays_and_dependencies(self):
        with tempfile.TemporaryDirectory() as folder:
            bin_dir = os.path.join(folder, "bin")
            os.mkdir(bin_dir)
            fake_bin(bin_dir, doubles=["fabric", "probe", "voxel", "lbm"])
            result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--config",
                                     os.path.join(WORKFLOWS, "configs", "e2e.toml"), "--out",
                                     os.path.join(folder, "run"), "--bin", bin_dir, "--ranks", "4",
                                     "--sbatch-arg=--partition=batch", "--dry-run"],
                                    capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            names, lines = (list(column) for column in zip(*submitted_plan(result.stdout)))
            per_checkpoint = ["probe", "probe-collect", "voxel", "lbm", "lbm-collect"]
            self.assertEqual(names, ["prepare", "load", "fabric"]
                             + [f"{s}-load_00{k}" for k in range(3) for s in per_checkpoint] + ["series", "report"])
            plan = dict(zip(names, lines))
            self.assertIn("--array=0-6", plan["probe-load_001"])  # the reference fork and six increments
            self.assertIn("--array=0-2", plan["lbm-load_001"])
            self.assertIn("--dependency=afterok:<voxel-load_001>", plan["lbm-load_001"])
            self.assertIn("--dependency=afterok:<probe-load_001>", plan["probe-collect-load_001"])
            self.assertIn("#SBATCH --ntasks=4", plan["load"])
            self.assertIn("#SBATCH --ntasks=1", plan["report"])
            self.assertIn("probe_load_001_fork{task}.h5", plan["probe-load_001"])
            self.assertTrue(all("#SBATCH --partition=batch" in line for line in lines))
            self.assertEqual(plan["series"].count("<"), len(names) - 2, "the series waits for every analysis")
            self.assertEqual(plan["report"].count("<"), len(names) - 1, "the report waits for every step")


    def test_paper_plan_runs_every_shape_and_realisation_then_the_figures(self):
        with tempfile.TemporaryDirectory() as folder:
            bin_dir = os.path.join(folder, "bin")
            os.mkdir(bin_dir)
            fake_bin(bin_dir, doubles=["fabric", "probe", "voxel", "lbm"])
            paper = os.path.join(folder, "paper")
            tiny = os.path.join(SOURCE, "tests", "e2e", "paper")
            result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--paper",
                                     "--out", paper, "--bin", bin_dir, "--paper-configs", tiny,
                                     "--paper-shapes", "spheres ovoids-0.5", "--realisations", "2", "--dry-run"],
                                    capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr)
            scripts = [line.split()[-1] for line in result.stdout.splitlines()]
            runs = [f"{shape}/r{k}" for shape in ("spheres", "ovoids-0.5") for k in (1, 2)]
            self.assertEqual([s for s in scripts if s.endswith("/prepare.sh")],
                             [os.path.join(paper, run, "slurm", "jobs", "prepare.sh") for run in runs])
            self.assertEqual(scripts[-1], os.path.join(paper, "slurm", "jobs", "paper-figures.sh"))
            self.assertIn("--dependency=afterok:" + ":".join(["<report>"] * 4), result.stdout.splitlines()[-1])
            with open(scripts[-1]) as f:
                figures = f.read()
            for variable in (f"PAPER_OUT={paper}", "REALISATIONS=2", "'PAPER_SHAPES=spheres ovoids-0.5'",
                             "paper-figures"):
                self.assertIn(variable, figures)
            import tomllib

            with open(os.path.join(paper, "configs", "ovoids-0.5-r2.toml"), "rb") as f:
                self.assertEqual(tomllib.load(f)["dem"]["seed"], 4)  # the tiny config's seed 3, plus one
            with open(os.path.join(paper, "ovoids-0.5", "r2", "slurm", "jobs", "load.sh")) as f:
                self.assertIn(f"CONFIG={paper}/configs/ovoids-0.5-r2.toml", f.read())

    def test_paper_submission_refuses_a_shape_without_a_config(self):
        result = subprocess.run([sys.executable, os.path.join(WORKFLOWS, "slurm", "submit.py"), "--paper", "--out",
                                 "/nonexistent/paper", "--bin", BUILD, "--paper-shapes", "cubes", "--dry-run"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 1)
        self.assertIn("--paper-shapes names 'cubes'", result.stderr)
        self.assertEqual(result.stdout, "")


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
