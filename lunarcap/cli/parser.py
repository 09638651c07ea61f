"""The argument parser of ``lunarcap`` (its commands run in :mod:`lunarcap.cli`).

Numbers are read by :mod:`lunarcap.errors`' one parser; a bad option is one line,
``lunarcap: error: --thrust: must be positive (N), got '-1'``, exit status 2. Every help
text states the option's real default: the plan's, for the options that override a plan.
"""

from __future__ import annotations

import argparse
import re
import sys

from lunarcap.errors import InputError, integer, number
from lunarcap.physics.forces import PRESETS

#: What a help text says of an option that overrides the plan's value.
PLAN_DEFAULT = "default: the plan's"


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line naming the option, exit status 2."""

    def error(self, message: str):
        """Print ``lunarcap: error: <option>: <reason>`` and exit with status 2."""
        message = re.sub(r"^argument ([^:]+): ", lambda m: m.group(1).split("/")[0] + ": ",
                         message)
        self.exit(2, f"lunarcap: error: {message}\n")


def _option(parse):
    """An argparse ``type`` from one of :mod:`lunarcap.errors`' parsers (field unnamed)."""
    def conv(text: str):
        try:
            return parse(text)
        except InputError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    return conv


def positive(unit: str):
    """An argparse type: a positive finite number of ``unit``."""
    return _option(lambda t: number(None, t, unit, positive=True))


def burn_number(text: str) -> int:
    """An argparse type: a burn number, from 1."""
    return _option(lambda t: integer(None, t, minimum=1))(text)


def starts(text: str) -> tuple:
    """Comma-separated ignition offsets (min) or 'free'."""
    items = [s.strip() for s in text.split(",")]
    if not text.strip() or any(s == "" for s in items):
        raise argparse.ArgumentTypeError(f"start offsets must be numbers of minutes (or "
                                         f"'free') separated by commas, got {text!r}")
    conv = _option(lambda t: number(None, t, "min"))
    try:
        return tuple("free" if s == "free" else conv(s) for s in items)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"start offsets must be numbers of minutes (or "
                                         f"'free') separated by commas, got {text!r}") from None


def start(text: str):
    """One ignition offset (min) or 'free'."""
    vals = starts(text)
    if len(vals) != 1:
        raise argparse.ArgumentTypeError(f"one start offset (min) expected, got {text!r}")
    return vals[0]


# ---------------------------------------------------------------------- options
def add_plan_options(p: argparse.ArgumentParser, plan_positional: bool) -> None:
    """PLAN (or --plan) and the options that override a plan's fields."""
    if plan_positional:
        p.add_argument("plan", metavar="PLAN",
                       help="a plan file (YAML) or the name of a packaged plan (list them "
                            "with `lunarcap plans`)")
        dflt = PLAN_DEFAULT
    else:
        p.add_argument("--plan", default=None, metavar="PLAN",
                       help="a plan file (YAML) or packaged plan name (default: the paper's "
                            "capture with the engine of --thrust and --isp)")
        dflt = PLAN_DEFAULT + ", or the paper's {} without --plan"
    p.add_argument("--thrust", type=positive("N"), default=None,
                   help=f"engine thrust, N ({dflt.format('150 N')})")
    p.add_argument("--isp", type=positive("s"), default=None,
                   help=f"specific impulse, s ({dflt.format('200 s')})")
    p.add_argument("--mass", type=positive("kg"), default=None,
                   help=f"mass at the first perilune, kg ({dflt.format('524.895 kg')})")
    p.add_argument("--dynamics", choices=list(PRESETS), default=None,
                   help=f"perturbations: full (J2, Earth, Sun), j2, or two-body "
                        f"({dflt.format('full')})")
    p.add_argument("--hemisphere", choices=["north", "south"], default=None,
                   help=f"lunar hemisphere of the arrival perilune ({dflt.format('north')})")
    p.add_argument("--ephemeris", default=None, metavar="BSP",
                   help=f"SPK file (.bsp) instead of the plan's ({dflt.format('DE405')})")
    p.add_argument("--lunar-pole", choices=["iau2009-j2000", "iau-constant", "of-date"],
                   default=None,
                   help=f"the pole fixing the plan's frame: the IAU (2009) expression at "
                        f"J2000, its constant terms only, or at the arrival epoch "
                        f"({dflt.format('iau2009-j2000')})")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")


def add_dask_options(p: argparse.ArgumentParser, what: str) -> None:
    """--workers, --scheduler, --out, --no-cache, --no-progress of a study."""
    p.add_argument("--workers", default="2", metavar="W",
                   help="local Dask worker processes, one thread each (default 2)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--out", default=None, metavar="PATH",
                   help=f"CSV table, appended as each {what} finishes and resumed on rerun "
                        f"(default: below .cache/study/)")
    p.add_argument("--no-cache", action="store_true",
                   help="recompute every case, ignoring the disk cache and the table")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def _solver_options(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--no-impulsive", action="store_true",
                   help=f"skip the impulsive {what} in the same dynamics (no loss)")
    p.add_argument("--no-cache", action="store_true", help="recompute, ignoring the disk cache")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")


# ---------------------------------------------------------------------- commands
def _add_plan(sub, func) -> None:
    p = sub.add_parser("plan", help="solve and verify every burn of a capture plan")
    add_plan_options(p, plan_positional=True)
    p.add_argument("--starts", type=starts, default=None, metavar="S1,S2,...",
                   help=f"ignition offsets of every burn, min from perilune (or 'free') "
                        f"({PLAN_DEFAULT})")
    _solver_options(p, "limits")
    p.add_argument("--export", default=None, metavar="DIR",
                   help="write the verified capture to DIR for other tools: <name>.oem (CCSDS "
                        "OEM), <name>.bsp (SPICE SPK), <name>_attitude.csv, "
                        "<name>_maneuvers.csv (Moon-centred ICRF)")
    p.add_argument("--time-system", choices=["TDB", "UTC"], default="TDB",
                   type=str.upper, help="time scale of the exported epochs (default TDB; "
                                        "the SPK is always in ET = TDB)")
    p.add_argument("--spk-id", type=int, default=-310001, metavar="ID",
                   help="NAIF ID of the spacecraft in the exported SPK and OEM (default "
                        "-310001)")
    p.add_argument("--after-days", type=positive("days"), default=None, metavar="DAYS",
                   help="also propagate the final orbit DAYS days after the last cut-off in "
                        "the plan's dynamics: each revolution's lowest and highest altitude "
                        "and mean inclination (in the JSON under 'after'; with --export the OEM "
                        "and SPK go on to that day; default none: nothing after the last "
                        "cut-off)")
    p.set_defaults(func=func)


def _add_solve(sub, func) -> None:
    p = sub.add_parser("solve", help="optimal finite burn of one burn of a plan, verified")
    add_plan_options(p, plan_positional=False)
    p.add_argument("--burn", "--loi", dest="burn", type=burn_number, default=1,
                   help="burn number, from 1 (--loi is the same; default 1)")
    p.add_argument("--start", type=start, default=None,
                   help=f"ignition, minutes from the nominal perilune (negative: before), or "
                        f"'free' to optimise it ({PLAN_DEFAULT})")
    p.add_argument("--previous-starts", type=starts, default=None, metavar="S1[,S2...]",
                   help=f"ignition offsets of the earlier burns ({PLAN_DEFAULT})")
    p.add_argument("--steering", choices=["optimal", "inertial", "antivelocity"],
                   default="optimal", help="steering law of this burn (default optimal; "
                                           "earlier burns: the plan's)")
    _solver_options(p, "limit")
    p.set_defaults(func=func)


def _add_bench(sub, func) -> None:
    p = sub.add_parser("bench", help="solve and verify all 37 paper cases, print timings")
    p.add_argument("--dynamics", choices=list(PRESETS), default=None,
                   help="dynamics (default: full; with --warm, two-body)")
    p.add_argument("--warm", action="store_true",
                   help="instead: warm verified solves of the dymos peer benchmark's cases")
    p.add_argument("--repeats", type=int, default=5,
                   help="warm solves per case (--warm; default 5)")
    p.add_argument("--studies", action="store_true",
                   help="instead: figures on where the time goes (NLP builds per shape, cold "
                        "and cached `lunarcap plan`, a trade-study engine, study walls)")
    p.add_argument("--no-cold", action="store_true",
                   help="with --studies: skip the cold `lunarcap plan` runs")
    p.add_argument("--resolve-earlier", action="store_true",
                   help="solve each case's earlier burns again (default: once per run)")
    p.set_defaults(func=func)


def _add_study(sub, func) -> None:
    p = sub.add_parser("study", help="engine trade study: loss vs thrust-to-weight on Dask")
    p.add_argument("--thrust-min", default="50", metavar="N",
                   help="lowest thrust, N (default 50)")
    p.add_argument("--thrust-max", default="2000", metavar="N",
                   help="highest thrust, N (default 2000)")
    p.add_argument("--points", default="30", metavar="K",
                   help="log-spaced thrusts (default 30)")
    p.add_argument("--isp", default="200,250,300", metavar="S1,S2,...",
                   help="specific impulses, s (default 200,250,300)")
    p.add_argument("--workers", default="2", metavar="W",
                   help="local Dask worker processes, one thread each (default 2)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--out", default=None, metavar="PATH",
                   help="CSV table, appended as engines finish and resumed on rerun "
                        "(default: .cache/study/engine_trade.csv)")
    p.add_argument("--dynamics", choices=list(PRESETS), default="full",
                   help="perturbations (default full)")
    p.add_argument("--retry-failed", action="store_true",
                   help="recompute engines that failed in an earlier run")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=func)


def _add_burns(sub, func) -> None:
    p = sub.add_parser("burns", help="how many capture burns: N burns, periods optimised")
    add_plan_options(p, plan_positional=True)
    p.add_argument("--counts", default="1,2,3,4,5", metavar="N1,N2,...",
                   help="numbers of burns to try (default 1,2,3,4,5)")
    p.add_argument("--max-period-h", default="12.235", metavar="H",
                   help="longest intermediate period, h (default 12.235)")
    p.add_argument("--max-days", default="3", metavar="D",
                   help="longest time from the arrival perilune to the end of the last burn, "
                        "days (default 3)")
    add_dask_options(p, "count")
    p.set_defaults(func=func)


def _add_missed(sub, func) -> None:
    p = sub.add_parser("missed", help="missed thrust or late ignition: a burn gone wrong, "
                                      "the capture re-planned")
    add_plan_options(p, plan_positional=True)
    p.add_argument("--burn", default="1", metavar="N", help="the burn cut short (default 1)")
    p.add_argument("--fractions", default=None, metavar="F1,F2,...",
                   help="fractions of the burn flown before the engine stops, in (0, 1] "
                        "(default 0.25,0.5,0.75,0.9; none if only --late-min is given)")
    p.add_argument("--delays-min", default="0,30,120,720", metavar="D1,D2,...",
                   help="minutes from the cut-off to the recovery window (default "
                        "0,30,120,720)")
    p.add_argument("--late-min", default=None, metavar="L1,L2,...",
                   help="late ignition: the burn ignites these minutes after its planned "
                        "ignition, is re-optimised from there and the later burns re-planned "
                        "(default: none)")
    p.add_argument("--max-period-h", default="24", metavar="H",
                   help="longest period of the orbit after the burn, in the recovery and "
                        "in the nominal it is compared with, h (default 24)")
    add_dask_options(p, "case")
    p.set_defaults(func=func)


_SIGMAS = (("--thrust-sigma-pct", "%", "thrust, per burn"),
           ("--isp-sigma-pct", "%", "specific impulse, per burn"),
           ("--pointing-sigma-deg", "deg", "thrust direction, each of two tilt angles, "
                                           "fixed over a burn"),
           ("--ignition-sigma-s", "s", "ignition epoch, per burn"),
           ("--arrival-sigma-km", "km", "arrival position, per RTN axis"),
           ("--arrival-sigma-mps", "m/s", "arrival velocity, per RTN axis"),
           ("--knowledge-sigma-km", "km", "orbit-determination position error of the "
                                          "state each re-plan starts from, per RTN axis"),
           ("--knowledge-sigma-mps", "m/s", "orbit-determination velocity error of the "
                                            "state each re-plan starts from, per RTN axis"),
           ("--gates-magnitude-pct", "%", "Gates proportional magnitude error, per burn"),
           ("--gates-magnitude-mps", "m/s", "Gates fixed magnitude error, per burn"),
           ("--gates-pointing-deg", "deg", "Gates proportional pointing error, per axis "
                                           "and burn"),
           ("--gates-pointing-mps", "m/s", "Gates fixed pointing error (a transverse "
                                           "delta-V), per axis and burn"))


def _add_dispersions(sub, func) -> None:
    p = sub.add_parser("dispersions", help="the capture's delta-V budget under execution and "
                                           "arrival errors (Monte Carlo, closed loop)")
    add_plan_options(p, plan_positional=True)
    p.add_argument("--samples", default="100", metavar="N", help="samples (default 100)")
    p.add_argument("--seed", default="0", metavar="S",
                   help="seed: sample k draws its errors from numpy's generator seeded by "
                        "(S, k), the same whatever the sigmas (default 0)")
    for opt, unit, what in _SIGMAS:
        p.add_argument(opt, default="0", metavar=unit.upper().replace("/", "").replace(
            "%", "PCT"), help=f"1-sigma error of the {what}, {unit.replace('%', '%%')} "
                                   "(default 0)")
    p.add_argument("--arrival-cov", default=None, metavar="FILE",
                   help="instead of --arrival-sigma-*: a 6x6 covariance of the arrival state "
                        "in its RTN frame, km and km/s (36 numbers, whitespace or commas)")
    p.add_argument("--knowledge-cov", default=None, metavar="FILE",
                   help="instead of --knowledge-sigma-*: a 6x6 covariance of the "
                        "orbit-determination error at each re-plan, RTN, km and km/s "
                        "(default none)")
    p.add_argument("--bplane-cov", default=None, metavar="FILE",
                   help="a 2x2 (B.R, B.T; km) or 3x3 (and the time of closest approach, s) "
                        "covariance of the arrival's B-plane target (4 or 9 numbers; default "
                        "none)")
    p.add_argument("--sensitivity", action="store_true",
                   help="instead of one budget: each non-zero sigma alone at 0.5, 1 and 2 "
                        "times its value (the others 0, the same draws), the mean and the "
                        "99 %% budget of each")
    p.add_argument("--formulation", choices=["orbit", "song2011"], default=None,
                   help=f"how the re-planned burns meet a period: orbit (the orbit asked, its "
                        f"perilune epoch free) or song2011 (the paper's: at the plan's nominal "
                        f"perilune epochs, a fixed timeline) ({PLAN_DEFAULT})")
    add_dask_options(p, "sample")
    p.set_defaults(func=func)


def build_parser(commands: dict, description: str) -> Parser:
    """The argument parser of every subcommand; ``commands`` maps each name to its function."""
    parser = Parser(prog="lunarcap", description=description)
    sub = parser.add_subparsers(dest="command", required=True)
    _add_plan(sub, commands["plan"])
    _add_solve(sub, commands["solve"])
    p = sub.add_parser("impulsive", help="a plan's two-body impulsive chain and Eq. (19)")
    add_plan_options(p, plan_positional=False)
    p.set_defaults(func=commands["impulsive"])
    p = sub.add_parser("plans", help="list the packaged plans, or print one as YAML")
    p.add_argument("name", nargs="?", default=None,
                   help="a packaged plan to print (default: list them all)")
    p.set_defaults(func=commands["plans"])
    _add_bench(sub, commands["bench"])
    _add_study(sub, commands["study"])
    _add_burns(sub, commands["burns"])
    _add_missed(sub, commands["missed"])
    _add_dispersions(sub, commands["dispersions"])
    return parser


_LIST_OPTIONS = ("--starts", "--previous-starts", "--start", "--counts", "--fractions",
                 "--delays-min", "--max-period-h", "--max-days", "--burn", "--workers",
                 "--samples", "--seed", "--thrust-sigma-pct", "--isp-sigma-pct",
                 "--pointing-sigma-deg", "--ignition-sigma-s", "--arrival-sigma-km",
                 "--arrival-sigma-mps", "--late-min", "--thrust", "--isp", "--mass",
                 "--knowledge-sigma-km", "--knowledge-sigma-mps", "--gates-magnitude-pct",
                 "--gates-magnitude-mps", "--gates-pointing-deg", "--gates-pointing-mps")


def join_negative_lists(argv: list) -> list:
    """Let ``--starts -10,-6,-5`` work: argparse would take '-10,-6,-5' for an option."""
    out = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in _LIST_OPTIONS and i + 1 < len(argv) and re.match(r"^-\d", argv[i + 1]):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def parse_args(commands: dict, description: str, argv=None) -> argparse.Namespace:
    """The parsed command line (``argv``; default ``sys.argv[1:]``)."""
    parser = build_parser(commands, description)
    return parser.parse_args(join_negative_lists(sys.argv[1:] if argv is None else list(argv)))
