// Mesh loading (mesh_io.hpp): small OBJ, PLY and glTF files written here load into the triangles,
// colours and normals they describe; malformed ones are an Error with a one-line message that
// names the file and the problem, never a crash or an abort inside Assimp; and the models that
// ship with Assimp (scripts/install-deps.sh installs them) load or are rejected as they should.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "tessera/io.hpp"
#include "tessera/tessera.hpp"
#include "tests/file_error.hpp"
#include "tests/temp_dir.hpp"
#include "tests/watchdog.hpp"

namespace tessera {
namespace {

using test::read_file;
using test::TempDir;
using test::write_file;

const std::filesystem::path kAssimpModels = "/usr/share/assimp/models";

constexpr const char* kQuadObj =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n"
    "f 1 2 3 4\n";

// Loads and expects Error(code) whose one-line message names the file and holds every one of
// `parts`; the file is left as it was.
void expect_load_error(const std::filesystem::path& path, ErrorCode code,
                       std::initializer_list<std::string> parts) {
  const std::string bytes_before = read_file(path);
  test::expect_file_error([](const std::filesystem::path& p) { load_mesh(p); }, path, code, parts);
  EXPECT_EQ(read_file(path), bytes_before);
}

// Every index names a vertex, every array has one entry per position, all values finite.
void expect_consistent(const Mesh& mesh) {
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
  for (uint32_t i : mesh.indices)
    ASSERT_LT(i, mesh.positions.size());
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
  EXPECT_EQ(mesh.colors.size(), mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
  for (const glm::vec3& n : mesh.normals) {
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
  }
}

// The colour of the vertex at `position`.
glm::vec4 color_at(const Mesh& mesh, glm::vec3 position) {
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (mesh.positions[i] == position) return mesh.colors[i];
  }
  ADD_FAILURE() << "no vertex at (" << position.x << ", " << position.y << ", " << position.z
                << ")";
  return glm::vec4(-1.0f);
}

void expect_unit_quad(const Mesh& mesh, glm::vec3 offset = glm::vec3(0.0f)) {
  expect_consistent(mesh);
  EXPECT_EQ(mesh.triangle_count(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);  // shared corners are merged
  const Bounds b = mesh_bounds(mesh);
  EXPECT_EQ(b.min, offset + glm::vec3(0, 0, 0));
  EXPECT_EQ(b.max, offset + glm::vec3(1, 1, 0));
  for (const glm::vec3& n : mesh.normals) {
    EXPECT_NEAR(n.z, 1.0f, 1e-6f);  // counter-clockwise in x-y faces +z
  }
}

// --- glTF written by hand: a JSON document with its buffer inline as a data URI ------------

std::string base64(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = static_cast<uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      v |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[i + 2]));
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

template <typename T>
std::string bytes_of(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// One triangle-list primitive with float positions and uint16 indices, a base colour, and one
// node with a translation.
std::string gltf(const std::vector<float>& positions, const std::vector<uint16_t>& indices,
                 const char* translation = "[0, 0, 0]") {
  std::string buffer = bytes_of(positions) + bytes_of(indices);
  const size_t position_bytes = positions.size() * sizeof(float);
  return R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": )" +
         std::string(translation) + R"(}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.2, 1.0]}}],
  "buffers": [{"byteLength": )" +
         std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
         base64(buffer) + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": )" +
         std::to_string(position_bytes) + R"(, "target": 34962},
    {"buffer": 0, "byteOffset": )" +
         std::to_string(position_bytes) + R"(, "byteLength": )" +
         std::to_string(indices.size() * 2) + R"(, "target": 34963}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": )" +
         std::to_string(positions.size() / 3) + R"(, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": )" +
         std::to_string(indices.size()) + R"(, "type": "SCALAR"}]
})";
}

const std::vector<float> kQuadPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

// --- Well-formed files -------------------------------------------------------------------------

TEST(MeshLoading, ObjQuadBecomesTwoTrianglesWithComputedNormals) {
  TempDir dir;
  write_file(dir / "quad.obj", kQuadObj);
  expect_unit_quad(load_mesh(dir / "quad.obj"));
}

// Float cross products of the edges overflow at these scales: past 2^31 the normals came out
// 0, past 2^63 NaN. Normals do not depend on the scale.
TEST(MeshLoading, NormalsOfHugeMeshesAreTheUnitNormalsOfTheirFaces) {
  TempDir dir;
  for (const char* scale : {"1e10", "1e30", "3e38"}) {
    SCOPED_TRACE(scale);
    const std::string s = scale;
    write_file(dir / "huge.obj",
               "v 0 0 0\nv " + s + " 0 0\nv " + s + " " + s + " 0\nv 0 " + s + " 0\nf 1 2 3 4\n");
    const Mesh mesh = load_mesh(dir / "huge.obj");
    expect_consistent(mesh);
    ASSERT_EQ(mesh.normals.size(), 4u);
    for (const glm::vec3& n : mesh.normals)
      EXPECT_EQ(n, glm::vec3(0, 0, 1));
  }
}

TEST(MeshLoading, ObjVertexColoursBecomeTheMeshColours) {
  TempDir dir;
  write_file(dir / "colours.obj",
             "v 0 0 0 1 0 0\n"
             "v 1 0 0 0 1 0\n"
             "v 1 1 0 0 0 1\n"
             "v 0 1 0 1 1 1\n"
             "f 1 2 3 4\n");
  const Mesh mesh = load_mesh(dir / "colours.obj");
  expect_unit_quad(mesh);
  EXPECT_EQ(color_at(mesh, {0, 0, 0}), glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(color_at(mesh, {1, 0, 0}), glm::vec4(0, 1, 0, 1));
  EXPECT_EQ(color_at(mesh, {1, 1, 0}), glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(color_at(mesh, {0, 1, 0}), glm::vec4(1, 1, 1, 1));
}

TEST(MeshLoading, ObjMaterialDiffuseColourIsTheMeshColour) {
  TempDir dir;
  write_file(dir / "quad.mtl", "newmtl red\nKd 1 0.25 0\n");
  write_file(dir / "red.obj", std::string("mtllib quad.mtl\nusemtl red\n") + kQuadObj);
  const Mesh mesh = load_mesh(dir / "red.obj");
  expect_unit_quad(mesh);
  for (const glm::vec4& c : mesh.colors)
    EXPECT_EQ(c, glm::vec4(1, 0.25f, 0, 1));
}

// OBJ with MTL: one object per material; map_Kd becomes the object's sRGB texture (mip chain
// generated), vt the texture coordinates with v flipped to run down from the image's top row.
TEST(MeshLoading, ObjMapKdBecomesTheObjectsTexture) {
  TempDir dir;
  const std::vector<uint8_t> texels = {255, 0, 0,   255, 0, 255, 0, 255,
                                       0,   0, 255, 255, 9, 9,   9, 255};
  write_image(dir / "tex.png", 2, 2, 4, std::span<const uint8_t>(texels));
  write_file(dir / "two.mtl",
             "newmtl textured\nKd 1 1 1\nmap_Kd tex.png\nnewmtl plain\nKd 0 1 0\n");
  write_file(dir / "two.obj",
             "mtllib two.mtl\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "v 2 0 0\nv 3 0 0\nv 3 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
             "usemtl textured\nf 1/1 2/2 3/3 4/4\n"
             "usemtl plain\nf 5 6 7\n");
  const std::vector<SceneObject> objects = load_scene_objects(dir / "two.obj");
  ASSERT_EQ(objects.size(), 2u);
  const SceneObject* textured = objects[0].texture ? &objects[0] : &objects[1];
  const SceneObject* plain = objects[0].texture ? &objects[1] : &objects[0];
  ASSERT_NE(textured->texture, nullptr);
  EXPECT_EQ(plain->texture, nullptr);
  EXPECT_EQ(plain->mesh.colors[0], glm::vec4(0, 1, 0, 1));
  EXPECT_EQ(textured->texture->desc().format, TextureFormat::kRGBA8Srgb);
  EXPECT_EQ(textured->texture->desc().width, 2u);
  EXPECT_EQ(textured->texture->levels(), 2u);
  EXPECT_EQ(textured->mesh.indices.size(), 6u);
  ASSERT_EQ(textured->mesh.texcoords.size(), textured->mesh.positions.size());
  for (size_t i = 0; i < textured->mesh.positions.size(); ++i) {
    // vt (x, y) at position (x, y): flipped, (x, 1 - y).
    const glm::vec3& p = textured->mesh.positions[i];
    EXPECT_EQ(textured->mesh.texcoords[i], glm::vec2(p.x, 1.0f - p.y)) << i;
  }
  // The texture as the file holds it: texel (0, 0) red.
  EXPECT_EQ(textured->texture->texel(0, 0, 0), (std::array<float, 4>{1, 0, 0, 1}));
  // A missing texture file is an error naming it.
  write_file(dir / "missing.mtl", "newmtl t\nmap_Kd nowhere.png\n");
  write_file(dir / "missing.obj",
             "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
             "usemtl t\nf 1/1 2/2 3/3\n");
  try {
    load_scene_objects(dir / "missing.obj");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kIo);
    EXPECT_NE(std::string(e.what()).find("nowhere.png"), std::string::npos) << e.what();
  }
}

// glTF 2.0's baseColorTexture, embedded in a .glb (PNG bytes decoded from memory) and in a
// .gltf beside it, from Assimp's test models (skipped without them).
TEST(MeshLoading, GltfBaseColourTexturesLoadEmbeddedAndFromFiles) {
  const std::filesystem::path models = "/usr/share/assimp/models/glTF2";
  for (const char* file :
       {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF/BoxTextured.gltf",
        "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    if (!std::filesystem::exists(models / file)) GTEST_SKIP() << "no " << (models / file);
    const std::vector<SceneObject> objects = load_scene_objects(models / file);
    ASSERT_EQ(objects.size(), 1u) << file;
    const SceneObject& box = objects[0];
    ASSERT_NE(box.texture, nullptr) << file;
    EXPECT_EQ(box.texture->desc().format, TextureFormat::kRGBA8Srgb) << file;
    EXPECT_GT(box.texture->desc().width, 1u) << file;
    EXPECT_GT(box.texture->levels(), 1u) << file;
    EXPECT_EQ(box.mesh.texcoords.size(), box.mesh.positions.size()) << file;
    EXPECT_EQ(box.mesh.indices.size(), 36u) << file;
  }
}

TEST(MeshLoading, PlyQuadWithVertexColoursLoads) {
  TempDir dir;
  write_file(dir / "quad.ply",
             "ply\nformat ascii 1.0\n"
             "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n"
             "4 0 1 2 3\n");
  const Mesh mesh = load_mesh(dir / "quad.ply");
  expect_unit_quad(mesh);
  EXPECT_EQ(color_at(mesh, {0, 0, 0}), glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(color_at(mesh, {1, 1, 0}), glm::vec4(0, 0, 1, 1));
}

TEST(MeshLoading, GltfQuadLoadsWithItsBaseColourAndNodeTranslation) {
  TempDir dir;
  write_file(dir / "quad.gltf", gltf(kQuadPositions, {0, 1, 2, 0, 2, 3}, "[10, 0, 0]"));
  const Mesh mesh = load_mesh(dir / "quad.gltf");
  expect_unit_quad(mesh, {10, 0, 0});
  for (const glm::vec4& c : mesh.colors)
    EXPECT_EQ(c, glm::vec4(0.8f, 0.1f, 0.2f, 1.0f));
}

TEST(MeshLoading, TextWithAByteOrderMarkLoadsLikeWithout) {
  TempDir dir;
  const std::string text = kQuadObj;
  std::string utf16le = "\xFF\xFE", utf16be = "\xFE\xFF";
  for (char c : text) {
    utf16le += c;
    utf16le += '\0';
    utf16be += '\0';
    utf16be += c;
  }
  write_file(dir / "utf8.obj", "\xEF\xBB\xBF" + text);
  write_file(dir / "utf16le.obj", utf16le);
  write_file(dir / "utf16be.obj", utf16be);
  const Mesh plain = [&] {
    write_file(dir / "plain.obj", text);
    return load_mesh(dir / "plain.obj");
  }();
  for (const char* name : {"utf8.obj", "utf16le.obj", "utf16be.obj"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_mesh(dir / name);
    EXPECT_EQ(mesh.positions, plain.positions);
    EXPECT_EQ(mesh.indices, plain.indices);
  }
}

// --- Missing and malformed files ---------------------------------------------------------------

TEST(MeshLoading, MissingFileIsAnIoErrorNamingTheFile) {
  TempDir dir;
  expect_load_error(dir / "missing.obj", ErrorCode::kIo, {"no such file"});
}

TEST(MeshLoading, DirectoryIsAnIoErrorNamingIt) {
  TempDir dir;
  std::filesystem::create_directory(dir / "folder.obj");
  expect_load_error(dir / "folder.obj", ErrorCode::kIo, {"not a regular file"});
}

TEST(MeshLoading, PointOnlyObjHasNoTriangles) {
  TempDir dir;
  write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  expect_load_error(dir / "points.obj", ErrorCode::kInvalidInput, {"no triangles"});
}

TEST(MeshLoading, VerticesWithoutFacesHaveNoTriangles) {
  TempDir dir;
  write_file(dir / "cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_load_error(dir / "cloud.obj", ErrorCode::kInvalidInput, {"no triangles"});
}

TEST(MeshLoading, LineOnlyObjHasNoTriangles) {
  TempDir dir;
  write_file(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n");
  expect_load_error(dir / "lines.obj", ErrorCode::kInvalidInput, {"no triangles"});
}

TEST(MeshLoading, ObjFaceIndexOutOfRangeIsRejected) {
  TempDir dir;
  write_file(dir / "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expect_load_error(dir / "index.obj", ErrorCode::kInvalidInput, {"out of range"});
}

TEST(MeshLoading, ObjNaNPositionIsRejectedNamingTheVertex) {
  TempDir dir;
  write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  expect_load_error(dir / "nan.obj", ErrorCode::kInvalidInput, {"vertex 2", "not finite"});
}

TEST(MeshLoading, ObjInfinitePositionIsRejectedNamingTheVertex) {
  TempDir dir;
  write_file(dir / "inf.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_load_error(dir / "inf.obj", ErrorCode::kInvalidInput, {"vertex 1", "not finite"});
}

TEST(MeshLoading, EmptyFileIsRejected) {
  TempDir dir;
  write_file(dir / "empty.obj", "");
  expect_load_error(dir / "empty.obj", ErrorCode::kInvalidInput, {});
}

TEST(MeshLoading, TextThatIsNotAMeshIsRejected) {
  TempDir dir;
  write_file(dir / "words.obj", "this is not a mesh\n");
  expect_load_error(dir / "words.obj", ErrorCode::kInvalidInput, {"no triangles"});
}

TEST(MeshLoading, UnknownFormatIsRejected) {
  TempDir dir;
  write_file(dir / "mesh.xyz", "nothing Assimp knows\n");
  expect_load_error(dir / "mesh.xyz", ErrorCode::kInvalidInput, {"cannot load mesh"});
}

TEST(MeshLoading, Utf16TextWithAnOddByteCountIsRejected) {
  TempDir dir;
  write_file(dir / "odd.obj", std::string("\xFF\xFEv\0 ", 5));
  expect_load_error(dir / "odd.obj", ErrorCode::kInvalidInput, {"odd number of bytes"});
}

constexpr const char* kPlyHeader =
    "ply\nformat ascii 1.0\n"
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";

TEST(MeshLoading, PlyWrongMagicIsRejected) {
  TempDir dir;
  write_file(dir / "magic.ply", "plx\nformat ascii 1.0\nend_header\n");
  expect_load_error(dir / "magic.ply", ErrorCode::kInvalidInput, {"magic"});
}

// Assimp's PLY reader turns such a face into one without indices, and its Triangulate step
// asserts on that (an abort): the loader must catch it first.
TEST(MeshLoading, PlyFaceIndexOutOfRangeIsRejectedWithoutAborting) {
  TempDir dir;
  write_file(dir / "index.ply", std::string(kPlyHeader) +
                                    "element face 1\nproperty list uchar int vertex_indices\n"
                                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
  expect_load_error(dir / "index.ply", ErrorCode::kInvalidInput, {"face 0"});
}

// Assimp would repeat the last face.
TEST(MeshLoading, PlyWithFewerFacesThanItsHeaderDeclaresIsRejected) {
  TempDir dir;
  write_file(dir / "cut.ply", std::string(kPlyHeader) +
                                  "element face 2\nproperty list uchar int vertex_indices\n"
                                  "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_load_error(dir / "cut.ply", ErrorCode::kInvalidInput,
                    {"truncated PLY file", "2 face elements", "ends after 1"});
}

TEST(MeshLoading, PlyWithMoreDataThanItsHeaderDeclaresIsRejected) {
  TempDir dir;
  write_file(dir / "long.ply", std::string(kPlyHeader) +
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n");
  expect_load_error(dir / "long.ply", ErrorCode::kInvalidInput,
                    {"more data than its header declares"});
}

TEST(MeshLoading, PlyListLengthThatIsNotANumberIsRejected) {
  TempDir dir;
  write_file(dir / "list.ply", std::string(kPlyHeader) +
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "end_header\n0 0 0\n1 0 0\n0 1 0\n2.5 0 1 2\n");
  expect_load_error(dir / "list.ply", ErrorCode::kInvalidInput, {"face 0", "list length '2.5'"});
}

// Assimp 5.2's PLY reader never returns from a header without end_header (or reads past the
// end of the file); the loader's own header walk must find that even where it stops following
// the header (a property type it does not know, a property before any element, a first line
// that Assimp takes for the magic but is not "ply").
TEST(MeshLoading, PlyHeaderWithoutEndHeaderIsRejectedWhateverElseItHolds) {
  TempDir dir;
  write_file(dir / "upper.ply", "PLY\nformat ascii 1.0\nelement vertex 1\nproperty float x\n1\n");
  write_file(dir / "magic.ply", "plyZZ\nformat ascii 1.0\nelement vertex 1\nproperty float x\n1\n");
  write_file(dir / "type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flo x\n1\n");
  write_file(dir / "order.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\n1\n");
  write_file(dir / "list.ply", std::string(kPlyHeader) +
                                   "element face 1\nproperty list double int vertex_indices\n" +
                                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const test::Watchdog watchdog(60);
  for (const char* name : {"upper.ply", "magic.ply", "type.ply", "order.ply", "list.ply"}) {
    SCOPED_TRACE(name);
    expect_load_error(dir / name, ErrorCode::kInvalidInput, {"without end_header"});
  }
}

// An element without properties takes no data, so its count, however large, costs nothing to
// check: the scan of an ASCII body reads no token for it rather than counting to 2^64.
TEST(MeshLoading, PlyElementsWithoutPropertiesTakeNoDataWhateverTheirCount) {
  TempDir dir;
  write_file(dir / "empty.ply", std::string(kPlyHeader) + "element junk 18446744073709551615\n" +
                                    "element face 1\nproperty list uchar int vertex_indices\n" +
                                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const test::Watchdog watchdog(60);
  const Mesh mesh = load_mesh(dir / "empty.ply");
  EXPECT_EQ(mesh.triangle_count(), 1u);
  EXPECT_EQ(mesh.positions.size(), 3u);
}

// A binary PLY quad: 4 float vertices, one face of 4 int indices with a uchar length, in the
// given byte order.
std::string binary_ply_quad(bool big_endian) {
  std::string header = std::string("ply\nformat ") +
                       (big_endian ? "binary_big_endian" : "binary_little_endian") +
                       " 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
  auto put = [&](uint32_t bits) {
    for (int k = 0; k < 4; ++k) {
      const int shift = big_endian ? 24 - 8 * k : 8 * k;
      header += static_cast<char>((bits >> shift) & 0xFF);
    }
  };
  for (float f : kQuadPositions) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put(bits);
  }
  header += '\x04';
  for (uint32_t i : {0u, 1u, 2u, 3u})
    put(i);
  return header;
}

TEST(MeshLoading, BinaryPlyQuadLoadsInEitherByteOrder) {
  TempDir dir;
  write_file(dir / "little.ply", binary_ply_quad(false));
  write_file(dir / "big.ply", binary_ply_quad(true));
  expect_unit_quad(load_mesh(dir / "little.ply"));
  expect_unit_quad(load_mesh(dir / "big.ply"));
}

TEST(MeshLoading, BinaryPlyCutShortIsRejected) {
  TempDir dir;
  const std::string whole = binary_ply_quad(false);
  write_file(dir / "cut.ply", whole.substr(0, whole.size() - 3));
  expect_load_error(dir / "cut.ply", ErrorCode::kInvalidInput,
                    {"truncated PLY file", "1 face elements", "ends after 0"});
  write_file(dir / "cut_vertices.ply", whole.substr(0, whole.size() - 20));
  expect_load_error(dir / "cut_vertices.ply", ErrorCode::kInvalidInput,
                    {"truncated PLY file", "4 vertex elements", "ends after 3"});
}

TEST(MeshLoading, BinaryPlyWithTrailingBytesIsRejected) {
  TempDir dir;
  write_file(dir / "long.ply", binary_ply_quad(false) + "xyz");
  expect_load_error(dir / "long.ply", ErrorCode::kInvalidInput, {"3 bytes more"});
}

TEST(MeshLoading, GltfIndexOutOfRangeIsRejectedThoughAssimpOnlyWarns) {
  TempDir dir;
  write_file(dir / "index.gltf", gltf(kQuadPositions, {0, 1, 2, 0, 2, 9}));
  expect_load_error(dir / "index.gltf", ErrorCode::kInvalidInput, {"out-of-range indices"});
}

TEST(MeshLoading, GltfWithEveryIndexOutOfRangeIsRejected) {
  TempDir dir;
  write_file(dir / "all.gltf", gltf(kQuadPositions, {4, 5, 6}));
  expect_load_error(dir / "all.gltf", ErrorCode::kInvalidInput, {"out-of-range indices"});
}

TEST(MeshLoading, GltfNaNPositionIsRejected) {
  TempDir dir;
  std::vector<float> positions = kQuadPositions;
  positions[7] = std::numeric_limits<float>::quiet_NaN();  // vertex 2, y
  write_file(dir / "nan.gltf", gltf(positions, {0, 1, 2, 0, 2, 3}));
  expect_load_error(dir / "nan.gltf", ErrorCode::kInvalidInput, {"vertex 2", "not finite"});
}

TEST(MeshLoading, TruncatedGltfIsRejected) {
  TempDir dir;
  const std::string whole = gltf(kQuadPositions, {0, 1, 2, 0, 2, 3});
  write_file(dir / "cut.gltf", whole.substr(0, whole.size() / 2));
  expect_load_error(dir / "cut.gltf", ErrorCode::kInvalidInput, {});
}

TEST(MeshLoading, GltfWithAMissingBufferFileIsRejectedNamingIt) {
  TempDir dir;
  std::string text = gltf(kQuadPositions, {0, 1, 2, 0, 2, 3});
  const size_t uri = text.find("data:");
  text.replace(uri, text.find('"', uri) - uri, "quad.bin");
  write_file(dir / "nobin.gltf", text);
  expect_load_error(dir / "nobin.gltf", ErrorCode::kInvalidInput, {"quad.bin"});
}

// --- The models that ship with Assimp ------------------------------------------------------

class AssimpModels : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::is_directory(kAssimpModels)) {
      GTEST_SKIP() << kAssimpModels << " is missing (scripts/install-deps.sh installs the "
                   << "assimp-testmodels package)";
    }
  }
};

TEST_F(AssimpModels, WellFormedModelsLoadConsistent) {
  for (const char* name :
       {"OBJ/spider.obj", "OBJ/WusonOBJ.obj", "OBJ/cube_with_vertexcolors.obj", "PLY/Wuson.ply",
        "PLY/cube_binary.ply", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
        "glTF2/BoxTextured-glTF/BoxTextured.gltf",
        "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_06.gltf"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_mesh(kAssimpModels / name);
    EXPECT_GT(mesh.triangle_count(), 0u);
    expect_consistent(mesh);
  }
}

TEST_F(AssimpModels, BoxIsTwelveTriangles) {
  const Mesh mesh = load_mesh(kAssimpModels / "OBJ/box.obj");
  EXPECT_EQ(mesh.triangle_count(), 12u);
  EXPECT_EQ(mesh.positions.size(), 8u);
}

TEST_F(AssimpModels, Utf16BoxIsTheSameMeshAsThePlainBox) {
  const Mesh plain = load_mesh(kAssimpModels / "OBJ/box.obj");
  const Mesh utf16 = load_mesh(kAssimpModels / "OBJ/box_UTF16BE.obj");
  EXPECT_EQ(utf16.positions, plain.positions);
  EXPECT_EQ(utf16.indices, plain.indices);
}

TEST_F(AssimpModels, BrokenModelsAreRejectedWithTheReason) {
  struct Case {
    const char* name;
    const char* reason;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "not finite"},
           {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf", "out-of-range indices"},
           {"glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", "out-of-range indices"},
           {"glTF2/SchemaFailures/sceneWrongType.gltf", "\"scene\" was not of type"},
           {"glTF2/wrongTypes/badArray.gltf", "was not of type \"array\""},
           {"glTF2/wrongTypes/badExtension.gltf", "was not of type \"object\""},
           {"glTF2/wrongTypes/badNumber.gltf", "was not of type \"number\""},
           {"glTF2/wrongTypes/badObject.gltf", "was not of type \"object\""},
           {"glTF2/wrongTypes/badString.gltf", "was not of type \"string\""},
           {"glTF2/wrongTypes/badUint.gltf", "was not of type \"uint\""},
           {"glTF2/MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
           {"OBJ/point_cloud.obj", "no triangles"},
           {"OBJ/testpoints.obj", "no triangles"},
           {"PLY/points.ply", "no triangles"},
           {"PLY/pond.0.ply", "truncated PLY file"},
           {"PLY/issue623.ply", "list length"},
       }) {
    SCOPED_TRACE(c.name);
    expect_load_error(kAssimpModels / c.name, ErrorCode::kInvalidInput, {c.reason});
  }
}

}  // namespace
}  // namespace tessera
