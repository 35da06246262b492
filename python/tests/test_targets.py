"""Multiple render targets through Python: one pass writes colour, eye depth, normals and exact
IDs, each as a draw of that output alone would."""

import numpy as np
import pytest

import tessera

from test_shading import phong_quad


def sheet(n=6):
    """A tilted, perspective sheet of 2 n^2 triangles with colour, normal and position
    varyings in the default roles 0, 4 and 7."""
    positions, varyings = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = -0.9 + 1.8 * i / n, -0.9 + 1.8 * j / n
            w = 1.5 + 0.5 * x
            positions.append((x * w, y * w, 0.4 * w, w))
            varyings.append([i / n, j / n, 0.5, 1, 0.3 * x, 0.2 * y, 1, x, y, -w])
    indices = []
    for j in range(n):
        for i in range(n):
            a, b = j * (n + 1) + i, j * (n + 1) + i + 1
            c, d = a + n + 1, b + n + 1
            indices += [a, b, d, a, d, c]
    return (
        np.array(positions, dtype=np.float32),
        np.array(varyings, dtype=np.float32),
        np.array(indices, dtype=np.uint32),
    )


@pytest.mark.parametrize("backend", ["fast", "reference"])
def test_each_target_holds_what_its_output_alone_draws(backend):
    positions, varyings, indices = sheet()
    renderer = tessera.Renderer(threads=2, backend=backend)
    fb = tessera.Framebuffer(48, 40, color="rgba32f", targets=["r32f", "rgba32f", "r32ui"])
    assert fb.target_count == 4
    assert [fb.target_format(t) for t in range(4)] == ["rgba32f", "r32f", "rgba32f", "r32ui"]
    fb.clear_target(3, 7)
    pipeline = tessera.Pipeline(extra_outputs=["eye_depth", "normal", "primitive_id"])
    assert pipeline.extra_outputs == ["eye_depth", "normal", "primitive_id"]
    renderer.draw(fb, positions, varyings, indices, pipeline=pipeline)

    def alone(output):
        single = tessera.Framebuffer(48, 40, color="rgba32f")
        renderer.draw(single, positions, varyings, indices, pipeline=tessera.Pipeline(output=output))
        return single.read_rgba32f()

    colour, depth, normals, ids = (fb.read_target(t) for t in range(4))
    assert depth.shape == (40, 48) and depth.dtype == np.float32
    assert normals.shape == (40, 48, 4)
    assert ids.shape == (40, 48) and ids.dtype == np.uint32
    np.testing.assert_allclose(colour, alone("color"), atol=2e-6)
    np.testing.assert_allclose(depth, alone("eye_depth")[..., 0], rtol=2e-6)
    np.testing.assert_allclose(normals, alone("normal"), atol=2e-6)
    drawn = alone("color")[..., 3] > 0
    assert drawn.sum() > 48 * 40 // 2
    np.testing.assert_array_equal(ids[drawn], alone("primitive_id")[..., 0][drawn].astype(np.uint32))
    assert (ids[~drawn] == 7).all()


def test_object_ids_past_2_to_the_24_are_exact_in_an_r32ui_target():
    positions, varyings, indices = phong_quad()
    fb = tessera.Framebuffer(16, 16, samples=4, targets=["r32ui"])
    pipeline = tessera.Pipeline(extra_outputs=["object_id"], object_id=(1 << 24) + 5)
    tessera.Renderer(threads=1).draw(fb, positions, varyings, indices, pipeline=pipeline)
    assert (fb.read_target(1) == (1 << 24) + 5).all()


def test_bad_targets_are_errors_naming_them():
    with pytest.raises(ValueError, match="targets"):
        tessera.Framebuffer(8, 8, targets=["rgba8", "r32f", "r32ui", "r32f"])
    with pytest.raises(ValueError, match="r16"):
        tessera.Framebuffer(8, 8, targets=["r16"])
    with pytest.raises(ValueError, match="extra_outputs"):
        tessera.Pipeline(extra_outputs=["normal", "color", "color", "color"])
    fb = tessera.Framebuffer(8, 8, targets=["r32ui"])
    with pytest.raises(ValueError, match="target 2 does not exist"):
        fb.read_target(2)
    positions, varyings, indices = phong_quad()
    with pytest.raises(ValueError, match="extra_outputs\\[0\\] kNormal"):
        tessera.Renderer().draw(
            fb, positions, varyings, indices, pipeline=tessera.Pipeline(extra_outputs=["normal"])
        )
