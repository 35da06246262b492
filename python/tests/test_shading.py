"""The built-in shaders and the vision outputs through Python."""

import numpy as np
import pytest

import tessera


def phong_quad():
    """A quad at z = 0.5 facing the viewer: varyings colour (white), normal (0, 0, 1) and
    position (the clip-space x, y, 0), in the default roles 0, 4 and 7."""
    positions = np.array(
        [[-1, -1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1], [-1, 1, 0.5, 1]], dtype=np.float32
    )
    varyings = np.zeros((4, 10), dtype=np.float32)
    varyings[:, 0:4] = 1
    varyings[:, 6] = 1
    varyings[:, 7:9] = positions[:, 0:2]
    indices = np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)
    return positions, varyings, indices


@pytest.mark.parametrize("backend", ["fast", "reference"])
def test_phong_with_a_head_on_directional_light_is_ambient_plus_diffuse(backend):
    positions, varyings, indices = phong_quad()
    pipeline = tessera.Pipeline(shader="phong")
    pipeline.phong.ks = 0
    pipeline.phong.eye = (0, 0, 4)
    pipeline.phong.lights = [tessera.Light(kind="directional", direction=(0, 0, -1))]
    assert pipeline.shader == "phong" and len(pipeline.phong.lights) == 1
    framebuffer = tessera.Framebuffer(32, 32, color="rgba32f")
    tessera.Renderer(threads=2, backend=backend).draw(
        framebuffer, positions, varyings, indices, pipeline=pipeline
    )
    color = framebuffer.read_color()
    assert color.shape == (32, 32, 4) and color.dtype == np.float32
    # I = ka Ia + kd (N.L) Id = 0.1 + 0.7, times the white base; alpha from the base.
    np.testing.assert_allclose(color[..., :3], 0.8, atol=1e-5)
    np.testing.assert_allclose(color[..., 3], 1.0)


def test_phong_point_light_is_brightest_under_it():
    positions, varyings, indices = phong_quad()
    pipeline = tessera.Pipeline(shader="phong")
    pipeline.phong.eye = (0, 0, 4)
    pipeline.phong.lights = [tessera.Light(kind="point", position=(0.5, 0.5, 0.25))]
    framebuffer = tessera.Framebuffer(64, 64)
    tessera.Renderer(threads=1).draw(framebuffer, positions, varyings, indices, pipeline=pipeline)
    luminance = framebuffer.read_rgba8()[..., 0].astype(int)
    # Clip-space (0.5, 0.5) is pixel (48, 16): window y runs down.
    y, x = np.unravel_index(np.argmax(luminance), luminance.shape)
    assert abs(x - 48) <= 3 and abs(y - 16) <= 3
    assert luminance[y, x] > luminance[63, 0] + 50


def test_object_id_output_labels_each_draw():
    framebuffer = tessera.Framebuffer(32, 32, color="rgba32f")
    renderer = tessera.Renderer(threads=1)
    left = np.array([[-1, -1, 0.5, 1], [0, -1, 0.5, 1], [0, 1, 0.5, 1]], dtype=np.float32)
    right = np.array([[0, -1, 0.25, 1], [1, -1, 0.25, 1], [1, 1, 0.25, 1]], dtype=np.float32)
    for object_id, positions in ((7, left), (9, right)):
        renderer.draw(
            framebuffer, positions, pipeline=tessera.Pipeline(output="object_id", object_id=object_id)
        )
    ids = framebuffer.read_rgba32f()[..., 0].astype(np.uint32)
    assert set(np.unique(ids)) == {0, 7, 9}
    assert ids[31, 2] == 7 and ids[31, 29] == 9 and ids[0, 2] == 0
    depth = framebuffer.read_depth()
    assert depth[31, 2] == pytest.approx(0.5, abs=1e-6)
    assert depth[31, 29] == pytest.approx(0.25, abs=1e-6)
    assert depth[0, 2] == 1.0


def test_primitive_id_output_numbers_the_triangles_of_a_draw(quad):
    positions, _, indices = quad
    framebuffer = tessera.Framebuffer(16, 16, color="rgba32f")
    tessera.Renderer(threads=1).draw(
        framebuffer, positions, indices=indices, pipeline=tessera.Pipeline(output="primitive_id")
    )
    ids = framebuffer.read_rgba32f()[..., 0]
    # Triangle 0 (0, 1, 2) is below the diagonal from the bottom left to the top right.
    assert ids[15, 14] == 0 and ids[0, 1] == 1


def test_pipeline_attributes_round_trip():
    pipeline = tessera.Pipeline(
        depth_compare="greater", cull="back", front_face="cw", interpolation="affine"
    )
    assert (pipeline.depth_compare, pipeline.cull, pipeline.front_face) == ("greater", "back", "cw")
    assert pipeline.interpolation == "affine" and pipeline.output == "color"
    pipeline.roles.normal = 8
    assert pipeline.roles.normal == 8
    pipeline.varying_modes = ["flat", "affine"]
    assert pipeline.varying_modes[:3] == ["flat", "affine", "default"]
    assert tessera.Light(kind="spot").kind == "spot"
