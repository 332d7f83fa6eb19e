"""The parts of tools/grade.py (the grader of rt submissions), one concern per module:

    common      errors, running a command, atomic writes, logging
    weights     the weights file (points per stage and suite, time limits)
    submission  unpacking a submission and finding its include/rt folder
    splice      the exercise regions of a submission: extracting, checking, splicing
    sandbox     running test cases as an unprivileged user, with limits
    cache       the pre-built trees a submission is graded in (calibrate)
    report      the table, results.json, JUnit XML and grades.csv
    batch       grading a folder of submissions

Python 3 standard library only; docs/instructor-guide.md describes the grader.
"""
