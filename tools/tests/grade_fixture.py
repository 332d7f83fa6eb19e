"""What the grader's tests share (tools/tests/test_grade*.py, test_autograder.py): a small
reference made with rt's own CMake files, temporary folders every user may enter, and the
user the tests of a submission run as."""

import contextlib
import json
import os
import pwd
import shutil
import tempfile
import textwrap
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent


def have_build_tools():
    return all(shutil.which(t) for t in ("cmake", "ninja")) and (shutil.which("g++") or shutil.which("c++"))


def temporary_folder(name: str) -> Path:
    """A new folder /tmp/grader-<name>-XXXX that every user may enter (the test user runs
    the programs of a submission from inside it)."""
    path = Path(tempfile.mkdtemp(prefix=f"grader-{name}-", dir="/tmp" if os.path.isdir("/tmp") else None))
    os.chmod(path, 0o711)
    return path


def run_as_arguments():
    """--run-as for grade.py when these tests run as root: rtgrader when it exists, else nobody."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return []
    for name in ("rtgrader", "nobody"):
        try:
            pwd.getpwnam(name)
            return ["--run-as", name]
        except KeyError:
            continue
    return []


FIXTURE_HEADER = """
    // fx.hpp - three exercises for the grader's tests.
    #pragma once

    #include <cstdlib>

    #include <rt/core/error.hpp>

    namespace rt {

    inline int add(int a, int b)
    {
        // RT_EXERCISE_BEGIN(stage01: add)
        return a + b;
        // RT_EXERCISE_END
    }

    inline int deref(const int* p)
    {
        // RT_EXERCISE_BEGIN(stage02: deref)
        return *p;
        // RT_EXERCISE_END
    }

    inline long identity(long n)
    {
        // RT_EXERCISE_BEGIN(stage03: identity)
        return n;
        // RT_EXERCISE_END
    }

    } // namespace rt
"""

FIXTURE_TESTS = {
    "tests/stage01_add.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("two and three make five") { CHECK(rt::add(2, 3) == 5); }
        TEST_CASE("minus two and two make zero, whatever the order") { CHECK(rt::add(-2, 2) == 0); }
    """,
    "tests/stage02_deref.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("seven") { const int x = 7; CHECK(rt::deref(&x) == 7); }
        TEST_CASE("four") { const int x = 4; CHECK(rt::deref(&x) == 4); }
    """,
    # stage 03's cases call stage 01's add too: judged alone, they use the reference's
    "tests/stage03_identity.cpp": """
        #include <doctest/doctest.h>
        #include <rt/fx.hpp>
        TEST_CASE("one") { CHECK(rt::identity(rt::add(1, 0)) == 1); }
        TEST_CASE("zero") { CHECK(rt::identity(0) == 0); }
    """,
}

HIDDEN_SUITE = ('#include <doctest/doctest.h>\n#include <rt/fx.hpp>\n'
                'TEST_CASE("negative") { CHECK(rt::add(-1, 1) == 0); }\n')


def dedent(text: str) -> str:
    return textwrap.dedent(text).lstrip()


def make_fixture_reference(into: Path) -> Path:
    """A reference with rt's CMake files and three stages of one exercise each (fx.hpp)."""
    ref = into / "reference"
    for rel in ("CMakeLists.txt", "cmake", "tests/CMakeLists.txt", "tests/doctest_main.cpp",
                "tests/rt_skip.hpp", "stages/CMakeLists.txt", "stages/common", "third_party", "include/rt/core/error.hpp",
                "tools/make_kit.py", "tools/kit_manifest.json"):
        source, destination = REPO / rel, ref / rel
        destination.parent.mkdir(parents=True, exist_ok=True)
        if source.is_dir():
            shutil.copytree(source, destination)
        else:
            shutil.copy2(source, destination)
    (ref / "include/rt/fx.hpp").write_text(dedent(FIXTURE_HEADER))
    for rel, text in FIXTURE_TESTS.items():
        (ref / rel).write_text(dedent(text))
    (ref / "tools/weights.json").write_text(json.dumps({
        "case_timeout_seconds": 3, "stage_timeout_seconds": 30,
        "stages": {"01": {"visible": 10, "hidden": 5}, "02": {"visible": 10}, "03": {"visible": 10}}}))
    os.chmod(ref, 0o700)    # the grader refuses a reference its test user can read
    return ref


def private_copy(source: Path, into: Path) -> Path:
    """A copy of the repository `source` that only its owner can read (the grader refuses a
    reference the test user can read), without builds and caches."""
    shutil.copytree(source, into, ignore=shutil.ignore_patterns(".git", "build", "build-*", "__pycache__", "*.pyc"))
    os.chmod(into, 0o700)
    return into


def student_copy(into: Path, header_text: str) -> Path:
    """A submission: include/rt/fx.hpp holding `header_text`."""
    folder = into / "include" / "rt"
    folder.mkdir(parents=True)
    (folder / "fx.hpp").write_text(dedent(header_text))
    return into


@contextlib.contextmanager
def scanner_off():
    """The region scanner (splice.check_body) accepts everything: the judge and its sandbox
    alone must hold."""
    from grading import splice
    saved = splice.check_body
    splice.check_body = lambda *args, **kwargs: ""
    try:
        yield
    finally:
        splice.check_body = saved
