"""What the stack's compiled modules share: the numba options and decorators of their
functions, and the small dense solve of their linear systems."""

from __future__ import annotations

from typing import Any

from numba import njit

from shaketable.core.numba_cache import register

register()

#: numba options of the compiled functions (called from compiled code only: no Python entry;
#: cached with the engine that links them). The error model is the package's ("numpy": a
#: division by zero gives inf or nan, as NumPy's, instead of raising).
COMPILED: Any = {"cache": True, "no_cpython_wrapper": True, "no_cfunc_wrapper": True,
                 "error_model": "numpy"}
KERNEL: Any = {**COMPILED, "_nrt": False}
#: The engine allocates nothing (its caller allocates every array), so that its functions
#: go without numba's reference counting (less code to generate and compile). Only a
#: function that calls none that allocates may use it: numba types a callee in its
#: caller's context.
kernel = njit(**KERNEL)
#: The functions called from one or two places, and thin wrappers, are inlined into their
#: caller in numba's IR, before typing, instead of compiled apart: a separately compiled
#: function is optimized again by LLVM, with all it calls, in every function compiled apart
#: that calls it (the module passes and the machine code of each such caller cover all it
#: links), so that each level of calls adds the compile of all below it. A large function
#: inlined costs numba's inliner (its IR copied block by block, each block with the whole
#: scope) and its own code at each call site: the large ones with a large subtree of their
#: own (the impact, the pattern choice, the plastic law) stay inlined or apart as measured
#: (the engine's first compile: 48 s of CPU with every function apart, 35 s with the small
#: ones inlined, about 28 s with the DOP853 segment apart and its step inlined).
inlined = njit(inline="always", error_model=COMPILED["error_model"])


@inlined
def solve(matrix, vector, size):
    """Solve the leading ``size`` x ``size`` system in place (Gaussian elimination with
    partial pivoting): the solution replaces ``vector[:size]``."""
    for col in range(size):
        pivot = col
        for row in range(col + 1, size):
            if abs(matrix[row, col]) > abs(matrix[pivot, col]):
                pivot = row
        if pivot != col:
            for k in range(size):
                matrix[col, k], matrix[pivot, k] = matrix[pivot, k], matrix[col, k]
            vector[col], vector[pivot] = vector[pivot], vector[col]
        for row in range(col + 1, size):
            factor = matrix[row, col] / matrix[col, col]
            for k in range(col, size):
                matrix[row, k] -= factor * matrix[col, k]
            vector[row] -= factor * vector[col]
    for row in range(size - 1, -1, -1):
        total = vector[row]
        for k in range(row + 1, size):
            total -= matrix[row, k] * vector[k]
        vector[row] = total / matrix[row, row]
