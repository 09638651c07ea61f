"""Exception types of lunarcap.

Every error a user can cause (bad input) is a :class:`InputError`; an optimisation
that did not converge or failed verification is a :class:`SolveError`. The CLI turns
both into one clear message and a non-zero exit status.
"""

from __future__ import annotations


class LunarcapError(Exception):
    """Base class of lunarcap's own errors."""


class InputError(LunarcapError, ValueError):
    """A parameter is out of its physical or valid range (bad input)."""


class EphemerisRangeError(InputError):
    """An epoch lies outside the time span covered by the ephemeris."""


class SolveError(LunarcapError, RuntimeError):
    """An optimisation failed to converge or its solution failed verification.

    Attributes
    ----------
    status : str
        IPOPT's return status (or ``"verification failed"``).
    details : dict
        Residuals and diagnostics (delta-V difference, terminal errors, mesh).
    """

    def __init__(self, message: str, status: str = "", details: dict | None = None):
        super().__init__(message)
        self.status = status
        self.details = dict(details or {})
