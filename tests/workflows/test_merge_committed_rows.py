#!/usr/bin/python3
"""workflows/merge_committed_rows.py (relaxed_csvs.sh KEEP_COMMITTED=1): a rebuilt run folder's CSV
gets the committed rows of the checkpoints it lacks, byte for byte and in checkpoint order; its own
rows win over committed ones; different columns, a missing key column and a row naming no
checkpoint stop with a message and leave the new file as it was.

usage: test_merge_committed_rows.py SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
SCRIPT = os.path.join(SOURCE, "workflows", "merge_committed_rows.py")
HEADER = "source,step,p"


def row(stem, p):
    return f'"runs/paper-x/relaxed/{stem}.h5",{len(stem)},{p}'


class MergeCommittedRows(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.new = os.path.join(self.folder, "new.csv")
        self.committed = os.path.join(self.folder, "committed.csv")

    def write(self, path, lines):
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")

    def read(self, path):
        with open(path) as f:
            return f.read().splitlines()

    def merge(self, key="source"):
        return subprocess.run(["/usr/bin/python3", SCRIPT, self.new, self.committed, key], capture_output=True,
                              text=True)

    def test_keeps_the_missing_rows_in_order_and_its_own_rows_win(self):
        self.write(self.new, [HEADER, row("load_000", "1.5"), row("load_002", "2.5")])
        self.write(self.committed, [HEADER, row("load_000", "9.9"), row("load_001", "1.0"), row("load_003", "3.0")])
        result = self.merge()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout.split(), ["load_001", "load_003"])
        self.assertEqual(self.read(self.new), [HEADER, row("load_000", "1.5"), row("load_001", "1.0"),
                                               row("load_002", "2.5"), row("load_003", "3.0")])

    def test_a_key_holding_the_stem_alone(self):
        self.write(self.new, ["checkpoint,steps", "load_005,10"])
        self.write(self.committed, ["checkpoint,steps", "load_014,7", "load_005,99"])
        result = self.merge("checkpoint")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(self.read(self.new), ["checkpoint,steps", "load_005,10", "load_014,7"])

    def test_nothing_committed_leaves_the_file(self):
        self.write(self.new, [HEADER, row("load_000", "1.5")])
        result = self.merge()
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout, "")
        self.assertEqual(self.read(self.new), [HEADER, row("load_000", "1.5")])

    def test_different_columns_stop_and_leave_the_file(self):
        self.write(self.new, [HEADER, row("load_000", "1.5")])
        self.write(self.committed, ["source,step,p,q", row("load_001", "1.0") + ",2"])
        result = self.merge()
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("different columns", result.stderr)
        self.assertEqual(self.read(self.new), [HEADER, row("load_000", "1.5")])

    def test_a_missing_key_column_is_named(self):
        self.write(self.new, [HEADER, row("load_000", "1.5")])
        self.write(self.committed, [HEADER])
        result = self.merge("checkpoint")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no column 'checkpoint'", result.stderr)

    def test_a_row_naming_no_checkpoint_is_named(self):
        self.write(self.new, [HEADER, row("load_000", "1.5")])
        self.write(self.committed, [HEADER, '"runs/x/prepared.h5",1,2'])
        result = self.merge()
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("prepared.h5", result.stderr)
        self.assertEqual(self.read(self.new), [HEADER, row("load_000", "1.5")])


if __name__ == "__main__":
    unittest.main()
