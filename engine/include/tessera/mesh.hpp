// Triangle meshes and the small utilities the scene layer needs. Loading them from files is
// tessera/mesh_io.hpp (Tessera::io).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "tessera/export.hpp"

namespace tessera {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // one per position (may be empty until computed)
  std::vector<glm::vec4> colors;     // one per position: base colour, before lighting
  std::vector<glm::vec2> texcoords;  // one per position (u right, v down), or none
  std::vector<uint32_t> indices;     // triangle list

  size_t triangle_count() const noexcept { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min{0.0f};
  glm::vec3 max{0.0f};
};

// Smooth vertex normals from the triangles (area-weighted).
TESSERA_API void compute_normals(Mesh& mesh);

TESSERA_API Bounds mesh_bounds(const Mesh& mesh);

// Appends `other` to `mesh`.
TESSERA_API void append_mesh(Mesh& mesh, const Mesh& other);

}  // namespace tessera
