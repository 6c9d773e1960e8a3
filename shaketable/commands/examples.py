"""``shaketable examples --out DIR``: the gallery scripts, copied out of the installed package."""

from __future__ import annotations

from pathlib import Path


def gallery_scripts() -> list[Path]:
    """The gallery's scripts (``plot_*.py``) and its README, as installed with the package."""
    from importlib.resources import files

    folder = Path(str(files("shaketable.examples")))
    return sorted(folder.glob("plot_*.py")) + sorted(folder.glob("README.rst"))


def _examples(args) -> int:
    from shaketable.core.files import copy_file, prepare_output_folder

    scripts = gallery_scripts()
    if not scripts:
        raise RuntimeError("no gallery scripts were installed with this shaketable "
                           "(the package data shaketable.examples is missing)")
    if args.list:
        print("\n".join(path.name for path in scripts if path.suffix == ".py"))
        return 0
    out = Path(args.out)
    existing = [path.name for path in scripts
                if (out / path.name).exists() or (out / path.name).is_symlink()]
    if existing and not args.force:
        raise ValueError(f"--out {str(out)!r} already has {', '.join(existing[:3])}"
                         f"{' ...' if len(existing) > 3 else ''}; give another folder or "
                         "--force to overwrite them")
    out = prepare_output_folder(out)
    for path in scripts:
        copy_file(path, out / path.name)   # a link in the way is replaced, not followed
    print(f"copied {len(scripts) - 1} gallery scripts and README.rst to {out}/")
    print(f"run one: python {out / 'plot_tutorial_rock_a_block.py'}")
    return 0


def register(commands) -> None:
    """Add the ``examples`` subcommand."""
    parser = commands.add_parser(
        "examples", help="copy the gallery's example scripts into a folder",
        description="Copy the gallery scripts (examples/plot_*.py of the documentation site, "
                    "installed with the package) into a folder, to read, run and change.")
    parser.add_argument("--out", default="shaketable-examples",
                        help="folder to copy them into (default shaketable-examples)")
    parser.add_argument("--list", action="store_true", help="list the scripts and stop")
    parser.add_argument("--force", action="store_true",
                        help="overwrite scripts of the same name already in --out")
    parser.set_defaults(handler=_examples)
