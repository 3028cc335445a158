"""Shared fixtures of the Python package's tests.

Core tests build their meshes in code (holey's primitives, or arrays
written here). Tests named after a real mesh read it from the shared data
next to the repository (../shared/data/meshes, or $HOLEY_SHARED_MESHES)
and skip, saying so, when it is absent.
"""

import os
import pathlib

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def shared_meshes() -> pathlib.Path:
    env = os.environ.get("HOLEY_SHARED_MESHES")
    return pathlib.Path(env) if env else REPO.parent / "shared" / "data" / "meshes"


@pytest.fixture
def shared():
    """The folder of shared real meshes, or a visible skip."""
    folder = shared_meshes()
    if not folder.is_dir():
        pytest.skip(f"SKIP: {folder} is absent (the shared real meshes)")
    return folder


def box(lo, hi):
    """An axis-aligned box as 8 vertices and 12 outward triangles."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    V = np.array([[(hi if i & 1 << k else lo)[k] for k in range(3)] for i in range(8)])
    F = np.array(
        [
            [0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
            [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5],
        ]
    )
    return V, F
