// Triangle meshes and loading them from Wavefront OBJ, glTF 2.0 (.gltf, .glb) and PLY files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace tessera {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // one per position (may be empty until computed)
  std::vector<glm::vec4> colors;   // one per position: base colour, before lighting
  std::vector<uint32_t> indices;   // triangle list

  size_t triangle_count() const noexcept { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
};

// Loads every triangle of every mesh in the file's scene, with node transforms applied, into
// one mesh. Colours come from vertex colours, else the material's diffuse colour, else a
// neutral grey. Missing normals are computed (smooth). Text files (OBJ, PLY, glTF) may start
// with a UTF-8 or UTF-16 byte-order mark. Throws Error(kIo) for a missing or unreadable file
// and Error(kInvalidInput) for a malformed one (an index out of range, a NaN or infinite
// position, anything Assimp cannot read) or one without triangles, with the file name and the
// reason in a one-line message. Loads are serialized: Assimp's logger, which load_mesh listens
// to during the import, is one per process.
Mesh load_mesh(const std::filesystem::path& path);

// Loads every vertex of every mesh in the file (of triangles, lines or points alike, e.g. a
// PLY point cloud with no faces), with node transforms applied, as a point cloud: positions
// and colours as load_mesh takes them, normals (0, 0, 1), no indices. Same checks and errors
// as load_mesh, except that a file without triangles is fine; one without vertices is
// Error(kInvalidInput).
Mesh load_point_cloud(const std::filesystem::path& path);

// Smooth vertex normals from the triangles (area-weighted).
void compute_normals(Mesh& mesh);

Bounds mesh_bounds(const Mesh& mesh);

// Appends `other` to `mesh`.
void append_mesh(Mesh& mesh, const Mesh& other);

}  // namespace tessera
