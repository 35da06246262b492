"""Meshes loaded from files through Python, drawn with the camera helpers."""

import numpy as np
import pytest

import tessera

pytestmark = pytest.mark.skipif(
    not hasattr(tessera, "load_mesh"), reason="built without Tessera::io"
)

# A unit square in the z = 0 plane, two triangles, with a normal.
SQUARE_OBJ = """v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vn 0 0 1
f 1//1 2//1 3//1
f 1//1 3//1 4//1
"""


def test_load_mesh_returns_numpy_arrays(tmp_path):
    path = tmp_path / "square.obj"
    path.write_text(SQUARE_OBJ)
    mesh = tessera.load_mesh(path)
    assert mesh.triangle_count == 2
    assert mesh.positions.shape == (4, 3) and mesh.positions.dtype == np.float32
    assert mesh.normals.shape == (4, 3) and mesh.colors.shape == (4, 4)
    assert mesh.indices.shape == (2, 3) and mesh.indices.dtype == np.uint32
    np.testing.assert_allclose(mesh.normals, [[0, 0, 1]] * 4)
    assert mesh.bounds() == ([-1, -1, 0], [1, 1, 0])
    assert tessera.load_mesh(str(path)).triangle_count == 2


def test_a_loaded_mesh_renders_with_metric_depth_and_an_object_id(tmp_path):
    path = tmp_path / "square.obj"
    path.write_text(SQUARE_OBJ)
    mesh = tessera.load_mesh(path)
    camera = tessera.Camera(eye=(0, 0, 2), target=(0, 0, 0))
    clip = tessera.to_clip_space(mesh.positions, camera.projection(1.0) @ camera.view())
    renderer = tessera.Renderer(threads=2)
    labels = tessera.Framebuffer(32, 32, color="rgba32f")
    renderer.draw(
        labels, clip, indices=mesh.indices, pipeline=tessera.Pipeline(output="object_id", object_id=5)
    )
    assert labels.read_rgba32f()[16, 16, 0] == 5
    eye = tessera.Framebuffer(32, 32, color="rgba32f")
    renderer.draw(eye, clip, indices=mesh.indices, pipeline=tessera.Pipeline(output="eye_depth"))
    assert eye.read_rgba32f()[16, 16, 0] == pytest.approx(2.0, rel=1e-5)


def test_a_missing_file_is_an_error_naming_it(tmp_path):
    with pytest.raises(RuntimeError, match="missing.obj"):
        tessera.load_mesh(tmp_path / "missing.obj")
