"""Regenerate the teaching gallery's figures: docs/figures/teaching_*.png.

Run from the repository root: ``python examples/teaching_gallery.py`` (about 5 s).
Each item is one function of :mod:`shaketable.studies.teaching`; its numbers are printed.
"""

from pathlib import Path

from shaketable.plots.teaching import save_item
from shaketable.studies import teaching

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"

#: figure file -> gallery item
GALLERY = {
    "teaching_period_amplitude.png": "period-amplitude",
    "teaching_cor_sweep.png": "cor-sweep",
    "teaching_similar_blocks.png": "similar-blocks",
    "teaching_rocking_onset.png": "rocking-onset",
}


def main() -> None:
    FIGURES.mkdir(parents=True, exist_ok=True)
    for file_name, name in GALLERY.items():
        item = teaching.run_item(name)
        print(f"== {name}\n{item.to_frame().round(4).to_string(index=False)}\n")
        save_item(item, FIGURES / file_name)
        print(f"wrote {FIGURES / file_name}\n")


if __name__ == "__main__":
    main()
