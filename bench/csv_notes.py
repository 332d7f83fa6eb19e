"""csv_notes.py - reads the benchmarks' CSV files: '# key: value' note lines, then a
header and rows; and writes tables made from them into a document, between two
marker lines (bench/plot.py and the *_runs.py scripts; standard
library only)."""

import argparse
import csv
import os
import re
import sys


def read(path):
    """(notes, rows): the '# key: value' lines as a dict, the rows as dicts."""
    notes, lines = {}, []
    try:
        with open(path, newline="") as f:
            for line in f:
                if line.startswith("#"):
                    key, _, value = line[1:].strip().partition(": ")
                    notes[key] = value
                else:
                    lines.append(line)
    except OSError as e:  # one line, not a traceback: a run folder without its CSV
        raise SystemExit(f"{path}: expected a benchmark's CSV file, found {e.strerror.lower()}; "
                         f"give the --out folder of a finished run")
    return notes, list(csv.DictReader(lines))


def write_block(doc_path, begin, end, text):
    """Replaces what lies between the lines `begin` and `end` of doc_path by text,
    atomically (a temporary file, then a rename); refuses a document without them."""
    with open(doc_path, encoding="utf-8") as f:
        doc = f.read()
    if doc.count(begin) != 1 or doc.count(end) != 1 or doc.index(begin) > doc.index(end):
        raise SystemExit(f"{doc_path}: expected one '{begin}' line and, after it, one '{end}' line; "
                         f"add them around the tables to replace")
    start, stop = doc.index(begin) + len(begin), doc.index(end)
    temporary = doc_path + ".tmp"
    try:
        with open(temporary, "w", encoding="utf-8") as f:
            f.write(doc[:start] + "\n" + text + doc[stop:])
        os.replace(temporary, doc_path)
    except BaseException:  # an error or an interruption (Ctrl-C) leaves no half-written file behind
        if os.path.exists(temporary):
            os.remove(temporary)
        raise


def runs_main(argv, description, make_text, begin, end, wrote, runs=("first", "second")):
    """The command line of the *_runs.py scripts: one folder per name in `runs`
    (each a run's --out folder), and --doc, the document whose block between
    `begin` and `end` receives make_text(*folders) (printed without it); `wrote`
    starts the message."""
    parser = argparse.ArgumentParser(description=description)
    for name in runs:
        parser.add_argument(name, help=f"the {name} run's --out folder")
    parser.add_argument("--doc", help="the document whose marked block to replace")
    parser.add_argument("--block", help="the name in the block's marker lines, for a document that holds more "
                        "than one such block (another machine's runs): <!-- NAME:begin --> and <!-- NAME:end -->; "
                        "default: " + begin[len("<!-- "):-len(":begin -->")])
    args = parser.parse_args(argv)
    if args.block is not None:
        # a marker is an HTML comment: no "--" inside it
        if not re.fullmatch(r"[A-Za-z0-9]+(-[A-Za-z0-9_]+)*", args.block):
            parser.error(f"expected --block to be a name such as embree-runs-amd, found '{args.block}'")
        begin, end = f"<!-- {args.block}:begin -->", f"<!-- {args.block}:end -->"
    folders = [getattr(args, name) for name in runs]
    text = make_text(*folders)
    if not args.doc:
        sys.stdout.write(text)
        return 0
    write_block(args.doc, begin, end, text)
    print(wrote, " and ".join(folders), "into", args.doc)
    return 0
