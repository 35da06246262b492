"""The Python module draws the same bytes as the C++ API for the same scene."""

import os
import subprocess

import numpy as np
import pytest

import tessera


def render_scene_in_python(scene, threads):
    positions, colors, indices = scene
    renderer = tessera.Renderer(threads=threads)
    framebuffer = tessera.Framebuffer(160, 120, samples=4)
    framebuffer.clear_color((0.125, 0.25, 0.5, 1.0))
    renderer.draw(framebuffer, positions, colors, indices, pipeline=tessera.Pipeline(cull="back"))
    return framebuffer.read_rgba8(), framebuffer.read_depth()


def test_python_image_equals_cpp_image_byte_for_byte(scene, tmp_path):
    helper = os.environ.get("TESSERA_REFERENCE_SCENE")
    if not helper:
        pytest.skip("TESSERA_REFERENCE_SCENE (the C++ renderer of the scene) is not set")
    out = tmp_path / "scene.bin"
    subprocess.run([helper, str(out)], check=True)
    expected = out.read_bytes()

    rgba, depth = render_scene_in_python(scene, threads=2)
    assert rgba.shape == (120, 160, 4) and rgba.dtype == np.uint8
    assert depth.shape == (120, 160) and depth.dtype == np.float32
    assert len(expected) == rgba.nbytes + depth.nbytes
    assert rgba.tobytes() == expected[: rgba.nbytes]
    assert depth.tobytes() == expected[rgba.nbytes :]
    # The scene is not trivial: it covers part of the image and leaves the clear colour elsewhere.
    covered = depth < 1.0
    assert 0.2 < covered.mean() < 0.99


def test_flat_and_2d_indices_draw_the_same_image(scene):
    positions, colors, indices = scene
    images = []
    for idx in (indices, indices.reshape(-1, 3)):
        framebuffer = tessera.Framebuffer(64, 48)
        tessera.Renderer(threads=1).draw(framebuffer, positions, colors, idx)
        images.append(framebuffer.read_rgba8())
    assert np.array_equal(images[0], images[1])
