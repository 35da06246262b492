"""Occlusion queries from Python: occluders into depth only, then rectangles, boxes and
triangle lists asked whether they would be visible, one at a time or as arrays."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import tessera


def quad(x0, y0, x1, y1, z, width, height):
    """Two clip-space triangles over window pixels [x0, x1) x [y0, y1) at depth z."""

    def cx(x):
        return x / width * 2 - 1

    def cy(y):
        return 1 - y / height * 2

    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y0), (x1, y1), (x0, y1)]
    return np.array([(cx(x), cy(y), z, 1) for x, y in corners], dtype=np.float32)


@pytest.fixture
def wall():
    """A 64 x 48 buffer with a wall at depth 0.5 over its left half (x < 32)."""
    occlusion = tessera.OcclusionBuffer(64, 48, threads=1)
    occlusion.draw_occluders(quad(0, 0, 32, 48, 0.5, 64, 48))
    return occlusion


@pytest.mark.parametrize("mode", ["conservative", "exact"])
def test_a_wall_hides_what_is_behind_it(wall, mode):
    assert (wall.width, wall.height, wall.samples) == (64, 48, 1)
    assert not wall.rect_visible(5, 7, 29, 40, 0.9, mode=mode)
    assert wall.rect_visible(5, 7, 29, 40, 0.4, mode=mode)
    assert wall.rect_visible(5, 7, 29, 40, 0.5, mode=mode)  # LESS_EQUAL
    assert wall.rect_visible(24, 7, 40, 40, 0.9, mode=mode)  # past the wall's edge
    assert not wall.triangles_visible(quad(4, 4, 28, 44, 0.7, 64, 48), mode=mode)
    assert wall.triangles_visible(quad(30, 4, 50, 44, 0.7, 64, 48), mode=mode)
    indexed = quad(4, 4, 28, 44, 0.7, 64, 48)[[0, 1, 2, 5]]
    indices = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    assert not wall.triangles_visible(indexed, indices, mode=mode)


def test_the_depth_buffer_reads_back_and_clears(wall):
    depth = wall.read_depth()
    assert depth.shape == (48, 64) and depth.dtype == np.float32
    assert np.all(depth[:, :32] == np.float32(0.5))
    assert np.all(depth[:, 32:] == 1.0)
    wall.clear()
    assert np.all(wall.read_depth() == 1.0)
    assert wall.rect_visible(5, 7, 29, 40, 0.9)


def test_exact_rectangles_equal_a_search_of_the_depth_buffer():
    rng = np.random.default_rng(3)
    occlusion = tessera.OcclusionBuffer(96, 80, threads=1)
    clip = rng.uniform(-1.2, 1.2, size=(180, 4)).astype(np.float32)
    clip[:, 2] = rng.uniform(0.05, 0.45, size=180)
    clip[:, 3] = 1
    occlusion.draw_occluders(clip)
    depth = occlusion.read_depth()
    corners = rng.integers(-4, 100, size=(400, 4))
    rects = np.stack(
        [
            np.minimum(corners[:, 0], corners[:, 1]),
            np.minimum(corners[:, 2], corners[:, 3]),
            np.maximum(corners[:, 0], corners[:, 1]),
            np.maximum(corners[:, 2], corners[:, 3]),
        ],
        axis=1,
    ).astype(np.float32)
    nearest = rng.uniform(0.05, 0.55, size=400).astype(np.float32)
    want = []
    for (x0, y0, x1, y1), z in zip(rects.astype(int), nearest):
        window = depth[max(y0, 0) : max(min(y1, 80), 0), max(x0, 0) : max(min(x1, 96), 0)]
        want.append(bool(np.any(z <= window)))
    exact = occlusion.rects_visible(rects, nearest, mode="exact")
    conservative = occlusion.rects_visible(rects, nearest)
    assert exact.dtype == np.bool_ and exact.shape == (400,)
    assert exact.tolist() == want
    assert np.all(conservative[exact])  # never hidden where the exact answer sees
    assert 40 < np.count_nonzero(~exact) < 360
#The array form answers as one call at a time does.
    for i in range(0, 400, 37):
        assert occlusion.rect_visible(*rects[i], nearest[i], mode="exact") == exact[i]


def test_boxes_behind_a_wall_through_a_camera():
    occlusion = tessera.OcclusionBuffer(128, 96, threads=1)
    camera = tessera.Camera(eye=(0, 0, 5), target=(0, 0, 0), near_plane=0.5, far_plane=100)
    view_projection = (camera.projection(128 / 96) @ camera.view()).astype(np.float32)
    wall = np.array(
        [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, -2, 0), (2, 2, 0), (-2, 2, 0)], dtype=np.float32
    )
    occlusion.draw_occluders(tessera.to_clip_space(wall, view_projection))
    lo = np.array([(-0.5, -0.5, -3), (-0.5, -0.5, 1), (8, -0.5, -10), (-1, -1, 3)], np.float32)
    hi = np.array([(0.5, 0.5, -1), (0.5, 0.5, 2), (10, 0.5, -5), (1, 1, 6)], np.float32)
    want = [False, True, True, True]  # behind, in front, beside, around the eye
    for mode in ("conservative", "exact"):
        got = occlusion.boxes_visible(lo, hi, view_projection, mode=mode)
        assert got.tolist() == want
        for i in range(4):
            assert occlusion.box_visible(lo[i], hi[i], view_projection, mode=mode) == want[i]


def test_queries_from_several_python_threads_match_serial_ones():
    rng = np.random.default_rng(8)
    occlusion = tessera.OcclusionBuffer(128, 128, samples=4, threads=2)
    clip = rng.uniform(-1.1, 1.1, size=(600, 4)).astype(np.float32)
    clip[:, 2] = rng.uniform(0.05, 0.45, size=600)
    clip[:, 3] = 1
    occlusion.draw_occluders(clip)
    queries = []
    for _ in range(200):
        q = rng.uniform(-1.1, 1.1, size=(6, 4)).astype(np.float32)
        q[:, :2] = q[:, :2] * 0.2 + rng.uniform(-1, 1, size=2)
        q[:, 2] = rng.uniform(0.1, 0.6, size=6)
        q[:, 3] = 1
        queries.append(q)
    serial = [occlusion.triangles_visible(q, mode="exact") for q in queries]
    assert 10 < sum(serial) < 190
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda q: occlusion.triangles_visible(q, mode="exact"), queries))
    assert threaded == serial


def test_bad_input_is_an_error_naming_it(wall):
    before = wall.read_depth()
    with pytest.raises(ValueError, match=r"mode \"fast\" is not one of \"conservative\", \"exact\""):
        wall.rect_visible(0, 0, 4, 4, 0.5, mode="fast")
    with pytest.raises(ValueError, match="NaN"):
        wall.rect_visible(float("nan"), 0, 4, 4, 0.5)
    with pytest.raises(ValueError, match="lo <= hi"):
        wall.box_visible((1, 0, 0), (0, 1, 1), np.eye(4, dtype=np.float32))
    with pytest.raises(ValueError, match=r"clip_from_object must have shape \(4, 4\)"):
        wall.box_visible((0, 0, 0), (1, 1, 1), np.eye(3, dtype=np.float32))
    with pytest.raises(TypeError, match="positions must be a float32 array"):
        wall.draw_occluders(quad(0, 0, 8, 8, 0.1, 64, 48).astype(np.float64))
    with pytest.raises(ValueError, match="7"):
        wall.draw_occluders(
            quad(0, 0, 8, 8, 0.1, 64, 48), np.array([0, 1, 7], dtype=np.uint32)
        )
    with pytest.raises(ValueError, match="depths holds 1 values for 2 rects"):
        wall.rects_visible(np.zeros((2, 4), np.float32), np.zeros(1, np.float32))
    with pytest.raises(ValueError, match="hi holds 1 corners for 2 in lo"):
        wall.boxes_visible(
            np.zeros((2, 3), np.float32), np.ones((1, 3), np.float32), np.eye(4, dtype=np.float32)
        )
    with pytest.raises(ValueError, match="width"):
        tessera.OcclusionBuffer(0, 16)
    with pytest.raises(ValueError, match=r"depth \"float16\" is not one of"):
        tessera.OcclusionBuffer(16, 16, depth="float16")
#Nothing was drawn by the failed draws.
    assert np.array_equal(wall.read_depth(), before)
