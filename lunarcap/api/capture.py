"""A plan solved and verified, one burn solved, a capture exported and flown in GMAT.

:func:`solve` solves every burn of a plan in order, each an optimal-control problem in
modified equinoctial elements transcribed by Legendre-Gauss-Radau collocation and solved
by IPOPT (Song et al. 2011, Sec. 2), and accepts a burn only after its steering has been
flown again from its initial state by an independent integrator (the verification gate,
:mod:`lunarcap.optim.verify`); each burn's impulsive limit in the same dynamics gives its
finite-burn loss. Solves are cached on disk by what they depend on, so a plan solved
once is read back at once. :func:`solve_burn` solves one burn (its earlier burns solved
or read first). The results (:class:`CaptureResult`, :class:`BurnSolution`,
:class:`GmatFlight`) are read as every result of the API (:class:`.results.Result`).
"""

from __future__ import annotations

from lunarcap.api.plans import load_plan
from lunarcap.api.results import Result
from lunarcap.errors import InputError, SolveError, number


def _plan(plan):
    """``plan`` as a CapturePlan (anything :func:`lunarcap.load_plan` takes)."""
    from lunarcap.mission.plan import CapturePlan

    return plan if isinstance(plan, CapturePlan) else load_plan(plan)


class CaptureResult(Result):
    """Every burn of a plan, solved and verified, with its totals (:func:`solve`).

    Attributes
    ----------
    plan : CapturePlan
    burns : list of lunarcap.capture.chain.BurnResult
        One per burn solved, in order (fewer than the plan's if a solve failed).
    after : Evolution or None
        The final orbit propagated ``after_days`` from the last cut-off, if asked and every
        burn was verified.
    after_days : float or None
        The days asked (the document then has an ``after`` record, null if not computed).

    Examples
    --------
    The plan of :func:`solve`'s example (read from the cache), its document, its figure
    and its OEM:

    >>> import tempfile, lunarcap
    >>> res = lunarcap.solve(lunarcap.load_plan("two-burn-8h", dynamics="two-body"),
    ...                      impulsive=False)
    >>> res
    <CaptureResult two-burn-8h: 2 of 2 burn(s), 890.253 m/s, verified>
    >>> doc = res.to_dict()
    >>> doc["complete"], doc["burns"][1]["target_orbit"], doc["totals"]["all_verified"]
    (True, 'circle', True)
    >>> len(res.plot().axes)
    1
    >>> ex = res.export(tempfile.mkdtemp(), formats=["oem"])
    >>> [p.name for p in ex.files.values()]
    ['two-burn-8h.oem']
    >>> res.export(tempfile.mkdtemp(), formats=["kml"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: formats: ['kml'] not among the registered writers (oem, ...)
    """

    def __init__(self, plan, burns, after=None, after_days=None):
        self.plan, self.burns = plan, list(burns)
        self.after, self.after_days = after, after_days

    def __repr__(self) -> str:
        tot = self.totals()
        dv = "no burn solved" if tot is None else f"{tot['total_delta_v_mps']:.3f} m/s"
        return (f"<CaptureResult {self.plan.name}: {len(self.burns)} of {self.plan.n_burns} "
                f"burn(s), {dv}, {'verified' if self.verified else 'NOT verified'}>")

    @property
    def stem(self) -> str:
        """The plan's name (the files' stem)."""
        return self.plan.name

    @property
    def complete(self) -> bool:
        """True if every burn of the plan was solved."""
        return len(self.burns) == self.plan.n_burns

    @property
    def verified(self) -> bool:
        """True if every burn was solved and passed verification (and its impulsive limit)."""
        return self.complete and bool(self.totals()["all_verified"])

    def _chain(self):
        from lunarcap.capture.chain import PlanResult

        return PlanResult(self.plan, self.burns)

    def totals(self) -> dict | None:
        """Total delta-V (m/s), impulsive limit, loss, fuel (kg), final orbit; None: no burn."""
        return self._chain().totals() if self.burns else None

    def rows(self) -> list:
        """One record per burn solved: its solution, impulsive limit, loss, verification."""
        return [b.row() | {"target_orbit": self.plan.burns[i].describe()}
                for i, b in enumerate(self.burns)]

    def document(self) -> dict:
        """``lunarcap plan --json``: the plan, ``complete``, the burns, the totals (``after``)."""
        out = {"plan": self.plan.to_dict(), "complete": self.complete, "burns": self.rows(),
               "totals": self.totals()}
        if self.after_days:
            out["after"] = self.after.to_dict() if self.after is not None else None
        return out

    def to_frame(self):
        """One row per burn (the ``burns`` records of :meth:`to_dict`)."""
        import pandas as pd

        return pd.DataFrame(self.rows())

    def check(self) -> CaptureResult:
        """Itself if every burn is verified; else SolveError naming the first failure.

        The error carries the burn's IPOPT status and its verification residuals
        (``details``), so a failed capture is never read as a number.
        """
        for r in self.rows():
            if not r["verification_passed"]:
                raise SolveError(
                    f"plan {self.plan.name}: burn {r['burn']} failed verification (IPOPT "
                    f"{r['ipopt_status']}; perilune radius off by "
                    f"{r['verification_rp_error_m']:.3g} m, inclination by "
                    f"{r['verification_inc_error_deg']:.3g} deg)", r["ipopt_status"],
                    {k: v for k, v in r.items() if k.startswith("verification_")})
        if not self.complete:
            raise SolveError(f"plan {self.plan.name}: {len(self.burns)} of "
                             f"{self.plan.n_burns} burns solved")
        return self

    def fly_final_orbit(self, days: float, dynamics=None, rtol: float | None = None):
        """The final orbit flown ``days`` after the last cut-off, in any dynamics.

        :attr:`after` is the final orbit in the plan's own dynamics; this flies it in
        another model too, so a design made in one model (J2) can be followed in another
        (the lunar field), as the book's real-Moon page does.

        Parameters
        ----------
        days : float
            Days flown from the last burn's cut-off (> 0).
        dynamics : str, dict or ForceModel, optional
            The model, as :func:`lunarcap.load_plan` takes it (``"j2"``,
            ``{"gravity": "LP165P", "degree": 20}``, ...); default the plan's.
        rtol : float, optional
            The propagation's relative tolerance (default the propagator's).

        Returns
        -------
        lunarcap.physics.evolution.Evolution
            Per whole revolution the perilune and apolune altitudes (km) and the mean
            inclination (deg); ``summary()`` their extremes; ``final_state`` the end.
            Cached on disk by plan, days, dynamics and tolerance; of the sampled states
            only the first and the last are kept.

        Raises
        ------
        InputError
            A burn not solved or not verified (there is no final orbit to fly), or
            ``days`` not positive.

        Examples
        --------
        The two-body capture of :func:`solve`'s example, its 100 km circle flown a day in
        J2 (seconds; cached):

        >>> import lunarcap
        >>> res = lunarcap.solve(lunarcap.load_plan("two-burn-8h", dynamics="two-body"),
        ...                      impulsive=False)
        >>> ev = res.fly_final_orbit(1.0, "j2")
        >>> ev.forces, ev.summary()["after_revolutions"]
        ('j2', 12)
        >>> round(ev.summary()["after_min_perilune_altitude_km"], 1)
        99.6
        """
        from lunarcap.capture.openloop import evolution

        if not self.verified:
            raise InputError(f"plan {self.plan.name}: every burn solved and verified before "
                             "its final orbit is flown")
        return evolution(self.plan, number("days", days, "days", positive=True), dynamics,
                         rtol)

    def fly_open_loop(self, dynamics=None, hold: str = "rtn", approach_min: float = 0.0):
        """The capture's burns flown open loop, as planned, in any dynamics: its miss.

        Each burn is flown at its designed epoch and duration, its steering held in the
        flown orbit's RTN axes or in inertial axes (10 s segments, as a GMAT script flies
        it), without re-targeting: flown in another model than the design's (the lunar
        field for a J2 design), the final orbit misses the design's.

        Parameters
        ----------
        dynamics : str, dict or ForceModel, optional
            The model flown, as :func:`lunarcap.load_plan` takes it; default the plan's
            (then the flight reproduces the design, to metres).
        hold : {"rtn", "inertial", "one-direction"}
            How the steering is held.
        approach_min : float
            Start this long before the first ignition (min, >= 0: the design's state
            there, so the approach too is flown in ``dynamics``); 0: from the design's
            state at the first ignition.

        Returns
        -------
        lunarcap.capture.openloop.OpenLoop
            ``final``: the final orbit flown (``rp_alt_km``, ``ra_alt_km``, ``inc_deg``),
            the design's (``design_...``) and the distance from the design's end state
            (``miss_km``, ``miss_mps``); ``events``: the distance at each ignition and
            cut-off; ``end``: the state flown at the end. Cached on disk.

        Raises
        ------
        InputError
            A burn not solved or not verified, or an unknown ``hold``.

        Examples
        --------
        The two-body capture of :func:`solve`'s example flown as planned in its own
        dynamics, then with J2 (seconds; cached):

        >>> import lunarcap
        >>> res = lunarcap.solve(lunarcap.load_plan("two-burn-8h", dynamics="two-body"),
        ...                      impulsive=False)
        >>> res.fly_open_loop().final["miss_km"] < 1e-3
        True
        >>> res.fly_open_loop("j2", approach_min=60.0).final["miss_km"] > 1.0
        True
        """
        from lunarcap.capture.openloop import open_loop

        if not self.verified:
            raise InputError(f"plan {self.plan.name}: every burn solved and verified before "
                             "it is flown open loop")
        approach = number("approach_min", approach_min, "min", minimum=0.0)
        return open_loop(self.plan, dynamics, hold, 60.0 * approach)

    def plot(self, hyperbola_hours: float = 3.0):
        """Fig. 2 of the book for this plan: the capture in the plane of the arrival orbit.

        The arrival hyperbola from ``hyperbola_hours`` before the first perilune, the burn
        arcs and the orbit each reaches, one revolution of the final orbit; lunar radii.
        """
        from lunarcap.capture.chain import arrival_for
        from lunarcap.report import figdata
        from lunarcap.report.figures.capture import plot_fig2_capture

        p = self.plan
        geo = figdata.capture_geometry([b.solution for b in self.burns],
                                       arrival_for(p.arrival, p.ephemeris, p.lunar_pole),
                                       hyperbola_hours=hyperbola_hours)
        return plot_fig2_capture(geo)

    def export(self, directory, formats=None, time_system: str = "TDB",
               object_id: int = -310001):
        """Write the verified capture for other tools (``lunarcap plan --export``).

        Parameters
        ----------
        directory : path, created if missing
        formats : sequence of str, optional
            Registered writers (``available()["export_formats"]``: OEM, SPK, attitude and
            maneuver CSV, GMAT script); default all.
        time_system : {"TDB", "UTC"}
            Of the epochs written as text (SPK epochs are always TDB).
        object_id : int
            The spacecraft's NAIF ID (negative).

        Returns
        -------
        lunarcap.capture.export.Export
            ``files`` (``{key: path}``), sizes, the OEM's interpolation error.

        Raises
        ------
        InputError
            A burn that failed verification, an unknown format, a directory that cannot
            be written.
        """
        from lunarcap.capture.export import export_plan
        from lunarcap.capture.writers import WRITERS

        writers = None
        if formats is not None:
            unknown = [f for f in formats if f not in WRITERS]
            if unknown or not formats:
                raise InputError(f"formats: {unknown or 'none'} not among the registered "
                                 f"writers ({', '.join(WRITERS)})")
            writers = {f: WRITERS[f] for f in WRITERS if f in formats}
        return export_plan(self._chain(), directory, time_system=time_system,
                           object_id=object_id, after=self.after, writers=writers)

    def fly_in_gmat(self, directory, python: str | None = None) -> GmatFlight:
        """Export the capture with its GMAT script, fly it in GMAT, compare the states.

        NASA's GMAT (``gmatpy``) flies each burn and coast from lunarcap's state and the
        whole capture open loop (:mod:`lunarcap.capture.gmat_flight`); ``python``: an
        interpreter with ``gmatpy`` (default this one). InputError if a burn failed
        verification (nothing is exported).
        """
        from lunarcap.capture.gmat_flight import fly_in_gmat

        return GmatFlight(fly_in_gmat(self._chain(), directory, python))


def solve(plan, *, impulsive: bool = True, after_days: float | None = None,
          verbose: bool = False, on_burn=None, use_cache: bool = True) -> CaptureResult:
    """Solve and verify every burn of a plan, in order (``lunarcap plan``).

    Parameters
    ----------
    plan : CapturePlan, or anything :func:`lunarcap.load_plan` takes
    impulsive : bool
        Also solve each burn's impulsive limit in the same dynamics (its loss).
    after_days : float, optional
        Propagate the final orbit this many days after the last cut-off, in the plan's
        dynamics, if every burn is verified (:attr:`CaptureResult.after`).
    verbose : bool
        Progress lines on stderr.
    on_burn : callable(BurnResult), optional
        Called as each burn is verified (what is done is kept if a later one fails).
    use_cache : bool
        False: every burn solved again, the earlier ones included (``--no-cache``).

    Returns
    -------
    CaptureResult
        Its ``verified`` says whether every burn passed verification
        (:meth:`CaptureResult.check` raises otherwise).

    Raises
    ------
    SolveError
        IPOPT did not converge on a burn (its status and residuals in the error).

    Examples
    --------
    Two burns in two-body dynamics (seconds; read back from the disk cache once solved):

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> res = lunarcap.solve(plan, impulsive=False)
    >>> res.verified, round(res.totals()["total_delta_v_mps"], 2)
    (True, 890.25)
    >>> res.to_frame()[["burn", "delta_v_mps", "burn_duration_min"]].round(1)
       burn  delta_v_mps  burn_duration_min
    0     1        435.4               22.8
    1     2        454.8               19.0
    """
    plan = _plan(plan)
    days = None if after_days is None else number("after_days", after_days, "days",
                                                  positive=True)
    from lunarcap.capture.chain import after_capture, plan_result

    with _cache(use_cache):
        res = plan_result(plan, impulsive=impulsive, verbose=verbose, on_burn=on_burn)
        after = after_capture(res, days) if days and res.totals()["all_verified"] else None
    return CaptureResult(plan, res.burns, after, days)


def _cache(use_cache: bool):
    """The cache switch off for the block if ``use_cache`` is False, else left as it is."""
    import contextlib

    from lunarcap.repro.cache import caching

    return caching(False) if use_cache is False else contextlib.nullcontext()


class BurnSolution(Result):
    """One burn of a plan, solved and verified (:func:`solve_burn`).

    Attributes
    ----------
    plan : CapturePlan
        The plan as solved (the ignitions and steering asked applied).
    burn : int
        The burn's number, from 1.
    result : lunarcap.capture.chain.BurnResult
        Its solution (``result.solution``) and impulsive limit.

    Examples
    --------
    The second burn of :func:`solve_burn`'s example (read from the cache): its record
    (units in the keys), its ``lunarcap solve --json`` document and its figure:

    >>> import lunarcap
    >>> b = lunarcap.solve_burn(lunarcap.load_plan("two-burn-8h", dynamics="two-body"), 2,
    ...                         impulsive=False)
    >>> b.verified, round(b.row()["delta_v_mps"], 1), round(b.row()["m_end_kg"])
    (True, 454.8, 333)
    >>> b.to_dict()["previous_starts_min"], b.to_frame().shape[0]
    (['free'], 1)
    >>> len(b.plot().axes) >= 1
    True
    """

    def __init__(self, plan, burn: int, result):
        self.plan, self.burn, self.result = plan, burn, result

    def __repr__(self) -> str:
        r = self.row()
        return (f"<BurnSolution {self.plan.name} burn {self.burn}: {r['delta_v_mps']:.3f} m/s "
                f"in {r['burn_duration_min']:.2f} min, "
                f"{'verified' if self.verified else 'NOT verified'}>")

    @property
    def stem(self) -> str:
        """``<plan>_burn<n>`` (the files' stem)."""
        return f"{self.plan.name}_burn{self.burn}"

    @property
    def solution(self):
        """The optimiser's solution (:class:`lunarcap.optim.solution.Solution`)."""
        return self.result.solution

    @property
    def verified(self) -> bool:
        """True if the burn passed verification."""
        return bool(self.solution.verification.passed)

    def row(self) -> dict:
        """The burn's record as in ``lunarcap plan`` (solution, limit, loss, verification)."""
        return self.result.row()

    def document(self) -> dict:
        """``lunarcap solve --json``: the solution, its loss, target and earlier ignitions."""
        out = self.solution.to_dict()
        row = self.row()
        for k in ("impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent",
                  "objective_loss_mps"):
            out[k] = row[k]
        out["target_orbit"] = self.plan.burns[self.burn - 1].describe()
        out["plan"] = self.plan.name
        out["previous_starts_min"] = [b.start_min for b in self.plan.burns[:self.burn - 1]]
        return out

    def to_frame(self):
        """One row: :meth:`row`."""
        import pandas as pd

        return pd.DataFrame([self.row()])

    def plot(self):
        """Fig. 4 of the book for this burn: thrust angles alpha, beta and mass in time."""
        from lunarcap.report.figdata import fig4_steering
        from lunarcap.report.figures.capture_sequence import plot_fig4_steering

        return plot_fig4_steering(fig4_steering(self.solution))


def solve_burn(plan, burn: int = 1, *, start=None, previous_starts=None,
               steering: str = "optimal", impulsive: bool = True,
               verbose: bool = False, use_cache: bool = True) -> BurnSolution:
    """Solve and verify one burn of a plan (``lunarcap solve``); earlier burns first.

    Parameters
    ----------
    plan : CapturePlan, or anything :func:`lunarcap.load_plan` takes
    burn : int
        The burn, from 1.
    start : float or "free", optional
        Its ignition, min from its nominal perilune (default the plan's).
    previous_starts : sequence, optional
        The earlier burns' ignitions (default the plan's).
    steering : {"optimal", "inertial", "antivelocity"}
        This burn's steering law (the earlier burns keep the plan's).
    impulsive, verbose, use_cache : bool
        As :func:`solve`.

    Raises
    ------
    InputError
        A burn the plan lacks, or the wrong number of earlier ignitions (the command
        line's messages).

    Examples
    --------
    The second burn of the plan of :func:`solve`'s example (its first read from the cache):

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> b = lunarcap.solve_burn(plan, 2, impulsive=False)
    >>> b.verified, round(b.row()["delta_v_mps"], 2), b.document()["target_orbit"]
    (True, 454.83, 'circle')
    >>> lunarcap.solve_burn("two-burn-8h", 3)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --burn 3: plan two-burn-8h has burns 1 to 2
    """
    from lunarcap.errors import integer

    plan = _plan(plan)
    n = integer("--burn", burn, minimum=1)
    if n > plan.n_burns:
        raise InputError(f"--burn {n}: plan {plan.name} has burns 1 to {plan.n_burns}")
    if previous_starts is not None:
        prev = list(previous_starts)
        if len(prev) != n - 1:
            raise InputError(f"--previous-starts needs {n - 1} offset(s) for burn {n}, "
                             f"got {len(prev)}")
        for j, s in enumerate(prev):
            plan = plan.with_start(j, s)
    if start is not None:
        plan = plan.with_start(n - 1, start)
    if steering != "optimal":
        plan = plan.with_steering(n - 1, steering)
    with _cache(use_cache):
        return BurnSolution(plan, n, _solved_burn(plan, n, impulsive, verbose))


def _solved_burn(plan, n: int, impulsive: bool, verbose: bool):
    """Burn ``n`` of ``plan`` and its impulsive limit (earlier burns reused in-process)."""
    from lunarcap.capture.chain import (
        BurnResult,
        impulsive_limit,
        labelled,
        prebuild_for,
        reuse_earlier_burns,
    )
    from lunarcap.capture.chain import solve_burn as chain_solve_burn

    key = plan.key(n)
    prebuild_for(key, [n], impulsive=impulsive, verbose=verbose)
    with reuse_earlier_burns(), labelled(plan):
        sol = chain_solve_burn(key, verbose=verbose)
        imp = impulsive_limit(key, verbose=verbose) if impulsive else None
    return BurnResult(sol, imp)


class GmatFlight(Result):
    """A capture flown in GMAT against lunarcap's flight (:meth:`CaptureResult.fly_in_gmat`).

    ``comparison``: :class:`lunarcap.capture.gmat_flight.GmatComparison`: per burn its
    cut-off, per coast its end, the whole capture flown open loop at each event (position
    m, velocity mm/s, mass kg, epoch s differences), and the final orbit's radii. The
    gates: each burn's cut-off within 0.5 m and 0.5 mm/s, each coast within 1 m and
    1 mm/s, the final orbit's perilune and apolune within 50 m.

    Examples
    --------
    Not run as a doctest (skipped: GMAT runs in a child process, seconds;
    tests/api/test_api_results.py flies a plan so):

    >>> import tempfile, lunarcap
    >>> res = lunarcap.solve(lunarcap.load_plan("two-burn-8h", dynamics="two-body"))
    >>> flight = res.fly_in_gmat(tempfile.mkdtemp())  # doctest: +SKIP
    >>> flight.passed, flight.failures()  # doctest: +SKIP
    (True, [])
    >>> flight.to_frame()[["flown", "burn", "position_diff_m"]]  # doctest: +SKIP
    """

    def __init__(self, comparison):
        self.comparison = comparison

    def __repr__(self) -> str:
        return (f"<GmatFlight {self.comparison.plan}: "
                f"{'within' if self.passed else 'OUTSIDE'} the gates>")

    @property
    def stem(self) -> str:
        """``<plan>_gmat`` (the files' stem)."""
        return f"{self.comparison.plan}_gmat"

    @property
    def passed(self) -> bool:
        """True if every residual is within its gate (:meth:`failures` empty)."""
        return not self.failures()

    def failures(self) -> list:
        """The gates missed, each in words with its numbers."""
        return self.comparison.failures()

    def document(self) -> dict:
        """The comparison's records (burns, coasts, capture, final_orbit, files)."""
        return self.comparison.to_dict()

    def to_frame(self):
        """One row per comparison (``flown``: burn, coast or capture), residuals in columns."""
        import pandas as pd

        c = self.comparison
        return pd.DataFrame([{"flown": kind, **row} for kind, rows in
                             (("burn", c.burns), ("coast", c.coasts), ("capture", c.capture))
                             for row in rows])

    def plot(self):
        """GMAT's position residuals (m, log scale) at each event, by what was flown."""
        import matplotlib.pyplot as plt

        from lunarcap.report.figstyle import FIG_WIDTH_IN, OTHER_COLOURS

        t = self.to_frame()
        # the events in the order they happen: (burn, event) sorts arrival, each burn's
        # ignition and cut-off, the end
        order = sorted({(int(b), int(e)) for b, e in zip(t.burn, t.event)})
        x = {be: i for i, be in enumerate(order)}
        fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 3.6), layout="constrained")
        for k, (kind, g) in enumerate(t.groupby("flown", sort=False)):
            ax.plot([x[int(b), int(e)] for b, e in zip(g.burn, g.event)],
                    g.position_diff_m.clip(lower=1e-6), "o", color=OTHER_COLOURS[k], label=kind)
        ax.set_xticks(range(len(order)), [_event_name(b, e) for b, e in order])
        ax.set_yscale("log")
        ax.set_ylabel("GMAT − lunarcap position (m)")
        ax.set_xlabel("event (arrival, each burn's ignition and cut-off, the end)")
        ax.tick_params(axis="x", rotation=60)
        ax.legend()
        ax.grid(alpha=0.3)
        return fig


def _event_name(burn: int, event: int) -> str:
    """An event of a GMAT report in words: "arrival", "2 ignition", "2 cut-off", "end"."""
    from lunarcap.exchange.gmat import CUTOFF, END, IGNITION

    if burn == 0 and event == IGNITION:
        return "arrival"
    return {IGNITION: f"{burn} ignition", CUTOFF: f"{burn} cut-off", END: "end"}[event]
