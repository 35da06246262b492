// Coverage of the reference rasterizer (ARCHITECTURE.md section 2): the top-left fill rule at
// pixel centres lying exactly on edges and vertices, watertight meshes (every sample exactly
// once), sub-pixel and zero-area triangles, face culling and sub-pixel snapping.
// Expected coverage is drawn as pictures: one text row per pixel row, '.' uncovered, 'X'
// covered once, a digit for more. Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Point;
using test::SampleHits;
using test::Viewport;

std::string rows(std::initializer_list<const char*> lines) {
  std::string s;
  for (const char* line : lines) {
    s += std::string(line) + "\n";
  }
  return s;
}

// Coverage of one triangle, given in window pixels, in an 8x8 single-sample framebuffer.
std::string picture_of(Point a, Point b, Point c, const PipelineState& pipeline = {}) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(a), v.at(b), v.at(c)}, pipeline);
  return hits.picture();
}

PipelineState with_subpixel_bits(uint32_t bits) {
  PipelineState p;
  p.subpixel_bits = bits;
  return p;
}

// --- The fill rule at pixel centres exactly on an edge ---------------------------------------
// Each triangle has one edge through a row, column or diagonal of pixel centres; its other
// edges lie outside the framebuffer.

TEST(ReferenceFillRule, HorizontalTopEdgeIncludesCentresOnIt) {
  EXPECT_EQ(picture_of({-8, 2.5}, {16, 2.5}, {4, 30}), rows({"........",  //
                                                             "........",  //
                                                             "XXXXXXXX",  // y = 2.5: on the edge
                                                             "XXXXXXXX",  //
                                                             "XXXXXXXX",  //
                                                             "XXXXXXXX",  //
                                                             "XXXXXXXX",  //
                                                             "XXXXXXXX"}));
}

TEST(ReferenceFillRule, HorizontalBottomEdgeExcludesCentresOnIt) {
  EXPECT_EQ(picture_of({-8, 5.5}, {16, 5.5}, {4, -22}), rows({"XXXXXXXX",  //
                                                              "XXXXXXXX",  //
                                                              "XXXXXXXX",  //
                                                              "XXXXXXXX",  //
                                                              "XXXXXXXX",  //
                                                              "........",  // y = 5.5: on the edge
                                                              "........",  //
                                                              "........"}));
}

TEST(ReferenceFillRule, VerticalLeftEdgeIncludesCentresOnIt) {
  // The edge x = 2.5 runs through column 2.
  EXPECT_EQ(picture_of({2.5, -8}, {2.5, 16}, {30, 4}), rows({"..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX",  //
                                                             "..XXXXXX"}));
}

TEST(ReferenceFillRule, VerticalRightEdgeExcludesCentresOnIt) {
  // The edge x = 5.5 runs through column 5.
  EXPECT_EQ(picture_of({5.5, -8}, {5.5, 16}, {-22, 4}), rows({"XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX...",  //
                                                              "XXXXX..."}));
}

// The diagonal x = y (down-right on screen) runs through the centres of pixels (i, i).
TEST(ReferenceFillRule, DownRightDiagonalIsALeftEdgeWhenTheTriangleLiesToItsRight) {
  EXPECT_EQ(picture_of({-8, -8}, {16, 16}, {16, -8}), rows({"XXXXXXXX",  //
                                                            ".XXXXXXX",  //
                                                            "..XXXXXX",  //
                                                            "...XXXXX",  //
                                                            "....XXXX",  //
                                                            ".....XXX",  //
                                                            "......XX",  //
                                                            ".......X"}));
}

TEST(ReferenceFillRule, DownRightDiagonalIsARightEdgeWhenTheTriangleLiesToItsLeft) {
  EXPECT_EQ(picture_of({-8, -8}, {16, 16}, {-8, 16}), rows({"........",  //
                                                            "X.......",  //
                                                            "XX......",  //
                                                            "XXX.....",  //
                                                            "XXXX....",  //
                                                            "XXXXX...",  //
                                                            "XXXXXX..",  //
                                                            "XXXXXXX."}));
}

// The diagonal x + y = 8 (up-right on screen) runs through the centres of pixels (i, 7 - i).
TEST(ReferenceFillRule, UpRightDiagonalIsALeftEdgeWhenTheTriangleLiesToItsRight) {
  EXPECT_EQ(picture_of({-8, 16}, {16, -8}, {16, 16}), rows({".......X",  //
                                                            "......XX",  //
                                                            ".....XXX",  //
                                                            "....XXXX",  //
                                                            "...XXXXX",  //
                                                            "..XXXXXX",  //
                                                            ".XXXXXXX",  //
                                                            "XXXXXXXX"}));
}

TEST(ReferenceFillRule, UpRightDiagonalIsARightEdgeWhenTheTriangleLiesToItsLeft) {
  EXPECT_EQ(picture_of({-8, 16}, {16, -8}, {-8, -8}), rows({"XXXXXXX.",  //
                                                            "XXXXXX..",  //
                                                            "XXXXX...",  //
                                                            "XXXX....",  //
                                                            "XXX.....",  //
                                                            "XX......",  //
                                                            "X.......",  //
                                                            "........"}));
}

TEST(ReferenceFillRule, EdgeRuleDoesNotDependOnVertexOrder) {
  const Point a{-8, 16}, b{16, -8}, c{16, 16};
  const std::string expected = picture_of(a, b, c);
  EXPECT_EQ(picture_of(b, c, a), expected);
  EXPECT_EQ(picture_of(c, a, b), expected);
  EXPECT_EQ(picture_of(a, c, b), expected);  // the other winding
  EXPECT_EQ(picture_of(c, b, a), expected);
}

// --- The fill rule at pixel centres exactly on a vertex --------------------------------------
// A centre on a vertex lies on two edges and is covered only when both include it.

TEST(ReferenceFillRule, VertexBetweenTopAndLeftEdgeIsCovered) {
  // Vertex (2.5, 2.5) joins the top edge y = 2.5 and the left edge x = 2.5; the hypotenuse
  // x + y = 9 is a right edge, so its vertices (6.5, 2.5) and (2.5, 6.5) are not covered.
  EXPECT_EQ(picture_of({2.5, 2.5}, {6.5, 2.5}, {2.5, 6.5}), rows({"........",  //
                                                                  "........",  //
                                                                  "..XXXX..",  //
                                                                  "..XXX...",  //
                                                                  "..XX....",  //
                                                                  "..X.....",  //
                                                                  "........",  //
                                                                  "........"}));
}

TEST(ReferenceFillRule, VertexBetweenBottomAndRightEdgeIsNotCovered) {
  // Vertex (5.5, 5.5) joins the bottom edge y = 5.5 and the right edge x = 5.5; the
  // hypotenuse x + y = 7 is a left edge (its centres are covered, its vertices are not).
  EXPECT_EQ(picture_of({5.5, 5.5}, {1.5, 5.5}, {5.5, 1.5}), rows({"........",  //
                                                                  "........",  //
                                                                  "....X...",  //
                                                                  "...XX...",  //
                                                                  "..XXX...",  //
                                                                  "........",  //
                                                                  "........",  //
                                                                  "........"}));
}

TEST(ReferenceFillRule, VertexPointingLeftIsCovered) {
  // Two left edges meet at (1.5, 3.5): x + y = 5 above, y - x = 2 below; x = 5.5 is a right
  // edge.
  EXPECT_EQ(picture_of({1.5, 3.5}, {5.5, -0.5}, {5.5, 7.5}), rows({"....X...",  //
                                                                   "...XX...",  //
                                                                   "..XXX...",  //
                                                                   ".XXXX...",  // the vertex
                                                                   "..XXX...",  //
                                                                   "...XX...",  //
                                                                   "....X...",  //
                                                                   "........"}));
}

TEST(ReferenceFillRule, VertexPointingRightIsNotCovered) {
  // Two right edges meet at (6.5, 3.5); x = 2.5 is a left edge.
  EXPECT_EQ(picture_of({6.5, 3.5}, {2.5, -0.5}, {2.5, 7.5}), rows({"..X.....",  //
                                                                   "..XX....",  //
                                                                   "..XXX...",  //
                                                                   "..XXXX..",  // the vertex
                                                                   "..XXX...",  //
                                                                   "..XX....",  //
                                                                   "..X.....",  //
                                                                   "........"}));
}

TEST(ReferenceFillRule, VertexPointingUpIsNotCovered) {
  // A left edge (x + y = 5) and a right edge (y - x = -2) meet at (3.5, 1.5).
  EXPECT_EQ(picture_of({3.5, 1.5}, {7.5, 5.5}, {-0.5, 5.5}), rows({"........",  //
                                                                   "........",  // the vertex
                                                                   "..XX....",  //
                                                                   ".XXXX...",  //
                                                                   "XXXXXX..",  //
                                                                   "........",  //
                                                                   "........",  //
                                                                   "........"}));
}

TEST(ReferenceFillRule, VertexPointingDownIsNotCovered) {
  // A left edge (y - x = 2) and a right edge (x + y = 9) meet at (3.5, 5.5).
  EXPECT_EQ(picture_of({3.5, 5.5}, {-0.5, 1.5}, {7.5, 1.5}), rows({"........",  //
                                                                   "XXXXXXX.",  //
                                                                   "XXXXXX..",  //
                                                                   ".XXXX...",  //
                                                                   "..XX....",  //
                                                                   "........",  // the vertex
                                                                   "........",  //
                                                                   "........"}));
}

// --- Watertight meshes: every sample exactly once ---------------------------------------------

TEST(ReferenceWatertight, TwoTrianglesSharingADiagonalThroughPixelCentresCoverEachOnce) {
  const Viewport v{8, 8};
  const Point a{0.5, 0.5}, b{6.5, 0.5}, c{6.5, 6.5}, d{0.5, 6.5};
  const std::string square = rows({"XXXXXX..",  //
                                   "XXXXXX..",  //
                                   "XXXXXX..",  //
                                   "XXXXXX..",  //
                                   "XXXXXX..",  //
                                   "XXXXXX..",  //
                                   "........",  //
                                   "........"});
  {
    SampleHits hits(8, 8);
    hits.add({v.at(a), v.at(b), v.at(c), v.at(a), v.at(c), v.at(d)});
    EXPECT_EQ(hits.picture(), square) << "same winding";
  }
  {
    SampleHits hits(8, 8);
    hits.add({v.at(a), v.at(b), v.at(c), v.at(a), v.at(d), v.at(c)});
    EXPECT_EQ(hits.picture(), square) << "opposite windings";
  }
}

// Two triangles sharing an edge of an arbitrary slope, at every sample of every MSAA pattern:
// the pair covers exactly the samples the fill rule gives their union, each once.
TEST(ReferenceWatertight, TwoTrianglesSharingASlantedEdgeCoverEachSampleOnce) {
  const Viewport v{16, 16};
  const std::vector<Point> quad = {
      {1.1875, 0.6875}, {14.9375, 2.3125}, {13.25, 15.0}, {0.75, 11.5}};
  for (uint32_t samples : {1u, 2u, 4u, 8u, 16u}) {
    SampleHits hits(16, 16, samples);
    hits.add(
        {v.at(quad[0]), v.at(quad[1]), v.at(quad[2]), v.at(quad[0]), v.at(quad[2]), v.at(quad[3])});
    uint64_t expected_total = 0;
    for (uint32_t y = 0; y < 16; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        for (uint32_t s = 0; s < samples; ++s) {
          const int expected = test::polygon_covers(quad, test::sample_position(samples, x, y, s));
          expected_total += static_cast<uint64_t>(expected);
          ASSERT_EQ(hits.at(x, y, s), expected)
              << samples << " samples, pixel (" << x << ", " << y << ") sample " << s;
        }
      }
    }
    EXPECT_GT(expected_total, 140u * samples);
  }
}

// Triangles around one vertex (listed in order around it) cover each sample of the polygon
// their outer vertices form exactly once; the shared vertex's own sample included.
void expect_fan_covers_its_polygon_once(Point centre, const std::vector<Point>& ring,
                                        uint32_t samples) {
  const Viewport v{16, 16};
  SampleHits hits(16, 16, samples);
  for (size_t i = 0; i < ring.size(); ++i) {
    hits.add({v.at(centre), v.at(ring[i]), v.at(ring[(i + 1) % ring.size()])});
  }
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) {
      for (uint32_t s = 0; s < samples; ++s) {
        ASSERT_EQ(hits.at(x, y, s),
                  test::polygon_covers(ring, test::sample_position(samples, x, y, s)) ? 1 : 0)
            << samples << " samples, pixel (" << x << ", " << y << ") sample " << s;
      }
    }
  }
}

TEST(ReferenceWatertight, FanAroundAVertexOnAPixelCentreCoversEachSampleOnce) {
  // Eight triangles around (8.5, 8.5) whose edges run along the row, the column and both
  // diagonals of pixel centres through it: the centre sample lies on all eight triangles.
  const Point centre{8.5, 8.5};
  const std::vector<Point> ring = {{12.5, 8.5}, {12.5, 12.5}, {8.5, 12.5}, {4.5, 12.5},
                                   {4.5, 8.5},  {4.5, 4.5},   {8.5, 4.5},  {12.5, 4.5}};
  const Viewport v{16, 16};
  SampleHits hits(16, 16);
  for (size_t i = 0; i < ring.size(); ++i) {
    hits.add({v.at(centre), v.at(ring[i]), v.at(ring[(i + 1) % ring.size()])});
  }
  EXPECT_EQ(hits.at(8, 8), 1);
  EXPECT_EQ(hits.picture(), rows({"................",  //
                                  "................",  //
                                  "................",  //
                                  "................",  //
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  // the shared vertex is pixel (8, 8)
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  //
                                  "....XXXXXXXX....",  //
                                  "................",  //
                                  "................",  //
                                  "................",  //
                                  "................"}));
  for (uint32_t samples : {4u, 16u}) {
    SCOPED_TRACE(samples);
    expect_fan_covers_its_polygon_once(centre, ring, samples);
  }
}

TEST(ReferenceWatertight, IrregularFanCoversEachSampleOnce) {
  // A convex ring of uneven spokes, around a vertex on a pixel centre and around one between
  // centres.
  const std::vector<Point> ring = {{14.25, 8.5}, {13.125, 13.6875}, {8.5, 15.0}, {2.3125, 12.875},
                                   {1.75, 8.5},  {3.375, 2.625},    {8.5, 1.25}, {13.875, 3.3125}};
  for (uint32_t samples : {1u, 4u, 16u}) {
    SCOPED_TRACE(samples);
    expect_fan_covers_its_polygon_once({8.5, 8.5}, ring, samples);
    expect_fan_covers_its_polygon_once({8.3125, 7.6875}, ring, samples);
  }
}

// A regular grid of quads, each split into two triangles with the diagonal alternating
// between the two directions and the winding alternating between columns, covering the
// rectangle [x0, x1) x [y0, y1): the top and left sides are included, the bottom and right
// sides are not, and every sample inside is covered exactly once.
std::vector<Float4> grid_mesh(const Viewport& v, Point origin, double step, int cells) {
  std::vector<Float4> triangles;
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const Point p00{origin.x + i * step, origin.y + j * step};
      const Point p10{p00.x + step, p00.y};
      const Point p01{p00.x, p00.y + step};
      const Point p11{p00.x + step, p00.y + step};
      std::vector<Point> t = (i + j) % 2 == 0 ? std::vector<Point>{p00, p10, p11, p00, p11, p01}
                                              : std::vector<Point>{p10, p11, p01, p10, p01, p00};
      if (i % 2 == 1) {
        std::swap(t[1], t[2]);
        std::swap(t[4], t[5]);
      }
      for (const Point& p : t) {
        triangles.push_back(v.at(p));
      }
    }
  }
  return triangles;
}

TEST(ReferenceWatertight, GridMeshThroughPixelCentresCoversEachPixelOnce) {
  // Vertices on the pixel centres (0.5 + 2i, 0.5 + 2j): every edge, diagonals included, runs
  // through pixel centres. The mesh spans [0.5, 14.5)^2, i.e. pixels 0..13.
  const Viewport v{16, 16};
  const std::vector<Float4> mesh = grid_mesh(v, {0.5, 0.5}, 2.0, 7);
  SampleHits hits(16, 16);
  hits.add(mesh);
  std::string expected;
  for (int j = 0; j < 16; ++j) {
    expected += j < 14 ? "XXXXXXXXXXXXXX..\n" : "................\n";
  }
  EXPECT_EQ(hits.picture(), expected);

  // Drawn as one draw, the covered-sample counter agrees: no sample is covered twice.
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  test::draw(renderer, fb, {}, mesh);
  EXPECT_EQ(renderer.counters().samples_covered, 14u * 14u);
  EXPECT_EQ(renderer.counters().triangles_rasterized, 7u * 7u * 2u);
}

TEST(ReferenceWatertight, GridMeshCoversEachMsaaSampleOnce) {
  // Vertices on the 1/16-pixel lattice of the sample positions, so edges run through samples.
  const Viewport v{16, 16};
  const Point origin{0.3125, 0.8125};
  const double step = 1.5625;
  const int cells = 9;
  const std::vector<Float4> mesh = grid_mesh(v, origin, step, cells);
  const double x1 = origin.x + cells * step, y1 = origin.y + cells * step;
  for (uint32_t samples : {4u, 8u, 16u}) {
    SampleHits hits(16, 16, samples);
    hits.add(mesh);
    for (uint32_t y = 0; y < 16; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        for (uint32_t s = 0; s < samples; ++s) {
          const Point p = test::sample_position(samples, x, y, s);
          const int expected = p.x >= origin.x && p.x < x1 && p.y >= origin.y && p.y < y1;
          ASSERT_EQ(hits.at(x, y, s), expected)
              << samples << " samples, pixel (" << x << ", " << y << ") sample " << s;
        }
      }
    }
  }
}

// --- Sub-pixel and zero-area triangles --------------------------------------------------------

TEST(ReferenceSubpixelTriangle, CoversTheOnePixelCentreInsideIt) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.25, 3.25), v.at(3.875, 3.25), v.at(3.25, 3.875)});
  EXPECT_EQ(hits.total(), 1u);
  EXPECT_EQ(hits.at(3, 3), 1);
  EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
  EXPECT_EQ(hits.counters().samples_covered, 1u);
}

TEST(ReferenceSubpixelTriangle, BetweenPixelCentresCoversNothingButIsNotCulled) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.625, 3.625), v.at(3.875, 3.625), v.at(3.625, 3.875)});
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_culled, 0u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
  EXPECT_EQ(hits.counters().samples_covered, 0u);
}

TEST(ReferenceSubpixelTriangle, CoversAPixelCentreOnItsTopEdge) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.25, 3.5), v.at(3.75, 3.5), v.at(3.5, 3.75)});
  EXPECT_EQ(hits.total(), 1u);
  EXPECT_EQ(hits.at(3, 3), 1);
}

TEST(ReferenceSubpixelTriangle, MissesAPixelCentreOnItsBottomEdge) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.25, 3.5), v.at(3.75, 3.5), v.at(3.5, 3.25)});
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
}

TEST(ReferenceSubpixelTriangle, CoversAPixelCentreAtItsTopLeftCorner) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.5, 3.5), v.at(3.75, 3.5), v.at(3.5, 3.75)});
  EXPECT_EQ(hits.total(), 1u);
  EXPECT_EQ(hits.at(3, 3), 1);
}

TEST(ReferenceSubpixelTriangle, MissesAPixelCentreAtItsBottomRightCorner) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.5, 3.5), v.at(3.25, 3.5), v.at(3.5, 3.25)});
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
}

TEST(ReferenceZeroArea, CollinearVerticesOnPixelCentresCoverNothingAndAreCulled) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(0.5, 0.5), v.at(4.5, 4.5), v.at(7.5, 7.5)});  // the diagonal of centres
  hits.add({v.at(0.5, 2.5), v.at(7.5, 2.5), v.at(3.5, 2.5)});  // a row of centres
  hits.add({v.at(2.5, 2.5), v.at(6.5, 6.5), v.at(2.5, 2.5)});  // a repeated vertex
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_culled, 3u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 0u);
  EXPECT_EQ(hits.counters().samples_covered, 0u);
}

TEST(ReferenceZeroArea, TriangleThatSnapsToALineIsCulled) {
  // (3, 1 + 1/1024) has y * 256 = 256.25, which snaps to the line y = 1 through the other two.
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(1, 1), v.at(6, 1), v.at(3, 1 + 1.0 / 1024)});
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_culled, 1u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 0u);
}

TEST(ReferenceZeroArea, TriangleSmallerThanTheSnappingStepIsCulled) {
  const Viewport v{8, 8};
  SampleHits hits(8, 8);
  hits.add({v.at(3.5, 3.5), v.at(3.5 + 1.0 / 1024, 3.5), v.at(3.5, 3.5 + 1.0 / 1024)});
  EXPECT_EQ(hits.total(), 0u);
  EXPECT_EQ(hits.counters().triangles_culled, 1u);
  EXPECT_EQ(hits.counters().triangles_rasterized, 0u);
}

// --- Face culling ----------------------------------------------------------------------------
// In NDC (y up) the triangle (-0.5, -0.5), (0.5, -0.5), (0, 0.5) runs counter-clockwise; in
// the 16x16 window (y down) it is (4, 12), (12, 12), (8, 4).

struct CullCase {
  CullMode cull;
  FrontFace front_face;
  bool counter_clockwise_drawn;
  bool clockwise_drawn;
  const char* name;
};

class ReferenceCulling : public ::testing::TestWithParam<CullCase> {};

TEST_P(ReferenceCulling, CullsExactlyTheFacesTheModeNames) {
  const CullCase c = GetParam();
  const Viewport v{16, 16};
  const Float4 a = v.at(4, 12), b = v.at(12, 12), top = v.at(8, 4);
  PipelineState pipeline;
  pipeline.cull = c.cull;
  pipeline.front_face = c.front_face;
  for (bool counter_clockwise : {true, false}) {
    SCOPED_TRACE(counter_clockwise ? "counter-clockwise in NDC" : "clockwise in NDC");
    const bool drawn = counter_clockwise ? c.counter_clockwise_drawn : c.clockwise_drawn;
    SampleHits hits(16, 16);
    if (counter_clockwise) {
      hits.add({a, b, top}, pipeline);
    } else {
      hits.add({a, top, b}, pipeline);
    }
    if (drawn) {
      EXPECT_EQ(hits.counters().triangles_culled, 0u);
      EXPECT_EQ(hits.counters().triangles_rasterized, 1u);
      EXPECT_EQ(hits.at(8, 8), 1);
      EXPECT_EQ(hits.total(), hits.counters().samples_covered);
    } else {
      EXPECT_EQ(hits.counters().triangles_culled, 1u);
      EXPECT_EQ(hits.counters().triangles_rasterized, 0u);
      EXPECT_EQ(hits.total(), 0u);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllModesAndFrontFaces, ReferenceCulling,
    ::testing::Values(  //                                      CCW drawn, CW drawn
        CullCase{CullMode::kNone, FrontFace::kCounterClockwise, true, true, "None_FrontCcw"},
        CullCase{CullMode::kBack, FrontFace::kCounterClockwise, true, false, "Back_FrontCcw"},
        CullCase{CullMode::kFront, FrontFace::kCounterClockwise, false, true, "Front_FrontCcw"},
        CullCase{CullMode::kNone, FrontFace::kClockwise, true, true, "None_FrontCw"},
        CullCase{CullMode::kBack, FrontFace::kClockwise, false, true, "Back_FrontCw"},
        CullCase{CullMode::kFront, FrontFace::kClockwise, true, false, "Front_FrontCw"}),
    [](const ::testing::TestParamInfo<CullCase>& param_info) { return param_info.param.name; });

TEST(ReferenceCullingCoverage, BothWindingsCoverTheSameSamples) {
  const Viewport v{16, 16};
  SampleHits ccw(16, 16, 4), cw(16, 16, 4);
  ccw.add({v.at(4, 12), v.at(12, 12), v.at(8, 4)});
  cw.add({v.at(4, 12), v.at(8, 4), v.at(12, 12)});
  EXPECT_GT(ccw.total(), 0u);
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 16; ++x) {
      for (uint32_t s = 0; s < 4; ++s) {
        ASSERT_EQ(ccw.at(x, y, s), cw.at(x, y, s));
      }
    }
  }
}

// --- Sub-pixel snapping -----------------------------------------------------------------------
// Window coordinates are rounded to the nearest multiple of 2^-bits before any coverage test.

TEST(ReferenceSnapping, FourBitsMoveALeftEdgeOntoPixelCentres) {
  // x = 3.5 + 1/64: 8 bits keep it right of column 3's centres; 4 bits round 56.25/16 to
  // 56/16 = 3.5, onto them, and a left edge includes them.
  const Point a{3.5 + 1.0 / 64, -8}, b{3.5 + 1.0 / 64, 16}, c{30, 4};
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(8)), rows({"....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX",  //
                                                              "....XXXX"}));
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(4)), rows({"...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX",  //
                                                              "...XXXXX"}));
}

TEST(ReferenceSnapping, FourBitsMoveABottomEdgeOntoPixelCentres) {
  // y = 3.5 + 1/64: 8 bits keep row 3's centres above it (inside); 4 bits put the edge on
  // them, and a bottom edge excludes them.
  const Point a{-8, 3.5 + 1.0 / 64}, b{16, 3.5 + 1.0 / 64}, c{4, -22};
  const std::string three_rows = rows({"XXXXXXXX",  //
                                       "XXXXXXXX",  //
                                       "XXXXXXXX",  //
                                       "........",  //
                                       "........",  //
                                       "........",  //
                                       "........",  //
                                       "........"});
  std::string four_rows = three_rows;
  four_rows.replace(3 * 9, 8, "XXXXXXXX");
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(8)), four_rows);
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(4)), three_rows);
}

TEST(ReferenceSnapping, SnappingRoundsToNearestRatherThanDown) {
  // 3.5 + 3/64 is 56.75/16: to nearest it is 57/16 = 3.5625 (right of column 3's centres);
  // rounding down would give 3.5, on them.
  const double x = 3.5 + 3.0 / 64;
  const std::string from_column_4 = rows({"....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX",  //
                                          "....XXXX"});
  EXPECT_EQ(picture_of({x, -8}, {x, 16}, {30, 4}, with_subpixel_bits(4)), from_column_4);
  // Same for y, on a bottom edge: to nearest 3.5625 keeps row 3 inside; down would drop it.
  EXPECT_EQ(picture_of({-8, x}, {16, x}, {4, -22}, with_subpixel_bits(4)),
            rows({"XXXXXXXX",  //
                  "XXXXXXXX",  //
                  "XXXXXXXX",  //
                  "XXXXXXXX",  //
                  "........",  //
                  "........",  //
                  "........",  //
                  "........"}));
}

TEST(ReferenceSnapping, CoverageIsDecidedOnSnappedCoordinatesNotFloats) {
  // x = 3.5 + 1/1024 snaps to 3.5 even with 8 bits: as a right edge it excludes column 3
  // (the unsnapped edge would include it), as a left edge it includes it.
  const double x = 3.5 + 1.0 / 1024;
  EXPECT_EQ(picture_of({x, -8}, {x, 16}, {-22, 4}), rows({"XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX.....",  //
                                                          "XXX....."}));
  EXPECT_EQ(picture_of({x, -8}, {x, 16}, {30, 4}), rows({"...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX",  //
                                                         "...XXXXX"}));
}

TEST(ReferenceSnapping, AVertexThatRoundsOntoAPixelCentreWithFourBitsGainsItsCoverage) {
  // The right-angle vertex (3.5 + 1/64, 3.5 + 1/64): with 4 bits the triangle snaps to
  // (3.5, 3.5), (7.5, 3.5), (3.5, 7.5) and its top-left vertex covers pixel (3, 3); with 8 bits
  // it stays just right of and below that centre.
  const double o = 1.0 / 64;
  const Point a{3.5 + o, 3.5 + o}, b{7.5 + o, 3.5 + o}, c{3.5 + o, 7.5 + o};
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(4)), rows({"........",  //
                                                              "........",  //
                                                              "........",  //
                                                              "...XXXX.",  //
                                                              "...XXX..",  //
                                                              "...XX...",  //
                                                              "...X....",  //
                                                              "........"}));
  // 8 bits: x >= 3.5 + 1/64 and y >= 3.5 + 1/64 exclude column and row 3; the hypotenuse
  // x + y = 11 + 1/32 now lies past the centres with i + j = 10 (a right edge, but off them).
  EXPECT_EQ(picture_of(a, b, c, with_subpixel_bits(8)), rows({"........",  //
                                                              "........",  //
                                                              "........",  //
                                                              "........",  //
                                                              "....XXX.",  //
                                                              "....XX..",  //
                                                              "....X...",  //
                                                              "........"}));
}

}  // namespace
}  // namespace tessera
