// Fuzzes load_mesh and load_point_cloud on OBJ and PLY text: a one-line tessera::Error naming the
// file, or a mesh whose arrays agree, whose indices name vertices and whose values are finite.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tessera/error.hpp"
#include "tessera/mesh_io.hpp"

namespace {

[[noreturn]] void broken(const char* rule) {
  std::fprintf(stderr, "mesh_loader_fuzzer: %s\n", rule);
  std::abort();
}

const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("tessera-mesh-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_mesh(const tessera::Mesh& m, bool point_cloud) {
  if (m.positions.empty()) broken("a loaded mesh has no vertices");
  if (m.normals.size() != m.positions.size()) broken("normals do not match positions");
  if (m.colors.size() != m.positions.size()) broken("colours do not match positions");
  if (point_cloud ? !m.indices.empty() : m.indices.empty() || m.indices.size() % 3 != 0)
    broken("wrong index count");
  for (uint32_t i : m.indices) {
    if (i >= m.positions.size()) broken("an index is out of range");
  }
  for (size_t v = 0; v < m.positions.size(); ++v) {
    if (!finite(m.positions[v])) broken("a position is not finite");
    if (!finite(m.normals[v])) broken("a normal is not finite");
    const glm::vec4& c = m.colors[v];
    for (int k = 0; k < 4; ++k) {
      if (!(c[k] >= 0.0f && c[k] <= 1.0f)) broken("a colour is outside 0..1");
    }
  }
}

void load_checked(const std::filesystem::path& path, bool point_cloud) {
  try {
    const tessera::Mesh m =
        point_cloud ? tessera::load_point_cloud(path) : tessera::load_mesh(path);
    check_mesh(m, point_cloud);
  } catch (const tessera::Error& e) {
    const std::string message = e.what();
    if (message.find('\n') != std::string::npos) broken("error message spans lines");
    if (message.find(path.string()) == std::string::npos) broken("error message misses the file");
    if (e.code() != tessera::ErrorCode::kInvalidInput) broken("a bad file is not kInvalidInput");
  }
}

}  // namespace

// The first byte chooses the format (bit 0: PLY, else OBJ) and the loader (bit 1: point
// cloud); the rest is the file.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::filesystem::path path = work_dir() / ((data[0] & 1) ? "input.ply" : "input.obj");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!out.flush()) broken("cannot write the fuzz input to a file");
  }
  load_checked(path, (data[0] & 2) != 0);
  return 0;
}
