"""Scenes shared by the Python module's tests."""

import numpy as np
import pytest


def lcg_scene(vertices=240, triangles=160):
    """The scene of render_reference_scene.cpp: dyadic rationals from a 32-bit LCG, so that
    Python and C++ build exactly the same floats. Returns positions (n, 4), colours (n, 4)
    and indices (3m,)."""
    state = 12345

    def next_value():
        nonlocal state
        state = (state * 1664525 + 1013904223) & 0xFFFFFFFF
        return state >> 8

    positions = []
    colors = []
    for _ in range(vertices):
        w = 1.0 + (next_value() % 8) / 8.0
        x = ((next_value() % 2561) - 1280.0) / 1024.0 * w
        y = ((next_value() % 2561) - 1280.0) / 1024.0 * w
        z = (next_value() % 1025) / 1024.0 * w
        positions.append((x, y, z, w))
        colors.append([(next_value() % 257) / 256.0 for _ in range(4)])
    indices = [next_value() % vertices for _ in range(3 * triangles)]
    return (
        np.array(positions, dtype=np.float32),
        np.array(colors, dtype=np.float32),
        np.array(indices, dtype=np.uint32),
    )


@pytest.fixture
def scene():
    return lcg_scene()


@pytest.fixture
def quad():
    """Two triangles covering the whole viewport at depth 0.5, counter-clockwise, with a
    colour per vertex: positions (4, 4), colours (4, 4), indices (2, 3)."""
    positions = np.array(
        [[-1, -1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1], [-1, 1, 0.5, 1]], dtype=np.float32
    )
    colors = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [1, 1, 1, 1]], dtype=np.float32)
    indices = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    return positions, colors, indices
