// Depth in the reference rasterizer (ARCHITECTURE.md section 2): every compare op decides
// which of two overlapping triangles wins; depth_write and depth_test switch writing and
// testing off; depth is z/w interpolated as a plane in screen space; the OpenGL clip-depth
// convention maps -w..w to 0..1.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Viewport;

constexpr std::array<float, 4> kRed{1, 0, 0, 1};
constexpr std::array<float, 4> kGreen{0, 1, 0, 1};

// Two triangles covering the whole viewport at NDC depth z (w = 1), in one colour.
struct FullScreenQuad {
  std::vector<Float4> positions;
  std::vector<float> rgba;

  FullScreenQuad(const Viewport& v, double z, std::array<float, 4> color) {
    const double w = v.width, h = v.height;
    positions = {v.at(0, 0, z), v.at(w, 0, z), v.at(w, h, z),
                 v.at(0, 0, z), v.at(w, h, z), v.at(0, h, z)};
    for (int i = 0; i < 6; ++i) {
      rgba.insert(rgba.end(), color.begin(), color.end());
    }
  }
};

void draw_quad(Renderer& renderer, Framebuffer& fb, const PipelineState& pipeline, double z,
               std::array<float, 4> color) {
  const FullScreenQuad quad({fb.width(), fb.height()}, z, color);
  test::draw(renderer, fb, pipeline, quad.positions, quad.rgba);
}

// Expects every pixel to have the colour `color` (components 0 or 1) and depth `depth`.
void expect_everywhere(const Framebuffer& fb, std::array<float, 4> color, float depth) {
  const std::vector<uint8_t> rgba = fb.read_rgba8();
  const std::vector<float> d = fb.read_depth();
  for (size_t p = 0; p < d.size(); ++p) {
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(rgba[p * 4 + c], color[c] > 0.0f ? 255 : 0) << "pixel " << p << " channel " << c;
    }
    ASSERT_EQ(d[p], depth) << "pixel " << p;
  }
}

// --- Compare ops ------------------------------------------------------------------------------
// A red quad at depth 0.5, then a green quad at depth 0.25, 0.5 or 0.75 with the op under test:
// green and its depth where the op passes, red and 0.5 where it fails.

struct CompareCase {
  CompareOp op;
  const char* name;
  std::array<bool, 3> passes;  // for the incoming depths 0.25 (nearer), 0.5 (equal), 0.75
};

class ReferenceDepthCompare : public ::testing::TestWithParam<CompareCase> {};

TEST_P(ReferenceDepthCompare, DecidesWhichOfTwoOverlappingTrianglesWins) {
  const CompareCase c = GetParam();
  const std::array<double, 3> incoming = {0.25, 0.5, 0.75};
  for (size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(testing::Message() << "incoming depth " << incoming[k] << " over 0.5");
    const bool passes = c.passes[k];
    Renderer renderer = test::reference_renderer();
    Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
    draw_quad(renderer, fb, {}, 0.5, kRed);
    expect_everywhere(fb, kRed, 0.5f);

    renderer.reset_counters();
    PipelineState pipeline;
    pipeline.depth_compare = c.op;
    draw_quad(renderer, fb, pipeline, incoming[k], kGreen);
    expect_everywhere(fb, passes ? kGreen : kRed, passes ? static_cast<float>(incoming[k]) : 0.5f);
    EXPECT_EQ(renderer.counters().samples_covered, 64u);
    EXPECT_EQ(renderer.counters().samples_passed, passes ? 64u : 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllOps, ReferenceDepthCompare,
    ::testing::Values(  //                                     nearer equal  farther
        CompareCase{CompareOp::kNever, "Never", {false, false, false}},
        CompareCase{CompareOp::kLess, "Less", {true, false, false}},
        CompareCase{CompareOp::kEqual, "Equal", {false, true, false}},
        CompareCase{CompareOp::kLessEqual, "LessEqual", {true, true, false}},
        CompareCase{CompareOp::kGreater, "Greater", {false, false, true}},
        CompareCase{CompareOp::kNotEqual, "NotEqual", {true, false, true}},
        CompareCase{CompareOp::kGreaterEqual, "GreaterEqual", {false, true, true}},
        CompareCase{CompareOp::kAlways, "Always", {true, true, true}}),
    [](const ::testing::TestParamInfo<CompareCase>& param_info) { return param_info.param.name; });

TEST(ReferenceDepth, NeverDrawsNothingEvenOverTheClearedDepth) {
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
  PipelineState pipeline;
  pipeline.depth_compare = CompareOp::kNever;
  draw_quad(renderer, fb, pipeline, 0.0, kGreen);
  expect_everywhere(fb, {0, 0, 0, 0}, 1.0f);
}

// A tilted triangle with a different w at each vertex: its per-sample depths vary and are
// not round numbers, yet the same triangle drawn again computes exactly the same ones.
std::vector<Float4> tilted_triangle(const Viewport& v) {
  return {v.at(0.75, 1.25, 0.125, 1.0), v.at(15.5, 3.0, 0.875, 2.5),
          v.at(4.25, 15.75, 0.4375, 4.0)};
}

TEST(ReferenceDepth, EqualPassesWhereTheSameTriangleIsDrawnAgain) {
  const Viewport v{16, 16};
  const std::vector<Float4> tri = tilted_triangle(v);
  const std::vector<float> red = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const std::vector<float> green = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, 4, ColorFormat::kRGBA8});
  test::draw(renderer, fb, {}, tri, red);
  const uint64_t covered = renderer.counters().samples_covered;
  ASSERT_GT(covered, 80u * 4u);

  PipelineState equal;
  equal.depth_compare = CompareOp::kEqual;
  renderer.reset_counters();
  test::draw(renderer, fb, equal, tri, green);
  EXPECT_EQ(renderer.counters().samples_passed, covered);

  // Every sample the triangle covers is now green: no pixel is left partly red.
  const std::vector<uint8_t> rgba = fb.read_rgba8();
  for (size_t p = 0; p < rgba.size() / 4; ++p) {
    EXPECT_EQ(rgba[p * 4 + 0], 0) << "pixel " << p;
  }

  PipelineState less;  // ... and it is not strictly nearer than itself anywhere
  renderer.reset_counters();
  test::draw(renderer, fb, less, tri, red);
  EXPECT_EQ(renderer.counters().samples_covered, covered);
  EXPECT_EQ(renderer.counters().samples_passed, 0u);
}

TEST(ReferenceDepth, DepthWriteOffTestsButLeavesDepthUnchanged) {
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
  draw_quad(renderer, fb, {}, 0.5, kRed);

  PipelineState no_write;
  no_write.depth_write = false;
  draw_quad(renderer, fb, no_write, 0.75, kGreen);  // fails LESS: nothing changes
  expect_everywhere(fb, kRed, 0.5f);
  draw_quad(renderer, fb, no_write, 0.25, kGreen);  // passes LESS: colour only
  expect_everywhere(fb, kGreen, 0.5f);

  // The depth buffer still holds 0.5, so a red quad at 0.375 passes LESS and writes.
  draw_quad(renderer, fb, {}, 0.375, kRed);
  expect_everywhere(fb, kRed, 0.375f);
}

TEST(ReferenceDepth, DepthTestOffDrawsInSubmissionOrderAndWritesNoDepth) {
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
  draw_quad(renderer, fb, {}, 0.25, kRed);

  PipelineState off;
  off.depth_test = false;
  off.depth_write = true;                      // ignored without the test (OpenGL semantics)
  off.depth_compare = CompareOp::kNever;       // ignored too
  draw_quad(renderer, fb, off, 0.75, kGreen);  // farther, and still drawn
  expect_everywhere(fb, kGreen, 0.25f);
  EXPECT_EQ(renderer.counters().samples_passed, 128u);

  // Later triangles overwrite earlier ones, whatever their depth.
  const Viewport v{8, 8};
  const std::vector<Float4> tris = {
      v.at(0, 0, 0.1), v.at(8, 0, 0.1), v.at(0, 8, 0.1),   // red, nearer
      v.at(0, 0, 0.9), v.at(8, 0, 0.9), v.at(0, 8, 0.9)};  // green, farther, drawn second
  const std::vector<float> rgba = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1,
                                   0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  fb.clear_color({0, 0, 1, 1});
  test::draw(renderer, fb, off, tris, rgba);
  const std::vector<uint8_t> px = fb.read_rgba8();
  EXPECT_EQ(px[(0 * 8 + 0) * 4 + 1], 255) << "the second triangle wins pixel (0, 0)";
  EXPECT_EQ(px[(0 * 8 + 0) * 4 + 0], 0);
  EXPECT_EQ(px[(7 * 8 + 7) * 4 + 2], 255) << "pixel (7, 7) is outside both";
  for (float d : fb.read_depth()) {
    ASSERT_EQ(d, 0.25f);
  }
}

// --- Depth is z/w, a plane in screen space ----------------------------------------------------
// The triangle (0, 0), (16, 0), (0, 16) with NDC depths 0, 0.5, 1 has depth x/32 + y/16; it
// covers the pixels with i + j < 15 (its hypotenuse is a right edge), where the depth at the
// centre is (i + 0.5)/32 + (j + 0.5)/16, exact in float.

float plane_depth(uint32_t i, uint32_t j) {
  return (static_cast<float>(i) + 0.5f) / 32.0f + (static_cast<float>(j) + 0.5f) / 16.0f;
}

void expect_plane_depth(const Framebuffer& fb) {
  const std::vector<float> depth = fb.read_depth();
  for (uint32_t j = 0; j < 16; ++j) {
    for (uint32_t i = 0; i < 16; ++i) {
      const float expected = i + j < 15 ? plane_depth(i, j) : 1.0f;
      ASSERT_EQ(depth[j * 16 + i], expected) << "pixel (" << i << ", " << j << ")";
    }
  }
}

TEST(ReferenceDepth, DepthIsThePlaneOfTheVertexDepthsAtPixelCentres) {
  const Viewport v{16, 16};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  const std::vector<Float4> tri = {v.at(0, 0, 0.0), v.at(16, 0, 0.5), v.at(0, 16, 1.0)};
  test::draw(renderer, fb, test::coverage_pipeline(), tri);
  expect_plane_depth(fb);
  EXPECT_EQ(fb.read_depth()[0], 1.0f / 64 + 1.0f / 32);  // pixel (0, 0), worked by hand
}

TEST(ReferenceDepth, DepthIsLinearInScreenSpaceWhateverTheVertexW) {
  // Same window positions and NDC depths, w = 1, 2, 4: z/w is interpolated as the same plane
  // (not z and w separately).
  const Viewport v{16, 16};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  const std::vector<Float4> tri = {v.at(0, 0, 0.0, 1.0), v.at(16, 0, 0.5, 2.0),
                                   v.at(0, 16, 1.0, 4.0)};
  test::draw(renderer, fb, test::coverage_pipeline(), tri);
  expect_plane_depth(fb);
}

// --- OpenGL clip depth ------------------------------------------------------------------------

TEST(ReferenceClipDepth, NegativeOneToOneMapsMinusWToZeroAndWToOne) {
  PipelineState gl = test::coverage_pipeline();
  gl.clip_depth = ClipDepth::kNegativeOneToOne;
  struct Case {
    double z_ndc;  // z / w in OpenGL's -1..1
    double w;
    float depth;
  };
  for (const Case& c : {Case{-1.0, 1.0, 0.0f}, Case{-1.0, 4.0, 0.0f}, Case{-0.5, 1.0, 0.25f},
                        Case{-0.5, 2.0, 0.25f}, Case{0.0, 1.0, 0.5f}, Case{0.5, 4.0, 0.75f},
                        Case{1.0, 1.0, 1.0f}, Case{1.0, 2.0, 1.0f}}) {
    SCOPED_TRACE(testing::Message() << "z/w " << c.z_ndc << ", w " << c.w);
    const Viewport v{8, 8};
    const std::vector<Float4> quad = {v.at(0, 0, c.z_ndc, c.w), v.at(8, 0, c.z_ndc, c.w),
                                      v.at(8, 8, c.z_ndc, c.w), v.at(0, 0, c.z_ndc, c.w),
                                      v.at(8, 8, c.z_ndc, c.w), v.at(0, 8, c.z_ndc, c.w)};
    Renderer renderer = test::reference_renderer();
    Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
    fb.clear_depth(0.625f);
    test::draw(renderer, fb, gl, quad);
    for (float d : fb.read_depth()) {
      ASSERT_EQ(d, c.depth);
    }
  }
}

TEST(ReferenceClipDepth, NegativeOneToOneInterpolatesTheMappedDepthPlane) {
  // NDC depths -1, 0, 1 map to 0, 0.5, 1: the plane of the zero-to-one test above.
  PipelineState gl = test::coverage_pipeline();
  gl.clip_depth = ClipDepth::kNegativeOneToOne;
  const Viewport v{16, 16};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  test::draw(
      renderer, fb, gl,
      std::vector<Float4>{v.at(0, 0, -1.0, 2.0), v.at(16, 0, 0.0, 1.0), v.at(0, 16, 1.0, 4.0)});
  expect_plane_depth(fb);
}

TEST(ReferenceClipDepth, NegativeDepthIsVisibleOnlyInTheOpenGlConvention) {
  // z = -w/2 lies behind the near plane z = 0 of the zero-to-one convention, but inside
  // OpenGL's -w <= z.
  const Viewport v{8, 8};
  const std::vector<Float4> tri = {v.at(0, 0, -0.5), v.at(8, 0, -0.5), v.at(0, 8, -0.5)};
  PipelineState vk = test::coverage_pipeline();
  PipelineState gl = vk;
  gl.clip_depth = ClipDepth::kNegativeOneToOne;
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
  test::draw(renderer, fb, vk, tri);
  EXPECT_EQ(renderer.counters().samples_covered, 0u);
  for (float d : fb.read_depth()) {
    ASSERT_EQ(d, 1.0f);
  }
  test::draw(renderer, fb, gl, tri);
  EXPECT_EQ(fb.read_depth()[0], 0.25f);
  EXPECT_EQ(renderer.counters().samples_covered, 28u);  // i + j < 7: 7 + 6 + ... + 1
}

// --- Depth formats ----------------------------------------------------------------------------
// Fixed-point formats store the step nearest z (ties to even) and read back step / (2^n - 1);
// float depth stores z itself.

TEST(ReferenceDepthFormat, FixedPointFormatsStoreTheNearestStep) {
  struct Case {
    DepthFormat format;
    double steps;
  };
  for (const Case c : {Case{DepthFormat::kUnorm16, 65535.0},
                       Case{DepthFormat::kUnorm24, 16777215.0}, Case{DepthFormat::kFloat32, 0.0}}) {
    Renderer renderer = test::reference_renderer();
    Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8, c.format});
    const double z = 0.3f;  // as the float vertex holds it: 0.3000000119...
    draw_quad(renderer, fb, test::coverage_pipeline(), z, kRed);
    const float expected = c.steps > 0.0 ? static_cast<float>(std::nearbyint(z * c.steps) / c.steps)
                                         : static_cast<float>(z);
    for (float d : fb.read_depth()) {
      ASSERT_EQ(d, expected) << "format " << static_cast<int>(c.format);
    }
  }
}

TEST(ReferenceDepthFormat, ClearsAreStoredInTheFormatAndClampedToTheUnitRange) {
  Framebuffer fb({4, 4, 1, ColorFormat::kRGBA8, DepthFormat::kUnorm16});
  EXPECT_EQ(fb.read_depth()[0], 1.0f);  // a new framebuffer holds the far plane
  fb.clear_depth(0.1f);
  EXPECT_EQ(fb.read_depth()[0], static_cast<float>(std::nearbyint(0.1f * 65535.0) / 65535.0));
  fb.clear_depth(2.0f);
  EXPECT_EQ(fb.read_depth()[0], 1.0f);
  fb.clear_depth(-1.0f);
  EXPECT_EQ(fb.read_depth()[0], 0.0f);
}

TEST(ReferenceDepthFormat, DepthsWithinOneStepTieAndTheTieGoesByTheCompareOp) {
  // Green lies 1/4 of a 16-bit step in front of red: a float buffer tells them apart, a
  // 16-bit one stores both as the same step, so LESS keeps red and LESS_EQUAL draws green.
  const double z_red = 20000.0 / 65535.0, z_green = z_red - 0.25 / 65535.0;
  struct Case {
    DepthFormat format;
    CompareOp op;
    std::array<float, 4> winner;
  };
  for (const Case c : {Case{DepthFormat::kFloat32, CompareOp::kLess, kGreen},
                       Case{DepthFormat::kUnorm16, CompareOp::kLess, kRed},
                       Case{DepthFormat::kUnorm16, CompareOp::kLessEqual, kGreen}}) {
    Renderer renderer = test::reference_renderer();
    Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8, c.format});
    PipelineState p;
    p.depth_compare = c.op;
    draw_quad(renderer, fb, p, z_red, kRed);
    draw_quad(renderer, fb, p, z_green, kGreen);
    const std::vector<uint8_t> rgba = fb.read_rgba8();
    for (size_t i = 0; i < rgba.size(); i += 4) {
      ASSERT_EQ(rgba[i + 1], c.winner[1] > 0 ? 255 : 0)
          << "format " << static_cast<int>(c.format) << " op " << static_cast<int>(c.op);
    }
  }
}

TEST(ReferenceDepthFormat, AnInvalidFormatIsAnError) {
  FramebufferDesc desc{4, 4, 1, ColorFormat::kRGBA8, static_cast<DepthFormat>(7)};
  EXPECT_THROW(Framebuffer fb(desc), Error);
}

}  // namespace
}  // namespace tessera
