"""The seeded plan families of the tests: :mod:`lunarcap.studies.families`, shared with tools.

Imported by the tests that must hold on any plan the load-time checks accept
(tests/optim/test_targets_as_asked.py, tests/studies/test_missed*.py).
"""

from lunarcap.studies.families import plan_family, plan_of, random_plan  # noqa: F401
