// Lines in the reference rasterizer (primitives.hpp, docs/PRIMITIVES.md): hand-computed pixel
// lists for the diamond-exit rule, midpoint/Bresenham and DDA in all eight octants and at
// ties; horizontal, vertical and 45-degree lines; polyline joints hit once; the lecture's
// stipple table; clipping at every viewport edge, the guard band and the near plane; depth
// test and perspective-correct colour along a line.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "tests/primitive_test_support.hpp"
#include "tests/watchdog.hpp"

namespace tessera::test {
namespace {

PixelSet line(LineAlgorithm algorithm, WindowVertex a, WindowVertex b, uint32_t size = 20,
              LineState state = {}) {
  const Viewport vp{size, size};
  state.algorithm = algorithm;
  return touched(size, size, [&](Renderer& r, Framebuffer& fb) {
    const Vertices v(vp, {a, b});
    r.draw_lines(fb, touch_pipeline(), state, v.input());
  });
}

PixelSet offsets_from(int x, int y, std::initializer_list<Pixel> offsets) {
  PixelSet s;
  for (const Pixel& o : offsets)
    s.insert({x + o.first, y + o.second});
  return s;
}

// A line from the centre of pixel (8, 8) by (dx, dy) pixels, |dx|, |dy| in {2, 5}: no ties,
// so every algorithm draws the pixels nearest the line, and the diamond-exit rule leaves out
// the last one (the line ends inside its diamond).
struct Octant {
  int dx, dy;
  std::vector<Pixel> pixels;  // offsets from (8, 8), in order from the start
};
const std::vector<Octant>& octants() {
  static const std::vector<Octant> table = {
      {5, 2, {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}}},
      {2, 5, {{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}}},
      {-2, 5, {{0, 0}, {0, 1}, {-1, 2}, {-1, 3}, {-2, 4}, {-2, 5}}},
      {-5, 2, {{0, 0}, {-1, 0}, {-2, 1}, {-3, 1}, {-4, 2}, {-5, 2}}},
      {-5, -2, {{0, 0}, {-1, 0}, {-2, -1}, {-3, -1}, {-4, -2}, {-5, -2}}},
      {-2, -5, {{0, 0}, {0, -1}, {-1, -2}, {-1, -3}, {-2, -4}, {-2, -5}}},
      {2, -5, {{0, 0}, {0, -1}, {1, -2}, {1, -3}, {2, -4}, {2, -5}}},
      {5, -2, {{0, 0}, {1, 0}, {2, -1}, {3, -1}, {4, -2}, {5, -2}}},
  };
  return table;
}

TEST(ReferenceLines, EveryAlgorithmDrawsTheNearestPixelsInAllEightOctants) {
  for (const Octant& o : octants()) {
    const WindowVertex a{8.5, 8.5}, b{8.5 + o.dx, 8.5 + o.dy};
    PixelSet all;
    for (const Pixel& p : o.pixels)
      all.insert({8 + p.first, 8 + p.second});
    PixelSet without_end = all;
    without_end.erase({8 + o.pixels.back().first, 8 + o.pixels.back().second});
    const std::string what = "octant (" + std::to_string(o.dx) + ", " + std::to_string(o.dy) + ")";
    EXPECT_EQ(line(LineAlgorithm::kBresenham, a, b), all) << what;
    EXPECT_EQ(line(LineAlgorithm::kDDA, a, b), all) << what;
    EXPECT_EQ(line(LineAlgorithm::kDiamondExit, a, b), without_end) << what;
    // Bresenham and DDA order the endpoints: the reversed line draws the same pixels.
    EXPECT_EQ(line(LineAlgorithm::kBresenham, b, a), all) << what;
    EXPECT_EQ(line(LineAlgorithm::kDDA, b, a), all) << what;
  }
}

TEST(ReferenceLines, TiesAreBrokenAsDocumentedForEachAlgorithm) {
  // Slope 1/2 from the centre of (0, 0) to the centre of (8, 4): every other column's ideal
  // y lies exactly between two pixel centres.
  const WindowVertex a{0.5, 0.5}, b{8.5, 4.5};
  // Midpoint: on a tie the minor coordinate does not step.
  EXPECT_EQ(
      line(LineAlgorithm::kBresenham, a, b),
      offsets_from(0, 0, {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}, {6, 3}, {7, 3}, {8, 4}}));
  // DDA rounds half up.
  EXPECT_EQ(
      line(LineAlgorithm::kDDA, a, b),
      offsets_from(0, 0, {{0, 0}, {1, 1}, {2, 1}, {3, 2}, {4, 2}, {5, 3}, {6, 3}, {7, 4}, {8, 4}}));
  // Diamond exit: the nudge (e, e^2) moves the line right, so a tie goes to the upper row;
  // the end pixel is not drawn.
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, a, b),
            offsets_from(0, 0, {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}, {6, 3}, {7, 3}}));
  // Reversed, it starts at (8, 4) and stops before (0, 0).
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, b, a),
            offsets_from(0, 0, {{8, 4}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}, {6, 3}, {7, 3}}));
}

TEST(ReferenceLines, HorizontalVerticalAndDiagonalLinesThroughPixelCentres) {
  for (LineAlgorithm alg :
       {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
    const bool end = alg != LineAlgorithm::kDiamondExit;
    PixelSet h = offsets_from(1, 2, {{0, 0}, {1, 0}, {2, 0}, {3, 0}});
    PixelSet v = offsets_from(2, 1, {{0, 0}, {0, 1}, {0, 2}, {0, 3}});
    PixelSet d = offsets_from(1, 1, {{0, 0}, {1, 1}, {2, 2}, {3, 3}});
    if (end) h.insert({5, 2}), v.insert({2, 5}), d.insert({5, 5});
    EXPECT_EQ(line(alg, {1.5, 2.5}, {5.5, 2.5}), h);
    EXPECT_EQ(line(alg, {2.5, 1.5}, {2.5, 5.5}), v);
    EXPECT_EQ(line(alg, {1.5, 1.5}, {5.5, 5.5}), d);
  }
  // Endpoints off the centres. Starting or ending inside a diamond (distance below 1/2 from
  // the centre) draws or skips that pixel whatever the column centre.
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, {1.25, 2.5}, {5.25, 2.5}),
            offsets_from(1, 2, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, {1.75, 2.5}, {5.75, 2.5}),
            offsets_from(1, 2, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // At y = 2.9 an end at x = 5.2 is in no diamond, and the line never reaches column 5's
  // diamond; at x = 5.6 it has crossed column 5's centre and left its diamond ((5.6, 2.9) is
  // on the border, and the nudge moves it out).
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, {1.5, 2.9}, {5.2, 2.9}),
            offsets_from(1, 2, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, {1.5, 2.9}, {5.6, 2.9}),
            offsets_from(1, 2, {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}}));
}

TEST(ReferenceLines, ZeroLengthLinesDrawNothing) {
  for (LineAlgorithm alg :
       {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
    EXPECT_TRUE(line(alg, {3.5, 3.5}, {3.5, 3.5}).empty());
    EXPECT_TRUE(line(alg, {3.2, 3.7}, {3.2, 3.7}).empty());
  }
  // A short line inside one pixel is not degenerate: midpoint and DDA draw that pixel.
  EXPECT_EQ(line(LineAlgorithm::kBresenham, {3.2, 3.5}, {3.7, 3.5}), PixelSet({{3, 3}}));
  EXPECT_EQ(line(LineAlgorithm::kDDA, {3.2, 3.5}, {3.7, 3.5}), PixelSet({{3, 3}}));
}

// Hits per pixel of the segments of a polyline, each drawn on its own.
std::map<Pixel, int> polyline_hits(const std::vector<WindowVertex>& points, uint32_t size) {
  std::map<Pixel, int> hits;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    for (const Pixel& p : line(LineAlgorithm::kDiamondExit, points[i], points[i + 1], size))
      ++hits[p];
  }
  return hits;
}

TEST(ReferenceLines, DiamondExitPolylineJointsAreHitOnce) {
  // Joints (10.3, 5.6) and (4.3, 12.4) lie inside the diamonds of pixels (10, 5) and (4, 12).
  const std::vector<WindowVertex> strip = {{2.5, 2.5}, {10.3, 5.6}, {4.3, 12.4}, {13.7, 13.1}};
  const auto hits = polyline_hits(strip, 16);
  for (const auto& [pixel, n] : hits)
    EXPECT_EQ(n, 1) << pixel.first << "," << pixel.second;
  EXPECT_EQ(hits.at({10, 5}), 1);
  EXPECT_EQ(hits.at({4, 12}), 1);

  // Drawn as one strip, the same pixels.
  const Viewport vp{16, 16};
  const PixelSet as_strip = touched(16, 16, [&](Renderer& r, Framebuffer& fb) {
    Vertices v(vp, {});
    for (const WindowVertex& p : strip)
      v.add(vp, p);
    LineState state;
    state.topology = LineTopology::kStrip;
    r.draw_lines(fb, touch_pipeline(), state, v.input());
  });
  PixelSet from_hits;
  for (const auto& [pixel, n] : hits)
    from_hits.insert(pixel);
  EXPECT_EQ(as_strip, from_hits);
}

TEST(ReferenceLines, DiamondExitJointsOfRandomPolylinesAreHitOnce) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(2 * 256, 30 * 256);  // 1/256-pixel grid
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<WindowVertex> pts;
    for (int k = 0; k < 3; ++k)
      pts.push_back({coord(rng) / 256.0, coord(rng) / 256.0});
    // The pixel whose diamond holds the joint, if any (with a margin, away from borders).
    const double jx = pts[1].x, jy = pts[1].y;
    const int px = static_cast<int>(std::floor(jx)), py = static_cast<int>(std::floor(jy));
    if (std::abs(jx - px - 0.5) + std::abs(jy - py - 0.5) > 0.45) continue;
    const auto hits = polyline_hits(pts, 32);
    EXPECT_EQ(hits.count({px, py}) ? hits.at({px, py}) : 0, 1)
        << "joint (" << jx << ", " << jy << ") from (" << pts[0].x << ", " << pts[0].y << ") to ("
        << pts[2].x << ", " << pts[2].y << ")";
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(ReferenceLines, DiamondExitLineSplitAtAPixelCentreDrawsTheSamePixels) {
  // (3.5, 4.5) -> (9.5, 7.5) -> (15.5, 10.5) is one straight line through a pixel centre.
  const PixelSet whole = line(LineAlgorithm::kDiamondExit, {3.5, 4.5}, {15.5, 10.5});
  PixelSet halves = line(LineAlgorithm::kDiamondExit, {3.5, 4.5}, {9.5, 7.5});
  const PixelSet second = line(LineAlgorithm::kDiamondExit, {9.5, 7.5}, {15.5, 10.5});
  for (const Pixel& p : second)
    EXPECT_TRUE(halves.insert(p).second) << "hit twice: " << p.first << "," << p.second;
  EXPECT_EQ(halves, whole);
}

// The lecture's glLineStipple table, on a horizontal line whose fragment s is column s.
TEST(ReferenceLines, StipplePatternsGiveTheLecturesRuns) {
  struct Row {
    uint16_t pattern;
    uint32_t factor;
    const char* runs;
  };
  const Row table[] = {
      {0x00FF, 1, "XXXXXXXX........XXXXXXXX........"},
      {0x00FF, 2, "XXXXXXXXXXXXXXXX................"},
      {0x00FF, 3, "XXXXXXXXXXXXXXXXXXXXXXXX........"},
      {0x00FF, 4, "XXXXXXXXXXXXXXXXXXXXXXXXXXXXXXXX"},
      {0x0C0F, 1, "XXXX......XX....XXXX......XX...."},
      {0x0C0F, 2, "XXXXXXXX............XXXX........"},
      {0x0C0F, 3, "XXXXXXXXXXXX..................XX"},
      {0x0C0F, 4, "XXXXXXXXXXXXXXXX................"},
      {0xAAAA, 1, ".X.X.X.X.X.X.X.X.X.X.X.X.X.X.X.X"},
      {0xAAAA, 2, "..XX..XX..XX..XX..XX..XX..XX..XX"},
      {0xAAAA, 3, "...XXX...XXX...XXX...XXX...XXX.."},
      {0xAAAA, 4, "....XXXX....XXXX....XXXX....XXXX"},
  };
  for (const Row& row : table) {
    ASSERT_EQ(std::string(row.runs).size(), 32u);
    for (LineAlgorithm alg :
         {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
      LineState state;
      state.stipple = {row.pattern, row.factor};
      const PixelSet s = line(alg, {0.5, 0.5}, {40.5, 0.5}, 32, state);
      EXPECT_EQ(row_picture(s, 0, 32), row.runs)
          << std::hex << "pattern 0x" << row.pattern << std::dec << " factor " << row.factor;
    }
  }
}

TEST(ReferenceLines, StippleCounterRunsOnAcrossAStripAndRestartsPerListSegment) {
  const Viewport vp{32, 4};
  auto draw = [&](LineTopology topology) {
    return touched(32, 4, [&](Renderer& r, Framebuffer& fb) {
      LineState state;
      state.topology = topology;
      state.stipple = {0x00FF, 1};
      const Vertices strip(vp, {{0.5, 0.5}, {12.5, 0.5}, {40.5, 0.5}});
      const Vertices list(vp, {{0.5, 0.5}, {12.5, 0.5}, {12.5, 0.5}, {40.5, 0.5}});
      r.draw_lines(fb, touch_pipeline(), state,
                   topology == LineTopology::kStrip ? strip.input() : list.input());
    });
  };
  EXPECT_EQ(row_picture(draw(LineTopology::kStrip), 0, 32), "XXXXXXXX........XXXXXXXX........");
  EXPECT_EQ(row_picture(draw(LineTopology::kList), 0, 32), "XXXXXXXX....XXXXXXXX........XXXX");
}

// A strip that runs 143,200 times across the guard band off screen (30,001 steps a time, over
// 2^32 in all) before it comes on screen stipples as one whose off-screen part is 16 steps: the
// counter is kept modulo the pattern's period (48 steps here), and does not wrap at 2^32 (which
// shifted the pattern by 2^32 mod 48 = 16 steps).
TEST(ReferenceLines, StippleOfAStripLongerThanTwoToTheThirtyTwoStepsKeepsItsPhase) {
  const Viewport vp{64, 16};
  auto draw = [&](uint32_t crossings, double first_x, Backend backend) {
    Vertices strip(vp, {{first_x, -100.5}});
    for (uint32_t i = 0; i < crossings; ++i)
      strip.add(vp, {i % 2 == 0 ? 30001.5 : 0.5, -100.5});
    strip.add(vp, {0.5, -100.5});
    strip.add(vp, {0.5, 8.5});
    strip.add(vp, {63.5, 8.5});
    return touched(
        64, 16,
        [&](Renderer& r, Framebuffer& fb) {
          LineState state;
          state.topology = LineTopology::kStrip;
          state.stipple = {0x00FF, 3};
          r.draw_lines(fb, touch_pipeline(), state, strip.input());
        },
        1, backend);
  };
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    SCOPED_TRACE(backend == Backend::kFast ? "fast" : "reference");
    const PixelSet long_strip = draw(143200, 0.5, backend);
    const PixelSet short_strip = draw(0, 16.5, backend);  // 143,200 x 30,001 = 16 (mod 48)
    EXPECT_EQ(row_picture(long_strip, 8, 64), row_picture(short_strip, 8, 64));
    EXPECT_EQ(long_strip, short_strip);
    EXPECT_NE(short_strip, draw(0, 0.5, backend));  // the phase shows
  }
}

// The pixels of a line in a 16x16 viewport equal those of the same window-space line in the
// middle of a 48x48 one: clipping against the viewport never moves a visible pixel.
TEST(ReferenceLines, LinesCrossingEveryViewportEdgeAreClippedWithoutMovingPixels) {
  const std::vector<std::pair<WindowVertex, WindowVertex>> lines = {
      {{7.3, 8.6}, {-9.2, 3.1}},   {{7.3, 8.6}, {25.7, 12.2}},   {{7.3, 8.6}, {2.1, -11.4}},
      {{7.3, 8.6}, {11.9, 27.3}},  {{-5.1, -3.3}, {21.4, 19.8}}, {{-3.7, 20.2}, {19.6, -4.4}},
      {{-30.2, 7.7}, {40.9, 8.3}}, {{4.4, -20.5}, {5.2, 36.6}},
  };
  for (LineAlgorithm alg :
       {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
    for (const auto& [a, b] : lines) {
      const PixelSet small = line(alg, a, b, 16);
      const PixelSet big = line(alg, {a.x + 16, a.y + 16}, {b.x + 16, b.y + 16}, 48);
      PixelSet window;
      for (const Pixel& p : big) {
        if (p.first >= 16 && p.first < 32 && p.second >= 16 && p.second < 32)
          window.insert({p.first - 16, p.second - 16});
      }
      EXPECT_EQ(small, window) << "(" << a.x << ", " << a.y << ") -> (" << b.x << ", " << b.y
                               << ")";
      EXPECT_FALSE(small.empty());
    }
  }
}

TEST(ReferenceLines, LinesBeyondTheGuardBandAndNearPlaneAreClippedInClipSpace) {
  // To x = -100000 pixels, far past the guard band: the part on screen is unchanged.
  EXPECT_EQ(line(LineAlgorithm::kDiamondExit, {4.5, 7.5}, {-100000.0, 7.5}, 16),
            offsets_from(0, 7, {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}}));

  // A line from z = 0.5 to z = -0.5 (w = 1) is cut at z = 0, halfway: window x 4.5 to 8.5.
  const Viewport vp{16, 16};
  auto clip_line = [&](Float4 a, Float4 b) {
    return touched(16, 16, [&](Renderer& r, Framebuffer& fb) {
      const std::vector<Float4> pos = {a, b};
      const std::vector<float> rgba = {1, 1, 1, 1, 1, 1, 1, 1};
      r.draw_lines(fb, touch_pipeline(), {}, {pos, rgba, 4, {}});
    });
  };
  EXPECT_EQ(clip_line({-0.4375f, 0.0625f, 0.5f, 1}, {0.5625f, 0.0625f, -0.5f, 1}),
            offsets_from(4, 7, {{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // Through the eye to w = -1: cut at z = 0 (t = 1/4, w = 1/2), window (4.5, 7.5) to
  // (4.75, 7.0); nothing of the part behind the eye wraps around to the other side.
  EXPECT_EQ(clip_line({-0.4375f, 0.0625f, 0.5f, 1}, {0.5f, 0.0625f, -1.5f, -1}),
            PixelSet({{4, 7}}));
  // Wholly behind the near plane: nothing.
  EXPECT_TRUE(clip_line({-0.5f, 0, -0.5f, 1}, {0.5f, 0, -0.25f, 1}).empty());
  (void)vp;
}

// A segment from A to a vertex at w = 0 (the homogeneous origin, or a point at infinity too
// near it to leave the w plane's reach) is cut at the w plane next to A: it projects onto A's
// window point and draws nothing. With the cut computed as a + t (b - a), t rounded to 1 and the
// vertex at w = 0 was kept as it was, and the viewport transform divided by 0.
TEST(ReferenceLines, LinesToVerticesAtWZeroAreCutAtTheWPlaneNextToTheirOtherEnd) {
  const Watchdog watchdog(60);                    // the division by 0 led the line walk on forever
  const Float4 a = {-0.4375f, 0.5625f, 0.5f, 1};  // window (4.5, 3.5)
  for (const Float4& b : {Float4{0, 0, 0, 0}, Float4{1e-45f, 0, 0, 0}}) {
    for (LineAlgorithm algorithm :
         {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
      SCOPED_TRACE(b.x);
      LineState state;
      state.algorithm = algorithm;
      const PixelSet drawn = touched(16, 16, [&](Renderer& r, Framebuffer& fb) {
        const std::vector<Float4> pos = {a, b};
        const std::vector<float> rgba = {1, 1, 1, 1, 1, 1, 1, 1};
        r.draw_lines(fb, touch_pipeline(), state, {pos, rgba, 4, {}});
      });
      EXPECT_LE(drawn.size(), 1u) << describe(drawn);
      EXPECT_TRUE(drawn.empty() || *drawn.begin() == Pixel(4, 3)) << describe(drawn);
    }
  }
}

TEST(ReferenceLines, LinesAreDepthTested) {
  const Viewport vp{16, 16};
  Renderer r(reference_options());
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  fb.clear_depth(0.5f);
  const Vertices near(vp, {{0.5, 3.5, 0.25}, {16.5, 3.5, 0.25}});
  const Vertices far(vp, {{0.5, 9.5, 0.75}, {16.5, 9.5, 0.75}});
  r.draw_lines(fb, {}, {}, near.input());
  r.draw_lines(fb, {}, {}, far.input());
  const std::vector<float> depth = fb.read_depth();
  const std::vector<uint8_t> rgba = fb.read_rgba8();
  for (int x = 0; x < 16; ++x) {
    EXPECT_EQ(depth[3 * 16 + x], 0.25f);
    EXPECT_EQ(rgba[(3 * 16 + x) * 4], 255);
    EXPECT_EQ(depth[9 * 16 + x], 0.5f);
    EXPECT_EQ(rgba[(9 * 16 + x) * 4], 0);
  }
  EXPECT_EQ(r.counters().lines_submitted, 2u);
}

TEST(ReferenceLines, ColourAndDepthArePerspectiveCorrectAlongTheLine) {
  // From w = 1 to w = 3, red 0 to 1, z/w 0.2 to 0.6: at screen parameter t the colour is
  // t / 3 / ((1 - t) + t / 3) and z/w is 0.2 + 0.4 t.
  const Viewport vp{32, 4};
  Renderer r(reference_options());
  Framebuffer fb({32, 4, 1, ColorFormat::kRGBA32F});
  Vertices v(vp, {});
  v.add(vp, {0.5, 1.5, 0.2, 1.0}, {0, 0, 0, 1});
  v.add(vp, {32.5, 1.5, 0.6, 3.0}, {1, 0, 0, 1});
  PipelineState p;
  p.depth_compare = CompareOp::kAlways;
  r.draw_lines(fb, p, {}, v.input());
  const std::vector<float> rgba = fb.read_rgba32f();
  const std::vector<float> depth = fb.read_depth();
  for (int x : {0, 8, 16, 24, 31}) {
    const double t = x / 32.0;
    EXPECT_NEAR(rgba[(1 * 32 + x) * 4], t / 3 / ((1 - t) + t / 3), 1e-5) << x;
    EXPECT_NEAR(depth[1 * 32 + x], 0.2 + 0.4 * t, 1e-6) << x;
  }
  // Affine: linear in the window.
  Framebuffer affine({32, 4, 1, ColorFormat::kRGBA32F});
  p.interpolation = Interpolation::kAffine;
  r.draw_lines(affine, p, {}, v.input());
  const std::vector<float> lin = affine.read_rgba32f();
  EXPECT_NEAR(lin[(1 * 32 + 16) * 4], 0.5, 1e-5);
}

}  // namespace
}  // namespace tessera::test
