#!/usr/bin/env python3
"""make_autograder.py - the zip to upload to Gradescope as a programming assignment's autograder.

    python3 tools/gradescope/make_autograder.py autograder.zip [--hidden tests/hidden]

The zip holds, at its root, setup.sh and run_autograder (from this folder), the reference
repository under rt/ (without build folders and without the hidden tests) and the hidden
suites under hidden/. See docs/instructor-guide.md. Python 3 standard library only.
"""

import argparse
import sys
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
import make_kit  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the zip to write")
    parser.add_argument("--source", default=str(make_kit.DEFAULT_SOURCE), help="the reference repository")
    parser.add_argument("--hidden", help="folder of hidden suites (default: <source>/tests/hidden if present)")
    args = parser.parse_args(argv)
    source = Path(args.source).resolve()
    hidden = Path(args.hidden).resolve() if args.hidden else source / "tests" / "hidden"
    output = Path(args.output).resolve()
    if source == output.parent or source in output.parents:
        if not make_kit._in_skipped_dir(output.relative_to(source).as_posix()):
            print(f"{output}: expected a path outside the repository (or in a build folder)", file=sys.stderr)
            return 2
    tmp = output.with_name(output.name + ".tmp-zip")
    count = 0
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for name in ("setup.sh", "run_autograder"):
            info = zipfile.ZipInfo(name)
            info.external_attr = 0o100755 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, (HERE / name).read_bytes())
        for rel in make_kit.repository_files(source):
            if rel.startswith("tests/hidden/"):
                continue
            z.write(source / rel, f"rt/{rel}")
            count += 1
        if hidden.is_dir():
            for f in sorted(hidden.rglob("*")):
                if f.is_file():
                    z.write(f, f"hidden/{f.relative_to(hidden).as_posix()}")
    tmp.replace(output)
    print(f"make_autograder: wrote {output}: setup.sh, run_autograder, {count} reference files"
          + (f", hidden suites from {hidden}" if hidden.is_dir() else ", no hidden suites"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
