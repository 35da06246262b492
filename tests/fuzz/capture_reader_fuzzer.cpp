// Fuzzes load_capture and save_capture: exactly the well-formed TRI1 and TRI2 files load, bit for
// bit, and save back as the same bytes (a TRI2 file of four varyings as the TRI1 file of the same
// data); the rest is a one-line Error naming the file, and nothing is lost.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tessera/capture.hpp"
#include "tessera/error.hpp"

namespace {

// A broken rule: the message and an abort, which libFuzzer reports with the input.
[[noreturn]] void broken(const char* rule) {
  std::fprintf(stderr, "capture_reader_fuzzer: %s\n", rule);
  std::abort();
}

const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("tessera-capture-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

void write_bytes(const std::filesystem::path& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) broken("cannot write the fuzz input to a file");
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

uint32_t u32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

float f32(const uint8_t* p) {
  float v;
  std::memcpy(&v, p, 4);
  return v;
}

// A file's layout as capture.hpp specifies it: the header's size and the floats per vertex.
struct Layout {
  size_t header = 16;
  uint32_t varyings = 4;
};

bool is_tri2(const uint8_t* data, size_t size) {
  return size >= 4 && std::memcmp(data, "TRI2", 4) == 0;
}

Layout layout_of(const uint8_t* data, size_t size) {
  Layout l;
  if (is_tri2(data, size) && size >= 20) {
    l.header = 20;
    l.varyings = u32(data + 16);
  }
  return l;
}

// What capture.hpp specifies, parsed here independently of capture.cpp.
bool well_formed(const uint8_t* data, size_t size) {
  const bool tri1 = size >= 16 && std::memcmp(data, "TRI1", 4) == 0;
  if (!tri1 && !(is_tri2(data, size) && size >= 20)) return false;
  const Layout l = layout_of(data, size);
  if (l.varyings > tessera::kMaxVaryings) return false;
  const uint32_t width = u32(data + 4), height = u32(data + 8), count = u32(data + 12);
  if (width < 1 || height < 1 || width > tessera::kMaxFramebufferSize ||
      height > tessera::kMaxFramebufferSize) {
    return false;
  }
  if (size != l.header + uint64_t{count} * 3 * (4 + l.varyings) * 4) return false;
  for (size_t i = l.header; i < size; i += 4) {
    if (!std::isfinite(f32(data + i))) return false;
  }
  return true;
}

// The error rule of error.hpp for a file: one line that names the file.
void check_error(const tessera::Error& e, const std::filesystem::path& path) {
  const std::string message = e.what();
  if (message.find('\n') != std::string::npos) broken("error message spans lines");
  if (message.find(path.string()) == std::string::npos) broken("error message misses the file");
}

// Whether two arrays hold the same bits (memcmp of an empty vector's null data is undefined).
template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_bits(const tessera::Capture& a, const tessera::Capture& b) {
  return a.width == b.width && a.height == b.height && a.varying_count == b.varying_count &&
         same_bytes(a.positions, b.positions) && same_bytes(a.varyings, b.varyings);
}

// The capture the bytes hold, read as capture.hpp says (only for well-formed bytes).
tessera::Capture expected_capture(const uint8_t* data, size_t size) {
  const Layout l = layout_of(data, size);
  const size_t vertex = (4 + size_t{l.varyings}) * 4;
  tessera::Capture c;
  c.width = u32(data + 4);
  c.height = u32(data + 8);
  c.varying_count = l.varyings;
  for (size_t v = l.header; v + vertex <= size; v += vertex) {
    c.positions.push_back(
        {f32(data + v), f32(data + v + 4), f32(data + v + 8), f32(data + v + 12)});
    for (size_t k = 0; k < l.varyings; ++k)
      c.varyings.push_back(f32(data + v + 16 + 4 * k));
  }
  return c;
}

// A capture with any sizes and values, decoded from the bytes, for save_capture: a frame size,
// a position count and a colour count, then floats.
tessera::Capture arbitrary_capture(const uint8_t* data, size_t size) {
  tessera::Capture c;
  if (size < 12) return c;
  c.width = u32(data) % (tessera::kMaxFramebufferSize + 2);
  c.height = u32(data + 4) % (tessera::kMaxFramebufferSize + 2);
  const size_t positions = data[8] % 16, colors = data[9] % 64;
  size_t at = 12;
  auto next = [&] {
    if (at + 4 > size) return 0.5f;
    const float f = f32(data + at);
    at += 4;
    return f;
  };
  for (size_t i = 0; i < positions; ++i)
    c.positions.push_back({next(), next(), next(), next()});
  for (size_t i = 0; i < colors; ++i)
    c.varyings.push_back(next());
  return c;
}

bool saveable(const tessera::Capture& c) {
  if (c.positions.size() % 3 != 0 || c.varyings.size() != c.positions.size() * 4) return false;
  if (c.width < 1 || c.height < 1 || c.width > tessera::kMaxFramebufferSize ||
      c.height > tessera::kMaxFramebufferSize) {
    return false;
  }
  for (const tessera::Float4& p : c.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w))
      return false;
  }
  for (float f : c.varyings) {
    if (!std::isfinite(f)) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = work_dir() / "input.tri";
  const std::filesystem::path copy = work_dir() / "copy.tri";
  write_bytes(file, data, size);

  const bool valid = well_formed(data, size);
  tessera::Capture c;
  try {
    c = tessera::load_capture(file);
  } catch (const tessera::Error& e) {
    if (valid) broken("a well-formed capture was rejected");
    if (e.code() != tessera::ErrorCode::kInvalidInput) broken("rejection is not kInvalidInput");
    check_error(e, file);

    // The same bytes as a capture of any shape for save_capture: it writes exactly what
    // load_capture accepts, and a rejected save leaves the file that was there.
    const tessera::Capture any = arbitrary_capture(data, size);
    const std::string before = "previous contents";
    write_bytes(copy, reinterpret_cast<const uint8_t*>(before.data()), before.size());
    try {
      tessera::save_capture(copy, any);
    } catch (const tessera::Error& save_error) {
      if (saveable(any)) broken("save_capture rejected a valid capture");
      if (read_bytes(copy) != before) broken("a rejected save changed the file");
      if (std::string(save_error.what()).find('\n') != std::string::npos)
        broken("save error message spans lines");
      return 0;
    }
    if (!saveable(any)) broken("save_capture wrote a capture that load_capture rejects");
    if (!same_bits(tessera::load_capture(copy), any)) broken("saved capture reads back changed");
    return 0;
  }
  if (!valid) broken("a malformed capture was accepted");
  if (!same_bits(c, expected_capture(data, size))) broken("loaded values differ from the file");

  // Round trip: what was read is written as the same bytes (a TRI2 file of four varyings as
  // TRI1: the magic and the header's varying count go), and reads back the same.
  tessera::save_capture(copy, c);
  const std::string written = read_bytes(copy);
  std::string original(reinterpret_cast<const char*>(data), size);
  if (is_tri2(data, size) && c.varying_count == 4)
    original = "TRI1" + original.substr(4, 12) + original.substr(20);
  if (written != original) broken("save_capture of a loaded capture wrote different bytes");
  if (!same_bits(tessera::load_capture(copy), c)) broken("round trip changed the capture");
  return 0;
}
