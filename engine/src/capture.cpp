// Reading and writing TRI1 captures (format in tessera/capture.hpp).
#include "tessera/capture.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <new>
#include <string>

#include "tessera/error.hpp"

namespace tessera {

static_assert(std::endian::native == std::endian::little,
              "TRI1 is little-endian; a big-endian host needs byte swapping here");

namespace {

constexpr char kMagic[4] = {'T', 'R', 'I', '1'};
constexpr uint64_t kHeaderBytes = 16;
constexpr uint64_t kVertexBytes = 8 * sizeof(float);
constexpr uint64_t kTriangleBytes = 3 * kVertexBytes;

[[noreturn]] void bad(const std::filesystem::path& path, const std::string& what) {
  throw Error(ErrorCode::kInvalidInput, path.string() + ": " + what);
}

uint32_t read_u32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

bool frame_size_ok(uint32_t width, uint32_t height) {
  return width >= 1 && height >= 1 && width <= kMaxFramebufferSize && height <= kMaxFramebufferSize;
}

std::string frame_size_range(uint32_t width, uint32_t height) {
  return "frame size " + std::to_string(width) + "x" + std::to_string(height) +
         " is out of range (1.." + std::to_string(kMaxFramebufferSize) + ")";
}

// Which of a vertex's 8 floats (x, y, z, w, r, g, b, a) is not finite, or -1.
int first_non_finite(const float* f) {
  for (int k = 0; k < 8; ++k) {
    if (!std::isfinite(f[k])) return k;
  }
  return -1;
}

std::string non_finite_message(size_t vertex, int component) {
  return std::string(component < 4 ? "position" : "colour") + " of vertex " +
         std::to_string(vertex) + " (triangle " + std::to_string(vertex / 3) + ") is not finite";
}

}  // namespace

Capture load_capture(const std::filesystem::path& path) {
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  if (ec) throw Error(ErrorCode::kIo, path.string() + ": cannot read: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::kIo, path.string() + ": cannot open for reading");

  unsigned char header[kHeaderBytes];
  if (file_size < kHeaderBytes || !in.read(reinterpret_cast<char*>(header), kHeaderBytes)) {
    bad(path, "truncated TRI1 header (" + std::to_string(file_size) + " bytes, need 16)");
  }
  if (std::memcmp(header, kMagic, 4) != 0) bad(path, "not a TRI1 capture (wrong magic)");
  Capture c;
  c.width = read_u32(header + 4);
  c.height = read_u32(header + 8);
  const uint32_t count = read_u32(header + 12);
  if (!frame_size_ok(c.width, c.height)) bad(path, frame_size_range(c.width, c.height));
  const uint64_t expected = kHeaderBytes + uint64_t{count} * kTriangleBytes;
  if (file_size != expected) {
    bad(path, "header says " + std::to_string(count) + " triangles (" + std::to_string(expected) +
                  " bytes) but the file has " + std::to_string(file_size) + " bytes");
  }

  // The size matches the header, so the allocation is what the file holds (at most 2^32
  // triangles of 96 bytes); a file too large for memory is an Error, not std::bad_alloc.
  const size_t vertices = size_t{count} * 3;
  std::vector<float> raw;
  try {
    raw.resize(vertices * 8);
    c.positions.resize(vertices);
    c.colors.resize(vertices * 4);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::kOutOfMemory,
                path.string() + ": not enough memory for " + std::to_string(count) + " triangles");
  }
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size() * 4))) {
    throw Error(ErrorCode::kIo, path.string() + ": read failed inside the triangle data");
  }
  for (size_t v = 0; v < vertices; ++v) {
    const float* f = &raw[v * 8];
    const int k = first_non_finite(f);
    if (k >= 0) bad(path, non_finite_message(v, k));
    c.positions[v] = {f[0], f[1], f[2], f[3]};
    std::memcpy(&c.colors[v * 4], f + 4, 4 * sizeof(float));
  }
  return c;
}

void save_capture(const std::filesystem::path& path, const Capture& c) {
  // Everything is checked before the file is opened: a capture that load_capture would reject
  // is not written, and a rejected save leaves an existing file as it was.
  if (c.positions.size() % 3 != 0 || c.colors.size() != c.positions.size() * 4) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() +
                    " needs 3 positions per triangle and 4 colour floats per position");
  }
  if (!frame_size_ok(c.width, c.height)) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() + ": " + frame_size_range(c.width, c.height));
  }
  if (c.positions.size() / 3 > UINT32_MAX) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() + " has more than 2^32 - 1 triangles");
  }
  for (size_t v = 0; v < c.positions.size(); ++v) {
    const Float4& p = c.positions[v];
    const float* rgba = &c.colors[v * 4];
    const float f[8] = {p.x, p.y, p.z, p.w, rgba[0], rgba[1], rgba[2], rgba[3]};
    const int k = first_non_finite(f);
    if (k >= 0) {
      throw Error(ErrorCode::kInvalidInput,
                  "capture for " + path.string() + ": " + non_finite_message(v, k));
    }
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(ErrorCode::kIo, path.string() + ": cannot open for writing");
  const uint32_t header[3] = {c.width, c.height, static_cast<uint32_t>(c.positions.size() / 3)};
  out.write(kMagic, 4);
  out.write(reinterpret_cast<const char*>(header), sizeof(header));
  for (size_t v = 0; v < c.positions.size(); ++v) {
    const float f[8] = {c.positions[v].x,    c.positions[v].y,   c.positions[v].z,
                        c.positions[v].w,    c.colors[v * 4],    c.colors[v * 4 + 1],
                        c.colors[v * 4 + 2], c.colors[v * 4 + 3]};
    out.write(reinterpret_cast<const char*>(f), sizeof(f));
  }
  if (!out.flush()) throw Error(ErrorCode::kIo, path.string() + ": write failed");
}

PipelineState capture_pipeline() {
  PipelineState p;
  p.clip_depth = ClipDepth::kNegativeOneToOne;
  p.depth_test = true;
  p.depth_write = true;
  p.depth_compare = CompareOp::kLess;
  p.cull = CullMode::kNone;
  return p;
}

}  // namespace tessera
