// Mesh loading through Assimp (OBJ, glTF 2.0, PLY and the other formats it reads), flattened
// into one triangle mesh, plus the small mesh utilities samples need.
#include <cmath>
#include <string>
#include <system_error>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/geometric.hpp>

#include "tessera/error.hpp"
#include "tessera/mesh.hpp"

namespace tessera {

namespace {

constexpr glm::vec4 kDefaultColor{0.72f, 0.74f, 0.78f, 1.0f};

[[noreturn]] void bad(const std::filesystem::path& path, const std::string& what) {
  throw Error(ErrorCode::kInvalidInput, path.string() + ": " + what);
}

glm::vec4 material_color(const aiScene& scene, unsigned material_index) {
  if (material_index >= scene.mNumMaterials) return kDefaultColor;
  const aiMaterial* m = scene.mMaterials[material_index];
  aiColor4D c;
  if (m->Get(AI_MATKEY_BASE_COLOR, c) == aiReturn_SUCCESS ||
      m->Get(AI_MATKEY_COLOR_DIFFUSE, c) == aiReturn_SUCCESS) {
    const glm::vec4 v{c.r, c.g, c.b, c.a};
    if (std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b) && std::isfinite(v.a)) {
      return glm::clamp(v, 0.0f, 1.0f);
    }
  }
  return kDefaultColor;
}

bool finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(ErrorCode::kIo, path.string() + ": no such file");
  }
  Assimp::Importer importer;
  // Triangles only (polygons are triangulated, points and lines sorted out), node transforms
  // applied, shared vertices merged, and the result checked for out-of-range indices.
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType |
                         aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices |
                         aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(path.string(), flags);
  if (scene == nullptr) {
    std::string reason = importer.GetErrorString();
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
    for (char& ch : reason) {
      if (ch == '\n') ch = ' ';
    }
    bad(path, "cannot load mesh: " + (reason.empty() ? std::string("unknown error") : reason));
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) bad(path, "incomplete scene");

  Mesh mesh;
  bool all_have_normals = true;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& am = *scene->mMeshes[m];
    if ((am.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    const glm::vec4 color = material_color(*scene, am.mMaterialIndex);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const aiVector3D& p = am.mVertices[v];
      if (!finite(p)) {
        bad(path, "vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                      " has a position that is not finite");
      }
      mesh.positions.emplace_back(p.x, p.y, p.z);
      if (am.HasVertexColors(0)) {
        const aiColor4D& c = am.mColors[0][v];
        const glm::vec4 vc{c.r, c.g, c.b, c.a};
        const bool ok = std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) &&
                        std::isfinite(c.a);
        mesh.colors.push_back(ok ? glm::clamp(vc, 0.0f, 1.0f) : color);
      } else {
        mesh.colors.push_back(color);
      }
      if (am.HasNormals() && finite(am.mNormals[v])) {
        mesh.normals.emplace_back(am.mNormals[v].x, am.mNormals[v].y, am.mNormals[v].z);
      } else {
        mesh.normals.emplace_back(0.0f);
        all_have_normals = false;
      }
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= am.mNumVertices) {
          bad(path, "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                        " has index " + std::to_string(face.mIndices[k]) + ", out of range (" +
                        std::to_string(am.mNumVertices) + " vertices)");
        }
        mesh.indices.push_back(base + face.mIndices[k]);
      }
    }
  }
  if (mesh.indices.empty()) bad(path, "no triangles to draw (the file holds only points, lines or nothing)");
  if (!all_have_normals) compute_normals(mesh);
  return mesh;
}

void compute_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    // The cross product's length is twice the triangle's area: an area-weighted sum.
    const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a],
                                   mesh.positions[c] - mesh.positions[a]);
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
  for (uint32_t i : other.indices) mesh.indices.push_back(base + i);
}

}  // namespace tessera
