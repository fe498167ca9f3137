"""A csv of measured runs that a chart script fills as it goes: runs already listed are reused, and
each new row is written at once, so an interrupted chart resumes where it stopped (delete the csv
to redo every run)."""
import csv
import os


class RunTable:
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
        """Appends a row (values kept as text, as read back) and rewrites the csv; returns the stored row."""
        self.rows.append({k: str(v) for k, v in row.items()})
        with open(self.path, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=self.fields)
            writer.writeheader()
            writer.writerows(self.rows)
        return self.rows[-1]
