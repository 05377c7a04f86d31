"""The normal law N*(a*) of a profile as plain Python: its descriptor, its evaluation, its table.

A normal law is described by a float64 vector ``law`` (the *descriptor*), so that one function
serves power laws and tabulated laws alike:

* power law, N*(a*) = a*^p (Hertz for the sphere, p = 3/2; cone p = 2; flat punch p = 1):
  ``law = [p]`` with p >= 1;
* tabulated law, from measured or computed (a*, N*) pairs: ``law = [-1, n, h, N_0..N_n,
  N'_0..N'_n]``, values and slopes of a monotone cubic (PCHIP, Fritsch and Carlson 1980) resampled
  on the uniform grid a_i = i h, evaluated as a cubic Hermite on each cell (so N*' is exactly the
  derivative of N*, which the memory-diagram integrals need); past the last node the law goes on
  along its last tangent.

N* = 0 and N*' = 0 for a* <= 0 (contact lost).

This module owns the law: the scene (:class:`~sawdrift.scene.profiles.Profile`) evaluates it in
Python, and :mod:`sawdrift.contact.normal` compiles these same functions (``_hermite``,
:func:`power_law`, ``_power_slope``, :func:`law_normal`, :func:`law_slope`) with numba for the
kernels. They are therefore written in the subset numba compiles, call each other by their
global names (which the compiled module binds to the compiled functions), and this module
imports no numba: the scene stays light to import.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

#: cells of the uniform grid a tabulated law is resampled on
TABLE_CELLS = 4096


def _hermite(z: float, law, off: int, derivative: bool) -> float:
    n = int(law[off + 1])
    h = law[off + 2]
    iv = off + 3
    idv = off + 4 + n
    x = z / h
    i = int(x)
    if i >= n:
        # past the last node: along the last tangent
        dn = law[idv + n]
        if derivative:
            return dn
        return law[iv + n] + dn * (z - n * h)
    s = x - i
    y0 = law[iv + i]
    y1 = law[iv + i + 1]
    m0 = law[idv + i] * h
    m1 = law[idv + i + 1] * h
    if derivative:
        s2 = s * s
        return ((6.0 * s2 - 6.0 * s) * (y0 - y1) + (3.0 * s2 - 4.0 * s + 1.0) * m0
                + (3.0 * s2 - 2.0 * s) * m1) / h
    s2 = s * s
    s3 = s2 * s
    return ((2.0 * s3 - 3.0 * s2 + 1.0) * y0 + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * y1 + (s3 - s2) * m1)


def power_law(z: float, p: float) -> float:
    """N*(z) = z^p for z > 0, else 0: the power law with a scalar exponent."""
    out = 0.0
    if z > 0.0:
        out = z**p
    return out


def _power_slope(z: float, p: float) -> float:
    """N*'(z) = p z^(p-1) of a power law at z > 0: no power for Hertz, the cone or the flat punch."""
    out = 0.0
    if p == 1.5:
        out = 1.5 * math.sqrt(z)
    elif p == 1.0:
        out = 1.0
    elif p == 2.0:
        out = 2.0 * z
    else:
        out = p * z ** (p - 1.0)
    return out


def law_normal(z: float, law, off: int) -> float:
    """N*(z) of the descriptor ``law[off:]``; 0 for z <= 0.

    A power law is evaluated as N*(z) = z N*'(z) / p (Euler's relation for the homogeneous z^p,
    N*' as :func:`law_slope` gives it): the rounding of the N*(z) the memory diagram stores for
    its kinks (:mod:`sawdrift_builtin.mmd_kernel`), so the normal slot and that law agree bit for
    bit, and a Hertz contact costs a square root instead of a power.
    """
    out = 0.0
    if z > 0.0:
        p = law[off]
        if p > 0.0:
            out = z * _power_slope(z, p) / p
        else:
            out = _hermite(z, law, off, False)
    return out


def law_slope(z: float, law, off: int) -> float:
    """N*'(z) of the descriptor ``law[off:]``; 0 for z <= 0 (convention N*'(0-) = 0).

    A flat punch (p = 1) thus carries its whole dN*' as a point mass at z = 0+.
    """
    out = 0.0
    if z > 0.0:
        p = law[off]
        if p > 0.0:
            out = _power_slope(z, p)
        else:
            out = _hermite(z, law, off, True)
    return out


#: The functions :mod:`sawdrift.contact.normal` compiles, callees first (each call between them
#: goes through its global name).
COMPILED = (_hermite, power_law, _power_slope, law_normal, law_slope)


# -- tabulated laws ----------------------------------------------------------------------------


def table_descriptor(a: np.ndarray, n: np.ndarray, cells: int = TABLE_CELLS) -> np.ndarray:
    """The descriptor of the tabulated law through the points (a_i, N_i).

    The points are joined by a monotone cubic (scipy's PCHIP), resampled on ``cells`` uniform
    cells over [0, max a]. (0, 0) is added if the table does not start there.
    """
    from scipy.interpolate import PchipInterpolator  # scipy: only when a table is read

    a = np.asarray(a, dtype=float)
    n = np.asarray(n, dtype=float)
    if a[0] > 0.0:
        a = np.concatenate([[0.0], a])
        n = np.concatenate([[0.0], n])
    interp = PchipInterpolator(a, n, extrapolate=False)
    grid = np.linspace(0.0, a[-1], cells + 1)
    values = interp(grid)
    slopes = interp.derivative()(grid)
    return np.concatenate([[-1.0, float(cells), a[-1] / cells], values, slopes])


#: the largest a*, N* of a tabulated law (a* in static compressions, N* in weights)
TABLE_MAX = 1e12


def check_table(a: np.ndarray, n: np.ndarray, source: str) -> None:
    """Raise ValueError (one line naming ``source``) unless (a, N) is a usable normal law.

    Needed: at least 4 finite points, a >= 0 strictly increasing, N >= 0 non-decreasing, N = 0
    at a = 0 if given, and N(1) = 1 to 1e-6 relative (a0 is the compression under M g, so N*(1) = 1
    by definition of the scaling).
    """
    bad = np.flatnonzero(~(np.isfinite(a) & np.isfinite(n)))
    if bad.size:  # a table of 5 rows, one NaN, was said to need "at least 4 finite rows"
        raise ValueError(f"{source}: every row must be finite: one has a = {a[bad[0]]:g}, "
                         f"N = {n[bad[0]]:g}")
    if a.size < 4:
        raise ValueError(f"{source}: needs at least 4 rows of columns a, N (it has {a.size})")
    if np.max(a) > TABLE_MAX or np.max(n) > TABLE_MAX:
        # 1e308 overflowed the interpolation's slopes: two numpy warnings and scipy's own error
        raise ValueError(f"{source}: a and N must be at most {TABLE_MAX:g} (units of the static "
                         "compression a0 and of the weight M g)")
    if a[0] < 0.0 or np.any(np.diff(a) <= 0.0):
        raise ValueError(f"{source}: column a must start at >= 0 and strictly increase")
    if np.any(n < 0.0) or np.any(np.diff(n) < 0.0):
        raise ValueError(f"{source}: column N must be >= 0 and non-decreasing")
    if a[0] == 0.0 and n[0] != 0.0:
        raise ValueError(f"{source}: N must be 0 at a = 0 (no force without compression)")
    if not a[0] <= 1.0 <= a[-1]:
        raise ValueError(f"{source}: the table must cover a = 1 (the static compression)")
    from scipy.interpolate import PchipInterpolator  # scipy: only when a table is read

    n1 = float(PchipInterpolator(a, n)(1.0))
    if abs(n1 - 1.0) > 1e-6:
        raise ValueError(
            f"{source}: N(1) = {n1:.8g}, must be 1 (normalized: N* = N/(M g), a* = a/a0, "
            "and a0 is the compression under M g)"
        )


def read_table(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Columns ``a`` and ``N`` of a CSV file (header row required), checked."""
    path = Path(path)
    source = f"profile table {str(path)!r}"
    try:
        with path.open(newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    except FileNotFoundError:
        raise ValueError(f"{source} does not exist") from None
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise ValueError(f"{source} cannot be read as UTF-8 CSV ({exc})") from None
    if not rows or not {"a", "N"} <= set(rows[0]):
        raise ValueError(f"{source} needs a header with columns a and N")
    try:
        a = np.array([float(r["a"]) for r in rows])
        n = np.array([float(r["N"]) for r in rows])
    except (TypeError, ValueError):
        raise ValueError(f"{source}: every a and N must be a number") from None
    check_table(a, n, source)
    return a, n
