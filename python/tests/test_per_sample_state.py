"""Per-sample state through Python: the scissor test and depth bias, in both backends."""

import numpy as np
import pytest

import tessera


@pytest.mark.parametrize("backend", ["fast", "reference"])
def test_a_screen_filling_draw_writes_only_the_scissor_rectangle(backend):
    positions = np.array(
        [[-1, -1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1], [-1, 1, 0.5, 1]], dtype=np.float32
    )
    colors = np.tile(np.array([1, 0, 0, 1], dtype=np.float32), (4, 1))
    indices = np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)
    pipeline = tessera.Pipeline(scissor_test=True, scissor=(5, 3, 11, 7))
    assert pipeline.scissor == (5, 3, 11, 7)
    framebuffer = tessera.Framebuffer(40, 24)
    tessera.Renderer(threads=2, backend=backend).draw(
        framebuffer, positions, colors, indices, pipeline=pipeline
    )
    red = framebuffer.read_rgba8()[..., 0] == 255
    expected = np.zeros((24, 40), dtype=bool)
    expected[3:10, 5:16] = True
    np.testing.assert_array_equal(red, expected)


@pytest.mark.parametrize("backend", ["fast", "reference"])
def test_depth_bias_lets_a_coplanar_decal_win(backend):
    positions = np.array(
        [[-1, -1, 0.5, 1], [1, -1, 0.25, 1], [1, 1, 0.75, 1], [-1, 1, 0.5, 1]], dtype=np.float32
    )
    indices = np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)
    red = np.tile(np.array([1, 0, 0, 1], dtype=np.float32), (4, 1))
    green = np.tile(np.array([0, 1, 0, 1], dtype=np.float32), (4, 1))
    renderer = tessera.Renderer(threads=2, backend=backend)
    for bias, winner in ((0.0, 0), (-8.0, 1)):
        framebuffer = tessera.Framebuffer(32, 24, depth="unorm24")
        renderer.draw(framebuffer, positions, red, indices, pipeline=tessera.Pipeline())
        decal = tessera.Pipeline(depth_bias_constant=bias, depth_bias_slope=0.0)
        assert decal.depth_bias_constant == bias
        renderer.draw(framebuffer, positions, green, indices, pipeline=decal)
        # Without a bias the equal depths fail LESS: red stays; with one, green wins.
        assert (framebuffer.read_rgba8()[..., winner] == 255).all()
