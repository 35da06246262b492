// Clipping in the reference rasterizer (ARCHITECTURE.md sections 1 and 2, clip.hpp): the near
// plane cuts every triangle that crosses it, so a vertex behind the eye never wraps around;
// x and y are cut only past the guard band (32768 pixels from the viewport centre), and a cut
// triangle covers exactly the pixels the uncut one would.
//
// Near-plane cases use clip coordinates with z = w - k (a perspective projection's depth is
// affine in w), chosen so that every cut point is exact in float: the visible polygon can then
// be written down by hand and drawn directly as the reference.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/src/clip.hpp"
#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Point;
using test::SampleHits;
using test::Viewport;

struct Image {
  std::vector<float> rgba;   // resolved RGBA32F
  std::vector<float> depth;  // one per pixel
  Counters counters;
};

// Draws a triangle list with colours into a 64x64 RGBA32F framebuffer cleared to (0, 0, 0, 0)
// and depth 1.
Image render(const std::vector<Float4>& positions, const std::vector<float>& rgba,
             Interpolation interpolation = Interpolation::kPerspective) {
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({64, 64, 1, ColorFormat::kRGBA32F});
  PipelineState pipeline;
  pipeline.interpolation = interpolation;
  test::draw(renderer, fb, pipeline, positions, rgba);
  return {fb.read_rgba32f(), fb.read_depth(), renderer.counters()};
}

bool covered(const Image& image, uint32_t x, uint32_t y) {
  return image.rgba[(y * 64 + x) * 4 + 3] != 0.0f;  // every vertex has alpha 1
}

// Expects `clipped` to cover exactly the pixels `reference` covers, with the same depth and
// colour (to rounding: the two may split the polygon differently). Returns the pixel count.
int expect_same_image(const Image& clipped, const Image& reference) {
  int count = 0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      EXPECT_EQ(covered(clipped, x, y), covered(reference, x, y))
          << "pixel (" << x << ", " << y << ")";
      if (!covered(reference, x, y)) continue;
      ++count;
      const size_t p = y * 64 + x;
      EXPECT_NEAR(clipped.depth[p], reference.depth[p], 1e-6) << "pixel (" << x << ", " << y << ")";
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(clipped.rgba[p * 4 + c], reference.rgba[p * 4 + c], 1e-6)
            << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
  }
  return count;
}

const std::array<float, 4> kRed{1, 0, 0, 1};
const std::array<float, 4> kGreen{0, 1, 0, 1};
const std::array<float, 4> kBlue{0, 0, 1, 1};

std::vector<float> colors(std::initializer_list<std::array<float, 4>> per_vertex) {
  std::vector<float> out;
  for (const auto& c : per_vertex) {
    out.insert(out.end(), c.begin(), c.end());
  }
  return out;
}

// --- Near plane -------------------------------------------------------------------------------

TEST(ReferenceNearClip, OneVertexBehindTheEyeDrawsOnlyTheVisibleQuad) {
  // z = w - 1. A and B (w = 2, z = 1) are at window (16, 48) and (48, 48); C = (2, 6, -3, -2)
  // is behind the eye. The near plane z = 0 cuts AC and BC at t = 1 / (1 + 3) = 1/4:
  //   A + (C - A)/4 = (-0.25, 0.75, 0, 1) -> window (24, 8), colour 3/4 red + 1/4 blue
  //   B + (C - B)/4 = ( 1.25, 0.75, 0, 1) -> window (72, 8), colour 3/4 green + 1/4 blue
  // Projected naively, C lands at window (0, 128), below A and B: the wrapped-around triangle
  // would cover rows 48 and below, which the visible quad (rows 8..47) never reaches.
  const Viewport v{64, 64};
  const Float4 a = v.at(16, 48, 0.5, 2), b = v.at(48, 48, 0.5, 2);
  const Float4 c{2, 6, -3, -2};
  const Image clipped = render({a, b, c}, colors({kRed, kGreen, kBlue}));

  const Float4 ac{-0.25f, 0.75f, 0, 1}, bc{1.25f, 0.75f, 0, 1};
  const std::array<float, 4> ac_color{0.75f, 0, 0.25f, 1}, bc_color{0, 0.75f, 0.25f, 1};
  const Image reference =
      render({a, b, bc, a, bc, ac}, colors({kRed, kGreen, bc_color, kRed, bc_color, ac_color}));

  EXPECT_EQ(clipped.counters.triangles_clipped, 1u);
  EXPECT_EQ(reference.counters.triangles_clipped, 0u);
  EXPECT_GT(expect_same_image(clipped, reference), 1000);
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      if (y < 8 || y >= 48) {
        ASSERT_FALSE(covered(clipped, x, y)) << x << ", " << y;
      }
    }
  }
  EXPECT_TRUE(covered(clipped, 32, 30));
}

TEST(ReferenceNearClip, TwoVerticesBehindTheEyeDrawOnlyTheVisibleTriangle) {
  // z = w - 1. A (w = 2) is at window (32, 56); B = (-3, 7.5, -3, -2) and C = (3, 7.5, -3, -2)
  // are behind the eye. The cuts at t = 1/4 are (-0.75, 0.75, 0, 1) -> window (8, 8) and
  // (0.75, 0.75, 0, 1) -> window (56, 8). Naively B and C land at (80, 152) and (-16, 152),
  // below A: nothing may be drawn below row 56 or above row 8.
  const Viewport v{64, 64};
  const Float4 a = v.at(32, 56, 0.5, 2);
  const Float4 b{-3, 7.5f, -3, -2}, c{3, 7.5f, -3, -2};
  const Image clipped = render({a, b, c}, colors({kRed, kGreen, kBlue}));

  const Float4 ab{-0.75f, 0.75f, 0, 1}, ac{0.75f, 0.75f, 0, 1};
  const std::array<float, 4> ab_color{0.75f, 0.25f, 0, 1}, ac_color{0.75f, 0, 0.25f, 1};
  const Image reference = render({a, ab, ac}, colors({kRed, ab_color, ac_color}));

  EXPECT_EQ(clipped.counters.triangles_clipped, 1u);
  EXPECT_GT(expect_same_image(clipped, reference), 1000);  // about 48 * 48 / 2
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      if (y < 8 || y >= 56) {
        ASSERT_FALSE(covered(clipped, x, y)) << x << ", " << y;
      }
    }
  }
  EXPECT_TRUE(covered(clipped, 32, 30));
}

TEST(ReferenceNearClip, VertexInFrontOfTheEyeButBeforeTheNearPlaneIsCutAway) {
  // z = w - 2: A and B (w = 5, z = 3) at window (16, 48) and (48, 48); C = (1.5, 2.5, -1, 1)
  // has w > 0 but z < 0. The cuts at t = 3 / (3 + 1) = 3/4 are (0.5, 1.25, 0, 2) -> window
  // (40, 12) and (1.75, 1.25, 0, 2) -> window (60, 12). C itself projects to (80, -48), so the
  // uncut triangle would also cover rows 0..11.
  const Float4 a{-2.5f, -2.5f, 3, 5}, b{2.5f, -2.5f, 3, 5};  // window (16, 48), (48, 48)
  const Float4 c{1.5f, 2.5f, -1, 1};
  const Image clipped = render({a, b, c}, colors({kRed, kGreen, kBlue}));

  const Float4 ac{0.5f, 1.25f, 0, 2}, bc{1.75f, 1.25f, 0, 2};
  const std::array<float, 4> ac_color{0.25f, 0, 0.75f, 1}, bc_color{0, 0.25f, 0.75f, 1};
  const Image reference =
      render({a, b, bc, a, bc, ac}, colors({kRed, kGreen, bc_color, kRed, bc_color, ac_color}));

  EXPECT_EQ(clipped.counters.triangles_clipped, 1u);
  EXPECT_GT(expect_same_image(clipped, reference), 800);  // about 36 * (32 + 20) / 2
  for (uint32_t y = 0; y < 12; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      ASSERT_FALSE(covered(clipped, x, y)) << x << ", " << y;
    }
  }
}

TEST(ReferenceNearClip, AffineColoursStayLinearInScreenSpaceAcrossTheCut) {
  // The previous triangle, all of its w > 0, with affine colours: its window positions A (16,
  // 48), B (48, 48), C (80, -48) define screen-space barycentrics, and the visible part keeps
  // the colours sum b_i c_i of the uncut triangle (the cut vertices get theirs accordingly).
  const Float4 a{-2.5f, -2.5f, 3, 5}, b{2.5f, -2.5f, 3, 5}, c{1.5f, 2.5f, -1, 1};
  const Image image = render({a, b, c}, colors({kRed, kGreen, kBlue}), Interpolation::kAffine);
  EXPECT_EQ(image.counters.triangles_clipped, 1u);
  int checked = 0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      if (!covered(image, x, y)) continue;
      // Barycentrics of the centre in A, B, C: solve p = A + u (B - A) + v (C - A).
      const double px = x + 0.5 - 16, py = y + 0.5 - 48;  // relative to A
      const double det = 32.0 * -96.0 - 0.0 * 64.0;       // (B - A) x (C - A)
      const double u = (px * -96.0 - py * 64.0) / det;
      const double v = (32.0 * py - 0.0 * px) / det;
      const double expected[3] = {1 - u - v, u, v};
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_NEAR(image.rgba[(y * 64 + x) * 4 + ch], expected[ch], 1e-5)
            << "pixel (" << x << ", " << y << ") channel " << ch;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 800);
}

TEST(ReferenceNearClip, TriangleEntirelyBehindTheEyeDrawsNothing) {
  // The negation of a visible triangle: (x, y, z, w) -> (-x, -y, -z, -w) projects to the same
  // window positions, but lies behind the eye.
  const Viewport v{64, 64};
  std::vector<Float4> visible = {v.at(4, 4), v.at(60, 4), v.at(4, 60)};
  std::vector<Float4> behind;
  for (const Float4& p : visible) {
    behind.push_back({-p.x, -p.y, -p.z, -p.w});
  }
  const Image image = render(behind, colors({kRed, kRed, kRed}));
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      ASSERT_FALSE(covered(image, x, y)) << x << ", " << y;
    }
  }
  EXPECT_EQ(image.counters.samples_covered, 0u);
  EXPECT_EQ(image.counters.triangles_rasterized, 0u);
  EXPECT_EQ(image.counters.triangles_culled, 1u);
  EXPECT_GT(render(visible, colors({kRed, kRed, kRed})).counters.samples_covered, 1000u);
}

// --- Guard band -------------------------------------------------------------------------------
// A triangle whose edge y = x + 10 crosses the 64x64 viewport, the rest of it far away to the
// upper right. The edge is a left edge (the triangle lies to its right), so pixel (i, j) is
// covered exactly when j + 0.5 <= i + 0.5 + 10, i.e. j <= i + 10, centres on it included.
// Every point of the edge with an integer x has an integer y, so where the guard band cuts it
// the cut points snap back exactly onto it.

void expect_covers_right_of_the_diagonal(const SampleHits& hits) {
  uint64_t expected = 0;
  for (uint32_t j = 0; j < 64; ++j) {
    for (uint32_t i = 0; i < 64; ++i) {
      const int inside = j <= i + 10 ? 1 : 0;
      expected += static_cast<uint64_t>(inside);
      ASSERT_EQ(hits.at(i, j), inside) << "pixel (" << i << ", " << j << ")";
    }
  }
  EXPECT_EQ(hits.counters().samples_covered, expected) << "a sample was covered twice";
}

TEST(ReferenceGuardBand, TriangleFarOutsideTheViewportButInsideTheBandIsNotClipped) {
  // Vertices 20000 pixels out, well inside the band.
  const Viewport v{64, 64};
  SampleHits hits(64, 64);
  hits.add({v.at(-20000, -19990), v.at(20000, 20010), v.at(20000, -20000)});
  EXPECT_EQ(hits.counters().triangles_clipped, 0u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
  expect_covers_right_of_the_diagonal(hits);
}

TEST(ReferenceGuardBand, TriangleBeyondTheBandIsClippedAndCoversTheSamePixels) {
  // The same edge, with vertices 100000 pixels out, past the band.
  const Viewport v{64, 64};
  SampleHits hits(64, 64);
  hits.add({v.at(-100000, -99990), v.at(100000, 100010), v.at(100000, -100000)});
  EXPECT_EQ(hits.counters().triangles_clipped, 1u);
  expect_covers_right_of_the_diagonal(hits);
}

TEST(ReferenceGuardBand, TriangleJustInsideTheBandIsNotClippedAndJustOutsideIs) {
  // The band reaches 32768 pixels from the viewport centre (32, 32): x in [-32736, 32800].
  const Viewport v{64, 64};
  SampleHits inside(64, 64), outside(64, 64);
  inside.add({v.at(-32736, -10), v.at(32800, -10), v.at(32, 60)});
  outside.add({v.at(-32737, -10), v.at(32800, -10), v.at(32, 60)});
  EXPECT_EQ(inside.counters().triangles_clipped, 0u);
  EXPECT_EQ(outside.counters().triangles_clipped, 1u);
  for (uint32_t j = 0; j < 64; ++j) {
    for (uint32_t i = 0; i < 64; ++i) {
      ASSERT_EQ(inside.at(i, j), outside.at(i, j));
    }
  }
  EXPECT_GT(inside.total(), 1000u);
}

TEST(ReferenceGuardBand, TwoClippedTrianglesSharingAnEdgeCoverEachSampleOnce) {
  // A quad 100000 pixels out on every side, split along a diagonal of an awkward slope that
  // crosses the 16x16 viewport. Both halves are cut by the band at bit-identical points on the
  // shared edge, so every sample of the viewport is covered exactly once.
  const Viewport v{16, 16};
  const Point p{-99997, -77777}, q{100003, 77789};
  const Point r{100003, -100000}, s{-99997, 100000};
  SampleHits hits(16, 16, 16);
  hits.add({v.at(p), v.at(r), v.at(q), v.at(p), v.at(q), v.at(s)});
  EXPECT_EQ(hits.counters().triangles_clipped, 2u);
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) {
      for (uint32_t k = 0; k < 16; ++k) {
        ASSERT_EQ(hits.at(x, y, k), 1) << "pixel (" << x << ", " << y << ") sample " << k;
      }
    }
  }
}

// --- Shared edges are cut identically ----------------------------------------------------------
// Through the clipper directly (clip.hpp): two triangles sharing an edge P-Q, listed in
// opposite directions, get bit-identical cut points on it, for many pseudo-random edges
// crossing the near plane or the guard band. Watertightness past the band depends on it.

ClipVertex clip_vertex(double x, double y, double z, double w, double attribute) {
  ClipVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.w = w;
  v.attributes[0] = attribute;
  return v;
}

// The vertex of `polygon` nearest to `point` (in x, y, z, w).
const ClipVertex& nearest(const ClipPolygon& polygon, const ClipVertex& point) {
  int best = 0;
  double best_d = 1e300;
  for (int i = 0; i < polygon.count; ++i) {
    const ClipVertex& v = polygon.vertices[i];
    const double d = std::abs(v.x - point.x) + std::abs(v.y - point.y) + std::abs(v.z - point.z) +
                     std::abs(v.w - point.w);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return polygon.vertices[best];
}

TEST(ReferenceClipper, SharedEdgeIsCutAtBitIdenticalPointsInBothTriangles) {
  uint64_t state = 12345;
  auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  const GuardBand band = GuardBand::for_viewport(64, 64);  // |x|, |y| <= 1024 w
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    const bool near = trial % 2 == 0;
    // P outside (behind the near plane, or past the left guard band), Q, R, S inside.
    const ClipVertex p = near ? clip_vertex(uniform(-1, 1), uniform(-1, 1), uniform(-2, -0.1),
                                            uniform(0.5, 2), uniform(0, 1))
                              : clip_vertex(uniform(-3000, -1100), uniform(-1, 1),
                                            uniform(0.1, 0.9), 1, uniform(0, 1));
    const ClipVertex q = clip_vertex(uniform(-1, 1), uniform(-1, 1), uniform(0.1, 0.9),
                                     uniform(1, 2), uniform(0, 1));
    const ClipVertex r = clip_vertex(uniform(-1, 1), uniform(-1, 1), uniform(0.1, 0.9), 1, 0.5);
    const ClipVertex s = clip_vertex(uniform(-1, 1), uniform(-1, 1), uniform(0.1, 0.9), 1, 0.5);

    ClipPolygon first, second;
    ASSERT_TRUE(clip_triangle({p, r, q}, 1, band, first).clipped);   // edge Q -> P
    ASSERT_TRUE(clip_triangle({p, q, s}, 1, band, second).clipped);  // edge P -> Q
    // Where the plane crosses P-Q, roughly.
    const double dp = near ? p.z : p.x + 1024 * p.w, dq = near ? q.z : q.x + 1024 * q.w;
    const double t = dq / (dq - dp);
    const ClipVertex approx = clip_vertex(q.x + t * (p.x - q.x), q.y + t * (p.y - q.y),
                                          q.z + t * (p.z - q.z), q.w + t * (p.w - q.w), 0);
    const ClipVertex& a = nearest(first, approx);
    const ClipVertex& b = nearest(second, approx);
    ASSERT_NEAR(a.x, approx.x, 1e-9 * (1 + std::abs(approx.x)));
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
    EXPECT_EQ(a.w, b.w);
    EXPECT_EQ(a.attributes[0], b.attributes[0]);
  }
}

}  // namespace
}  // namespace tessera
