"""What :func:`~shaketable.models.api.simulate` and the batch share: the compiled methods,
their default tolerances, the checked run options, the motion cut or padded to a
duration and the info array turned into a :class:`~shaketable.models.rocking.result.RockingResult`.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numba
import numpy as np

from shaketable.core.motion import MIN_SAMPLE_INTERVAL, Motion, whole_number
from shaketable.core.validation import MAX_FIXED_STEPS, in_range, sample_count
from shaketable.models.rocking import engine
from shaketable.models.rocking.layout import METHODS
from shaketable.models.rocking.result import STATUSES, RockingResult

DEFAULT_RTOL = {"fast": 1e-11, "reference": 1e-12}

#: The smallest relative tolerance accepted [-]: double precision's unit roundoff (a smaller
#: one cannot be met, and one of 1e-320 made the tolerances underflow and the run endless).
MIN_RTOL = 1e-16

COMPILED_METHODS = {"fast": engine.METHOD_FAST,
             "predictor-corrector": engine.METHOD_PREDICTOR_CORRECTOR,
             "linear": engine.METHOD_LINEAR}


@dataclass(frozen=True)
class RunOptions:
    """The options of a run, checked once for :func:`~shaketable.models.api.simulate` and
    the batch (:mod:`shaketable.models.rocking.batch`) alike.

    Attributes
    ----------
    method : str
        A name of the solver registry :data:`~shaketable.models.rocking.layout.METHODS`.
    theta0 : float
        Initial rotation [rad], |theta0| < pi/2.
    theta_dot0 : float
        Initial angular velocity [rad/s].
    duration : float or None
        Length of the run [s] (``None``: the motion's own).
    rtol : float
        Relative tolerance of the adaptive methods [-], in (0, 1].
    subdivisions : int
        Predictor-corrector steps per input interval, >= 1.
    rest_tolerance : float
        Cascade duration [s] below which it is summed in closed form; -1 means the
        engine's default, 1e-6 / p.
    top_force : float
        Horizontal force at the top per unit mass [m/s^2].
    """

    method: str
    theta0: float
    theta_dot0: float
    duration: float | None
    rtol: float
    subdivisions: int
    rest_tolerance: float
    top_force: float


def run_options(method: str = "fast", *, methods=METHODS, theta0: float = 0.0,
                theta_dot0: float = 0.0, duration: float | None = None,
                rtol: float | None = None, subdivisions: int = 4,
                rest_tolerance: float | None = None, top_force: float = 0.0) -> RunOptions:
    """Check the options of a run and give them as :class:`RunOptions`.

    Parameters
    ----------
    method : str
        The solver; it must be one of ``methods``.
    methods : collection of str
        The methods the caller runs (the batch runs only the compiled ones).
    theta0, theta_dot0, duration, rtol, subdivisions, rest_tolerance, top_force
        As in :func:`shaketable.models.api.simulate`.

    Raises
    ------
    ValueError
        Naming the option and what it must be.
    """
    if method not in methods:
        hint = (" (the reference solver runs one at a time: use shaketable.simulate)"
                if method == "reference" and method in METHODS else "")
        raise ValueError(f"unknown method {method!r}; expected one of {sorted(methods)}{hint}")
    theta0 = in_range("theta0", theta0)
    if abs(theta0) >= math.pi / 2:
        raise ValueError(f"theta0 must satisfy |theta0| < pi/2 rad, got {theta0!r}")
    if duration is not None:
        duration = in_range("duration", duration, 0.0, low_open=True)
    if rtol is None:
        rtol = DEFAULT_RTOL.get(method, 1e-10)
    return RunOptions(
        method=method, theta0=theta0, theta_dot0=in_range("theta_dot0", theta_dot0),
        duration=duration, rtol=in_range("rtol", rtol, MIN_RTOL, 1.0),
        subdivisions=whole_number("subdivisions", subdivisions),
        rest_tolerance=(-1.0 if rest_tolerance is None
                        else in_range("rest_tolerance", rest_tolerance, 0.0)),
        top_force=in_range("top_force", top_force))


def starting_at_zero(motion: Motion) -> Motion:
    """The motion with its clock starting at 0; its own start in ``metadata["start time [s]"]``."""
    start = float(motion.t[0])
    if start == 0.0:
        return motion
    metadata = dict(motion.metadata)
    metadata["start time [s]"] = start + float(metadata.get("start time [s]", 0.0))
    return Motion(motion.t - start, motion.horizontal, motion.vertical, name=motion.name,
                  rotation=motion.rotation, metadata=metadata)


def run_motion(motion: Motion | None, duration: float | None, output_dt: float) -> Motion:
    """The motion a run integrates: free rocking (``motion=None``) on a table at rest for
    ``duration`` with output every ``output_dt`` [s], else the motion cut or padded to
    ``duration`` (:func:`extended`); ValueError naming what is wrong."""
    if motion is None:
        if duration is None:
            raise ValueError("free rocking (motion=None) needs a duration [s]")
        return Motion.at_rest(duration, in_range("output_dt", output_dt, 0.0, low_open=True))
    if not isinstance(motion, Motion):
        raise ValueError(f"motion must be a shaketable.Motion or None, got {type(motion).__name__}")
    return extended(motion, duration)


def extended(motion: Motion, duration: float | None) -> Motion:
    """The motion cut or padded with zeros (table at rest) to end at exactly ``duration``.

    Cut: the samples before ``t[0] + duration`` and one at that time,
    interpolated linearly (exact: a motion is linear between samples); a
    sample already within rounding of it is kept as it is. Padded: zeros
    every ``motion.dt`` after the last sample, the last interval shortened
    to end at ``t[0] + duration``.

    A motion that does not start at t = 0 (a record whose time column starts at an
    epoch offset, say t0 = 1.7e9 s) is first shifted to start at 0, its start kept
    in ``metadata["start time [s]"]``: a run's clock starts at the motion's first
    sample, and times of 1e9 s would leave the event location (1e-12 s) no digits.
    """
    motion = starting_at_zero(motion)
    if duration is None:
        return motion
    t = motion.t
    end = t[0] + duration
    tolerance = max(1e-9 * motion.dt, MIN_SAMPLE_INTERVAL)
    if end <= t[-1] + tolerance:
        k = int(np.searchsorted(t, end - tolerance, side="left"))
        if t[k] <= end + tolerance:       # a sample at the end already
            times, index = t[:k + 1], slice(0, k + 1)
            interpolate = False
        else:
            times, index = np.append(t[:k], end), slice(0, k)
            interpolate = True
        if times.size < 2:
            raise ValueError(f"duration {duration!r} s is shorter than the shortest accepted "
                             f"sample interval {MIN_SAMPLE_INTERVAL:g} s")

        def cut(values):
            if values is None:
                return None
            if not interpolate:
                return values[index]
            return np.append(values[index], np.interp(end, t, values))

        return Motion(times, cut(motion.horizontal), cut(motion.vertical), name=motion.name,
                      rotation=cut(motion.rotation))
    dt = motion.dt
    extra = sample_count(math.ceil((end - t[-1]) / dt - 1e-9),
                         f"extending the motion to duration {duration:g} s at its dt = {dt:g} s")
    added = t[-1] + dt * np.arange(1, extra + 1)
    added[-1] = end
    if added.size > 1 and end - added[-2] < tolerance:
        added = np.delete(added, -2)
    times = np.concatenate([t, added])

    def padded(values):
        return None if values is None else np.concatenate([values, np.zeros(added.size)])

    return Motion(times, padded(motion.horizontal), padded(motion.vertical), name=motion.name,
                  rotation=padded(motion.rotation))


def result_from_info(block, motion, cor, method, t_grid, theta, omega, acceleration, impact_times,
            impact_velocities, info) -> RockingResult:
    filled = int(info[engine.INFO_N_OUTPUT])
    status = STATUSES[int(info[engine.INFO_STATUS])]
    t = t_grid[:filled]
    t_end = info[engine.INFO_T_END]
    if status != "completed" and t_end > t[-1]:
        # the end state after the last sample: written into the solver's own arrays when
        # the run left room in them (it stopped early), rather than by np.append's copies
        if filled >= theta.size:
            theta, omega, acceleration = (np.append(x, 0.0) for x in
                                          (theta, omega, acceleration))
        t = np.empty(filled + 1)
        t[:filled] = t_grid[:filled]
        t[filled] = t_end
        theta[filled] = info[engine.INFO_THETA_END]
        omega[filled] = info[engine.INFO_THETA_DOT_END]
        acceleration[filled] = np.nan if status == "airborne" else 0.0
        filled += 1
        if status == "overturned":
            acceleration[filled - 1] = acceleration[filled - 2]
    theta, omega, acceleration = theta[:filled], omega[:filled], acceleration[:filled]
    if status == "airborne":
        acceleration[-1] = acceleration[-2] if acceleration.size > 1 else 0.0
    n_impacts = int(info[engine.INFO_N_IMPACTS])
    kept = min(n_impacts, impact_times.size)

    def direction(index):
        value = info[index]
        return 0 if not np.isfinite(value) else int(value)

    return RockingResult(
        block=block, motion=motion, cor=cor, method=method, t=t, theta=theta, theta_dot=omega,
        theta_ddot=acceleration, impact_times=impact_times[:kept].copy(),
        impact_velocities=impact_velocities[:kept].copy(),
        t_start=info[engine.INFO_T_START], t_unstable=info[engine.INFO_T_UNSTABLE],
        unstable_direction=direction(engine.INFO_UNSTABLE_DIRECTION),
        t_overturn=info[engine.INFO_T_OVERTURN],
        overturn_direction=direction(engine.INFO_OVERTURN_DIRECTION),
        t_airborne=info[engine.INFO_T_AIRBORNE], t_rest=info[engine.INFO_T_REST],
        max_abs_theta=info[engine.INFO_MAX_ABS_THETA], t_max=info[engine.INFO_T_MAX],
        n_impacts=n_impacts, cascades=int(info[engine.INFO_CASCADES]), status=status,
        statistics={"steps": int(info[engine.INFO_STEPS]),
                    "rejected": int(info[engine.INFO_REJECTED]),
                    "evaluations": int(info[engine.INFO_EVALUATIONS])},
    )


def engine_arrays(*arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """The arrays as the compiled engine takes its inputs: float64, C-contiguous, read-only.

    ``simulate`` and the batch hand the engine arrays of one type (a motion's arrays
    are read-only, ``Motion.rotation_or_zero`` may be a fresh writable array), so numba
    compiles :func:`~shaketable.models.rocking.engine.integrate` once, whichever comes first
    (an array's ``writeable`` flag is part of the compiled signature). Read-only views
    are made without copying the data.
    """
    views = []
    for values in arrays:
        view = np.ascontiguousarray(values, dtype=np.float64)
        if view.flags.writeable:
            view = view.view()
            view.flags.writeable = False
        views.append(view)
    return tuple(views)


_SCRATCH = threading.local()


def impact_buffers(size: int, work: int) -> tuple[np.ndarray, np.ndarray]:
    """Arrays of ``size`` for the impact times and velocities a run records.

    The engine writes only the impacts it records and :func:`result_from_info` copies
    those out, so a short run (``work`` up to :data:`INTERRUPTIBLE_WORK`) borrows this
    thread's scratch pair, grown as needed: a fresh 100,000-entry pair (the default
    ``max_recorded_impacts``) cost 0.1-0.2 ms a run in mmap, page faults and munmap,
    more than a third of a typical run. A long run gets its own pair, which an
    abandoned run (Ctrl-C, :func:`call_interruptibly`) may go on writing.
    """
    if work > INTERRUPTIBLE_WORK:
        return np.zeros(size), np.zeros(size)
    pair = getattr(_SCRATCH, "impacts", None)
    if pair is None or pair[0].size < size:
        pair = (np.zeros(size), np.zeros(size))
        _SCRATCH.impacts = pair
    return pair[0][:size], pair[1][:size]


#: Runs with more work than this (sample intervals, or fixed steps) run in a worker
#: thread so that Ctrl-C reaches Python within ~0.1 s; shorter runs (well under a
#: second) are called directly and keep their microsecond overhead.
INTERRUPTIBLE_WORK = 2_000_000


def call_interruptibly(function, arguments: tuple, work: int):
    """``function(*arguments)``; a long compiled run in a thread that Ctrl-C can leave.

    The compiled engine (``nogil``) cannot see Ctrl-C while it runs. For work above
    :data:`INTERRUPTIBLE_WORK` it runs in a daemon thread while the main thread waits
    in 0.1 s slices, so KeyboardInterrupt is raised at once in the caller (the
    abandoned thread finishes into arrays nobody reads; a CLI process exits). The
    arithmetic is the same either way: results are bit-identical.
    """
    if work <= INTERRUPTIBLE_WORK or threading.current_thread() is not threading.main_thread():
        return function(*arguments)
    outcome: dict = {}

    def target():
        try:
            outcome["value"] = function(*arguments)
        except BaseException as error:  # handed back to the caller below
            outcome["error"] = error

    worker = threading.Thread(target=target, name="shaketable-engine", daemon=True)
    worker.start()
    while worker.is_alive():
        worker.join(0.1)
    if "error" in outcome:
        raise outcome["error"]
    return outcome.get("value")


def check_fixed_steps(method: str, samples: int, subdivisions: int) -> None:
    """Refuse a fixed-step run whose work exceeds :data:`MAX_FIXED_STEPS` before it starts.

    ``predictor-corrector`` takes ``subdivisions`` equal steps per sample interval,
    whatever the motion: (samples - 1) x subdivisions steps in all.
    """
    if method != "predictor-corrector":
        return
    steps = (samples - 1) * subdivisions
    if steps > MAX_FIXED_STEPS:
        raise ValueError(f"subdivisions {subdivisions:,} x {samples - 1:,} sample intervals = "
                         f"{steps:.3g} predictor-corrector steps; the limit is "
                         f"{MAX_FIXED_STEPS:.3g} per run (use fewer subdivisions, or "
                         f"method='fast', which chooses its own steps)")


def labelled(name: str, values, kind: type, default_label: Callable, *,
             wrong_type: type[Exception] = ValueError,
             qualifier: str = "shaketable.") -> tuple[list[str], list]:
    """(labels, objects) of a batch's inputs given as one object, a sequence, or a
    label -> object mapping; ``default_label(object)`` labels the unlabelled.

    Raises ValueError when there are none, and ``wrong_type`` naming ``name[k]`` and
    ``qualifier + kind.__name__`` for an item that is not a ``kind``.
    """
    if isinstance(values, kind):
        values = [values]
    if isinstance(values, Mapping):
        labels, objects = [str(key) for key in values], list(values.values())
    else:
        objects = list(values)
        labels = None
    if not objects:
        raise ValueError(f"{name} must not be empty")
    for k, item in enumerate(objects):
        if not isinstance(item, kind):
            raise wrong_type(f"{name}[{k}] must be a {qualifier}{kind.__name__}, got "
                             f"{type(item).__name__}")
    if labels is None:
        labels = [default_label(item) for item in objects]
    return labels, objects


def thread_count(threads) -> int:
    """The threads of a batch: ``threads`` checked, or numba's setting when it is None.

    Parameters
    ----------
    threads : int or None
        A whole number from 1 to :data:`numba.config.NUMBA_NUM_THREADS` (the cores numba
        found; ``2.0`` is 2, ``1.5`` is refused); None: ``numba.get_num_threads()`` (all
        cores unless set lower, e.g. by :func:`shaketable.models.rocking.batch.set_default_threads`).

    Raises
    ------
    ValueError
        Naming ``threads``.
    """
    if threads is None:
        return int(numba.get_num_threads())
    most = numba.config.NUMBA_NUM_THREADS  # type: ignore[attr-defined]  # set at import
    count = whole_number("threads", threads)
    if count > most:
        raise ValueError(f"threads must be an integer from 1 to {most} (the cores numba "
                         f"found), got {threads!r}")
    return count


def _wait_for(done: list[threading.Event]) -> KeyboardInterrupt | None:
    """Wait until every worker thread has set its ``done``; a Ctrl-C that reaches the
    calling thread while it waits is held until they have (their warnings and rows land
    before the batch returns) and returned; a second one is not waited out. (Events, not
    ``Thread.join``: a join interrupted by Ctrl-C marks the thread ended while it runs.)"""
    interrupted = None
    for event in done:
        while not event.is_set():
            try:
                event.wait()
            except KeyboardInterrupt as error:
                if interrupted is not None:
                    raise
                interrupted = error
    return interrupted


def run_in_chunks(run: Callable[[int, int], None], n_cases: int, threads: int,
                  chunk: int) -> None:
    """``run(start, stop)`` over the cases 0 to ``n_cases - 1`` on ``threads`` threads.

    Each thread (the calling one is one of them) takes the next ``chunk`` cases when it is
    done with its last: dynamic scheduling, since run costs differ a lot (a block that never
    rocks costs a hundredth of one that rocks to the end). ``run`` calls compiled code
    that releases the GIL (``nogil``), so the threads run in parallel; these are Python
    threads, not numba's threading layer, so batches may run at once in several threads of
    one process (a Dask worker's tasks). On one thread, or one chunk, ``run(0, n_cases)``
    in the calling thread. An exception in any thread (Ctrl-C in the calling one, too,
    while it waits for the others) lets the others finish their chunk and take no other,
    and is raised here once they have.
    """
    if threads <= 1 or n_cases <= chunk:
        run(0, n_cases)
        return
    starts = iter(range(0, n_cases, chunk))
    lock = threading.Lock()
    stop = threading.Event()
    errors: list[BaseException] = []

    def work():
        try:
            while not stop.is_set():
                with lock:
                    start = next(starts, None)
                if start is None:
                    return
                run(start, min(start + chunk, n_cases))
        except BaseException as error:  # Ctrl-C in the calling thread, too: handed back below
            errors.append(error)
            stop.set()  # the other threads finish their chunk and take no other

    done = [threading.Event() for _ in range(threads - 1)]

    def worker(k: int) -> None:
        try:
            work()
        finally:
            done[k].set()

    for k in range(threads - 1):
        threading.Thread(target=worker, args=(k,), name=f"shaketable-batch-{k}",
                         daemon=True).start()
    try:
        work()  # the calling thread is one of them
    finally:
        stop.set()   # all chunks are taken, or the others take no other
        interrupted = _wait_for(done)
    if interrupted is not None:
        raise interrupted
    if errors:
        raise errors[0]
