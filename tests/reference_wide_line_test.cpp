// Wide lines (primitives.hpp): rectangles of the line's width point-sampled with the
// triangles' fill rule, cut into dashes by the stipple, and the joins of strips (miter with
// its limit, round, bevel, none), with hand-counted pixels.
#include <gtest/gtest.h>

#include <vector>

#include "engine/src/primitive_triangles.hpp"
#include "tests/primitive_test_support.hpp"

namespace tessera::test {
namespace {

PixelSet wide(const std::vector<WindowVertex>& points, LineState state, uint32_t size = 16) {
  const Viewport vp{size, size};
  return touched(size, size, [&](Renderer& r, Framebuffer& fb) {
    Vertices v(vp, {});
    for (const WindowVertex& p : points)
      v.add(vp, p);
    r.draw_lines(fb, touch_pipeline(), state, v.input());
  });
}

PixelSet rect(int x0, int y0, int x1, int y1) {  // inclusive
  PixelSet s;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x)
      s.insert({x, y});
  }
  return s;
}

PixelSet operator|(PixelSet a, const PixelSet& b) {
  a.insert(b.begin(), b.end());
  return a;
}

TEST(ReferenceWideLines, WideLinesAreRectanglesSampledWithTheFillRule) {
  LineState s;
  s.width = 3;
  // y in [6.5, 9.5): the top edge holds row 6's centres (inside), the bottom edge row 9's
  // (outside); x in [2, 12): columns 2..11.
  EXPECT_EQ(wide({{2, 8}, {12, 8}}, s), rect(2, 6, 11, 8));
  s.width = 2;
  EXPECT_EQ(wide({{5, 2}, {5, 10}}, s), rect(4, 2, 5, 9));
}

TEST(ReferenceWideLines, JoinsFillTheOuterCornerOfAStrip) {
  // Width 4, right along y = 10 then up along x = 10: the rectangles leave the outer corner
  // square [10, 12] x [10, 12] (pixels 10..11) open.
  const std::vector<WindowVertex> strip = {{2, 10}, {10, 10}, {10, 2}};
  const PixelSet legs = rect(2, 8, 9, 11) | rect(8, 2, 11, 9);
  LineState s;
  s.width = 4;
  s.topology = LineTopology::kStrip;
  s.join = LineJoin::kNone;
  EXPECT_EQ(wide(strip, s), legs);
  // Miter: the whole corner square (the miter of a right angle is sqrt(2) half-widths).
  s.join = LineJoin::kMiter;
  EXPECT_EQ(wide(strip, s), legs | rect(10, 10, 11, 11));
  // Bevel: the triangle (10, 10), (12, 10), (10, 12); the centres (11.5, 10.5) and
  // (10.5, 11.5) lie on its hypotenuse, a right edge, so only (10, 10) is added.
  s.join = LineJoin::kBevel;
  EXPECT_EQ(wide(strip, s), legs | PixelSet({{10, 10}}));
  // Round: a disc of radius 2 at (10, 10) holds the centres at 0.71 and 1.58 from it, not the
  // one at 2.12.
  s.join = LineJoin::kRound;
  EXPECT_EQ(wide(strip, s), legs | PixelSet({{10, 10}, {11, 10}, {10, 11}}));
  // A miter longer than the limit falls back to a bevel.
  s.join = LineJoin::kMiter;
  s.miter_limit = 1.4f;
  EXPECT_EQ(wide(strip, s), legs | PixelSet({{10, 10}}));
  // A loop joins its last segment to the first as well.
  s.topology = LineTopology::kLoop;
  s.miter_limit = 4;
  // Its four sides span [1, 14] around a hole [5, 10], and the mitred corners close the
  // frame: pixels 1..13 except the hole's 5..9.
  PixelSet frame = rect(1, 1, 13, 13);
  for (const Pixel& p : rect(5, 5, 9, 9))
    frame.erase(p);
  const PixelSet loop = wide({{3, 3}, {12, 3}, {12, 12}, {3, 12}}, s);
  EXPECT_EQ(loop, frame) << describe(loop);
}

TEST(ReferenceWideLines, StippleCutsWideLinesIntoDashes) {
  LineState s;
  s.width = 3;
  s.stipple = {0x00FF, 1};
  const PixelSet dashes = wide({{0, 8}, {32, 8}}, s, 32);
  EXPECT_EQ(dashes, rect(0, 6, 7, 8) | rect(16, 6, 23, 8));
}

// A stippled wide line across the whole guard band (64,000 steps, 32,000 one-pixel dashes)
// draws the dashes that reach the viewport and no others: the same pixels as the part from 16
// steps before the viewport, whose steps have the same parity, and a few triangles, not 64,000.
TEST(ReferenceWideLines, StippledWideLinesDrawOnlyTheDashesThatReachTheViewport) {
  LineState s;
  s.width = 3;
  s.stipple = {0x5555, 1};  // every even step
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    SCOPED_TRACE(backend == Backend::kFast ? "fast" : "reference");
    const Viewport vp{16, 16};
    Counters counters;
    auto draw = [&](double x0, double x1) {
      return touched(
          16, 16,
          [&](Renderer& r, Framebuffer& fb) {
            const Vertices v(vp, {{x0, 8}, {x1, 8}});
            r.draw_lines(fb, touch_pipeline(), s, v.input());
            counters = r.counters();
          },
          1, backend);
    };
    const PixelSet across = draw(-32000, 32000);
    EXPECT_GT(counters.triangles_submitted, 0u);
    EXPECT_LT(counters.triangles_submitted, 40u);
    EXPECT_EQ(across, draw(-16, 32));
    PixelSet expected;
    for (int x = 0; x < 16; x += 2)
      expected.insert({{x, 6}, {x, 7}, {x, 8}});
    EXPECT_EQ(across, expected);
  }
}

// A line list whose dashes make far more triangles than one chunk reaches the triangle pipeline
// in lists of about kWideLineChunk triangles, in order, each segment's dashes whole: 3,000
// segments across a 64-pixel viewport, each cut into 32 one-step dashes (64 triangles).
TEST(ReferenceWideLines, ManyStippledWideLinesReachTheTrianglesInBoundedLists) {
  LineState s;
  s.width = 3;
  s.stipple = {0x5555, 1};
  std::vector<WindowSegment> segments(3000);
  for (size_t i = 0; i < segments.size(); ++i) {
    const double y = 8.5 + static_cast<double>(i % 48);
    segments[i].a.x = 0.0;
    segments[i].b.x = 64.0;
    segments[i].a.y = segments[i].b.y = y;
    segments[i].a.color[0] = segments[i].b.color[0] = static_cast<float>(i) / 4096.0f;
  }
  constexpr size_t kPerSegment = 64;
  std::vector<size_t> sizes;
  std::vector<float> first_red;  // the first vertex's red of each list: whose segment it is
  wide_lines(segments, s, 64, 64, [&](const TriangleList& list) {
    ASSERT_EQ(list.positions.size() % 3, 0u);
    ASSERT_EQ(list.colors.size(), 4 * list.positions.size());
    sizes.push_back(list.positions.size() / 3);
    first_red.push_back(list.colors[0]);
  });
  size_t total = 0;
  for (size_t k = 0; k < sizes.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(sizes[k] % kPerSegment, 0u);  // no segment's dashes split
    EXPECT_LE(sizes[k], kWideLineChunk + kPerSegment);
    if (k + 1 < sizes.size()) {
      EXPECT_GE(sizes[k], kWideLineChunk);
    }
    EXPECT_EQ(first_red[k], static_cast<float>(total / kPerSegment) / 4096.0f);  // in order
    total += sizes[k];
  }
  EXPECT_EQ(total, segments.size() * kPerSegment);
  EXPECT_EQ(sizes.size(), (segments.size() * kPerSegment + kWideLineChunk - 1) / kWideLineChunk);
}

}  // namespace
}  // namespace tessera::test
