// Points in the reference rasterizer (primitives.hpp): square points cover the pixels whose
// centres lie in the point's square, with the top-left rule on its border; round points are
// antialiased discs blended over the framebuffer; both are depth-tested and clipped by their
// centre against the near plane.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/primitive_test_support.hpp"

namespace tessera::test {
namespace {

PixelSet square_point(double x, double y, float size, uint32_t samples = 1) {
  const Viewport vp{16, 16};
  return touched(
      16, 16,
      [&](Renderer& r, Framebuffer& fb) {
        const Vertices v(vp, {{x, y}});
        r.draw_points(fb, touch_pipeline(), {size, PointShape::kSquare}, v.input());
      },
      samples);
}

PixelSet square(int x0, int y0, int x1, int y1) {  // inclusive
  PixelSet s;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x)
      s.insert({x, y});
  }
  return s;
}

TEST(ReferencePoints, SquarePointsCoverThePixelCentresInTheirSquare) {
  EXPECT_EQ(square_point(5.5, 5.5, 1), square(5, 5, 5, 5));
  EXPECT_EQ(square_point(5.5, 5.5, 2), square(4, 4, 5, 5));  // [4.5, 6.5): centres 4.5, 5.5
  EXPECT_EQ(square_point(5.5, 5.5, 3), square(4, 4, 6, 6));
  EXPECT_EQ(square_point(5.0, 5.0, 2), square(4, 4, 5, 5));
  EXPECT_EQ(square_point(5.0, 5.0, 4), square(3, 3, 6, 6));
  // Size 1 on a pixel corner: the square [4.5, 5.5)^2 holds the centre of (4, 4) on its left
  // and top edges (inside) and no other.
  EXPECT_EQ(square_point(5.0, 5.0, 1), square(4, 4, 4, 4));
  // Partly off screen: the rest is drawn.
  EXPECT_EQ(square_point(0.5, 15.5, 4), square(0, 13, 1, 15));  // [-1.5, 2.5) x [13.5, 17.5)
}

TEST(ReferencePoints, SquarePointsAreSampledPerSampleWithMsaa) {
  // A size-1 point centred on a pixel centre covers the pixel's 4 samples, all within
  // 6/16 px of the centre; one centred on the pixel's corner covers one sample of each of the
  // four pixels around the corner, so sample 0 shows only some of them.
  const Viewport vp{16, 16};
  Renderer r(reference_options());
  Framebuffer fb({16, 16, 4, ColorFormat::kRGBA8});
  fb.clear_depth(-1);
  const Vertices v(vp, {{5.5, 5.5}});
  r.draw_points(fb, touch_pipeline(), {1, PointShape::kSquare}, v.input());
  EXPECT_EQ(r.counters().samples_covered, 4u);
}

TEST(ReferencePoints, PointsAreDepthTestedAndClippedByTheNearPlane) {
  const Viewport vp{16, 16};
  Renderer r(reference_options());
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  fb.clear_depth(0.5f);
  const Vertices v(vp, {{2.5, 2.5, 0.25}, {6.5, 6.5, 0.75}, {10.5, 10.5, -0.25}});
  r.draw_points(fb, {}, {1, PointShape::kSquare}, v.input());
  const std::vector<float> depth = fb.read_depth();
  EXPECT_EQ(depth[2 * 16 + 2], 0.25f);
  EXPECT_EQ(depth[6 * 16 + 6], 0.5f);    // behind the stored depth
  EXPECT_EQ(depth[10 * 16 + 10], 0.5f);  // in front of the near plane: clipped
  EXPECT_EQ(r.counters().points_submitted, 3u);
}

TEST(ReferencePoints, RoundPointsBlendTheirCoverage) {
  // Diameter 4 at (8, 8): a pixel whose centre is d from it has coverage
  // clamp(2.5 - d, 0, 1), and the colour is blended source-over.
  const Viewport vp{16, 16};
  Renderer r(reference_options());
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA32F});
  fb.clear_color({0, 0, 1, 1});
  Vertices v(vp, {});
  v.add(vp, {8.0, 8.0, 0.5}, {1, 0, 0, 1});
  r.draw_points(fb, {}, {4, PointShape::kRound}, v.input());
  const std::vector<float> rgba = fb.read_rgba32f();
  auto at = [&](int x, int y, int c) { return rgba[(y * 16 + x) * 4 + c]; };
  for (int y = 3; y < 13; ++y) {
    for (int x = 3; x < 13; ++x) {
      const double d = std::hypot(x + 0.5 - 8.0, y + 0.5 - 8.0);
      const double c = std::clamp(2.5 - d, 0.0, 1.0);
      EXPECT_NEAR(at(x, y, 0), c, 1e-6) << x << "," << y;
      EXPECT_NEAR(at(x, y, 2), 1 - c, 1e-6) << x << "," << y;
    }
  }
  EXPECT_EQ(at(7, 7, 0), 1.0f);  // d = 0.71: fully covered
  EXPECT_GT(at(6, 7, 0), 0.9f);  // d = 1.58
  EXPECT_LT(at(6, 7, 0), 0.95f);
  EXPECT_EQ(at(5, 7, 0), 0.0f);  // d = 2.55: outside
}

}  // namespace
}  // namespace tessera::test
