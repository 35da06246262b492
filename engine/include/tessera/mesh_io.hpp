// Loading meshes from Wavefront OBJ, glTF 2.0 (.gltf, .glb) and PLY files through Assimp. Part of
// Tessera::io (the tessera_io library), which links Assimp and OpenImageIO; the core library
// (Tessera::tessera) needs neither.
#pragma once

#include <filesystem>
#include <vector>

#include "tessera/export.hpp"
#include "tessera/mesh.hpp"
#include "tessera/scene.hpp"

namespace tessera {

// Loads every triangle of every mesh in the file's scene, with node transforms applied, into
// one mesh. Colours come from vertex colours, else the material's diffuse colour, else a
// neutral grey. Missing normals are computed (smooth). Text files (OBJ, PLY, glTF) may start
// with a UTF-8 or UTF-16 byte-order mark. Throws Error(kIo) for a missing or unreadable file
// and Error(kInvalidInput) for a malformed one (an index out of range, a NaN or infinite
// position, anything Assimp cannot read) or one without triangles, with the file name and the
// reason in a one-line message. Loads are serialized: Assimp's logger, which load_mesh listens
// to during the import, is one per process.
TESSERA_API Mesh load_mesh(const std::filesystem::path& path);

// Loads every vertex of every mesh in the file (of triangles, lines or points alike, e.g. a
// PLY point cloud with no faces), with node transforms applied, as a point cloud: positions
// and colours as load_mesh takes them, normals (0, 0, 1), no indices. Same checks and errors
// as load_mesh, except that a file without triangles is fine; one without vertices is
// Error(kInvalidInput).
TESSERA_API Mesh load_point_cloud(const std::filesystem::path& path);

// Loads the file's triangles as load_mesh does, one scene object per material (identity model
// matrices), each with its texture coordinates (v down from the image's top row) and, when its
// material has a base colour texture (glTF's baseColorTexture, OBJ's map_Kd) and the mesh has
// texture coordinates, that texture (sRGB, with its mip chain; from its file beside the model
// or embedded in it) and the material's wrap modes. Same errors as load_mesh; a texture that
// cannot be read is an error naming it.
TESSERA_API std::vector<SceneObject> load_scene_objects(const std::filesystem::path& path);

}  // namespace tessera
