"""The one way the package reaches pyplot, and saving a figure.

Every figure of the package is drawn in :mod:`shaketable.plots`, the only
folder that imports matplotlib (``tests/test_layering.py``). The package never
sets a global backend: :func:`pyplot` imports pyplot under the user's backend,
and falls back to the file-only Agg backend only where the configured
interactive backend cannot be imported (a machine without a display).
"""

from __future__ import annotations


def pyplot():
    """matplotlib.pyplot, imported on first use (Agg if the configured backend cannot load)."""
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "module://matplotlib_inline.backend_inline"):
        try:
            import matplotlib.pyplot as plt  # noqa: F401
        except ImportError:  # pragma: no cover
            matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, path, dpi: int = 110) -> None:
    """Save a figure to ``path`` (format from the suffix, written atomically) and close it."""
    from shaketable.core.files import atomic_write

    plt = pyplot()
    try:
        atomic_write(path, lambda temporary: fig.savefig(temporary, dpi=dpi, bbox_inches="tight"))
    finally:
        plt.close(fig)
