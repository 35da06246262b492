"""Bad input: each is an exception whose message names the argument, and the framebuffer is
left as it was."""

import numpy as np
import pytest

import tessera


@pytest.fixture
def target():
    framebuffer = tessera.Framebuffer(16, 16)
    framebuffer.clear_color((0.25, 0.25, 0.25, 1.0))
    return framebuffer


def unchanged(framebuffer):
    return np.all(framebuffer.read_rgba8() == np.array([64, 64, 64, 255], dtype=np.uint8))


def test_positions_of_wrong_dtype_are_a_type_error(target, quad):
    positions, colors, indices = quad
    with pytest.raises(TypeError, match="positions must be a float32 array, got dtype float64"):
        tessera.Renderer(threads=1).draw(target, positions.astype(np.float64), colors, indices)
    assert unchanged(target)


def test_positions_of_wrong_shape_are_a_value_error(target, quad):
    positions, colors, indices = quad
    with pytest.raises(ValueError, match=r"positions must have shape \(n, 4\), got \(4, 3\)"):
        tessera.Renderer(threads=1).draw(target, positions[:, :3].copy(), colors, indices)
    with pytest.raises(ValueError, match=r"positions must have shape \(n, 4\), got \(16,\)"):
        tessera.Renderer(threads=1).draw(target, positions.ravel(), colors, indices)
    assert unchanged(target)


def test_non_contiguous_positions_are_a_value_error(target, quad):
    positions, colors, indices = quad
    strided = np.zeros((8, 4), dtype=np.float32)[::2]
    strided[:] = positions
    with pytest.raises(ValueError, match="positions must be C-contiguous"):
        tessera.Renderer(threads=1).draw(target, strided, colors, indices)
    fortran = np.asfortranarray(positions)
    with pytest.raises(ValueError, match="positions must be C-contiguous"):
        tessera.Renderer(threads=1).draw(target, fortran, colors, indices)
    assert unchanged(target)


def test_nan_position_is_a_value_error_naming_the_vertex(target, quad):
    positions, colors, indices = quad
    positions = positions.copy()
    positions[1, 0] = np.nan
    with pytest.raises(ValueError, match="position of vertex 1 is not finite"):
        tessera.Renderer(threads=1).draw(target, positions, colors, indices)
    assert unchanged(target)


def test_bad_varyings_name_the_argument(target, quad):
    positions, colors, indices = quad
    renderer = tessera.Renderer(threads=1)
    with pytest.raises(TypeError, match="varyings must be a float32 array"):
        renderer.draw(target, positions, colors.astype(np.float16), indices)
    with pytest.raises(ValueError, match=r"varyings must have shape \(n, k\), got \(16,\)"):
        renderer.draw(target, positions, colors.ravel(), indices)
    with pytest.raises(ValueError, match="varyings must be C-contiguous"):
        renderer.draw(target, positions, colors.T, indices)
    # Counts are the C++ API's checks, with its message.
    with pytest.raises(ValueError, match="attributes hold 12 floats, but 4 vertices"):
        renderer.draw(target, positions, colors[:3].copy(), indices)
    with pytest.raises(ValueError, match="attribute 2 of vertex 3 is not finite"):
        bad = colors.copy()
        bad[3, 2] = np.inf
        renderer.draw(target, positions, bad, indices)
    assert unchanged(target)


def test_bad_indices_name_the_argument(target, quad):
    positions, colors, indices = quad
    renderer = tessera.Renderer(threads=1)
    with pytest.raises(TypeError, match="indices must be a uint32 array, got dtype int64"):
        renderer.draw(target, positions, colors, indices.astype(np.int64))
    with pytest.raises(ValueError, match=r"indices must have shape \(n, 3\), got \(3, 2\)"):
        renderer.draw(target, positions, colors, indices.reshape(3, 2))
    with pytest.raises(ValueError, match="indices must be C-contiguous"):
        renderer.draw(target, positions, colors, indices.ravel()[::2])
    with pytest.raises(ValueError, match="index 7 at position 5 is out of range"):
        bad = indices.copy()
        bad[1, 2] = 7
        renderer.draw(target, positions, colors, bad)
    with pytest.raises(ValueError, match="a triangle list needs a multiple of 3 indices, got 4"):
        renderer.draw(target, positions, colors, indices.ravel()[:4].copy())
    assert unchanged(target)


def test_library_errors_become_python_exceptions_with_its_message():
    with pytest.raises(ValueError, match=r"framebuffer width 0 is out of range \(1..16384\)"):
        tessera.Framebuffer(0, 16)
    with pytest.raises(ValueError, match="framebuffer sample count 3 is not one of 1, 2, 4, 8, 16"):
        tessera.Framebuffer(16, 16, samples=3)
    with pytest.raises(MemoryError, match="more than the limit of 8192 MiB"):
        tessera.Framebuffer(16384, 16384, samples=16)
    with pytest.raises(ValueError, match="subpixel_bits 2 is out of range"):
        tessera.Renderer(threads=1).draw(
            tessera.Framebuffer(4, 4),
            np.zeros((3, 4), dtype=np.float32),
            pipeline=tessera.Pipeline(subpixel_bits=2),
        )


def test_bad_names_and_options_are_errors():
    with pytest.raises(ValueError, match='backend "gpu" is not one of "fast", "reference"'):
        tessera.Renderer(backend="gpu")
    with pytest.raises(ValueError, match='color "rgb8" is not one of'):
        tessera.Framebuffer(4, 4, color="rgb8")
    with pytest.raises(ValueError, match='output "segmentation" is not one of'):
        tessera.Pipeline(output="segmentation")
    with pytest.raises(AttributeError):
        tessera.Pipeline(depth_tset=False)
    with pytest.raises(ValueError, match="phong.lights holds 9 lights"):
        tessera.Pipeline().phong.lights = [tessera.Light()] * 9
