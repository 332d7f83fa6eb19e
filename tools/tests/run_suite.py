"""run_suite.py MODULE - runs one of the tools' test modules as ctest runs it (label tools):
unittest -v, then the exit code 1 when a test failed or erred, 77 (ctest's SKIP_RETURN_CODE)
when every test that ran was skipped, else 0. Each skip's reason is in unittest's output;
a module whose tests partly skip passes, its skips counted there ("OK (skipped=N)").

Run: python3 run_suite.py test_make_kit   (from tools/tests)
     python3 ../../tests/run_suite.py test_batch   (from tools/grading/tests)
The module is looked up in the working folder first, as ctest runs each suite from its own.
"""

import os
import sys
import unittest


def main(argv):
    if len(argv) != 2:
        print("usage: run_suite.py MODULE", file=sys.stderr)
        return 2
    sys.path.insert(0, os.getcwd())
    suite = unittest.defaultTestLoader.loadTestsFromName(argv[1])
    result = unittest.TextTestRunner(verbosity=2).run(suite)
    if not result.wasSuccessful():
        return 1
    if result.testsRun > 0 and len(result.skipped) == result.testsRun:
        return 77
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
