"""``shaketable classroom``: the live page (a block on a shaking table) in the browser."""

from __future__ import annotations

import sys


def _classroom(args) -> int:
    import importlib.util

    if importlib.util.find_spec("panel") is None:   # the optional extra the page is built with
        # a set-up error (exit status 2, as a missing pyarrow for --parquet): said with the
        # install line for an installed package and for a checkout of the source
        raise ValueError("the classroom page needs Panel, an optional extra: pip install "
                         "'shaketable[classroom]' (from a checkout of the source, in its "
                         "folder: pip install '.[classroom]')")
    from shaketable.commands.common import notice_first_compile

    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port must be from 0 to 65535 (0: a free port), got {args.port}")
    notice_first_compile(args.quiet, which=("engine",))
    from shaketable.classroom.model import LESSONS, compute
    from shaketable.classroom.page import serve

    compute(LESSONS["period"].settings)   # the engine compiled (or loaded) before the page opens
    from dataclasses import replace

    from shaketable.commands.common import compiled_before

    if compiled_before("planar"):   # loaded now (0.5 s) rather than at the first friction run
        compute(replace(LESSONS["period"].settings, motion="harmonic", duration="1 s",
                        friction=True, compare="none"))
    elif not args.quiet:
        print("shaketable classroom: the first run with friction compiles the planar engine "
              "(~15 s) once", file=sys.stderr)
    def ready(url: str) -> None:   # the address is needed: on stderr when stdout is quiet
        print(f"shaketable classroom: {url}  (Ctrl-C stops it)",
              file=sys.stderr if args.quiet else sys.stdout, flush=True)

    serve(port=args.port, address=args.address, browser=not args.no_browser, out=args.out,
          ready=ready)
    print("shaketable classroom: stopped", flush=True)
    return 0


def register(commands) -> None:
    """Add the ``classroom`` subcommand."""
    parser = commands.add_parser(
        "classroom", help="a live page in the browser: move a slider, the block answers",
        description="Serve the classroom page on this machine and open it in the browser: "
                    "fields and sliders for the block, the COR, friction and the table "
                    "motion; the block drawn to scale on the moving table with θ/α, the "
                    "table acceleration and the mode band revealed as time advances; the "
                    "three lessons one click away; a button that saves the figure and a "
                    "scene file that `shaketable run` reproduces. Needs the classroom extra "
                    "(pip install 'shaketable[classroom]'; from a checkout of the source, in "
                    "its folder: pip install '.[classroom]'); no internet. Ctrl-C stops it.")
    parser.add_argument("--port", type=int, default=0,
                        help="TCP port to listen on (default 0: a free port, printed)")
    parser.add_argument("--address", default="localhost",
                        help="interface to listen on (default localhost: this machine only; "
                             "0.0.0.0 lets other machines of the network in)")
    parser.add_argument("--no-browser", action="store_true",
                        help="do not open a browser (a lab machine, a projector's computer)")
    parser.add_argument("--out", default="classroom-out",
                        help="folder the save button writes scenes and figures to "
                             "(default classroom-out)")
    parser.set_defaults(handler=_classroom)
