"""Tests of lunarcap.physics.gravity: the field files and the spherical-harmonic acceleration.

The acceleration (normalised Cunningham V/W recursions) is checked against an independent
formulation: the potential from a second, simple recursion (unnormalised associated
Legendre functions of sin(latitude) = z/r, with cos^m(lat) e^{i m lon} written as the
polynomials Re, Im (x + i y)^m / r^m), differentiated by the complex step
(df/dx = Im f(x + i h) / h, exact to rounding for an analytic f: no cancellation), so
the two agree to rounding, 1e-12 relative, at any point including over the poles.
"""

import gzip
import math

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.physics import gravity as G

LP = G.packaged_field("LP165P")
R, MU = LP.radius_km, 4902.800


def _potential(pos, C, S, radius, mu, nmax, mmax):
    """U at a (possibly complex) position by the unnormalised recursion in t = z/r."""
    x, y, z = pos
    r = np.sqrt(x * x + y * y + z * z)
    t = z / r
    re, im = [1.0 + 0 * x], [0.0 * x]          # Re, Im (x + i y)^m, real polynomials
    for m in range(1, mmax + 1):
        re, im = re + [x * re[-1] - y * im[-1]], im + [x * im[-1] + y * re[-1]]
    u = 0.0 * x
    for m in range(0, mmax + 1):
        # Q_nm(t) = d^m P_n / dt^m: Q_mm = (2m-1)!!, Q_m+1,m = (2m+1) t Q_mm,
        # (n - m) Q_nm = (2n - 1) t Q_n-1,m - (n + m - 1) Q_n-2,m
        q_prev, q = 0.0 * t, math.prod(range(1, 2 * m, 2)) + 0 * t
        for n in range(m, nmax + 1):
            if n > m:
                q_prev, q = q, ((2 * n - 1) * t * q - (n + m - 1) * q_prev) / (n - m)
            if n < 2:
                continue
            norm = math.sqrt((2 - (m == 0)) * (2 * n + 1) * math.factorial(n - m)
                             / math.factorial(n + m))
            term = norm * (C[n, m] * re[m] + S[n, m] * im[m]) / r ** m
            u = u + mu / r * (radius / r) ** n * q * term
    return u


def _gradient_complex_step(pos, *args):
    h = 1e-20
    g = np.zeros(3)
    for j in range(3):
        p = np.array(pos, dtype=complex)
        p[j] += 1j * h
        g[j] = _potential(p, *args).imag / h
    return g


POINTS = [
    (1838.0, 0.0, 0.0),                     # equator
    (0.0, 0.0, 1838.0),                     # north pole, exactly
    (0.0, 0.0, -1790.0),                    # south pole, exactly
    (1e-6, -2e-6, 1900.0),                  # a micrometre from the pole
    (3.0, -1.0, -1838.0),                   # 0.1 deg from the south pole
    (1234.5, -987.6, 1012.3),
    (-400.0, 1700.0, 300.0),
    (5000.0, 3000.0, -8000.0),              # far (apolune of a 12 h orbit)
]


@pytest.mark.parametrize("pos", POINTS)
@pytest.mark.parametrize("nmax", [2, 8, 20])
def test_acceleration_equals_complex_step_gradient_of_independent_potential(pos, nmax):
    ref = _gradient_complex_step(pos, LP.C, LP.S, R, MU, nmax, nmax)
    got = np.array(G.sh_acceleration(*pos, LP.C, LP.S, R, MU, nmax, nmax))
    assert np.linalg.norm(got - ref) <= 1e-12 * np.linalg.norm(ref)


def test_acceleration_without_c20_at_degree_20():
    # the part the J2 term does not carry: the same check on the field less its C20
    C = LP.C.copy()
    C[2, 0] = 0.0
    for pos in POINTS:
        ref = _gradient_complex_step(pos, C, LP.S, R, MU, 20, 20)
        got = np.array(G.sh_acceleration(*pos, LP.C, LP.S, R, MU, 20, 20, skip_c20=True))
        assert np.linalg.norm(got - ref) <= 1e-12 * np.linalg.norm(ref)


def test_order_truncation():
    # degree 8, order 3: only m <= 3 terms
    C, S = LP.C.copy(), LP.S.copy()
    C[:, 4:], S[:, 4:] = 0.0, 0.0
    pos = POINTS[5]
    ref = _gradient_complex_step(pos, C, S, R, MU, 8, 3)
    got = np.array(G.sh_acceleration(*pos, LP.C, LP.S, R, MU, 8, 3))
    assert np.linalg.norm(got - ref) <= 1e-12 * np.linalg.norm(ref)


def test_packaged_lp165p_is_the_shared_file_truncated():
    assert (LP.degree, LP.order) == (100, 100)
    assert LP.gm_km3ps2 == pytest.approx(4902.80105600)
    assert LP.radius_km == 1738.0
    assert LP.C[2, 0] == -9.08901807506000e-05 and LP.S[2, 2] == 1.67294905383000e-08
    assert LP.C[100, 100] == 8.42627241710000e-09
    assert LP.j2 == pytest.approx(2.0324e-4, rel=1e-4)   # Konopliv et al. 2001


def test_cof_and_shadr_readers_agree(tmp_path):
    text = gzip.decompress((G._DATA / G.PACKAGED["LP165P"]).read_bytes()).decode()
    cof = tmp_path / "small.cof"
    keep = [ln for ln in text.splitlines()
            if not ln.startswith("RECOEF") or int(ln[8:11]) <= 6]
    cof.write_text("\n".join(keep) + "\n")
    a = G.load_field(str(cof))
    rows = ["   1.7380000000000000E+03,   4.9028010560000000E+03,  0.0E+00,    6,    6,"
            "    1,   0.0E+00,   0.0E+00"]
    for n in range(2, 7):
        for m in range(n + 1):
            rows.append(f"{n:5d},{m:5d},{LP.C[n, m]:23.16E},{LP.S[n, m]:23.16E},"
                        f"{0.0:23.16E},{0.0:23.16E}")
    sha = tmp_path / "small.sha"
    sha.write_text("\n".join(rows) + "\n")
    b = G.load_field(str(sha))
    assert (a.degree, b.degree) == (6, 6)
    assert a.radius_km == b.radius_km and a.gm_km3ps2 == pytest.approx(b.gm_km3ps2)
    np.testing.assert_array_equal(a.C, b.C)
    np.testing.assert_array_equal(a.S, b.S)


def test_bad_field_files_are_refused_with_the_reason(tmp_path):
    with pytest.raises(InputError, match="not a packaged field"):
        G.load_field("LP999")
    bad = tmp_path / "bad.cof"
    bad.write_text("POTFIELD  2  2  0 4.9e12 1.738e6 1.0\nRECOEF    2  0   abc\n")
    with pytest.raises(InputError, match="line 2: not a .cof record"):
        G.load_field(str(bad))
    sha = tmp_path / "bad.sha"
    sha.write_text("1738.0, 4902.8, 0.0, 2, 2, 0, 0.0, 0.0\n2, 0, -9e-5, 0, 0, 0\n")
    with pytest.raises(InputError, match="normalisation state 0"):
        G.load_field(str(sha))
