"""Fixtures shared by the test folders (which mirror the package's layers)."""

from __future__ import annotations

import pytest

from tests.helpers import REPOSITORY, SHARED_RECORDS


@pytest.fixture(scope="session")
def repository():
    """The repository's root folder."""
    return REPOSITORY


@pytest.fixture(scope="session")
def shared_records():
    """The shared real-records folder; the test is skipped where it is absent."""
    if not (SHARED_RECORDS / "PROVENANCE.md").is_file():
        pytest.skip("the shared records folder is absent")
    return SHARED_RECORDS
