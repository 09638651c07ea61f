"""Missed thrust and late ignition: a capture burn gone wrong, the capture re-planned.

One concept per module: the orbits a fault leaves (:mod:`.orbits`), the nominal a penalty
is measured against (:mod:`.nominal`), the make-up NLP from one guess (:mod:`.makeup`),
the recovery's starts declared in order (:mod:`.starts`), where the make-up is made
(:mod:`.recovery`: the window, then the perilunes, declared in order), one case and its
row (:mod:`.contingency`), the solvers' messages counted rather than printed
(:mod:`.messages`), and the study's cases, table and declaration (:mod:`.cases`,
``STUDY``).
"""

#: The study's modules, relative to the package: its tables' and cached cases' code
#: version is :func:`lunarcap.repro.cache.code_version` of the numerical code and these.
MODULES = tuple(f"studies/missed/{m}.py" for m in (
    "__init__", "orbits", "nominal", "makeup", "starts", "recovery", "contingency", "messages",
    "cases"))
