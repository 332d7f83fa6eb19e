"""Tests of tools/planted_mistakes.py: every row of every stage page's "Common mistakes"
section has one planted mistake, each applies to the reference, and the first failing
case is read from doctest's output. The planting itself runs in check_kit.py --mistakes.

Run: python3 -m unittest -v test_planted_mistakes   (ctest runs it as tools.planted_mistakes)
"""

import sys
import textwrap
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))
import planted_mistakes as pm  # noqa: E402


class Coverage(unittest.TestCase):
    def test_every_row_of_every_page_has_one_planted_mistake(self):
        self.assertEqual(pm.coverage(REPO), [])

    def test_every_mistake_applies_to_the_reference(self):
        for mistake in pm.MISTAKES:
            with self.subTest(mistake.label()):
                originals, planted, problems = pm.planted_texts(REPO, mistake)
                self.assertEqual(problems, [])
                self.assertTrue(all(planted[p] != originals[p] for p in planted))
                self.assertTrue(mistake.names, "a mistake names words its message must hold")

    def test_a_new_row_without_a_mistake_is_reported(self):
        page = textwrap.dedent("""\
            ## Common mistakes, and what you see

            | mistake | the first failing test |
            |---|---|
            | `if (a || b)` | "a case" |
            | a new one | "another" |

            - **A bold item**. Text.

            ## Next
            | not | a mistake |
            """)
        self.assertEqual(pm.page_items(page), ["`if (a || b)`", "a new one", "A bold item"])


class FirstFailure(unittest.TestCase):
    OUTPUT = textwrap.dedent("""\
        [doctest] doctest version is "2.4.11"
        ===============================================================================
        tests/stage03_sphere.cpp:20:
        TEST CASE:  a passing case that prints a message

        tests/stage03_sphere.cpp:22: MESSAGE: worst in ulps: 26.8

        ===============================================================================
        tests/stage03_sphere.cpp:26:
        TEST CASE:  closed-form hits: unit sphere at distance 5

        tests/sphere_contract.hpp:40: ERROR: CHECK( t == Approx(4) ) is NOT correct!
          values: CHECK( 6 == Approx( 4 ) )
          logged: expected the nearer root

        ===============================================================================
        tests/stage03_sphere.cpp:46:
        TEST CASE:  tmin and tmax are respected

        tests/sphere_contract.hpp:90: ERROR: CHECK( hit ) is NOT correct!

        ===============================================================================
        [doctest] test cases: 9 | 7 passed | 2 failed | 0 skipped
        """)

    def test_the_first_failing_case_and_its_block(self):
        name, block = pm.first_failure(self.OUTPUT)
        self.assertEqual(name, "closed-form hits: unit sphere at distance 5")
        self.assertIn("expected the nearer root", block)
        self.assertNotIn("tmin and tmax", block)

    def test_judge_wants_the_named_case_and_words(self):
        mistake = pm.Mistake(3, "the far root", (), "closed-form hits", ("nearer root",))
        name, block = pm.first_failure(self.OUTPUT)
        self.assertEqual(pm.judge(mistake, pm.FirstFailure(name, block, "t")), [])
        other = pm.Mistake(3, "tmin", (), "tmin and tmax", ("tmin",))
        self.assertIn("to fail first, found 'closed-form hits", pm.judge(other, pm.FirstFailure(name, block, "t"))[0])
        silent = pm.Mistake(3, "x", (), "closed-form hits", ("the far root",))
        self.assertIn("does not name the mistake", pm.judge(silent, pm.FirstFailure(name, block, "t"))[0])
        self.assertIn("cannot see this mistake", pm.judge(silent, pm.FirstFailure())[0])


if __name__ == "__main__":
    unittest.main()
