"""The camera helpers of the C++ scene layer through Python."""

import numpy as np
import pytest

import tessera


def test_default_camera_view_moves_the_world_in_front_of_the_eye():
    camera = tessera.Camera()
    assert camera.eye == [0.0, 0.0, 5.0]
    view = camera.view()
    assert view.shape == (4, 4) and view.dtype == np.float32
    np.testing.assert_allclose(view @ np.array([0, 0, 0, 1], np.float32), [0, 0, -5, 1])


def test_projection_maps_the_near_and_far_planes_to_depth_0_and_1():
    camera = tessera.Camera(eye=(0, 0, 0), target=(0, 0, -1), near_plane=1.0, far_plane=10.0)
    mvp = camera.projection(4 / 3) @ camera.view()
    points = np.array([[0, 0, -1], [0, 0, -10], [0, 0, -5]], dtype=np.float32)
    clip = tessera.to_clip_space(points, mvp)
    assert clip.shape == (3, 4) and clip.dtype == np.float32
    depth = clip[:, 2] / clip[:, 3]
    np.testing.assert_allclose(depth[:2], [0, 1], atol=1e-6)
    np.testing.assert_allclose(clip[:, 3], [1, 10, 5], rtol=1e-6)  # w = distance along the view
    opengl = camera.projection(4 / 3, clip_depth="negative_one_to_one") @ camera.view()
    clip = tessera.to_clip_space(points, opengl)
    np.testing.assert_allclose((clip[:, 2] / clip[:, 3])[:2], [-1, 1], atol=1e-6)


def test_a_cube_seen_through_the_camera_has_metric_eye_depth():
    camera = tessera.Camera(eye=(0, 0, 3), target=(0, 0, 0), near_plane=0.5, far_plane=20.0)
    mvp = camera.projection(1.0) @ camera.view()
    # A square at z = 0, facing the camera: its eye depth is 3 everywhere.
    square = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    framebuffer = tessera.Framebuffer(32, 32, color="rgba32f")
    tessera.Renderer(threads=1).draw(
        framebuffer,
        tessera.to_clip_space(square, mvp),
        indices=np.array([0, 1, 2, 0, 2, 3], np.uint32),
        pipeline=tessera.Pipeline(output="eye_depth"),
    )
    eye_depth = framebuffer.read_rgba32f()[16, 16, 0]
    assert eye_depth == pytest.approx(3.0, rel=1e-5)


def test_to_clip_space_checks_its_arrays():
    with pytest.raises(ValueError, match=r"positions must have shape \(n, 3\)"):
        tessera.to_clip_space(np.zeros((2, 4), np.float32), np.eye(4, dtype=np.float32))
    with pytest.raises(ValueError, match=r"mvp must have shape \(4, 4\), got \(3, 4\)"):
        tessera.to_clip_space(np.zeros((2, 3), np.float32), np.eye(4, dtype=np.float32)[:3])
    with pytest.raises(TypeError, match="mvp must be a float32 array"):
        tessera.to_clip_space(np.zeros((2, 3), np.float32), np.eye(4))
