// Mesh loading through Assimp (OBJ, glTF 2.0, PLY and the other formats it reads), flattened
// into one triangle mesh. Part of the tessera_io library (Tessera::io); the mesh utilities it
// uses are the core library's (mesh.cpp).
//
// Assimp 5.2 is lenient in ways a renderer cannot be: its glTF 2 importer drops faces with
// out-of-range indices and only logs a warning; its PLY importer turns faces that reference
// missing vertices into faces without indices, on which its Triangulate step asserts (an abort
// in Debian's build); its OBJ reader finds nothing in UTF-16 text. So the raw import is checked
// here before any post-processing step runs, Assimp's warnings are listened to while a file is
// imported, and text files with a byte-order mark are handed to Assimp as plain UTF-8.
// What is rejected follows the glTF Validator's line: an error there (an index out of range) is
// an error here; a warning there (a trailing incomplete triangle) is dropped, as OpenGL drops
// incomplete primitives.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <span>
#include <sstream>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <glm/geometric.hpp>

#include "engine/src/image_decode.hpp"
#include "tessera/error.hpp"
#include "tessera/image_io.hpp"
#include "tessera/mesh_io.hpp"

namespace tessera {

namespace {

constexpr glm::vec4 kDefaultColor{0.72f, 0.74f, 0.78f, 1.0f};

[[noreturn]] void bad(const std::filesystem::path& path, const std::string& what) {
  throw Error(ErrorCode::kInvalidInput, path.string() + ": " + what);
}

// Assimp's messages may end in a newline or span lines; ours are one line.
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  while (!s.empty() && s.back() == ' ')
    s.pop_back();
  return s;
}

bool mentions_out_of_range(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s.find("out-of-range") != std::string::npos || s.find("out of range") != std::string::npos;
}

// Collects the warnings Assimp logs while one file is imported. Assimp's logger is one
// process-wide object, so the guard holds a mutex for its whole life: imports through
// load_mesh run one at a time. An application's own DefaultLogger is kept and only lent a
// stream; otherwise a silent logger (no file, no console) exists for the import's duration.
class AssimpWarnings {
 public:
  AssimpWarnings() : lock_(mutex()) {
    created_ = Assimp::DefaultLogger::isNullLogger();
    if (created_) Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    attached_ = Assimp::DefaultLogger::get()->attachStream(&stream_, Assimp::Logger::Warn);
  }
  ~AssimpWarnings() {
    // Detached before the logger is killed: the logger deletes the streams it still holds.
    if (attached_) Assimp::DefaultLogger::get()->detachStream(&stream_, Assimp::Logger::Warn);
    if (created_) Assimp::DefaultLogger::kill();
  }
  AssimpWarnings(const AssimpWarnings&) = delete;
  AssimpWarnings& operator=(const AssimpWarnings&) = delete;

  // The first warning that says some of the file's data was out of range, or "".
  std::string out_of_range() const {
    for (const std::string& w : stream_.messages) {
      if (mentions_out_of_range(w)) return w;
    }
    return {};
  }

 private:
  struct Stream : Assimp::LogStream {
    void write(const char* message) override {
      // "Warn,  T0: text\n" -> "text"
      std::string m = message;
      const size_t colon = m.find(": ");
      if (colon != std::string::npos) m.erase(0, colon + 2);
      messages.push_back(one_line(m));
    }
    std::vector<std::string> messages;
  };
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }

  std::lock_guard<std::mutex> lock_;
  Stream stream_;
  bool created_ = false;
  bool attached_ = false;
};

void append_utf8(std::string& out, uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// UTF-16 (after its byte-order mark) to UTF-8; an unpaired surrogate becomes U+FFFD.
std::string utf16_to_utf8(const std::filesystem::path& path, const std::string& bytes,
                          bool big_endian) {
  if (bytes.size() % 2 != 0) bad(path, "UTF-16 text with an odd number of bytes");
  auto unit = [&](size_t i) {
    const auto hi = static_cast<unsigned char>(bytes[big_endian ? i : i + 1]);
    const auto lo = static_cast<unsigned char>(bytes[big_endian ? i + 1 : i]);
    return static_cast<uint32_t>(hi << 8 | lo);
  };
  std::string out;
  out.reserve(bytes.size() / 2);
  for (size_t i = 2; i < bytes.size(); i += 2) {
    uint32_t cp = unit(i);
    if (cp >= 0xD800 && cp < 0xDC00 && i + 3 < bytes.size() && unit(i + 2) >= 0xDC00 &&
        unit(i + 2) < 0xE000) {
      cp = 0x10000 + ((cp - 0xD800) << 10) + (unit(i + 2) - 0xDC00);
      i += 2;
    } else if (cp >= 0xD800 && cp < 0xE000) {
      cp = 0xFFFD;
    }
    append_utf8(out, cp);
  }
  return out;
}

// The file's text as plain UTF-8 when it starts with a byte-order mark, else "" (Assimp reads
// the file itself). Only for the text formats of mesh.hpp: a binary file may begin with any
// bytes.
std::string without_byte_order_mark(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".ply" && ext != ".gltf") return {};
  std::ifstream in(path, std::ios::binary);
  char head[3] = {};
  in.read(head, 3);
  const auto b = [&](int i) { return static_cast<unsigned char>(head[i]); };
  const std::streamsize n = in.gcount();
  const bool utf8 = n == 3 && b(0) == 0xEF && b(1) == 0xBB && b(2) == 0xBF;
  const bool utf16be = n >= 2 && b(0) == 0xFE && b(1) == 0xFF;
  const bool utf16le = n >= 2 && b(0) == 0xFF && b(1) == 0xFE;
  if (!utf8 && !utf16be && !utf16le) return {};
  std::error_code ec;
  std::string bytes(std::filesystem::file_size(path, ec), '\0');
  in.seekg(0);
  if (ec || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    throw Error(ErrorCode::kIo, path.string() + ": read failed");
  }
  if (utf8) return bytes.substr(3);
  return utf16_to_utf8(path, bytes, utf16be);
}

// Serves one file from memory (its UTF-8 text) and every other file (materials, buffers) from
// disk as usual.
class Utf8TextIOSystem : public Assimp::DefaultIOSystem {
 public:
  Utf8TextIOSystem(std::string file, std::string text)
      : file_(std::move(file)), text_(std::move(text)) {}
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (file_ == file && std::strchr(mode, 'w') == nullptr) {
      return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(text_.data()),
                                        text_.size(), /*own=*/false);
    }
    return Assimp::DefaultIOSystem::Open(file, mode);
  }

 private:
  std::string file_;
  std::string text_;
};

// --- PLY element counts ------------------------------------------------------------------
// A PLY header declares how many of each element follow. Assimp's reader does not check that
// the body holds them: a file cut short loads with its last face repeated or with vertices
// read from past the end. So the body is walked here (numbers are not converted, only list
// lengths read) and must hold exactly what the header declares; whitespace may follow in ASCII.
// Anything this walk does not understand (a bad magic, an unknown type) is left to Assimp, but
// only a header that ends: Assimp 5.2's reader never returns from a header without end_header.

struct PlyProperty {
  int size = 0;  // bytes of a scalar, or of one list item
  bool list = false;
  int count_size = 0;  // bytes of a list's length
  bool count_signed = false;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// Size and signedness of a PLY scalar type, or size 0 for an unknown one.
std::pair<int, bool> ply_type(const std::string& t) {
  if (t == "char" || t == "int8") return {1, true};
  if (t == "uchar" || t == "uint8") return {1, false};
  if (t == "short" || t == "int16") return {2, true};
  if (t == "ushort" || t == "uint16") return {2, false};
  if (t == "int" || t == "int32") return {4, true};
  if (t == "uint" || t == "uint32") return {4, false};
  if (t == "float" || t == "float32") return {4, true};
  if (t == "double" || t == "float64") return {8, true};
  return {0, false};
}

void check_ply_counts(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  auto next_line = [&] {
    if (!std::getline(in, line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  // Assimp takes any file whose first line starts with "ply", in any case, for PLY.
  if (!next_line() || line.size() < 3 ||
      !std::equal(line.begin(), line.begin() + 3, "ply", [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == b;
      })) {
    return;
  }
  enum class Format { kUnknown, kAscii, kLittle, kBig } format = Format::kUnknown;
  std::vector<PlyElement> elements;
  bool understood = line == "ply";  // every header line so far is one this walk can follow
  for (;;) {
    if (!next_line()) bad(path, "PLY header without end_header");
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") break;
    if (!understood) continue;
    if (word == "format") {
      words >> word;
      format = word == "ascii"                  ? Format::kAscii
               : word == "binary_little_endian" ? Format::kLittle
               : word == "binary_big_endian"    ? Format::kBig
                                                : Format::kUnknown;
    } else if (word == "element") {
      PlyElement e;
      words >> e.name >> e.count;
      understood = static_cast<bool>(words);
      if (understood) elements.push_back(e);
    } else if (word == "property") {
      PlyProperty p;
      words >> word;
      if (word == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        std::tie(p.count_size, p.count_signed) = ply_type(count_type);
        p.size = ply_type(item_type).first;
        p.list = true;
      } else {
        p.size = ply_type(word).first;
      }
      understood =
          !elements.empty() && p.size != 0 && (!p.list || (p.count_size != 0 && p.count_size != 8));
      if (understood) elements.back().properties.push_back(p);
    }
  }
  if (!understood || format == Format::kUnknown) return;

  std::streambuf& body = *in.rdbuf();
  const auto truncated = [&](const PlyElement& e, uint64_t complete) {
    bad(path, "truncated PLY file: the header declares " + std::to_string(e.count) + " " + e.name +
                  " elements, the data ends after " + std::to_string(complete));
  };
  if (format == Format::kAscii) {
    // Skips whitespace, then reads one token (or returns false at the end of the file).
    std::string token;
    auto next_token = [&] {
      token.clear();
      int c = body.sgetc();
      while (c != EOF && std::isspace(c))
        c = body.snextc();
      while (c != EOF && !std::isspace(c)) {
        token += static_cast<char>(c);
        c = body.snextc();
      }
      return !token.empty();
    };
    for (const PlyElement& e : elements) {
      if (e.properties.empty()) continue;  // no tokens, whatever its count
      for (uint64_t i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.properties) {
          if (!next_token()) truncated(e, i);
          if (!p.list) continue;
          char* end = nullptr;
          const long long n = std::strtoll(token.c_str(), &end, 10);
          if (*end != '\0' || n < 0) {
            bad(path,
                "PLY " + e.name + " " + std::to_string(i) + " has the list length '" + token + "'");
          }
          for (long long k = 0; k < n; ++k) {
            if (!next_token()) truncated(e, i);
          }
        }
      }
    }
    if (next_token()) {
      bad(path, "PLY file holds more data than its header declares (from '" + token + "' on)");
    }
    return;
  }

  // Binary: the position is tracked against the file size, since seeking past the end is not
  // an error for a stream.
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return;
  uint64_t pos = static_cast<uint64_t>(body.pubseekoff(0, std::ios::cur, std::ios::in));
  for (const PlyElement& e : elements) {
    bool fixed = true;
    uint64_t bytes = 0;
    for (const PlyProperty& p : e.properties) {
      fixed = fixed && !p.list;
      bytes += static_cast<uint64_t>(p.size);
    }
    if (fixed) {
      // count * bytes <= size - pos after this check, so the product cannot overflow.
      if (bytes > 0 && e.count > (size - pos) / bytes) truncated(e, (size - pos) / bytes);
      pos += e.count * bytes;
      continue;
    }
    body.pubseekpos(static_cast<std::streamoff>(pos), std::ios::in);
    for (uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (!p.list) {
          if (size - pos < static_cast<uint64_t>(p.size)) truncated(e, i);
          pos += static_cast<uint64_t>(p.size);
          body.pubseekoff(p.size, std::ios::cur, std::ios::in);
          continue;
        }
        unsigned char b[4] = {};
        if (size - pos < static_cast<uint64_t>(p.count_size) ||
            body.sgetn(reinterpret_cast<char*>(b), p.count_size) != p.count_size) {
          truncated(e, i);
        }
        pos += static_cast<uint64_t>(p.count_size);
        uint64_t n = 0;
        for (int k = 0; k < p.count_size; ++k) {
          const int byte = format == Format::kLittle ? p.count_size - 1 - k : k;
          n = n << 8 | b[byte];
        }
        const uint64_t sign_bit = uint64_t{1} << (8 * p.count_size - 1);
        if (p.count_signed && (n & sign_bit) != 0) {
          bad(path, "PLY " + e.name + " " + std::to_string(i) + " has a negative list length");
        }
        if (n > (size - pos) / static_cast<uint64_t>(p.size)) truncated(e, i);
        pos += n * static_cast<uint64_t>(p.size);
        body.pubseekoff(static_cast<std::streamoff>(n) * p.size, std::ios::cur, std::ios::in);
      }
    }
  }
  if (pos != size) {
    bad(path,
        "PLY file holds " + std::to_string(size - pos) + " bytes more than its header declares");
  }
}

std::string describe(const aiVector3D& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string mesh_name(const aiMesh& mesh, unsigned index) {
  std::string s = "mesh " + std::to_string(index);
  if (mesh.mName.length > 0) s += " (\"" + one_line(mesh.mName.C_Str()) + "\")";
  return s;
}

// Checks the importer's output before any post-processing step reads it: every array that a
// count promises is there, every face has indices and each index names a vertex, every
// position is finite, and at least one face is a triangle or polygon.
void check_raw_scene(const std::filesystem::path& path, const aiScene& scene, bool need_polygons) {
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr)
    bad(path, "the scene's mesh list is missing");
  bool has_polygons = false;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    if (scene.mMeshes[m] == nullptr) bad(path, "mesh " + std::to_string(m) + " is missing");
    const aiMesh& mesh = *scene.mMeshes[m];
    if (mesh.mNumVertices > 0 && mesh.mVertices == nullptr) {
      bad(path, mesh_name(mesh, m) + " has no vertex positions");
    }
    if (mesh.mNumFaces > 0 && mesh.mFaces == nullptr)
      bad(path, mesh_name(mesh, m) + " has no faces");
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr) {
        bad(path, "face " + std::to_string(f) + " of " + mesh_name(mesh, m) +
                      " has no vertex indices (the file's face is malformed or names vertices "
                      "that do not exist)");
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          bad(path, "face " + std::to_string(f) + " of " + mesh_name(mesh, m) + " has index " +
                        std::to_string(face.mIndices[k]) + ", out of range (" +
                        std::to_string(mesh.mNumVertices) + " vertices)");
        }
      }
      if (face.mNumIndices >= 3) has_polygons = true;
    }
  }
  if (need_polygons && !has_polygons) {
    bad(path, "no triangles to draw (the file holds only points, lines or nothing)");
  }
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      if (!finite(mesh.mVertices[v])) {
        bad(path, "vertex " + std::to_string(v) + " of " + mesh_name(mesh, m) +
                      " has a position that is not finite: " + describe(mesh.mVertices[v]));
      }
    }
  }
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

}  // namespace

namespace {

// The base colour texture of material `index` (glTF's baseColorTexture, OBJ's map_Kd), from
// its file beside the model or embedded in it, and its sampler (wrap modes; glTF's
// magnification filter); null when the material has none.
std::shared_ptr<const Texture> material_texture(const std::filesystem::path& path,
                                                const aiScene& scene, unsigned index,
                                                Sampler& sampler) {
  if (index >= scene.mNumMaterials) return nullptr;
  const aiMaterial& m = *scene.mMaterials[index];
  aiTextureType type = aiTextureType_BASE_COLOR;
  if (m.GetTextureCount(type) == 0) type = aiTextureType_DIFFUSE;
  aiString name;
  if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &name) != aiReturn_SUCCESS) {
    return nullptr;
  }
  const auto wrap_of = [&](const char* key, unsigned semantic) {
    int mode = aiTextureMapMode_Wrap;
    m.Get(key, type, semantic, mode);
    return mode == aiTextureMapMode_Clamp    ? Wrap::kClampToEdge
           : mode == aiTextureMapMode_Mirror ? Wrap::kMirroredRepeat
           : mode == aiTextureMapMode_Decal  ? Wrap::kClampToBorder
                                             : Wrap::kRepeat;
  };
  sampler.wrap_u = wrap_of(_AI_MATKEY_MAPPINGMODE_U_BASE, 0);
  sampler.wrap_v = wrap_of(_AI_MATKEY_MAPPINGMODE_V_BASE, 0);
  const std::string file = name.C_Str();
  // Colour textures are sRGB-encoded (glTF 2.0 section 3.9.2; the de facto rule for OBJ).
  if (const aiTexture* embedded = scene.GetEmbeddedTexture(name.C_Str())) {
    if (embedded->mHeight == 0) {  // a compressed file (PNG, JPEG, ...) in memory
      const std::string hint = embedded->achFormatHint;
      return std::make_shared<Texture>(decode_texture(
          path.string() + " (embedded texture " + file + ")", "texture." + hint,
          std::span<const std::byte>(reinterpret_cast<const std::byte*>(embedded->pcData),
                                     embedded->mWidth),
          true, true));
    }
    std::vector<uint8_t> texels;
    texels.reserve(size_t{embedded->mWidth} * embedded->mHeight * 4);
    for (size_t i = 0; i < size_t{embedded->mWidth} * embedded->mHeight; ++i) {
      const aiTexel& t = embedded->pcData[i];
      texels.insert(texels.end(), {t.r, t.g, t.b, t.a});
    }
    return std::make_shared<Texture>(
        TextureDesc{embedded->mWidth, embedded->mHeight, TextureFormat::kRGBA8Srgb},
        std::as_bytes(std::span<const uint8_t>(texels)), true);
  }
  std::string relative = file;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  return std::make_shared<Texture>(load_texture(path.parent_path() / relative, true, true));
}

Mesh load(const std::filesystem::path& path, bool point_cloud,
          std::vector<SceneObject>* objects = nullptr) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw Error(ErrorCode::kIo, path.string() + ": no such file");
  if (!std::filesystem::is_regular_file(status)) {
    throw Error(ErrorCode::kIo, path.string() + ": not a regular file");
  }
  if (!std::ifstream(path, std::ios::binary)) {
    throw Error(ErrorCode::kIo, path.string() + ": cannot open for reading");
  }

  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".ply") check_ply_counts(path);

  AssimpWarnings warnings;
  Assimp::Importer importer;
  std::string text = without_byte_order_mark(path);
  if (!text.empty()) {
    // The importer takes ownership of its IO system.
    importer.SetIOHandler(new Utf8TextIOSystem(path.string(), std::move(text)));
  }
  // The import alone first, checked by check_raw_scene; only then the post-processing steps,
  // which trust their input.
  // Fails on an Assimp error or on a warning that some of the file's data was out of range
  // (Assimp then dropped it and carried on).
  auto check = [&](const aiScene* result) {
    const std::string out_of_range = warnings.out_of_range();
    const std::string reason = one_line(importer.GetErrorString());
    if (!out_of_range.empty()) {
      bad(path, "data out of range (Assimp: " + out_of_range +
                    (result == nullptr && !reason.empty() ? "; " + reason : std::string()) + ")");
    }
    if (result == nullptr) {
      bad(path, "cannot load mesh: " + (reason.empty() ? std::string("unknown error") : reason));
    }
    return result;
  };
  const aiScene* scene = check(importer.ReadFile(path.string(), 0));
  check_raw_scene(path, *scene, !point_cloud);
  if (point_cloud) {
    // No post-processing: Assimp's validation and its node-transform step reject meshes
    // without faces, which a point cloud is (check_raw_scene has checked what is read here).
    // Each mesh is taken with the transforms of the nodes that reference it, or untransformed
    // when no node does (a PLY file's single mesh).
    Mesh cloud;
    std::vector<bool> placed(scene->mNumMeshes, false);
    auto add_mesh = [&](unsigned m, const aiMatrix4x4& transform) {
      const aiMesh& am = *scene->mMeshes[m];
      const glm::vec4 color = material_color(*scene, am.mMaterialIndex);
      for (unsigned v = 0; v < am.mNumVertices; ++v) {
        const aiVector3D p = transform * am.mVertices[v];
        if (!finite(p)) {
          bad(path, "vertex " + std::to_string(v) + " of " + mesh_name(am, m) +
                        " is not finite after its node transforms: " + describe(p));
        }
        cloud.positions.emplace_back(p.x, p.y, p.z);
        glm::vec4 vc = color;
        if (am.HasVertexColors(0)) {
          const aiColor4D& c = am.mColors[0][v];
          if (std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) &&
              std::isfinite(c.a)) {
            vc = glm::clamp(glm::vec4{c.r, c.g, c.b, c.a}, 0.0f, 1.0f);
          }
        }
        cloud.colors.push_back(vc);
        cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
      }
    };
    auto walk = [&](auto&& self, const aiNode* node, const aiMatrix4x4& parent, int depth) -> void {
      if (node == nullptr || depth > 1000) return;
      const aiMatrix4x4 transform = parent * node->mTransformation;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        if (node->mMeshes[k] >= scene->mNumMeshes) bad(path, "a node names a missing mesh");
        placed[node->mMeshes[k]] = true;
        add_mesh(node->mMeshes[k], transform);
      }
      for (unsigned k = 0; k < node->mNumChildren; ++k)
        self(self, node->mChildren[k], transform, depth + 1);
    };
    walk(walk, scene->mRootNode, aiMatrix4x4(), 0);
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
      if (!placed[m]) add_mesh(m, aiMatrix4x4());
    }
    if (cloud.positions.empty()) bad(path, "no vertices to draw");
    return cloud;
  }

  // Assimp's own structural validation, then: polygons triangulated, points and lines sorted
  // out, node transforms applied, shared vertices merged.
  check(importer.ApplyPostProcessing(aiProcess_ValidateDataStructure));
  // Texture coordinates flipped to Tessera's convention: v down from the image's top row.
  scene = check(importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType |
                                             aiProcess_PreTransformVertices |
                                             aiProcess_JoinIdenticalVertices | aiProcess_FlipUVs));
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    bad(path, "incomplete scene (Assimp could not read all of it)");
  }

  // One mesh, or with `objects` one per material.
  std::vector<Mesh> meshes(objects != nullptr ? std::max(1u, scene->mNumMaterials) : 1);
  std::vector<bool> all_have_normals(meshes.size(), true), any_texcoords(meshes.size(), false);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& am = *scene->mMeshes[m];
    if ((am.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const size_t which =
        objects != nullptr ? std::min<size_t>(am.mMaterialIndex, meshes.size() - 1) : 0;
    Mesh& mesh = meshes[which];
    if (mesh.positions.size() + am.mNumVertices > UINT32_MAX) {
      bad(path, "more than 2^32 vertices in all meshes together");
    }
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    const glm::vec4 color = material_color(*scene, am.mMaterialIndex);
    for (unsigned v = 0; v < am.mNumVertices; ++v) {
      const aiVector3D& p = am.mVertices[v];
      if (!finite(p)) {
        bad(path, "vertex " + std::to_string(v) + " of " + mesh_name(am, m) +
                      " is not finite after its node transforms: " + describe(p));
      }
      mesh.positions.emplace_back(p.x, p.y, p.z);
      if (am.HasVertexColors(0)) {
        const aiColor4D& c = am.mColors[0][v];
        const glm::vec4 vc{c.r, c.g, c.b, c.a};
        const bool ok =
            std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && std::isfinite(c.a);
        mesh.colors.push_back(ok ? glm::clamp(vc, 0.0f, 1.0f) : color);
      } else {
        mesh.colors.push_back(color);
      }
      if (am.HasNormals() && finite(am.mNormals[v])) {
        mesh.normals.emplace_back(am.mNormals[v].x, am.mNormals[v].y, am.mNormals[v].z);
      } else {
        mesh.normals.emplace_back(0.0f);
        all_have_normals[which] = false;
      }
      glm::vec2 uv(0.0f);
      if (am.HasTextureCoords(0) && finite(am.mTextureCoords[0][v])) {
        uv = {am.mTextureCoords[0][v].x, am.mTextureCoords[0][v].y};
        any_texcoords[which] = true;
      }
      mesh.texcoords.push_back(uv);
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= am.mNumVertices) {
          bad(path, "face " + std::to_string(f) + " of " + mesh_name(am, m) + " has index " +
                        std::to_string(face.mIndices[k]) + ", out of range (" +
                        std::to_string(am.mNumVertices) + " vertices)");
        }
        mesh.indices.push_back(base + face.mIndices[k]);
      }
    }
  }
  size_t triangles = 0;
  for (size_t k = 0; k < meshes.size(); ++k) {
    triangles += meshes[k].indices.size();
    if (!any_texcoords[k]) meshes[k].texcoords.clear();
    if (!all_have_normals[k]) compute_normals(meshes[k]);
  }
  if (triangles == 0) {
    bad(path, "no triangles to draw (the file holds only points, lines or nothing)");
  }
  if (objects != nullptr) {
    for (size_t k = 0; k < meshes.size(); ++k) {
      if (meshes[k].indices.empty()) continue;
      SceneObject o;
      o.mesh = std::move(meshes[k]);
      if (!o.mesh.texcoords.empty()) {
        o.texture = material_texture(path, *scene, static_cast<unsigned>(k), o.sampler);
      }
      objects->push_back(std::move(o));
    }
    return {};
  }
  return std::move(meshes[0]);
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  return load(path, false);
}

Mesh load_point_cloud(const std::filesystem::path& path) {
  return load(path, true);
}

std::vector<SceneObject> load_scene_objects(const std::filesystem::path& path) {
  std::vector<SceneObject> objects;
  load(path, false, &objects);
  return objects;
}

}  // namespace tessera
