"""Each compiled integrator calls its own method's functions.

:func:`shaketable.models.rocking.engine._integrator` compiles one integrator per method from a copy
of the engine's namespace in which ``model_acceleration``, ``flight_model`` and ``advance``
are the method's functions (``steppers.METHOD_FUNCTIONS``) and the helpers that call them
are compiled again. Two ways this could go wrong without a compile error: a helper left on
the module's names (they are an uncompiled placeholder, so it fails to compile), and two
methods' helpers compiled under one symbol name, which numba's cache then links into both
integrators once they are loaded into one process (found in review: the linear run started
rocking at the exact model's instant and gave 19 impacts instead of 17).
"""

import json
import os
import subprocess
import sys

import pytest

from shaketable.models.rocking import engine, events, steppers
from shaketable.models.rocking.layout import METHOD_FAST, METHOD_LINEAR, METHOD_PREDICTOR_CORRECTOR

INTEGRATORS = {METHOD_FAST: engine.integrate_fast,
               METHOD_PREDICTOR_CORRECTOR: engine.integrate_predictor_corrector,
               METHOD_LINEAR: engine.integrate_linear}


def test_each_integrator_binds_its_methods_functions_and_helpers_of_its_own():
    qualified_names = set()
    for method, integrator in INTEGRATORS.items():
        namespace = integrator.py_func.__globals__
        for name, function in steppers.METHOD_FUNCTIONS[method].items():
            assert namespace[name] is function, (method, name)
        for helper_name in engine._METHOD_HELPERS:
            helper = namespace[helper_name]
            # the engine's helpers read the integrator's namespace, those of
            # models.rocking.events a copy of their own module's, bound the same way
            own = helper.py_func.__globals__
            if helper_name in events.METHOD_HELPERS:
                assert own is not vars(events), (method, helper_name)
                assert own[helper_name] is helper, (method, helper_name)
            else:
                assert own is namespace, (method, helper_name)
            for name, function in steppers.METHOD_FUNCTIONS[method].items():
                assert own[name] is function, (method, helper_name, name)
            qualified_names.add(helper.py_func.__qualname__)
    # one compiled name per method and helper: the symbols numba's cache links by name
    assert len(qualified_names) == len(INTEGRATORS) * len(engine._METHOD_HELPERS)
    with pytest.raises(NotImplementedError):
        engine.advance()
    with pytest.raises(NotImplementedError):
        events.advance()


# One run of each listed method, printed as JSON (the numbers that differed in review).
_RUN = r"""
import json, sys
import shaketable as st
from shaketable.ground import records
motion = records.load("pacoima-dam-s16e")
results = {}
for method in sys.argv[1].split(","):
    run = st.simulate(st.Block.parse("4x1ft"), motion, cor=0.9, method=method)
    results[method] = [repr(run.t_start), run.n_impacts, [repr(t) for t in run.impact_times]]
print(json.dumps(results))
"""


@pytest.mark.slow
def test_integrators_compiled_in_separate_processes_stay_apart_when_loaded_together(tmp_path):
    """Compile linear and predictor-corrector in two processes into one empty cache, then
    load both into a third: each must give what it gave when compiled alone."""
    environment = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))

    def run(methods):
        output = subprocess.run([sys.executable, "-c", _RUN, methods], env=environment,
                                capture_output=True, text=True, check=True).stdout
        return json.loads(output.strip().splitlines()[-1])

    alone = {**run("linear"), **run("predictor-corrector")}
    together = run("predictor-corrector,linear")
    assert together == alone
