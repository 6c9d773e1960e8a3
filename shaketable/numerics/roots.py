"""Root finders for compiled engines: Brent's method on a function of one variable.

An engine locates an event as the zero of an event function on a step's continuous
extension (:func:`shaketable.numerics.dop853.dense_state`); it passes that function as a
compiled ``f(x, args)`` and numba compiles the finder for it (inlined into the caller, as
:mod:`shaketable.numerics.dop853`'s functions).
"""

from __future__ import annotations

from numba import njit

from shaketable.numerics.dop853 import INLINE

#: Iterations of :func:`brent` before it returns its last iterate.
MAX_ITERATIONS = 100


@njit(**INLINE)
def brent(f, args, xa, xb, xtol, rtol):
    """A zero of ``f(x, args)`` in [xa, xb] by Brent's method (SciPy's ``brentq``, as its C
    code ``brentq.c``: inverse quadratic interpolation or the secant, safeguarded by
    bisection), to |dx| < (xtol + rtol |x|) / 2.

    The ends are tried first: one where f is 0 is returned; with no sign change between
    them (left by rounding) ``xb`` is.
    """
    xpre, xcur = xa, xb
    fpre = f(xpre, args)
    fcur = f(xcur, args)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if (fpre < 0.0) == (fcur < 0.0):
        return xcur
    xblk, fblk, spre, scur = 0.0, 0.0, 0.0, 0.0
    for _ in range(MAX_ITERATIONS):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2.0
        sbis = (xblk - xcur) / 2.0
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
        fcur = f(xcur, args)
    return xcur
