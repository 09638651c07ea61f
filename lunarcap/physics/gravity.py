"""Lunar gravity fields in spherical harmonics: the files, and the acceleration they give.

A field is a set of fully normalised coefficients C_nm, S_nm (Kaula's normalisation,
no Condon-Shortley phase) with a reference radius R and a GM, defined in a body-fixed
frame of the Moon. The potential is

    U = GM/r sum_n (R/r)^n sum_m P_nm(sin lat) (C_nm cos m lon + S_nm sin m lon).

Fields are read from two formats:

* GMAT's ``.cof`` (fixed columns: ``POTFIELD`` degree, order, GM m^3/s^2, R m; one
  ``RECOEF n m C S`` line per term; comment lines start with ``C``; GMAT's
  ``GravityFileUtil::ReadCofFile`` reads the same columns);
* PDS SHADR (Spherical Harmonics ASCII Data Record; the Software Interface Specification
  of the PDS Geosciences node): a comma-separated header record (R km, GM km^3/s^2, its
  uncertainty, degree, order, normalisation state 1 = normalised, reference longitude and
  latitude), then one record per term ``n, m, C, S, sigma C, sigma S``.

The packaged field is **LP165P** (Konopliv, Asmar, Carranza, Sjogren & Yuan 2001,
"Recent gravity models as a result of the Lunar Prospector mission", Icarus 150, 1-18,
doi:10.1006/icar.2000.6573; Lunar Prospector gravity from NASA's Planetary Data System,
as distributed with NASA's GMAT, ``data/gravity/luna/LP165P.cof``), truncated to degree
and order :data:`PACKAGED_DEGREE` (see :func:`packaged_field`). Its coefficients are a
work of the U.S. Government (NASA/JPL) published in the PDS without restriction; the
citation above is owed. Its frame is the Moon's principal-axis frame of its solution,
which lunarcap takes as the DE405 principal-axis frame (the libration angles, as GMAT
does).

:func:`sh_acceleration` evaluates the gradient with the normalised Cunningham (V, W)
recursions (Montenbruck & Gill 2000, Satellite Orbits, Sec. 3.2.4-3.2.5, normalised):
Cartesian, so regular at the poles, and written over generic operations (numpy arrays or
CasADi symbols) like the rest of the dynamics.
"""

from __future__ import annotations

import gzip
import hashlib
import math
import os
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops

#: Degree and order of the packaged LP165P (of 165 in the file): see :func:`packaged_field`.
PACKAGED_DEGREE = 100
#: The packaged fields by name.
PACKAGED = {"LP165P": "LP165P_100.cof.gz"}
_DATA = Path(__file__).with_name("data")


@dataclass(frozen=True, eq=False)
class GravityField:
    """A spherical-harmonic gravity field (fully normalised coefficients).

    Attributes
    ----------
    name : str
        The packaged name, or the file's stem.
    gm_km3ps2 : float
        The field's GM, km^3/s^2 (lunarcap's dynamics use the plan's GM; see
        :mod:`lunarcap.physics.forces.harmonics`).
    radius_km : float
        Reference radius R, km.
    degree, order : int
        Largest degree and order present.
    C, S : ndarray, shape (degree + 1, degree + 1)
        C[n, m], S[n, m]; zero where the file gives none (and for n < 2).
    source : str
        The file read.
    sha256 : str
        SHA-256 of the file's bytes (a cache key of anything computed with it).
    """

    name: str
    gm_km3ps2: float
    radius_km: float
    degree: int
    order: int
    C: np.ndarray = field(repr=False)
    S: np.ndarray = field(repr=False)
    source: str = ""
    sha256: str = ""

    @property
    def j2(self) -> float:
        """Unnormalised J2 = -sqrt(5) C20."""
        return -math.sqrt(5.0) * float(self.C[2, 0])

    def describe(self) -> dict:
        """Provenance: name, file, SHA-256, degree and order, GM and radius."""
        return {"field": self.name, "path": self.source, "sha256": self.sha256,
                "degree": self.degree, "order": self.order, "gm_km3ps2": self.gm_km3ps2,
                "radius_km": self.radius_km}


def _text(path: Path) -> tuple[str, str]:
    """(text, sha256) of a field file, gunzipped if it ends in .gz."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"gravity field {path}: cannot read it: {exc}") from None
    sha = hashlib.sha256(raw).hexdigest()
    if path.suffix == ".gz":
        raw = gzip.decompress(raw)
    try:
        return raw.decode("ascii"), sha
    except UnicodeDecodeError:
        raise InputError(f"gravity field {path}: not a text file") from None


def _arrays(terms: dict, where: str) -> tuple:
    """(degree, order, C, S) from {(n, m): (C, S)}."""
    if not terms:
        raise InputError(f"{where}: no coefficients")
    deg = max(n for n, _ in terms)
    C, S = np.zeros((deg + 1, deg + 1)), np.zeros((deg + 1, deg + 1))
    for (n, m), (c, s) in terms.items():
        C[n, m], S[n, m] = c, s
    C[:2, :] = S[:2, :] = 0.0   # the central term is the GM; degree 1 is the origin
    return deg, max(m for _, m in terms), C, S


def read_cof(path) -> GravityField:
    """A field from GMAT's ``.cof`` format (normalised coefficients; GM m^3/s^2, R m)."""
    path = Path(path)
    text, sha = _text(path)
    head, terms = None, {}
    for k, line in enumerate(text.splitlines(), 1):
        if not line.strip() or line[0] == "C":
            continue
        key = line[:8].strip()
        try:
            if key == "END":
                break
            if key == "POTFIELD":
                words = line[14:].split()
                head = (float(words[1]) * 1e-9, float(words[2]) * 1e-3)
            elif key == "RECOEF":
                n, m = int(line[8:11]), int(line[11:14])
                s_txt = line[38:59].strip()
                terms[(n, m)] = (float(line[17:38]), float(s_txt) if s_txt else 0.0)
            else:
                raise ValueError(f"unknown record {key!r}")
        except (ValueError, IndexError) as exc:
            raise InputError(f"gravity field {path.name}, line {k}: not a .cof record "
                             f"({exc})") from None
    if head is None:
        raise InputError(f"gravity field {path.name}: no POTFIELD line (GM and radius)")
    deg, order, C, S = _arrays(terms, f"gravity field {path.name}")
    return GravityField(_stem(path), head[0], head[1], deg, order, C, S, str(path), sha)


def read_shadr(path) -> GravityField:
    """A field from a PDS SHADR table (header: R km, GM km^3/s^2, ...; normalised only)."""
    path = Path(path)
    text, sha = _text(path)
    rows = [ln for ln in text.splitlines() if ln.strip()]
    try:
        head = [w.strip() for w in rows[0].replace("D", "E").split(",")]
        radius, gm, norm = float(head[0]), float(head[1]), int(head[5])
    except (ValueError, IndexError):
        raise InputError(f"gravity field {path.name}: the first record is not a SHADR "
                         "header (R km, GM km^3/s^2, sigma GM, degree, order, "
                         "normalisation, lon, lat)") from None
    if norm != 1:
        raise InputError(f"gravity field {path.name}: normalisation state {norm}; lunarcap "
                         "reads fully normalised fields (state 1)")
    terms = {}
    for k, line in enumerate(rows[1:], 2):
        w = line.replace("D", "E").split(",")
        try:
            terms[(int(w[0]), int(w[1]))] = (float(w[2]), float(w[3]))
        except (ValueError, IndexError):
            raise InputError(f"gravity field {path.name}, record {k}: not 'n, m, C, S, "
                             "sigma C, sigma S'") from None
    deg, order, C, S = _arrays(terms, f"gravity field {path.name}")
    return GravityField(_stem(path), gm, radius, deg, order, C, S, str(path), sha)


def _stem(path: Path) -> str:
    name = path.name
    for suffix in (".gz", ".cof", ".sha", ".tab", ".txt"):
        name = name.removesuffix(suffix)
    return name


@lru_cache(maxsize=8)
def _load(path: str, mtime_ns: int) -> GravityField:
    p = Path(path)
    text_head = _text(p)[0][:200]
    if text_head.startswith(("C", "POTFIELD")) or ".cof" in p.name:
        return read_cof(p)
    return read_shadr(p)


def packaged_field(name: str = "LP165P") -> GravityField:
    """A packaged field, truncated to degree and order :data:`PACKAGED_DEGREE`.

    Why 100 (the most the package may carry; 97 kB gzipped, of 842 kB for all 165):
    measured on 200 random points, the terms of degree 61-100 carry 2 % (median; up to
    34 % over mascons) of the acceleration of the field less its C20 at 100 km altitude,
    16 % at 30 km; those of degree 101-165 carry 0.14 % (up to 1.8 %) at 100 km but 10 %
    at 30 km. So the packaged field is complete for orbits at 100 km and above; for lower
    orbits give the whole file (``gravity: /path/LP165P.cof``).
    """
    if name not in PACKAGED:
        raise InputError(f"no packaged gravity field {name!r} (packaged: "
                         f"{', '.join(PACKAGED)}); or give the path of a .cof or SHADR file")
    f = _load(str(_DATA / PACKAGED[name]), 0)
    return GravityField(name, f.gm_km3ps2, f.radius_km, f.degree, f.order, f.C, f.S,
                        f.source, f.sha256)


def load_field(spec: str, base_dir=None) -> GravityField:
    """A packaged field by name, or a ``.cof`` / SHADR file by path (relative to ``base_dir``)."""
    if spec in PACKAGED:
        return packaged_field(spec)
    p = Path(os.path.expanduser(spec))
    if not p.is_absolute() and base_dir is not None:
        p = Path(base_dir) / p
    if not p.is_file():
        raise InputError(f"gravity field {spec!r}: not a packaged field "
                         f"({', '.join(PACKAGED)}) and no such file")
    return _load(str(p.resolve()), p.stat().st_mtime_ns)


# ---------------------------------------------------------------------- the acceleration
def _vw(x, y, z, radius, nmax, mmax):
    """Normalised V_nm, W_nm (n <= nmax, m <= min(n, mmax)) at body-fixed (x, y, z)."""
    xp = ops(x, y, z)
    r2 = x * x + y * y + z * z
    rr = radius / r2
    x0, y0, z0, rho2 = x * rr, y * rr, z * rr, radius * rr
    V = [[0.0] * (nmax + 1) for _ in range(nmax + 1)]
    W = [[0.0] * (nmax + 1) for _ in range(nmax + 1)]
    V[0][0] = radius / xp.sqrt(r2)
    for m in range(0, mmax + 1):
        if m > 0:   # sectorial: V_mm from V_m-1,m-1
            g = math.sqrt(3.0) if m == 1 else math.sqrt((2 * m + 1) / (2 * m))
            V[m][m] = g * (x0 * V[m - 1][m - 1] - y0 * W[m - 1][m - 1])
            W[m][m] = g * (x0 * W[m - 1][m - 1] + y0 * V[m - 1][m - 1])
        for n in range(m + 1, nmax + 1):
            a = math.sqrt((2 * n + 1) * (2 * n - 1) / ((n - m) * (n + m)))
            V[n][m] = a * z0 * V[n - 1][m]
            W[n][m] = a * z0 * W[n - 1][m] if m > 0 else 0.0
            if n >= m + 2:
                b = math.sqrt((2 * n + 1) * (n + m - 1) * (n - m - 1)
                              / ((2 * n - 3) * (n + m) * (n - m)))
                V[n][m] = V[n][m] - b * rho2 * V[n - 2][m]
                if m > 0:
                    W[n][m] = W[n][m] - b * rho2 * W[n - 2][m]
    return V, W


def sh_acceleration(x, y, z, C, S, radius, mu, degree, order, skip_c20=False):
    """Acceleration of a normalised field at body-fixed (x, y, z) km, km/s^2.

    Parameters
    ----------
    x, y, z : float, ndarray or CasADi symbols
        Position in the field's body-fixed frame, km.
    C, S : ndarray
        Normalised coefficients (C[n, m], S[n, m]); terms of degree 2..``degree`` and
        order 0..``order`` are summed (the central term is not included).
    radius : float
        Reference radius, km.
    mu : float
        GM that scales the field, km^3/s^2.
    skip_c20 : bool
        Leave C20 out (the dynamics add it as the zonal J2 term about the body's pole).

    Returns
    -------
    ax, ay, az : in the body-fixed frame, km/s^2
    """
    V, W = _vw(x, y, z, radius, degree + 1, min(order, degree) + 1)
    ax = ay = az = 0.0
    for n in range(2, degree + 1):
        for m in range(0, min(n, order) + 1):
            c = 0.0 if (skip_c20 and n == 2 and m == 0) else float(C[n, m])
            s = float(S[n, m])
            if c == 0.0 and s == 0.0:
                continue
            kz = math.sqrt((2 * n + 1) * (n + m + 1) * (n - m + 1) / (2 * n + 3))
            az = az - kz * (c * V[n + 1][m] + s * W[n + 1][m])
            if m == 0:
                k1 = math.sqrt((2 * n + 1) * (n + 1) * (n + 2) / (2 * (2 * n + 3)))
                ax = ax - k1 * c * V[n + 1][1]
                ay = ay - k1 * c * W[n + 1][1]
                continue
            kp = math.sqrt((2 * n + 1) * (n + m + 1) * (n + m + 2) / (2 * n + 3))
            km = math.sqrt(2 * (2 * n + 1) * (n - m + 2) * (n - m + 1)
                           / ((1 if m == 1 else 2) * (2 * n + 3)))
            ax = ax + 0.5 * (-kp * (c * V[n + 1][m + 1] + s * W[n + 1][m + 1])
                             + km * (c * V[n + 1][m - 1] + s * W[n + 1][m - 1]))
            ay = ay + 0.5 * (kp * (-c * W[n + 1][m + 1] + s * V[n + 1][m + 1])
                             + km * (-c * W[n + 1][m - 1] + s * V[n + 1][m - 1]))
    k = mu / (radius * radius)
    return k * ax, k * ay, k * az
