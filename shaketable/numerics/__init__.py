"""What every event-driven engine shares, compiled once for any model's equations: DOP853's
step, error control, initial step and continuous extension (:mod:`~shaketable.numerics.dop853`),
root finding on the extension (:mod:`~shaketable.numerics.roots`) and the closed-form sum of
an endless cascade of impacts (:mod:`~shaketable.numerics.cascade`).

The bottom layer of the package with :mod:`shaketable.core`: it imports nothing else of it.
"""
