"""Blending through Python: the blend state's attributes, a hand-computed blend, and the two
backends giving the same bytes."""

import numpy as np
import pytest

import tessera


def screen_quad(color):
    positions = np.array(
        [[-1, -1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1], [-1, 1, 0.5, 1]], dtype=np.float32
    )
    colors = np.tile(np.array(color, dtype=np.float32), (4, 1))
    return positions, colors, np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)


@pytest.mark.parametrize("backend", ["fast", "reference"])
def test_half_transparent_red_over_blue_gives_the_hand_computed_bytes(backend):
    positions, colors, indices = screen_quad((1, 0, 0, 0.5))
    pipeline = tessera.Pipeline(depth_test=False, blend=tessera.Blend.over())
    assert pipeline.blend.enable and pipeline.blend.src_color == "src_alpha"
    framebuffer = tessera.Framebuffer(24, 16)
    framebuffer.clear_color((0.2, 0.4, 0.6, 0.5))
    tessera.Renderer(threads=2, backend=backend).draw(
        framebuffer, positions, colors, indices, pipeline=pipeline
    )
    # The clear is stored as bytes (51, 102, 153, 128): 0.5 + 0.5 * 51/255 = 0.6 (153),
    # 0.5 * 102/255 = 0.2 (51), 0.5 * 153/255 = 0.3 (76.5 -> 77), alpha 0.5 + 0.5 * 128/255
    # (191.5 -> 192).
    assert (framebuffer.read_rgba8() == np.array([153, 51, 77, 192], dtype=np.uint8)).all()


def test_write_mask_and_constant_blend_match_across_backends():
    positions, colors, indices = screen_quad((0.9, 0.3, 0.6, 0.8))
    blend = tessera.Blend(
        enable=True,
        src_color="constant_color",
        dst_color="one_minus_src_color",
        color_op="reverse_subtract",
        src_alpha="src_alpha_saturate",
        dst_alpha="one",
        alpha_op="max",
        write_mask=1 | 4 | 8,
    )
    pipeline = tessera.Pipeline(depth_test=False, blend=blend, blend_constant=(0.25, 0.5, 0.75, 1))
    images = []
    for backend in ("fast", "reference"):
        framebuffer = tessera.Framebuffer(40, 24, samples=4)
        framebuffer.clear_color((0.7, 0.2, 0.4, 0.3))
        tessera.Renderer(threads=1, backend=backend).draw(
            framebuffer, positions, colors, indices, pipeline=pipeline
        )
        images.append(framebuffer.read_rgba8())
    np.testing.assert_array_equal(images[0], images[1])
    # Green is masked: the clear's 0.2 (51) stays.
    assert (images[0][..., 1] == 51).all()


def test_bad_blend_names_and_masks_are_value_errors():
    with pytest.raises(ValueError, match="src_color \"half\" is not one of"):
        tessera.Blend(src_color="half")
    with pytest.raises(ValueError, match="write_mask 16"):
        tessera.Blend(write_mask=16)
