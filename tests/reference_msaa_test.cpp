// Multisampling in the reference rasterizer (ARCHITECTURE.md section 2): coverage and depth per
// sample at the D3D11/Vulkan standard positions, shading once per pixel, and the box resolve.
// The positions are found by probing, not read from the engine's table: a tiny triangle around
// each point of the 1/16-pixel lattice shows which sample, if any, sits there.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Point;
using test::Viewport;

class ReferenceMsaaPattern : public ::testing::TestWithParam<uint32_t> {};

TEST_P(ReferenceMsaaPattern, SamplesSitAtTheStandardPositions) {
  const uint32_t n = GetParam();
  const Viewport v{4, 4};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({4, 4, n, ColorFormat::kRGBA8});
  const PipelineState pipeline = test::coverage_pipeline();

  // found[s]: the lattice points of pixel (1, 1) whose probe covered sample s of that pixel.
  std::vector<std::vector<Point>> found(n);
  for (int l = 0; l < 16; ++l) {
    for (int k = 0; k < 16; ++k) {
      // The probe contains (x, y) strictly and no other point of the 1/16 lattice.
      const double x = 1 + k / 16.0, y = 1 + l / 16.0;
      const double e = 1.0 / 64;
      const std::vector<Float4> probe = {v.at(x - e, y - e), v.at(x + 2 * e, y - e),
                                         v.at(x - e, y + 2 * e)};
      fb.clear_depth(1.0f);
      renderer.reset_counters();
      test::draw(renderer, fb, pipeline, probe);
      const std::vector<float> depth = fb.read_sample_depth();
      uint64_t hits = 0;
      for (uint32_t s = 0; s < n; ++s) {
        if (depth[(1 * 4 + 1) * n + s] != 1.0f) {
          found[s].push_back({x - 1, y - 1});
          ++hits;
        }
      }
      // Whatever the probe covered lies in pixel (1, 1).
      ASSERT_EQ(renderer.counters().samples_covered, hits) << "probe at (" << x << ", " << y << ")";
      ASSERT_LE(hits, 1u) << "two samples at (" << x << ", " << y << ")";
    }
  }
  const std::vector<Point> standard = test::standard_sample_positions(n);
  for (uint32_t s = 0; s < n; ++s) {
    ASSERT_EQ(found[s].size(), 1u)
        << "sample " << s << " found at " << found[s].size() << " lattice points";
    EXPECT_EQ(found[s][0].x, standard[s].x) << "sample " << s;
    EXPECT_EQ(found[s][0].y, standard[s].y) << "sample " << s;
  }
}

TEST_P(ReferenceMsaaPattern, EachSampleTakesTheDepthPlaneAtItsOwnPosition) {
  // Depth x/32 + y/64 over the whole 16x16 viewport; sample offsets are multiples of 1/16, so
  // every expected depth is exact in float.
  const uint32_t n = GetParam();
  const Viewport v{16, 16};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, n, ColorFormat::kRGBA8});
  test::draw(renderer, fb, test::coverage_pipeline(),
             std::vector<Float4>{v.at(0, 0, 0.0), v.at(32, 0, 1.0), v.at(0, 32, 0.5)});
  EXPECT_EQ(renderer.counters().samples_covered, 16u * 16u * n);
  const std::vector<float> depth = fb.read_sample_depth();
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) {
      for (uint32_t s = 0; s < n; ++s) {
        const Point p = test::sample_position(n, x, y, s);
        ASSERT_EQ(depth[(y * 16 + x) * n + s], static_cast<float>(p.x / 32 + p.y / 64))
            << "pixel (" << x << ", " << y << ") sample " << s;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllSampleCounts, ReferenceMsaaPattern,
                         ::testing::Values(1u, 2u, 4u, 8u, 16u),
                         [](const ::testing::TestParamInfo<uint32_t>& param_info) {
                           return std::to_string(param_info.param) + "Samples";
                         });

// --- Box resolve ------------------------------------------------------------------------------
// A white triangle covering x < edge over opaque black: pixels left of the edge are white,
// pixels right of it black, and the pixel the edge crosses resolves to the fraction of its
// samples left of the edge (a right edge: a sample on it stays black).

std::vector<float> draw_white_left_of(uint32_t samples, ColorFormat format, double edge,
                                      std::vector<uint8_t>* rgba8 = nullptr) {
  const Viewport v{8, 8};
  const std::vector<Float4> tri = {v.at(edge, -8), v.at(edge, 16), v.at(-22, 4)};
  const std::vector<float> white(12, 1.0f);
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, samples, format});
  fb.clear_color({0, 0, 0, 1});
  test::draw(renderer, fb, {}, tri, white);
  if (rgba8 != nullptr) *rgba8 = fb.read_rgba8();
  return fb.read_rgba32f();
}

TEST(ReferenceMsaaResolve, PixelHalfCoveredByWhiteOverBlackResolvesToHalf) {
  // The edge x = 4.5 runs through the centres of column 4; every standard pattern of 2 or
  // more samples has exactly half its samples at x < 0.5 (and in the 16-sample pattern one
  // sample exactly on it, at 0.5, which a right edge excludes).
  for (uint32_t n : {2u, 4u, 8u, 16u}) {
    SCOPED_TRACE(n);
    const std::vector<float> image = draw_white_left_of(n, ColorFormat::kRGBA32F, 4.5);
    for (uint32_t y = 0; y < 8; ++y) {
      for (uint32_t x = 0; x < 8; ++x) {
        const float expected = x < 4 ? 1.0f : x == 4 ? 0.5f : 0.0f;
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(image[(y * 8 + x) * 4 + c], expected) << x;
        }
        ASSERT_EQ(image[(y * 8 + x) * 4 + 3], 1.0f);
      }
    }
  }
}

struct ResolveCase {
  uint32_t samples;
  double edge;       // x of the triangle's right edge, inside pixel column 4
  uint32_t covered;  // samples of a column-4 pixel left of it, counted from the standard table
  uint8_t rgba8;     // 255 * covered / samples, rounded to nearest
};

TEST(ReferenceMsaaResolve, ResolveIsTheAverageOfTheSamplesRoundedToNearest) {
  for (const ResolveCase& c : {
           ResolveCase{4, 4.25, 1, 64},      // 63.75
           ResolveCase{4, 4.75, 3, 191},     // 191.25
           ResolveCase{8, 4.375, 3, 96},     // 95.625
           ResolveCase{8, 4.625, 5, 159},    // 159.375
           ResolveCase{16, 4.3125, 5, 80},   // 79.6875
           ResolveCase{16, 4.6875, 11, 175}  // 175.3125
       }) {
    SCOPED_TRACE(testing::Message() << c.samples << " samples, edge " << c.edge);
    std::vector<uint8_t> bytes;
    const std::vector<float> from_rgba8 =
        draw_white_left_of(c.samples, ColorFormat::kRGBA8, c.edge, &bytes);
    const std::vector<float> from_rgba32f =
        draw_white_left_of(c.samples, ColorFormat::kRGBA32F, c.edge);
    for (uint32_t y = 0; y < 8; ++y) {
      const size_t p = (y * 8 + 4) * 4;
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_EQ(bytes[p + ch], c.rgba8);
        ASSERT_EQ(from_rgba8[p + ch], c.rgba8 / 255.0f);
        ASSERT_EQ(from_rgba32f[p + ch],
                  static_cast<float>(c.covered) / static_cast<float>(c.samples));
      }
      ASSERT_EQ(bytes[p + 3], 255);
      ASSERT_EQ(bytes[p - 4], 255) << "column 3 is white";
      ASSERT_EQ(bytes[p + 4], 0) << "column 5 is black";
    }
  }
}

TEST(ReferenceMsaaResolve, ShadingHappensOncePerPixelAtItsCentre) {
  // Affine red = x / 8 on a triangle covering x < 4.5, 4 samples: column 4 has 2 of 4 samples
  // covered, each storing red at the pixel centre, 4.5 / 8 = 0.5625, so it resolves to
  // 0.5625 / 2 = 0.28125. (Shading each sample at its own position would give
  // (4.375 / 8 + 4.125 / 8) / 4 = 0.265625.)
  const Viewport v{8, 8};
  const std::vector<Float4> tri = {v.at(4.5, -8), v.at(4.5, 16), v.at(-22, 4)};
  const std::vector<float> red_is_x_over_8 = {4.5f / 8, 0, 0,          1, 4.5f / 8, 0,
                                              0,        1, -22.0f / 8, 0, 0,        1};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 4, ColorFormat::kRGBA32F});
  PipelineState pipeline;
  pipeline.interpolation = Interpolation::kAffine;
  test::draw(renderer, fb, pipeline, tri, red_is_x_over_8);
  const std::vector<float> image = fb.read_rgba32f();
  for (uint32_t y = 0; y < 8; ++y) {
    EXPECT_FLOAT_EQ(image[(y * 8 + 4) * 4], 0.28125f) << "row " << y;
    EXPECT_FLOAT_EQ(image[(y * 8 + 2) * 4], 2.5f / 8) << "row " << y << ": fully covered";
  }
}

}  // namespace
}  // namespace tessera
