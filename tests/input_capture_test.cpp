// TRI1 captures (capture.hpp): what save_capture writes load_capture reads back exactly; a bad
// file is an Error whose one-line message names the file and says what is wrong; a capture
// replays with the OpenGL depth convention.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/file_error.hpp"
#include "tests/temp_dir.hpp"

namespace tessera {
namespace {

using test::read_file;
using test::TempDir;
using test::write_file;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A TRI1 file's bytes: the magic, then width, height and triangle count, then the floats.
std::string tri1_bytes(uint32_t width, uint32_t height, uint32_t count,
                       const std::vector<float>& floats, const char* magic = "TRI1") {
  std::string bytes(magic, 4);
  for (uint32_t v : {width, height, count})
    bytes.append(reinterpret_cast<const char*>(&v), 4);
  bytes.append(reinterpret_cast<const char*>(floats.data()), floats.size() * sizeof(float));
  return bytes;
}

// `triangles` triangles of 3 vertices x 8 floats, all finite and distinct.
std::vector<float> triangle_floats(uint32_t triangles) {
  std::vector<float> f(size_t{triangles} * 24);
  for (size_t i = 0; i < f.size(); ++i)
    f[i] = 0.25f * static_cast<float>(i % 7) - 0.5f;
  return f;
}

// Loads and expects Error(code) whose one-line message names the file and holds every one of
// `parts`.
void expect_load_error(const std::filesystem::path& path, ErrorCode code,
                       std::initializer_list<std::string> parts) {
  test::expect_file_error([](const std::filesystem::path& p) { load_capture(p); }, path, code,
                          parts);
}

Capture two_triangles() {
  Capture c;
  c.width = 320;
  c.height = 200;
  c.positions = {{-1, -1, 0, 1},    {1, -1, 0.5f, 1},  {0, 1, -0.5f, 1},
                 {-0.0f, 2, -3, 4}, {1e-30f, 5, 6, 7}, {-8e20f, 9, 10, 11}};
  for (size_t i = 0; i < c.positions.size() * 4; ++i)
    c.varyings.push_back(0.125f * float(i));
  return c;
}

TEST(CaptureFile, SaveThenLoadGivesTheSameCapture) {
  TempDir dir;
  const Capture c = two_triangles();
  save_capture(dir / "two.tri", c);
  EXPECT_EQ(std::filesystem::file_size(dir / "two.tri"), 16u + 2u * 3u * 8u * 4u);
  const Capture back = load_capture(dir / "two.tri");
  EXPECT_EQ(back.width, c.width);
  EXPECT_EQ(back.height, c.height);
  EXPECT_EQ(back.positions, c.positions);
  EXPECT_EQ(back.varyings, c.varyings);
  EXPECT_TRUE(std::signbit(back.positions[3].x));  // -0 stays -0: the bits round-trip
}

TEST(CaptureFile, EmptyCaptureRoundTrips) {
  TempDir dir;
  Capture c;
  c.width = 1;
  c.height = kMaxFramebufferSize;
  save_capture(dir / "empty.tri", c);
  const Capture back = load_capture(dir / "empty.tri");
  EXPECT_EQ(back.width, 1u);
  EXPECT_EQ(back.height, kMaxFramebufferSize);
  EXPECT_TRUE(back.positions.empty());
  EXPECT_TRUE(back.varyings.empty());
}

TEST(CaptureFile, MissingFileIsAnIoErrorNamingTheFile) {
  TempDir dir;
  expect_load_error(dir / "missing.tri", ErrorCode::kIo, {});
}

TEST(CaptureFile, DirectoryIsAnIoErrorNamingIt) {
  TempDir dir;
  std::filesystem::create_directory(dir / "folder.tri");
  expect_load_error(dir / "folder.tri", ErrorCode::kIo, {});
}

TEST(CaptureFile, WrongMagicIsRejected) {
  TempDir dir;
  write_file(dir / "magic.tri", tri1_bytes(4, 4, 1, triangle_floats(1), "TRI3"));
  expect_load_error(dir / "magic.tri", ErrorCode::kInvalidInput, {"wrong magic"});
}

// A TRI2 file's bytes: the magic, width, height, triangle count and varying count, then the
// floats.
std::string tri2_bytes(uint32_t width, uint32_t height, uint32_t count, uint32_t varyings,
                       const std::vector<float>& floats) {
  std::string bytes("TRI2", 4);
  for (uint32_t v : {width, height, count, varyings})
    bytes.append(reinterpret_cast<const char*>(&v), 4);
  bytes.append(reinterpret_cast<const char*>(floats.data()), floats.size() * sizeof(float));
  return bytes;
}

TEST(CaptureFile, Tri2CapturesOfAnyVaryingCountRoundTrip) {
  for (uint32_t k : {0u, 1u, 10u, 32u}) {
    TempDir dir;
    Capture c;
    c.width = 7;
    c.height = 5;
    c.varying_count = k;
    for (int v = 0; v < 6; ++v) {
      const float f = static_cast<float>(v);
      c.positions.push_back({f * 0.1f, -f * 0.2f, 0.5f, 1.0f + f});
      for (uint32_t i = 0; i < k; ++i)
        c.varyings.push_back(f * 100.0f + static_cast<float>(i));
    }
    save_capture(dir / "k.tri", c);
    const std::string bytes = read_file(dir / "k.tri");
    EXPECT_EQ(bytes.substr(0, 4), k == 4 ? "TRI1" : "TRI2");
    EXPECT_EQ(bytes.size(), (k == 4 ? 16u : 20u) + 6 * (4 + k) * sizeof(float));
    const Capture back = load_capture(dir / "k.tri");
    EXPECT_EQ(back.varying_count, k);
    EXPECT_EQ(back.width, 7u);
    EXPECT_EQ(back.positions, c.positions);
    EXPECT_EQ(back.varyings, c.varyings);
  }
}

TEST(CaptureFile, BadTri2FilesAreRejectedNamingTheProblem) {
  TempDir dir;
  const std::vector<float> two(3 * 6, 0.5f);  // one triangle of 4 + 2 floats a vertex
  write_file(dir / "ok.tri", tri2_bytes(4, 4, 1, 2, two));
  EXPECT_EQ(load_capture(dir / "ok.tri").varying_count, 2u);
  write_file(dir / "many.tri", tri2_bytes(4, 4, 1, 33, two));
  expect_load_error(dir / "many.tri", ErrorCode::kInvalidInput, {"varying count 33"});
  write_file(dir / "short.tri", tri2_bytes(4, 4, 1, 2, two).substr(0, 18));
  expect_load_error(dir / "short.tri", ErrorCode::kInvalidInput, {"truncated TRI2 header"});
  write_file(dir / "size.tri", tri2_bytes(4, 4, 2, 2, two));
  expect_load_error(dir / "size.tri", ErrorCode::kInvalidInput, {"header says 2 triangles"});
  std::vector<float> nan = two;
  nan[6 + 4 + 1] = std::numeric_limits<float>::quiet_NaN();  // vertex 1, varying 1
  write_file(dir / "nan.tri", tri2_bytes(4, 4, 1, 2, nan));
  expect_load_error(dir / "nan.tri", ErrorCode::kInvalidInput, {"varying 1 of vertex 1"});
}

TEST(CaptureFile, TruncatedHeaderIsRejected) {
  TempDir dir;
  write_file(dir / "header.tri", tri1_bytes(4, 4, 1, {}).substr(0, 10));
  expect_load_error(dir / "header.tri", ErrorCode::kInvalidInput,
                    {"truncated capture header", "10 bytes"});
}

TEST(CaptureFile, EmptyFileIsATruncatedHeader) {
  TempDir dir;
  write_file(dir / "zero.tri", "");
  expect_load_error(dir / "zero.tri", ErrorCode::kInvalidInput,
                    {"truncated capture header", "0 bytes"});
}

TEST(CaptureFile, CountLargerThanTheFileIsRejected) {
  TempDir dir;
  write_file(dir / "short.tri", tri1_bytes(4, 4, 3, triangle_floats(2)));
  expect_load_error(dir / "short.tri", ErrorCode::kInvalidInput,
                    {"header says 3 triangles", "304 bytes", "has 208 bytes"});
}

TEST(CaptureFile, LargestCountIsRejectedWithoutAllocatingForIt) {
  TempDir dir;
  write_file(dir / "huge.tri", tri1_bytes(4, 4, 0xFFFFFFFFu, triangle_floats(1)));
  expect_load_error(dir / "huge.tri", ErrorCode::kInvalidInput,
                    {"header says 4294967295 triangles", "has 112 bytes"});
}

TEST(CaptureFile, CountSmallerThanTheFileIsRejected) {
  TempDir dir;
  write_file(dir / "long.tri", tri1_bytes(4, 4, 1, triangle_floats(2)));
  expect_load_error(dir / "long.tri", ErrorCode::kInvalidInput,
                    {"header says 1 triangles", "112 bytes", "has 208 bytes"});
}

TEST(CaptureFile, TriangleCutShortIsRejected) {
  TempDir dir;
  write_file(dir / "cut.tri", tri1_bytes(4, 4, 1, triangle_floats(1)).substr(0, 16 + 95));
  expect_load_error(dir / "cut.tri", ErrorCode::kInvalidInput, {"has 111 bytes"});
}

TEST(CaptureFile, ZeroWidthIsRejected) {
  TempDir dir;
  write_file(dir / "w0.tri", tri1_bytes(0, 4, 1, triangle_floats(1)));
  expect_load_error(dir / "w0.tri", ErrorCode::kInvalidInput, {"frame size 0x4", "out of range"});
}

TEST(CaptureFile, ZeroHeightIsRejected) {
  TempDir dir;
  write_file(dir / "h0.tri", tri1_bytes(4, 0, 1, triangle_floats(1)));
  expect_load_error(dir / "h0.tri", ErrorCode::kInvalidInput, {"frame size 4x0"});
}

TEST(CaptureFile, WidthAboveTheFramebufferLimitIsRejected) {
  TempDir dir;
  write_file(dir / "wide.tri", tri1_bytes(kMaxFramebufferSize + 1, 4, 1, triangle_floats(1)));
  expect_load_error(dir / "wide.tri", ErrorCode::kInvalidInput, {"frame size 16385x4", "1..16384"});
}

TEST(CaptureFile, AbsurdWidthIsRejected) {
  TempDir dir;
  write_file(dir / "absurd.tri", tri1_bytes(0xFFFFFFFFu, 4, 1, triangle_floats(1)));
  expect_load_error(dir / "absurd.tri", ErrorCode::kInvalidInput, {"frame size 4294967295x4"});
}

TEST(CaptureFile, NaNPositionIsRejectedNamingVertexAndTriangle) {
  TempDir dir;
  std::vector<float> f = triangle_floats(2);
  f[4 * 8 + 1] = kNaN;  // vertex 4 (triangle 1), y
  write_file(dir / "nan.tri", tri1_bytes(4, 4, 2, f));
  expect_load_error(dir / "nan.tri", ErrorCode::kInvalidInput,
                    {"position of vertex 4", "triangle 1", "not finite"});
}

TEST(CaptureFile, InfinitePositionIsRejectedNamingVertexAndTriangle) {
  TempDir dir;
  std::vector<float> f = triangle_floats(1);
  f[2 * 8 + 3] = -kInf;  // vertex 2, w
  write_file(dir / "inf.tri", tri1_bytes(4, 4, 1, f));
  expect_load_error(dir / "inf.tri", ErrorCode::kInvalidInput,
                    {"position of vertex 2", "triangle 0", "not finite"});
}

TEST(CaptureFile, NaNColourIsRejected) {
  TempDir dir;
  std::vector<float> f = triangle_floats(1);
  f[1 * 8 + 6] = kNaN;  // vertex 1, blue
  write_file(dir / "colour.tri", tri1_bytes(4, 4, 1, f));
  expect_load_error(dir / "colour.tri", ErrorCode::kInvalidInput, {"colour of vertex 1"});
}

TEST(CaptureFile, RejectedLoadLeavesTheFileAsItWas) {
  TempDir dir;
  const std::string bytes = tri1_bytes(4, 4, 3, triangle_floats(2));
  write_file(dir / "keep.tri", bytes);
  EXPECT_THROW(load_capture(dir / "keep.tri"), Error);
  EXPECT_EQ(read_file(dir / "keep.tri"), bytes);
}

// save_capture writes only what load_capture accepts, and checks before touching the file.
void expect_save_error(const Capture& c, ErrorCode code, const std::string& part) {
  TempDir dir;
  write_file(dir / "old.tri", "previous contents");
  try {
    save_capture(dir / "old.tri", c);
    ADD_FAILURE() << "expected tessera::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find("old.tri"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_file(dir / "old.tri"), "previous contents");
}

TEST(CaptureFile, SaveRejectsPositionsThatAreNotWholeTriangles) {
  Capture c = two_triangles();
  c.positions.pop_back();
  c.varyings.resize(c.positions.size() * 4);
  expect_save_error(c, ErrorCode::kInvalidArgument, "3 positions per triangle");
}

TEST(CaptureFile, SaveRejectsAColourArrayOfTheWrongSize) {
  Capture c = two_triangles();
  c.varyings.pop_back();
  expect_save_error(c, ErrorCode::kInvalidArgument, "4 varying floats");
}

TEST(CaptureFile, SaveRejectsAFrameSizeThatLoadWouldReject) {
  Capture c = two_triangles();
  c.width = 0;
  expect_save_error(c, ErrorCode::kInvalidArgument, "frame size 0x200");
  c.width = kMaxFramebufferSize + 1;
  expect_save_error(c, ErrorCode::kInvalidArgument, "frame size 16385x200");
}

TEST(CaptureFile, SaveRejectsANonFiniteValue) {
  Capture c = two_triangles();
  c.positions[5].z = kInf;
  expect_save_error(c, ErrorCode::kInvalidInput, "position of vertex 5");
  c = two_triangles();
  c.varyings[7] = kNaN;
  expect_save_error(c, ErrorCode::kInvalidInput, "colour of vertex 1");
}

TEST(CaptureFile, SaveIntoAMissingDirectoryIsAnIoErrorNamingTheFile) {
  TempDir dir;
  try {
    save_capture(dir / "no" / "such.tri", two_triangles());
    FAIL() << "expected tessera::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kIo);
    EXPECT_NE(std::string(e.what()).find("such.tri"), std::string::npos) << e.what();
  }
}

// A capture replays with the OpenGL depth convention: z_ndc = -0.5 is window depth 0.25 and
// in front of z_ndc = +0.5 (depth 0.75), whichever is drawn first. Under the Vulkan
// convention the first triangle would be clipped away (z < 0).
TEST(CaptureReplay, OpenGlDepthRangeIsMappedToZeroToOne) {
  TempDir dir;
  Capture c;
  c.width = 4;
  c.height = 4;
  // Two triangles covering the whole frame, at w = 2: the near one (orange) first, then the
  // far one (blue).
  c.positions = {{-2, -2, -1, 2}, {6, -2, -1, 2}, {-2, 6, -1, 2},
                 {-2, -2, 1, 2},  {6, -2, 1, 2},  {-2, 6, 1, 2}};
  for (int v = 0; v < 3; ++v)
    c.varyings.insert(c.varyings.end(), {1.0f, 0.2f, 0.0f, 1.0f});
  for (int v = 0; v < 3; ++v)
    c.varyings.insert(c.varyings.end(), {0.0f, 0.0f, 1.0f, 1.0f});
  save_capture(dir / "depth.tri", c);
  const Capture loaded = load_capture(dir / "depth.tri");

  Framebuffer fb({loaded.width, loaded.height, 1, ColorFormat::kRGBA8});
  fb.clear_depth(1.0f);
  Renderer renderer;
  renderer.draw(fb, capture_pipeline(), {loaded.positions, loaded.varyings, 4, {}});
  const std::vector<uint8_t> px = fb.read_rgba8();
  const std::vector<float> depth = fb.read_depth();
  for (uint32_t i = 0; i < 16; ++i) {
    EXPECT_EQ(px[i * 4 + 0], 255) << "pixel " << i;
    EXPECT_EQ(px[i * 4 + 1], 51) << "pixel " << i;
    EXPECT_EQ(px[i * 4 + 2], 0) << "pixel " << i;
    EXPECT_EQ(px[i * 4 + 3], 255) << "pixel " << i;
    EXPECT_FLOAT_EQ(depth[i], 0.25f) << "pixel " << i;
  }
}

TEST(CaptureReplay, CapturePipelineIsOpenGlDepthLessWithoutCulling) {
  const PipelineState p = capture_pipeline();
  EXPECT_EQ(p.clip_depth, ClipDepth::kNegativeOneToOne);
  EXPECT_TRUE(p.depth_test);
  EXPECT_TRUE(p.depth_write);
  EXPECT_EQ(p.depth_compare, CompareOp::kLess);
  EXPECT_EQ(p.cull, CullMode::kNone);
}

}  // namespace
}  // namespace tessera
