// Polygons (primitives.hpp): the scanline fill with the even-odd and nonzero rules on concave,
// self-intersecting and holed polygons, hand-checked; tessellation covers exactly the samples
// the scanline fill covers for simple polygons and polygons with holes; degenerate polygons
// draw nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "tests/primitive_test_support.hpp"

namespace tessera::test {
namespace {

struct Polygon {
  std::vector<std::vector<WindowVertex>> contours;
};

// Per-sample coverage (depth != -1) of a polygon drawn with `state`.
std::vector<bool> coverage(const Polygon& poly, PolygonState state, uint32_t size = 16,
                           uint32_t samples = 1, Backend backend = Backend::kReference,
                           uint32_t threads = 1) {
  const Viewport vp{size, size};
  Renderer r(RendererOptions{threads, backend});
  Framebuffer fb({size, size, samples, ColorFormat::kRGBA8});
  fb.clear_depth(-1);
  Vertices v(vp, {});
  std::vector<uint32_t> sizes;
  for (const auto& c : poly.contours) {
    for (const WindowVertex& p : c)
      v.add(vp, p);
    sizes.push_back(static_cast<uint32_t>(c.size()));
  }
  r.draw_polygon(fb, touch_pipeline(), state, v.input(), sizes);
  const std::vector<float> depth = fb.read_sample_depth();
  std::vector<bool> out(depth.size());
  for (size_t i = 0; i < depth.size(); ++i)
    out[i] = depth[i] != -1.0f;
  return out;
}

std::string picture(const std::vector<bool>& cov, uint32_t size) {
  std::string s;
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x)
      s += cov[y * size + x] ? 'X' : '.';
    s += '\n';
  }
  return s;
}

PolygonState state(FillRule rule, PolygonMethod method = PolygonMethod::kScanline) {
  return {rule, method};
}

constexpr PolygonMethod kMethods[] = {PolygonMethod::kScanline, PolygonMethod::kTessellation};

TEST(ReferencePolygons, ConcavePolygonCoversTheSamplesInside) {
  // An L: the 8x8 square at (2, 2) without its bottom-right 4x4 quarter.
  const Polygon l{{{{2, 2}, {10, 2}, {10, 6}, {6, 6}, {6, 10}, {2, 10}}}};
  for (PolygonMethod m : kMethods) {
    for (FillRule rule : {FillRule::kEvenOdd, FillRule::kNonZero}) {
      const std::vector<bool> cov = coverage(l, state(rule, m), 12);
      EXPECT_EQ(picture(cov, 12),
                "............\n"
                "............\n"
                "..XXXXXXXX..\n"
                "..XXXXXXXX..\n"
                "..XXXXXXXX..\n"
                "..XXXXXXXX..\n"
                "..XXXX......\n"
                "..XXXX......\n"
                "..XXXX......\n"
                "..XXXX......\n"
                "............\n"
                "............\n");
    }
  }
}

// A pentagram (one contour crossing itself): the inner pentagon has winding number 2.
Polygon pentagram(double cx, double cy, double r) {
  Polygon p{{{}}};
  for (int k = 0; k < 5; ++k) {
    const double a = -std::numbers::pi / 2 + k * 4 * std::numbers::pi / 5;
    p.contours[0].push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return p;
}

TEST(ReferencePolygons, SelfIntersectingStarFollowsTheFillRule) {
  const Polygon star = pentagram(16, 16, 14);
  const std::vector<bool> even = coverage(star, state(FillRule::kEvenOdd), 32);
  const std::vector<bool> nonzero = coverage(star, state(FillRule::kNonZero), 32);
  // The centre is in the inner pentagon: empty under even-odd, filled under nonzero.
  EXPECT_FALSE(even[16 * 32 + 16]);
  EXPECT_TRUE(nonzero[16 * 32 + 16]);
  // A point of the star (winding 1) is filled under both.
  EXPECT_TRUE(even[5 * 32 + 16]);
  EXPECT_TRUE(nonzero[5 * 32 + 16]);
  // Nonzero covers everything even-odd covers.
  for (size_t i = 0; i < even.size(); ++i) {
    if (even[i]) {
      EXPECT_TRUE(nonzero[i]) << i;
    }
  }
}

TEST(ReferencePolygons, HolesUnderBothFillRules) {
  const std::vector<WindowVertex> outer = {{2, 2}, {14, 2}, {14, 14}, {2, 14}};
  const std::vector<WindowVertex> hole_reversed = {{5, 5}, {5, 11}, {11, 11}, {11, 5}};
  const std::vector<WindowVertex> hole_same = {{5, 5}, {11, 5}, {11, 11}, {5, 11}};
  const std::string ring =
      "................\n"
      "................\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXX......XXX..\n"
      "..XXX......XXX..\n"
      "..XXX......XXX..\n"
      "..XXX......XXX..\n"
      "..XXX......XXX..\n"
      "..XXX......XXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "................\n"
      "................\n";
  const std::string full =
      "................\n"
      "................\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "..XXXXXXXXXXXX..\n"
      "................\n"
      "................\n";
  for (PolygonMethod m : kMethods) {
    // An oppositely wound hole is a hole under both rules.
    EXPECT_EQ(picture(coverage({{outer, hole_reversed}}, state(FillRule::kEvenOdd, m)), 16), ring);
    EXPECT_EQ(picture(coverage({{outer, hole_reversed}}, state(FillRule::kNonZero, m)), 16), ring);
    // Wound the same way it is a hole for even-odd only: nonzero fills it (winding 2).
    EXPECT_EQ(picture(coverage({{outer, hole_same}}, state(FillRule::kEvenOdd, m)), 16), ring);
    EXPECT_EQ(picture(coverage({{outer, hole_same}}, state(FillRule::kNonZero, m)), 16), full);
  }
}

TEST(ReferencePolygons, DegeneratePolygonsDrawNothing) {
  const std::vector<Polygon> degenerate = {
      {{{{2, 2}, {8, 8}, {12, 12}}}},          // collinear
      {{{{2, 2}, {8, 8}, {12, 12}, {5, 5}}}},  // collinear, folded back
      {{{{3, 3}, {9, 3}}}},                    // two vertices
      {{{{4, 4}}}},                            // one
      {{{{4, 4}, {4, 4}, {4, 4}}}},            // one place
  };
  for (const Polygon& p : degenerate) {
    for (PolygonMethod m : kMethods) {
      for (FillRule rule : {FillRule::kEvenOdd, FillRule::kNonZero}) {
        const std::vector<bool> cov = coverage(p, state(rule, m));
        EXPECT_EQ(std::count(cov.begin(), cov.end(), true), 0);
      }
    }
  }
}

// A random simple polygon: n >= 3 vertices at increasing angles around a centre, one in each
// of n equal sectors (so no gap reaches pi and the polygon is star-shaped around the centre),
// with random radii, on the 1/256-pixel grid. For n >= 5 it contains the disc of radius
// r_min cos(0.9 * 2 pi / 5) > 0.42 r_min around the centre.
std::vector<WindowVertex> random_star(std::mt19937& rng, double cx, double cy, double r_min,
                                      double r_max, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> angles;
  for (int k = 0; k < n; ++k)
    angles.push_back((k + 0.9 * u(rng)) * 2 * std::numbers::pi / n);
  std::vector<WindowVertex> out;
  for (double a : angles) {
    const double r = r_min + (r_max - r_min) * u(rng);
    out.push_back({std::round((cx + r * std::cos(a)) * 256) / 256,
                   std::round((cy + r * std::sin(a)) * 256) / 256});
  }
  return out;
}

TEST(ReferencePolygons, TessellationCoversTheSamplesTheScanlineFillCovers) {
  std::mt19937 rng(11);
  int compared = 0;
  for (int trial = 0; trial < 120; ++trial) {
    Polygon p;
    const bool holed = trial % 3 == 0;
    p.contours.push_back(random_star(rng, 24, 24, holed ? 9 : 4, 22, (holed ? 5 : 3) + trial % 14));
    if (holed) {
      // A hole inside the disc of radius 3.8 the outline contains, in either orientation.
      std::vector<WindowVertex> hole = random_star(rng, 24, 24, 1, 3.5, 3 + trial % 5);
      if (trial % 2) std::reverse(hole.begin(), hole.end());
      p.contours.push_back(hole);
    }
    if (trial % 2) std::reverse(p.contours[0].begin(), p.contours[0].end());
    for (FillRule rule : {FillRule::kEvenOdd, FillRule::kNonZero}) {
      for (uint32_t samples : {1u, 4u}) {
        const auto scan = coverage(p, state(rule, PolygonMethod::kScanline), 48, samples);
        const auto tess = coverage(p, state(rule, PolygonMethod::kTessellation), 48, samples);
        size_t differ = 0;
        for (size_t i = 0; i < scan.size(); ++i)
          differ += scan[i] != tess[i];
        EXPECT_EQ(differ, 0u) << "trial " << trial << " samples " << samples;

        EXPECT_GT(std::count(scan.begin(), scan.end(), true), 0);
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 480);
}

TEST(ReferencePolygons, PolygonsAreFlatShadedAndDepthTestedOnTheirPlane) {
  const Viewport vp{16, 16};
  for (PolygonMethod m : kMethods) {
    Renderer r(reference_options());
    Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
    fb.clear_depth(0.5f);
    Vertices v(vp, {});
    // z rises with x: 0.25 at x = 0 to 0.75 at x = 16 (a plane).
    v.add(vp, {0, 0, 0.25}, {1, 0, 0, 1});
    v.add(vp, {16, 0, 0.75}, {0, 1, 0, 1});
    v.add(vp, {16, 16, 0.75}, {0, 1, 0, 1});
    v.add(vp, {0, 16, 0.25}, {0, 0, 1, 1});
    r.draw_polygon(fb, {}, {FillRule::kEvenOdd, m}, v.input());
    const std::vector<float> depth = fb.read_depth();
    const std::vector<uint8_t> rgba = fb.read_rgba8();
    for (int x = 0; x < 16; ++x) {
      const double z = 0.25 + 0.5 * (x + 0.5) / 16;
      if (z < 0.5) {
        EXPECT_NEAR(depth[8 * 16 + x], z, 1e-6) << x;
        EXPECT_EQ(rgba[(8 * 16 + x) * 4 + 0], 255) << x;  // the first vertex's red
        EXPECT_EQ(rgba[(8 * 16 + x) * 4 + 1], 0) << x;
      } else {
        EXPECT_EQ(depth[8 * 16 + x], 0.5f) << x;
      }
    }
  }
}

}  // namespace
}  // namespace tessera::test
