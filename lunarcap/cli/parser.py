"""The argument parser of ``lunarcap`` (its commands run in :mod:`lunarcap.cli`).

lunarcap's own commands (plan, solve, impulsive, plans, bench) are declared here; each
registered study (:mod:`lunarcap.studies.registry`) adds its command after them, with the
plan's options (:func:`add_plan_options`), its own and the Dask options
(:func:`add_dask_options`) as it declares.

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
from lunarcap.studies.registry import PLAN_DEFAULT, studies


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


def _add_study(sub, study, func) -> None:
    """A registered study's command: the plan's options, its own, the Dask options."""
    p = sub.add_parser(study.name, help=study.help)
    if study.plan:
        add_plan_options(p, plan_positional=True)
    study.options(p)
    if study.dask:
        add_dask_options(p, study.dask)
    p.set_defaults(func=func)


def build_parser(commands: dict, description: str, study_command) -> Parser:
    """The argument parser of every subcommand.

    ``commands`` maps lunarcap's own commands (plan, solve, impulsive, plans, bench) to
    their functions; every registered study (:func:`lunarcap.studies.registry.studies`)
    follows them, its function ``study_command(study)``.
    """
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
    for study in studies().values():
        _add_study(sub, study, study_command(study))
    return parser


#: lunarcap's own options whose value may begin with '-' (a study declares its own).
_SIGNED = ("--starts", "--previous-starts", "--start", "--burn", "--workers", "--thrust",
           "--isp", "--mass")


def signed_options() -> set:
    """Every option whose value may begin with '-': lunarcap's and the studies'."""
    return {*_SIGNED, *(opt for study in studies().values() for opt in study.signed)}


def join_negative_lists(argv: list, signed=None) -> list:
    """Let ``--starts -10,-6,-5`` work: argparse would take '-10,-6,-5' for an option.

    ``signed``: the options concerned (default :func:`signed_options`).
    """
    signed = signed_options() if signed is None else signed
    out = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in signed and i + 1 < len(argv) and re.match(r"^-\d", argv[i + 1]):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def parse_args(parser: Parser, argv=None) -> argparse.Namespace:
    """The command line ``argv`` (default ``sys.argv[1:]``) parsed by ``parser``."""
    return parser.parse_args(join_negative_lists(sys.argv[1:] if argv is None else list(argv)))
