// Reading and writing TRI1 and TRI2 captures (formats in tessera/capture.hpp).
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
              "TRI1 and TRI2 are little-endian; a big-endian host needs byte swapping here");

namespace {

constexpr char kMagic1[4] = {'T', 'R', 'I', '1'};
constexpr char kMagic2[4] = {'T', 'R', 'I', '2'};

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

// Which of a vertex's floats (x, y, z, w, then the varyings) is not finite, or -1.
int first_non_finite(const float* f, uint32_t n) {
  for (uint32_t k = 0; k < n; ++k) {
    if (!std::isfinite(f[k])) return static_cast<int>(k);
  }
  return -1;
}

std::string non_finite_message(size_t vertex, int component, bool tri1) {
  const std::string what = component < 4 ? "position"
                           : tri1        ? "colour"
                                         : "varying " + std::to_string(component - 4);
  return what + " of vertex " + std::to_string(vertex) + " (triangle " +
         std::to_string(vertex / 3) + ") is not finite";
}

}  // namespace

Capture load_capture(const std::filesystem::path& path) {
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  if (ec) throw Error(ErrorCode::kIo, path.string() + ": cannot read: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::kIo, path.string() + ": cannot open for reading");

  // The magic and TRI1's header, then TRI2's varying count.
  unsigned char header[20];
  if (file_size < 16 || !in.read(reinterpret_cast<char*>(header), 16)) {
    bad(path, "truncated capture header (" + std::to_string(file_size) + " bytes, need 16)");
  }
  const bool tri1 = std::memcmp(header, kMagic1, 4) == 0;
  if (!tri1 && std::memcmp(header, kMagic2, 4) != 0) {
    bad(path, "not a TRI1 or TRI2 capture (wrong magic)");
  }
  uint64_t header_bytes = 16;
  Capture c;
  if (!tri1) {
    if (file_size < 20 || !in.read(reinterpret_cast<char*>(header + 16), 4)) {
      bad(path, "truncated TRI2 header (" + std::to_string(file_size) + " bytes, need 20)");
    }
    header_bytes = 20;
    c.varying_count = read_u32(header + 16);
    if (c.varying_count > kMaxVaryings) {
      bad(path, "varying count " + std::to_string(c.varying_count) + " is more than " +
                    std::to_string(kMaxVaryings));
    }
  }
  c.width = read_u32(header + 4);
  c.height = read_u32(header + 8);
  const uint32_t count = read_u32(header + 12);
  if (!frame_size_ok(c.width, c.height)) bad(path, frame_size_range(c.width, c.height));
  const uint32_t floats = 4 + c.varying_count;  // per vertex
  const uint64_t expected = header_bytes + uint64_t{count} * 3 * floats * sizeof(float);
  if (file_size != expected) {
    bad(path, "header says " + std::to_string(count) + " triangles (" + std::to_string(expected) +
                  " bytes) but the file has " + std::to_string(file_size) + " bytes");
  }

  // The size matches the header, so the allocation is what the file holds (at most 2^32
  // triangles of 3 * 36 floats); a file too large for memory is an Error, not std::bad_alloc.
  const size_t vertices = size_t{count} * 3;
  std::vector<float> raw;
  try {
    raw.resize(vertices * floats);
    c.positions.resize(vertices);
    c.varyings.resize(vertices * c.varying_count);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::kOutOfMemory,
                path.string() + ": not enough memory for " + std::to_string(count) + " triangles");
  }
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size() * 4))) {
    throw Error(ErrorCode::kIo, path.string() + ": read failed inside the triangle data");
  }
  for (size_t v = 0; v < vertices; ++v) {
    const float* f = &raw[v * floats];
    const int k = first_non_finite(f, floats);
    if (k >= 0) bad(path, non_finite_message(v, k, tri1));
    c.positions[v] = {f[0], f[1], f[2], f[3]};
    if (c.varying_count > 0) {
      std::memcpy(&c.varyings[v * c.varying_count], f + 4, c.varying_count * sizeof(float));
    }
  }
  return c;
}

void save_capture(const std::filesystem::path& path, const Capture& c) {
  // Everything is checked before the file is opened: a capture that load_capture would reject
  // is not written, and a rejected save leaves an existing file as it was.
  if (c.varying_count > kMaxVaryings) {
    throw Error(ErrorCode::kInvalidArgument, "capture for " + path.string() + ": varying count " +
                                                 std::to_string(c.varying_count) +
                                                 " is more than " + std::to_string(kMaxVaryings));
  }
  if (c.positions.size() % 3 != 0 || c.varyings.size() != c.positions.size() * c.varying_count) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() + " needs 3 positions per triangle and " +
                    std::to_string(c.varying_count) + " varying floats per position");
  }
  if (!frame_size_ok(c.width, c.height)) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() + ": " + frame_size_range(c.width, c.height));
  }
  if (c.positions.size() / 3 > UINT32_MAX) {
    throw Error(ErrorCode::kInvalidArgument,
                "capture for " + path.string() + " has more than 2^32 - 1 triangles");
  }
  const bool tri1 = c.varying_count == 4;
  const uint32_t floats = 4 + c.varying_count;
  std::vector<float> vertex(floats);
  const auto fill = [&](size_t v) {
    const Float4& p = c.positions[v];
    vertex[0] = p.x, vertex[1] = p.y, vertex[2] = p.z, vertex[3] = p.w;
    for (uint32_t k = 0; k < c.varying_count; ++k)
      vertex[4 + k] = c.varyings[v * c.varying_count + k];
  };
  for (size_t v = 0; v < c.positions.size(); ++v) {
    fill(v);
    const int k = first_non_finite(vertex.data(), floats);
    if (k >= 0) {
      throw Error(ErrorCode::kInvalidInput,
                  "capture for " + path.string() + ": " + non_finite_message(v, k, tri1));
    }
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(ErrorCode::kIo, path.string() + ": cannot open for writing");
  const uint32_t header[4] = {c.width, c.height, static_cast<uint32_t>(c.positions.size() / 3),
                              c.varying_count};
  out.write(tri1 ? kMagic1 : kMagic2, 4);
  out.write(reinterpret_cast<const char*>(header), tri1 ? 12 : 16);
  for (size_t v = 0; v < c.positions.size(); ++v) {
    fill(v);
    out.write(reinterpret_cast<const char*>(vertex.data()),
              static_cast<std::streamsize>(floats * sizeof(float)));
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
