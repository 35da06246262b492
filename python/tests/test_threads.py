"""Images are the same bytes for any thread count, and draws release the GIL."""

from concurrent.futures import ThreadPoolExecutor

import numpy as np

import tessera


def draw(scene, threads, backend="fast"):
    positions, colors, indices = scene
    framebuffer = tessera.Framebuffer(160, 120, samples=4)
    tessera.Renderer(threads=threads, backend=backend).draw(framebuffer, positions, colors, indices)
    return framebuffer.read_rgba8(), framebuffer.read_depth()


def test_one_and_two_threads_draw_identical_images(scene):
    one = draw(scene, 1)
    two = draw(scene, 2)
    assert tessera.Renderer(threads=2).threads == 2
    assert np.array_equal(one[0], two[0])
    assert np.array_equal(one[1], two[1])


def test_reference_backend_draws_with_one_and_two_threads_alike(scene):
    one = draw(scene, 1, "reference")
    two = draw(scene, 2, "reference")
    assert tessera.Renderer(backend="reference").backend == "reference"
    assert np.array_equal(one[0], two[0])


def test_draws_from_two_python_threads_match_serial_draws(scene):
    expected = draw(scene, 1)
    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(lambda _: draw(scene, 1), range(4)))
    for rgba, depth in results:
        assert np.array_equal(rgba, expected[0])
        assert np.array_equal(depth, expected[1])
