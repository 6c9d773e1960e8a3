"""Command line: ``shaketable SUBCOMMAND ...``, a thin layer over the library.

Each subcommand lives in ``shaketable/commands/<name>.py`` and exposes
``register(subparsers)``; :data:`SUBCOMMANDS` lists them in help order.

Exit status: 0 success, 1 a run that failed (a scene that could not be
reproduced, a file that could not be written, not enough memory, an internal
error, 130 interrupted with Ctrl-C, 141 the output pipe closed: quietly), 2 bad usage or bad input (an unknown
option, a malformed value, a missing or malformed file, an unusable output path, a missing
optional extra).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import os
import sys

#: Subcommand modules in ``shaketable.commands``, in the order ``--help`` shows them.
SUBCOMMANDS = ["simulate", "run", "reproduce", "calibrate", "sweep", "bench", "animate",
               "slide", "spectrum", "examples"]
SUBCOMMANDS.insert(SUBCOMMANDS.index("sweep") + 1, "risk")
SUBCOMMANDS.insert(SUBCOMMANDS.index("risk") + 1, "assess")
SUBCOMMANDS.insert(SUBCOMMANDS.index("calibrate"), "records")
SUBCOMMANDS.insert(SUBCOMMANDS.index("spectrum"), "modemap")
SUBCOMMANDS.insert(SUBCOMMANDS.index("calibrate") + 1, "validate")
SUBCOMMANDS.insert(SUBCOMMANDS.index("animate") + 1, "classroom")

#: Exit statuses (documented in ``shaketable --help``).
EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130

EPILOG = ("exit status: 0 success; 1 a run that failed (e.g. a scene that could not be "
          "reproduced, a file that could not be written, not enough memory); 2 bad usage or "
          "input (unknown option, malformed value, missing or malformed file, unusable output "
          "path, missing optional extra such as Panel or pyarrow); 130 interrupted (Ctrl-C); "
          "141 the output pipe was closed (e.g. by head). Set SHAKETABLE_TRACEBACK=1 to see "
          "Python tracebacks of unexpected errors.")


class _Parser(argparse.ArgumentParser):
    """argparse's parser whose usage errors are one line and a pointer to the help, so
    that the message is not buried under the usage of every option; the subcommands'
    parsers are of this class too (argparse gives them the top parser's)."""

    def error(self, message: str):   # type: ignore[override]
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message}\n"
                                  f"see '{self.prog} --help'\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand registered."""
    from shaketable.version import __version__

    parser = _Parser(
        prog="shaketable",
        description="Virtual shaking-table tests of rocking rigid blocks "
                    "(Aslam, Godden & Scalise; BLOKROC).", epilog=EPILOG)
    parser.add_argument("--version", action="version", version=f"shaketable {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in SUBCOMMANDS:
        importlib.import_module(f"shaketable.commands.{name}").register(commands)
    for subparser in commands.choices.values():
        subparser.epilog = subparser.epilog or EPILOG
        if not any("--quiet" in action.option_strings for action in subparser._actions):
            subparser.add_argument("-q", "--quiet", action="store_true",
                                   help="print nothing but errors (no progress, no summary)")
    return parser


def main(argv=None) -> int:
    """Entry point of the ``shaketable`` console script; returns the exit status."""
    from shaketable.commands.options import join_negative_values

    parser = build_parser()
    # a negative value after an option (--block -30x6in) is read as the option's value
    args, unknown = parser.parse_known_args(join_negative_values(
        parser, list(sys.argv[1:] if argv is None else argv)))
    if unknown:   # said by the subcommand's parser, with the option meant when it is close
        _refuse_unknown(parser, args.command, unknown)
    prefix = f"shaketable {args.command}: error:"
    quiet = getattr(args, "quiet", False)
    from shaketable.core.files import CREATED_FOLDERS

    made_before = len(CREATED_FOLDERS)   # the output folders this command makes come after
    try:
        with contextlib.redirect_stdout(io.StringIO()) if quiet else contextlib.nullcontext():
            status = int(args.handler(args) or 0)
        sys.stdout.flush()   # a closed pipe shows here, not in Python's flush at exit
        return status
    except KeyboardInterrupt:
        print(f"shaketable {args.command}: interrupted; files already written are complete",
              file=sys.stderr)
        if argv is None and (_compiled_run_still_going() or _worker_processes_all_ended()):
            _end_now(EXIT_INTERRUPTED)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # `shaketable ... | head -1`: the reader left; end quietly
        return _closed_pipe()
    except (ValueError, FileNotFoundError, NotADirectoryError, IsADirectoryError) as error:
        print(f"{prefix} {error}", file=sys.stderr)
        # a refused input leaves no empty output folder of its own behind
        _remove_empty_folders(CREATED_FOLDERS[made_before:])
        return EXIT_BAD_INPUT
    except RuntimeError as error:  # a run that failed and says why (e.g. cluster chunks)
        print(f"{prefix} {error}", file=sys.stderr)
        return EXIT_FAILED
    except MemoryError:
        print(f"{prefix} not enough memory for this run (make it shorter or its output step "
              f"coarser)", file=sys.stderr)
        return EXIT_FAILED
    except OSError as error:
        where = f" {error.filename!r}" if error.filename else ""
        print(f"{prefix} cannot read or write{where}: {error.strerror or error}",
              file=sys.stderr)
        return EXIT_FAILED
    except Exception as error:  # the last line of defence: a bug, said as one
        if os.environ.get("SHAKETABLE_TRACEBACK"):
            raise
        print(f"{prefix} internal error ({type(error).__name__}: {error}). This is a bug in "
              f"shaketable; please report it with the command you ran (SHAKETABLE_TRACEBACK=1 "
              f"shows the traceback)", file=sys.stderr)
        return EXIT_FAILED
    finally:   # whatever the outcome (Ctrl-C that ends at once has done it already)
        try:
            if argv is None and _worker_processes_all_ended():
                _stop_process_helpers()
        except KeyboardInterrupt:   # during the wait for the helpers: the outcome stands
            pass


def _remove_empty_folders(folders: list) -> None:
    """Remove each of ``folders`` (made by this command: ``core.files.CREATED_FOLDERS``)
    and the folders in it, if they hold no file: a refusal found after the output folder
    was made leaves nothing, and a folder that existed before, or that another process
    made meanwhile, is never touched.

    A folder holding a file anywhere in it stays whole: another process that found the
    folder this command made may be writing in it (its lock file comes first), and its
    empty subfolders are its own."""
    for folder in folders:
        if not folder.is_dir() or folder.is_symlink():
            continue
        walked = sorted(os.walk(folder), key=lambda level: -len(level[0]))
        if any(files for _, _, files in walked):
            continue
        try:
            for inner, _, _ in walked:
                os.rmdir(inner)   # deepest first; a file that came meanwhile stops it
        except OSError:
            pass


def _refuse_unknown(parser: argparse.ArgumentParser, command: str, unknown: list) -> None:
    """Exit with status 2 naming the subcommand and the arguments it does not know, and
    for a misspelt option the closest one it has (``--duraton``: did you mean
    ``--duration``?)."""
    import difflib

    subparsers = next(action for action in parser._actions
                      if isinstance(action, argparse._SubParsersAction))
    subparser = subparsers.choices[command]
    known = [option for action in subparser._actions for option in action.option_strings
             if option.startswith("--")]
    hints = []
    for word in unknown:
        if word.startswith("--"):
            close = difflib.get_close_matches(word.split("=")[0], known, n=1, cutoff=0.75)
            if close:
                hints.append(f"{word.split('=')[0]}: did you mean {close[0]}?")
    subparser.error("unrecognized arguments: " + " ".join(unknown)
                    + ("; " + "; ".join(hints) if hints else ""))


def _compiled_run_still_going() -> bool:
    """Whether a compiled run left behind by Ctrl-C still runs (its worker thread,
    ``models.rocking.run.call_interruptibly``: compiled code cannot be stopped). By its
    name among the running threads: a ``join`` that Ctrl-C interrupted leaves the thread
    marked stopped on Python 3.11 (``is_alive()`` False while it runs)."""
    import threading

    return any(thread.name == "shaketable-engine" for thread in threading.enumerate())


def _worker_processes_all_ended() -> bool:
    """Whether the command started worker processes (a sweep's ``--workers N`` and
    ``reproduce``: ``core.workers.pool_started``) and every one of them has ended (they
    end theirs on Ctrl-C, ``core.workers.end_workers``); a worker still running is left to
    Python's exit, which waits for it."""
    from shaketable.core.workers import pool_started

    if not pool_started():
        return False
    import multiprocessing

    return not multiprocessing.active_children()


#: Seconds the command waits for multiprocessing's resource tracker to end once told to.
TRACKER_WAIT = 1.0


def _stop_process_helpers() -> None:
    """After a command whose worker processes have all ended: run multiprocessing's own
    exit (its semaphores released) and stop its resource-tracker process and wait for it
    (at most :data:`TRACKER_WAIT` s, :func:`_stop_resource_tracker`), so that no process of
    the command outlives it (Python's exit leaves the tracker to end after the command, an
    orphan). With a worker still alive nothing is done here."""
    if "multiprocessing.resource_tracker" not in sys.modules:
        return
    try:
        import multiprocessing.util

        if multiprocessing.active_children():
            # a process still running holds the tracker's pipe (the tracker would not end)
            # and would be waited for: both left to Python's own exit
            return

        multiprocessing.util._exit_function()  # type: ignore[attr-defined]  # as at exit
        _stop_resource_tracker(TRACKER_WAIT)
    except Exception:   # ending anyway; the tracker then ends on its own
        pass


def _stop_resource_tracker(timeout: float) -> bool:
    """Tell multiprocessing's resource tracker to end (its pipe closed) and wait for it
    at most ``timeout`` s; whether it ended. The tracker ends when every holder of its
    pipe has closed it, so a process this one did not start through multiprocessing and
    that holds the pipe (not among ``active_children``) would keep it, and a plain wait,
    running: the wait is in a thread of its own and given up after ``timeout``."""
    import threading

    tracker = sys.modules["multiprocessing.resource_tracker"]._resource_tracker
    stop = getattr(tracker, "_stop", None)   # Python >= 3.11; older: it ends on its own
    if stop is None:
        return False
    waiting = threading.Thread(target=stop, name="shaketable-tracker-stop", daemon=True)
    waiting.start()
    waiting.join(timeout)
    return not waiting.is_alive()


def _end_now(status: int) -> None:
    """End the program at once with ``status``, its output flushed. After Ctrl-C with a
    compiled run still going, Python's own exit (tearing down every module, about 0.35 s
    of CPU) would run beside the abandoned run, which goes on using a core until the
    process ends; every file written is already complete (atomic writes). A sweep's
    worker processes are ended by then; multiprocessing's own exit (its semaphores
    released) and its resource-tracker process (stopped and waited for, so that it does
    not outlive the command) are run here, as Python's exit would."""
    _stop_process_helpers()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(status)


#: Exit status after the output pipe was closed (128 + SIGPIPE, as a Unix tool killed by it).
EXIT_BROKEN_PIPE = 141


def _closed_pipe() -> int:
    """Point stdout at /dev/null (Python's flush at exit would fail again) and give 141."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):  # no real stdout (redirected in-process)
        pass
    return EXIT_BROKEN_PIPE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
