// The mesh utilities of tessera/mesh.hpp: smooth normals, bounds, concatenation. In the core
// library, apart from mesh_io.cpp's file loading, because the scene layer and the demo scene
// need them without Assimp.
#include "tessera/mesh.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace tessera {

void compute_normals(Mesh& mesh) {
  // Normals do not depend on the mesh's scale, but float products of its edges do: past
  // coordinates of about 2^31 a cross product's squared length overflows (the normal comes out
  // 0), past 2^63 the cross product itself (inf / inf, NaN). So the positions are scaled by the
  // power of two that brings the largest coordinate into [0.5, 1). That is exact: a mesh whose
  // products neither overflow nor underflow gets the same bits as unscaled.
  float largest = 0.0f;
  for (const glm::vec3& p : mesh.positions)
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  int exponent = 0;
  if (std::isfinite(largest)) std::frexp(largest, &exponent);
  const auto at = [&](uint32_t i) {
    return glm::vec3(std::ldexp(mesh.positions[i].x, -exponent),
                     std::ldexp(mesh.positions[i].y, -exponent),
                     std::ldexp(mesh.positions[i].z, -exponent));
  };
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    // The cross product's length is twice the triangle's area: an area-weighted sum.
    const glm::vec3 n = glm::cross(at(b) - at(a), at(c) - at(a));
    mesh.normals[a] += n;
    mesh.normals[b] += n;
    mesh.normals[c] += n;
  }
  for (glm::vec3& n : mesh.normals) {
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

Bounds mesh_bounds(const Mesh& mesh) {
  if (mesh.positions.empty()) return {};
  Bounds b{mesh.positions[0], mesh.positions[0]};
  for (const glm::vec3& p : mesh.positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

void append_mesh(Mesh& mesh, const Mesh& other) {
  const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), other.positions.begin(), other.positions.end());
  mesh.normals.insert(mesh.normals.end(), other.normals.begin(), other.normals.end());
  mesh.colors.insert(mesh.colors.end(), other.colors.begin(), other.colors.end());
  // Texture coordinates when either has them, (0, 0) for the vertices of the other.
  if (!mesh.texcoords.empty() || !other.texcoords.empty()) {
    mesh.texcoords.resize(base, glm::vec2(0.0f));
    mesh.texcoords.insert(mesh.texcoords.end(), other.texcoords.begin(), other.texcoords.end());
    mesh.texcoords.resize(mesh.positions.size(), glm::vec2(0.0f));
  }
  for (uint32_t i : other.indices)
    mesh.indices.push_back(base + i);
}

}  // namespace tessera
