"""csv_notes.py - reads the benchmarks' CSV files: '# key: value' note lines, then a
header and rows (bench/plot.py and bench/embree_runs.py; standard library only)."""

import csv


def read(path):
    """(notes, rows): the '# key: value' lines as a dict, the rows as dicts."""
    notes, lines = {}, []
    with open(path, newline="") as f:
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].strip().partition(": ")
                notes[key] = value
            else:
                lines.append(line)
    return notes, list(csv.DictReader(lines))
