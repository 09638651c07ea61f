"""Exception types of lunarcap.

Every error a user can cause (bad input) is a :class:`InputError`; an optimisation
that did not converge or failed verification is a :class:`SolveError`. The CLI turns
both into one clear message and a non-zero exit status. The numbers a user gives are
parsed here, once (:func:`number`, :func:`positive_number`, :func:`integer`,
:func:`number_list`), so every message names the field the same way.
"""

from __future__ import annotations

import math


class LunarcapError(Exception):
    """Base class of lunarcap's own errors (catch it to catch any of them).

    >>> import lunarcap
    >>> issubclass(lunarcap.InputError, lunarcap.LunarcapError)
    True
    """


class InputError(LunarcapError, ValueError):
    """A parameter is out of its physical or valid range (bad input).

    The message names the field and its unit as the command line does, whose exit status
    for it is 2.

    >>> import lunarcap
    >>> lunarcap.solve_burn("two-burn-8h", 0)
    Traceback (most recent call last):
    ...
    lunarcap.errors.InputError: --burn: must be an integer >= 1, got 0
    """


class EphemerisRangeError(InputError):
    """An epoch lies outside the time span covered by the ephemeris."""


class SolveError(LunarcapError, RuntimeError):
    """An optimisation failed to converge or its solution failed verification.

    The command line's exit status for it is 3. ``lunarcap.solve(plan).check()`` raises
    it for a burn that failed verification, e.g. ``plan two-burn-8h: burn 1 failed
    verification (IPOPT ...; perilune radius off by ... m, inclination by ... deg)``.
    Caught like any of lunarcap's errors, its status and residuals (m, deg) are at hand:

    >>> import lunarcap
    >>> try:
    ...     raise lunarcap.SolveError("burn 1 failed verification", "Solve_Succeeded",
    ...                               {"verification_rp_error_m": 12.5})
    ... except lunarcap.LunarcapError as exc:
    ...     print(exc, "|", exc.status, exc.details)
    burn 1 failed verification | Solve_Succeeded {'verification_rp_error_m': 12.5}

    Attributes
    ----------
    status : str
        IPOPT's return status (or ``"verification failed"``).
    details : dict
        Residuals and diagnostics (delta-V difference, terminal errors, mesh).
    unverified : tuple or None
        A converged solution that failed verification: (its plan, one solved leg per
        burn), for a caller that refines from it (:mod:`lunarcap.studies.missed.recovery`).
    """

    def __init__(self, message: str, status: str = "", details: dict | None = None,
                 unverified: tuple | None = None):
        super().__init__(message)
        self.status = status
        self.details = dict(details or {})
        self.unverified = unverified


# ---------------------------------------------------------------------- numbers
# The one parser of the numbers a user gives (a plan's fields, the command line's options):
# each error names the field as the user wrote it (``engine.thrust_N``, ``--max-days``),
# the value and the reason.
def _named(field: str | None, reason: str) -> str:
    return f"{field}: {reason}" if field else reason


def _real(value) -> float | None:
    """``value`` as a float if it is a real number or numeric text, else None."""
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, str):
        value = value.strip()
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def _shown(value) -> str:
    """A value as the user wrote it: text quoted, numbers plainly (-8, not -8.0)."""
    v = None if isinstance(value, str) else _real(value)
    return repr(value) if v is None else f"{v:g}"


def number(field: str | None, value, unit: str, *, positive: bool = False,
           minimum: float | None = None, maximum: float | None = None,
           limit: str = "") -> float:
    """A finite number (int, float, numpy scalar or numeric text) in range, as a float.

    ``positive`` refuses zero and below; ``minimum`` / ``maximum`` are inclusive bounds;
    ``limit`` says why ``maximum`` is the largest (appended to its message). InputError
    naming ``field`` (as the user wrote it), the value and the reason otherwise.
    """
    u = f" {unit}" if unit else ""
    v = _real(value)
    if v is None:
        raise InputError(_named(field, f"must be a number{' of ' + unit if unit else ''}, "
                                       f"got {_shown(value)}"))
    if not math.isfinite(v):
        raise InputError(_named(field, f"must be a finite number{' of ' + unit if unit else ''}"
                                       f", got {_shown(value)}"))
    if positive and v <= 0:
        raise InputError(_named(field, f"must be positive ({unit or 'a number'}), got "
                                       f"{_shown(value)}"))
    if minimum is not None and v < minimum:
        raise InputError(_named(field, f"{v:g}{u} is below the smallest allowed, "
                                       f"{minimum:g}{u}"))
    if maximum is not None and v > maximum:
        why = f" ({limit})" if limit else ""
        raise InputError(_named(field, f"{v:g}{u} is above the largest allowed, "
                                       f"{maximum:g}{u}{why}"))
    return v


def positive_number(field: str | None, value, unit: str) -> float:
    """A positive finite number, as a float (see :func:`number`)."""
    return number(field, value, unit, positive=True)


def integer(field: str | None, value, minimum: int | None = None) -> int:
    """An integer (int, integral float or digits) >= ``minimum``, else InputError."""
    v = _real(value)
    if v is None or not math.isfinite(v) or v != int(v):
        raise InputError(_named(field, f"must be an integer, got {_shown(value)}"))
    if minimum is not None and v < minimum:
        raise InputError(_named(field, f"must be an integer >= {minimum}, got {_shown(value)}"))
    return int(v)


def number_list(field: str | None, value, unit: str, *, positive: bool = False,
                minimum: float | None = None, maximum: float | None = None,
                distinct: bool = False) -> tuple:
    """Numbers from ``"1,2.5,3"`` or a sequence, each checked as by :func:`number`.

    InputError naming the field on an empty list or item, a bad number, or (``distinct``)
    a duplicate.
    """
    if isinstance(value, str):
        items = [s.strip() for s in value.split(",")]
        if not value.strip() or any(s == "" for s in items):
            raise InputError(_named(field, f"must be numbers{' of ' + unit if unit else ''} "
                                           f"separated by commas, got {_shown(value)}"))
    elif _real(value) is not None and not isinstance(value, str):
        items = [value]
    else:
        try:
            items = list(value)
        except TypeError:
            raise InputError(_named(field, f"must be a list of numbers, got {_shown(value)}")) \
                from None
    if not items:
        raise InputError(_named(field, "must not be empty"))
    out = tuple(number(f"{field}[{j + 1}]" if field and not isinstance(value, str) else field,
                       x, unit, positive=positive, minimum=minimum, maximum=maximum)
                for j, x in enumerate(items))
    if distinct and len(set(out)) != len(out):
        raise InputError(_named(field, f"has duplicates: {_shown(value)}"))
    return out
