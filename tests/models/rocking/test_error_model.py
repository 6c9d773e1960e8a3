"""Every compiled function of the engines is compiled with numba's "numpy" error model,
given explicitly (``shaketable.models.rocking.physics.ERROR_MODEL``; why, in its comment).

numba's cache and its compiled overloads ignore a function's options, so one left to
inherit its caller's error model would be compiled, and cached, with whichever model its
first caller had: a helper called from Python first ("python") would then be linked into
an engine compiled after it. That the results do not depend on the model (the engines'
divisions are guarded) is checked bit for bit by the engines' own tests against their
references; here, that no function lost the option.
"""

from __future__ import annotations

import importlib
import pkgutil

from numba.core.dispatcher import Dispatcher

import shaketable.core
import shaketable.models
from shaketable.models.rocking import engine
from shaketable.models.rocking.physics import ERROR_MODEL


def _compiled_functions() -> dict:
    """Every numba dispatcher defined in shaketable.core and shaketable.models, and the
    per-method helper copies of each rocking integrator (compiled in a namespace of their
    own, :func:`shaketable.models.rocking.engine._integrator`)."""
    found = {}
    for package in (shaketable.core, shaketable.models):
        for info in pkgutil.walk_packages(package.__path__, f"{package.__name__}."):
            module = importlib.import_module(info.name)
            for value in vars(module).values():
                if isinstance(value, Dispatcher) \
                        and value.py_func.__module__.startswith("shaketable."):
                    found[f"{value.py_func.__module__}.{value.py_func.__qualname__}"] = value
    for integrator in engine.INTEGRATORS.values():
        for value in integrator.py_func.__globals__.values():
            if isinstance(value, Dispatcher):
                found[value.py_func.__qualname__] = value
    return found


def test_every_engine_function_has_the_numpy_error_model_explicitly():
    functions = _compiled_functions()
    # the three engines and their helpers are all found (a sanity floor: the rocking
    # integrators, the planar driver, the sliding integrator and the batch loops)
    for name in ("integrate_fast", "integrate_linear.locate", "integrate_fast.step_events",
                 "integrate_fast._start_of_rocking",
                 "shaketable.models.planar.engine.integrate", "shaketable.models.planar.steps.dop853_step",
                 "shaketable.models.planar.physics.impact",
                 "shaketable.models.sliding.engine.stick_slip_kernel",
                 "shaketable.models.rocking.batch._run_cases_fast", "shaketable.models.rocking.steppers.nystrom"):
        assert name in functions, name
    assert len(functions) > 60
    wrong = sorted(name for name, function in functions.items()
                   if function.targetoptions.get("error_model") != ERROR_MODEL)
    assert not wrong, f"compiled without error_model={ERROR_MODEL!r}: {wrong}"
    assert ERROR_MODEL == "numpy"
