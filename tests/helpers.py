"""Paths shared by the tests (the repository, and the project's shared data outside it)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

#: The repository's root folder.
REPOSITORY = Path(__file__).resolve().parents[1]

#: The project's shared folder (report, real records); ``SHAKETABLE_SHARED`` overrides.
SHARED = Path(os.environ.get("SHAKETABLE_SHARED") or REPOSITORY.parent / "shared")

#: The real records with their ``PROVENANCE.md`` (read by tests, never committed).
SHARED_RECORDS = SHARED / "data" / "records"

#: Skip a test cleanly where the shared records are absent (e.g. a bare CI machine).
needs_shared = pytest.mark.skipif(not (SHARED_RECORDS / "PROVENANCE.md").is_file(),
                                  reason="the shared records folder is absent")

#: The measured shake-table tests of two granite rocks (GPL-3.0: read from the shared
#: folder, never copied into the repository); ``SHAKETABLE_PBR`` overrides.
SHARED_PBR = Path(os.environ.get("SHAKETABLE_PBR") or SHARED / "data" / "pbr")

#: Skip a test cleanly where the measured tests are absent.
needs_pbr = pytest.mark.skipif(not (SHARED_PBR / "metadata.csv").is_file(),
                               reason="the measured tests folder (shared/data/pbr) is absent")
