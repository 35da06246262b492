"""Textures through Python: the textured shader draws a texture mapped one texel per pixel
exactly on both backends; bad textures, samplers and states are errors naming them."""

import numpy as np
import pytest

import tessera

W, H = 24, 16


def one_to_one_quad():
    """A full-window quad whose (u, v) runs over [0, 1], varyings 0 and 1."""
    positions = np.array(
        [[-1, 1, 0.5, 1], [1, 1, 0.5, 1], [1, -1, 0.5, 1], [-1, -1, 0.5, 1]], dtype=np.float32
    )
    uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32)
    indices = np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)
    return positions, uv, indices


def texels():
    return ((np.arange(H * W * 4, dtype=np.uint32) * 37 + 11) % 256).astype(np.uint8).reshape(
        H, W, 4
    )


@pytest.mark.parametrize("backend", ["fast", "reference"])
@pytest.mark.parametrize("filter_", ["nearest", "linear"])
def test_a_texture_mapped_one_to_one_draws_its_texels(backend, filter_):
    pixels = texels()
    texture = tessera.Texture(pixels)
    assert (texture.width, texture.height, texture.format) == (W, H, "rgba8")
    assert texture.levels == 5  # 24x16 down to 1x1
    pipeline = tessera.Pipeline(shader="textured", texture=texture)
    pipeline.roles.texcoord = 0
    pipeline.sampler = tessera.Sampler(mag_filter=filter_, min_filter=filter_)
    assert pipeline.shader == "textured" and pipeline.sampler.mag_filter == filter_
    framebuffer = tessera.Framebuffer(W, H, samples=4)
    positions, uv, indices = one_to_one_quad()
    tessera.Renderer(threads=2, backend=backend).draw(
        framebuffer, positions, uv, indices, pipeline=pipeline
    )
    np.testing.assert_array_equal(framebuffer.read_rgba8(), pixels)


def test_textures_load_from_files(tmp_path):
    if not hasattr(tessera, "load_texture"):
        pytest.skip("built without the io library")
    # A 2x1 binary PPM (RGB, 8 bits): an rgba8 texture with alpha 255, sRGB when asked.
    path = tmp_path / "two.ppm"
    path.write_bytes(b"P6\n2 1\n255\n" + bytes([10, 20, 30, 200, 100, 0]))
    texture = tessera.load_texture(str(path), mipmaps=False)
    assert (texture.width, texture.height, texture.format, texture.levels) == (2, 1, "rgba8", 1)
    assert tessera.load_texture(str(path), srgb=True).format == "rgba8_srgb"
    # Drawn one texel per pixel, it is its texels.
    pipeline = tessera.Pipeline(shader="textured", texture=texture)
    pipeline.roles.texcoord = 0
    framebuffer = tessera.Framebuffer(2, 1)
    positions, uv, indices = one_to_one_quad()
    tessera.Renderer(threads=1).draw(framebuffer, positions, uv, indices, pipeline=pipeline)
    np.testing.assert_array_equal(
        framebuffer.read_rgba8()[0], [[10, 20, 30, 255], [200, 100, 0, 255]]
    )
    assert tessera.Texture(np.full((3, 5), 0.25, dtype=np.float32)).format == "r32f"
    with pytest.raises(RuntimeError, match="missing.png"):
        tessera.load_texture(str(tmp_path / "missing.png"))


def test_bad_textures_samplers_and_states_are_errors():
    with pytest.raises(TypeError, match="uint8 or float32"):
        tessera.Texture(np.zeros((4, 4, 4), dtype=np.int32))
    with pytest.raises(ValueError, match=r"\(h, w, 4\)"):
        tessera.Texture(np.zeros((4, 4, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="16385"):
        tessera.Texture(np.zeros((1, 16385), dtype=np.uint8))
    with pytest.raises(ValueError, match="wrap_u"):
        tessera.Sampler(wrap_u="wrap")
    positions, uv, indices = one_to_one_quad()
    pipeline = tessera.Pipeline(shader="textured")
    pipeline.roles.texcoord = 0
    with pytest.raises(ValueError, match="needs a texture"):
        tessera.Renderer().draw(tessera.Framebuffer(8, 8), positions, uv, indices, pipeline=pipeline)
    pipeline.texture = tessera.Texture(texels())
    pipeline.sampler = tessera.Sampler(min_lod=3, max_lod=1)
    with pytest.raises(ValueError, match="min_lod"):
        tessera.Renderer().draw(tessera.Framebuffer(8, 8), positions, uv, indices, pipeline=pipeline)
    pipeline.sampler = tessera.Sampler(max_anisotropy=32)
    with pytest.raises(ValueError, match="max_anisotropy"):
        tessera.Renderer().draw(tessera.Framebuffer(8, 8), positions, uv, indices, pipeline=pipeline)
