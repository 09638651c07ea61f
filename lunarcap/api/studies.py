"""The studies of a plan, run from Python as the command line runs them, locally or on Dask.

Every registered study (:data:`lunarcap.studies.registry.STUDIES`: the engine trade, the
number of burns, missed thrust, dispersions) runs through :func:`run_study`: its options
are the command's (their names without the dashes: ``delays_min`` for ``--delays-min``),
with the command's defaults, read by the study's own ``prepare`` (so that a bad value is
refused before any work, with the command line's message, as an InputError); the run is
the study's campaign (one Dask task per case, a table resumed on rerun, Ctrl-C keeping
what finished), locally (``workers``) or on a running cluster (``scheduler``, its
address). A study added to the registry is run here with no change. :func:`missed`,
:func:`burns`, :func:`dispersions` and :func:`engine_trade` name the options of the
packaged studies. The command line runs a study the same way
(:func:`run_prepared`), so the API and ``lunarcap <study> --json`` give the same document.

In a notebook a study runs as it is; in a script, call it under ``if __name__ ==
"__main__":``, since the local cluster's worker processes import the script's main module
(without the guard each would run the script again and the cluster would not start).
"""

from __future__ import annotations

import argparse
import contextlib

from lunarcap.api.results import Result
from lunarcap.errors import InputError

#: The Dask options every study run takes (the command's ``--workers`` ... by their names;
#: ``lock_wait_s`` has no command-line twin: a command refuses a table in use at once).
RUN_OPTIONS = ("workers", "scheduler", "out", "progress", "use_cache", "lock_wait_s")
#: The same options as the command's parsed arguments name them.
_DASK_DESTS = ("workers", "scheduler", "out", "no_progress", "no_cache")


class StudyResult(Result):
    """A study's run: its table, its ``--json`` document, its text, its figure.

    Attributes
    ----------
    name : str or None
        The study's command (``"missed"``), which chooses the figure of :meth:`plot`.
    plan : CapturePlan or None
        The plan studied (None for the engine trade study).
    raw : object
        What the study's run returned: a :class:`lunarcap.studies.campaign.CampaignResult`
        (``table``, ``path``, ``run``), or (models, CampaignResult) for a sensitivity.

    The table's columns are glossary names with their units (``penalty_mps``,
    ``delay_min``, ``time_to_final_orbit_h``); :meth:`to_dict` is the command's ``--json``
    document, :meth:`text` its printed report.

    Examples
    --------
    Not run as a doctest (skipped: a local Dask cluster starts, 10 to 40 s;
    tests/api/test_api_cli.py runs it):

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> r = lunarcap.missed(plan, fractions=[0.5], delays_min=[0], workers=1)  # doctest: +SKIP
    >>> r.answered, r.to_frame().status.tolist()  # doctest: +SKIP
    (True, ['recovered'])
    >>> print(r.text())  # doctest: +SKIP
    >>> r.plot(); r.export("out/")  # doctest: +SKIP
    """

    def __init__(self, study_run, raw, name: str | None = None, plan=None):
        self._study_run, self.raw, self.name, self.plan = study_run, raw, name, plan

    def __repr__(self) -> str:
        return (f"<StudyResult {self.name} of {self.plan.name if self.plan else 'its grid'}: "
                f"{len(self.to_frame())} row(s), "
                f"{'every case answered' if self.answered else 'NOT every case answered'}>")

    def __str__(self) -> str:
        return self.text()

    @property
    def stem(self) -> str:
        """``<study>_<plan>`` (the files' stem)."""
        return "_".join(x for x in (self.name or "study", self.plan and self.plan.name) if x)

    @property
    def campaign(self):
        """The campaign's result (``table``, ``path`` of the CSV table, ``run`` record)."""
        return self.raw[1] if isinstance(self.raw, tuple) else self.raw

    @property
    def answered(self) -> bool:
        """True if every case has an answer (the command exits 0; else 3)."""
        return bool(self._study_run.answered(self.raw))

    def text(self) -> str:
        """The study's plain-text report, as the command prints it."""
        return self._study_run.text(self.raw)

    def document(self) -> dict:
        """The command's ``--json`` document (the plan, the options, the run, the rows)."""
        return self._study_run.document(self.raw)

    def to_frame(self):
        """The study's table: one row per case, glossary column names (a sensitivity: its rows).

        A case without an answer has a ``status`` other than the study's answers and a
        ``reason`` in physical terms.
        """
        import pandas as pd

        if isinstance(self.raw, tuple):   # a sensitivity: (models, campaign)
            return pd.DataFrame(self.document()["sensitivity"])
        return self.campaign.table.copy()

    def plot(self):
        """The book's figure of this study (see :data:`FIGURES`); ValueError if it has none."""
        draw = FIGURES.get("sensitivity" if isinstance(self.raw, tuple) else self.name)
        if draw is None:
            raise ValueError(f"study {self.name!r} has no figure (figures: "
                             f"{', '.join(FIGURES)})")
        return draw(self)


# ---------------------------------------------------------------------- running
def _options(command) -> dict:
    """The study's own options with the command's defaults, ``{dest: default}``."""
    p = argparse.ArgumentParser(add_help=False)
    command.options(p)
    return vars(p.parse_args([]))


def run_prepared(study_run, name: str | None = None, plan=None,
                 use_cache: bool | None = None, lock_wait_s: float = 0.0) -> StudyResult:
    """Run a prepared study (:class:`lunarcap.studies.registry.StudyRun`) and wrap its result.

    ``use_cache`` False: every case computed again (the cache switch off for the run);
    None or True: the switch as it is. ``lock_wait_s``: how long the run waits for its
    table if another run is writing it, s (:func:`lunarcap.studies.study.waiting_for_table`;
    0: refused at once). The command line's runner.
    """
    from lunarcap.repro.cache import caching
    from lunarcap.studies.study import waiting_for_table

    with caching(False) if use_cache is False else contextlib.nullcontext(), \
            waiting_for_table(lock_wait_s):
        raw = study_run.run()
    return StudyResult(study_run, raw, name, plan)


def run_study(name: str, plan=None, *, workers: int = 2, scheduler: str | None = None,
              out=None, progress: bool = False, use_cache: bool = True,
              lock_wait_s: float = 0.0, **options) -> StudyResult:
    """Run a registered study on a plan, as ``lunarcap <name> PLAN --<option> ...`` does.

    Parameters
    ----------
    name : str
        The study's command (``available()["studies"]``).
    plan : CapturePlan, or anything :func:`lunarcap.load_plan` takes
        The plan studied (not taken by the engine trade study, ``"study"``).
    workers : int
        Local Dask worker processes (one thread each), when no ``scheduler`` is given.
    scheduler : str, optional
        Address of a running Dask scheduler (``"tcp://host:8786"``) to run the cases on.
    out : path, optional
        The CSV table, appended as each case finishes and resumed on rerun (default
        below ``.cache/study/``).
    progress : bool
        A progress bar on stderr.
    use_cache : bool
        False: every case computed again (the disk cache and the table ignored).
    lock_wait_s : float
        How long to wait for another run writing the same table ``out`` (a command line
        run, another notebook) before refusing, s; default 0: refused at once, as the
        command line does.
    **options
        The study's own options by the command's names (``fractions``, ``delays_min``),
        as numbers, lists or the command line's text; the command's defaults otherwise.

    Raises
    ------
    InputError
        An unknown study or option, or a value the study refuses: before any work, with
        the command line's message.

    Examples
    --------
    Bad input is refused before any work, with the command line's message:

    >>> import lunarcap
    >>> lunarcap.run_study("missed", "two-burn-8h", fractions="0.5,1.5")
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --fractions: 1.5 is above the largest allowed, 1
    >>> lunarcap.run_study("landing", "two-burn-8h")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: study 'landing': not a registered study (study, burns, ...)
    >>> lunarcap.run_study("missed", "two-burn-8h", lock_wait_s=-1)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: lock_wait_s: -1 s is below the smallest allowed, 0 s
    """
    from lunarcap.api.plans import load_plan
    from lunarcap.errors import number
    from lunarcap.studies.registry import studies

    known = studies()
    if name not in known:
        raise InputError(f"study {name!r}: not a registered study ({', '.join(known)})")
    command = known[name]
    args = _options(command)
    own = set(args) - set(_DASK_DESTS)
    unknown = sorted(set(options) - own)
    if unknown:
        raise InputError(f"{name}: unknown option {unknown[0]!r} (options: "
                         f"{', '.join(sorted(own | set(RUN_OPTIONS)))})")
    args.update(options, workers=workers, scheduler=scheduler, out=out,
                no_progress=not progress, no_cache=use_cache is False)
    if command.plan:
        if plan is None:
            raise InputError(f"{name}: needs a plan")
        plan = load_plan(plan)
    wait_s = number("lock_wait_s", lock_wait_s, "s", minimum=0.0)
    study_run = command.prepare(argparse.Namespace(**args), plan if command.plan else None)
    return run_prepared(study_run, name, plan if command.plan else None, use_cache, wait_s)


def _given(**kw) -> dict:
    """The keywords given (not None): the others keep the command's defaults."""
    return {k: v for k, v in kw.items() if v is not None}


def missed(plan, *, burn: int | None = None, fractions=None, delays_min=None, late_min=None,
           max_period_h: float | None = None, **run) -> StudyResult:
    """Missed thrust or late ignition of one burn, the capture re-planned (``lunarcap missed``).

    Burn ``burn`` (from 1; default 1) is cut off after each fraction of its nominal
    duration in ``fractions`` (in (0, 1]; default 0.25, 0.5, 0.75, 0.9, none if only
    ``late_min`` is given), the recovery window opening ``delays_min`` minutes after the
    cut-off (default 0, 30, 120, 720), or ignited ``late_min`` minutes late (default none);
    each case is re-optimised to the plan's final orbit, the orbit after the burn at most
    ``max_period_h`` h (default 24). ``run``: :func:`run_study`'s options. The table's
    ``penalty_mps`` is the case's delta-V above the nominal's; a case with no recovery
    says why in ``reason``.

    Examples
    --------
    A half-way cut-off of the first burn, the recovery window open at once. Not run as a
    doctest (skipped): a local Dask cluster starts and the case re-plans the capture, 10 to
    40 s (tests/api/test_api_cli.py runs it):

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> r = lunarcap.missed(plan, fractions=[0.5], delays_min=[0], workers=1)  # doctest: +SKIP
    >>> r.to_frame()[["fraction", "delay_min", "status"]]  # doctest: +SKIP
       fraction  delay_min     status
    0       0.5        0.0  recovered
    >>> lunarcap.missed(plan, burn=3)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --burn 3: plan two-burn-8h has burns 1 to 2
    """
    return run_study("missed", plan, **_given(burn=burn, fractions=fractions,
                                              delays_min=delays_min, late_min=late_min,
                                              max_period_h=max_period_h), **run)


def burns(plan, *, counts=None, max_period_h: float | None = None,
          max_days: float | None = None, **run) -> StudyResult:
    """The capture in N burns for each N of ``counts`` (``lunarcap burns``).

    The plan's arrival, engine and final orbit reached through N - 1 intermediate
    ellipses whose periods are optimised for the least total delta-V, each at most
    ``max_period_h`` h (default 12.235) and the last burn ending within ``max_days`` days
    of the arrival perilune (default 3); ``counts`` default 1 to 5. ``run``:
    :func:`run_study`'s options.

    Examples
    --------
    Not run here (a Dask cluster and N solves, minutes): ``lunarcap.burns(plan,
    counts=[1, 2, 3]).to_frame()`` gives one row per count. Bad input:

    >>> import lunarcap
    >>> lunarcap.burns("two-burn-8h", counts=[0])
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --counts: must be an integer >= 1, got 0
    """
    return run_study("burns", plan, **_given(counts=counts, max_period_h=max_period_h,
                                             max_days=max_days), **run)


def dispersions(plan, *, samples: int | None = None, seed: int | None = None, **options
                ) -> StudyResult:
    """The capture's delta-V budget under execution, arrival and navigation errors.

    ``samples`` Monte Carlo samples (default 100), sample k drawing its errors from numpy's
    generator seeded by (``seed``, k) (default seed 0); the 1-sigma errors by the
    command's names (``thrust_sigma_pct``, ``isp_sigma_pct``, ``pointing_sigma_deg``,
    ``ignition_sigma_s``, ``arrival_sigma_km``, ``arrival_sigma_mps``,
    ``knowledge_sigma_km``, ``knowledge_sigma_mps``, the Gates model's ``gates_*``; default
    0) or covariance files (``arrival_cov``, ``knowledge_cov``, ``bplane_cov``); each burn
    re-planned from the state reached (``lunarcap dispersions``). ``sensitivity=True``:
    each non-zero sigma alone at 0.5, 1 and 2 times its value instead (``factors``: other
    multiples). ``antithetic=True``: samples in pairs of negated draws, a pair one
    independent draw (``samples`` even). ``formulation``:
    how the re-plans meet a period (``"orbit"`` or ``"song2011"``). Other keywords:
    :func:`run_study`'s. The document's ``summary`` has the 99 % budget above the nominal
    with its confidence interval (not estimated with too few samples, saying how many).

    Examples
    --------
    Not run here (skipped: a Dask cluster and re-planned burns per sample, 10 to 40 s;
    tests/api/test_api_cli.py runs two samples):

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> d = lunarcap.dispersions(plan, samples=2, thrust_sigma_pct=1)  # doctest: +SKIP
    >>> d.to_dict()["summary"]["nominal_delta_v_mps"]  # doctest: +SKIP
    890.2529...
    >>> lunarcap.dispersions(plan, samples=0)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --samples: must be an integer >= 1, got 0
    """
    return run_study("dispersions", plan, **_given(samples=samples, seed=seed), **options)


def engine_trade(*, thrust_min_N: float | None = None, thrust_max_N: float | None = None,
                 points: int | None = None, isp_s=None, dynamics: str | None = None,
                 retry_failed: bool = False, **run) -> StudyResult:
    """The engine trade study: finite-burn loss against thrust-to-weight (``lunarcap study``).

    The paper's arrival and three-burn capture flown with ``points`` log-spaced thrusts
    from ``thrust_min_N`` to ``thrust_max_N`` (default 30 from 50 to 2000 N) for each
    specific impulse of ``isp_s`` (default 200, 250, 300 s), ignitions optimised, in
    ``dynamics`` (default ``"full"``); four rows per engine (each burn and the sequence).
    ``retry_failed``: solve again the engines that failed in an earlier run of the table.
    ``run``: :func:`run_study`'s options: ``out`` the table (default the one ``lunarcap
    study`` resumes, ``.cache/study/engine_trade.csv``), ``lock_wait_s`` how long to wait
    for another run writing it, s.

    Examples
    --------
    Not run here (a Dask cluster and four solves per engine, minutes in full dynamics):
    ``lunarcap.engine_trade(points=6, dynamics="two-body").plot()``. Bad input:

    >>> import lunarcap
    >>> lunarcap.engine_trade(points=1)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --points: must be an integer >= 2, got 1
    """
    return run_study("study", **_given(thrust_min=thrust_min_N, thrust_max=thrust_max_N,
                                       points=points, isp=isp_s, dynamics=dynamics),
                     retry_failed=retry_failed, **run)


# ---------------------------------------------------------------------- figures
def _missed_figure(res: StudyResult):
    """The penalty map of the cut-offs (fraction flown x delay), as on the book's page."""
    from lunarcap.report.figures.missed_thrust import plot_missed_penalty

    t = res.to_frame()
    if "contingency" in t:
        t = t[t.contingency.fillna("cut-off") == "cut-off"].reset_index(drop=True)
    if not len(t):
        raise ValueError("missed: no cut-off case to draw (late ignitions only)")
    return plot_missed_penalty(t)


def _burns_figure(res: StudyResult):
    """Total loss and time to the final orbit against the number of burns."""
    from lunarcap.report.figures.burn_count import plot_burn_count

    t = res.to_frame()
    t.insert(0, "label", t["plan"])
    return plot_burn_count(t)


def _dispersions_figure(res: StudyResult):
    """The empirical CDF of the delta-V above the nominal."""
    from lunarcap.report.figures.dispersions import plot_cdf

    return plot_cdf({res.plan.name: res.to_frame()})


def _sensitivity_figure(res: StudyResult):
    """The mean delta-V above the nominal against each source's sigma (x its asked value)."""
    from lunarcap.report.figures.dispersions import plot_sensitivity
    from lunarcap.report.pages.dispersions import SOURCE_LABELS
    from lunarcap.studies.dispersions.sensitivity import FACTORS

    rows = res.document()["sensitivity"]
    asked = {}
    for r in rows:   # the asked sigma: the middle factor (1) of each source's sigmas
        asked.setdefault(r["source"], set()).add(r["sigma"])
    asked = {s: sorted(v)[FACTORS.index(1.0)] for s, v in asked.items()}
    drawn = [r | {"engine": res.plan.name, "factor": r["sigma"] / asked[r["source"]],
                  "example": asked[r["source"]]} for r in rows]
    return plot_sensitivity(drawn, res.plan.name, SOURCE_LABELS)


def _trade_figure(res: StudyResult):
    """Loss against thrust-to-weight per burn and for the sequence, with Robbins' estimate."""
    import numpy as np

    from lunarcap.report.figures.trade_study import plot_trade_study_loss
    from lunarcap.report.pages.trade_study import (
        DENSE_POINTS,
        LOSS_AXIS_PERCENT,
        PART_TITLES,
        ROBBINS_VALID_OMEGA_T,
    )
    from lunarcap.studies.engine_trade import trade

    t = res.to_frame()
    ok = t[t.status == "ok"]
    isp_s = sorted(set(t.isp_s.astype(float)))
    theory = trade.analytic_curves(np.geomspace(t.thrust_N.min(), t.thrust_N.max(),
                                                DENSE_POINTS), isp_s)
    return plot_trade_study_loss(ok, theory[theory.omega_t_rad <= ROBBINS_VALID_OMEGA_T],
                                 trade.paper_points(), isp_s, PART_TITLES,
                                 float(trade.thrust_from_weight_ratio(1.0)), LOSS_AXIS_PERCENT)


#: The figure of each study's result, by command (the book's drawing of its page).
FIGURES = {"missed": _missed_figure, "burns": _burns_figure,
           "dispersions": _dispersions_figure, "sensitivity": _sensitivity_figure,
           "study": _trade_figure}
