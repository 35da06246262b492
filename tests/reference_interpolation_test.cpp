// Attribute interpolation in the reference rasterizer (ARCHITECTURE.md section 2): colours are
// perspective-correct by default, (sum b_i a_i / w_i) / (sum b_i / w_i) with b_i the screen-space
// barycentrics of the pixel centre, or affine, sum b_i a_i, when declared so; guard-band
// clipping does not change either; RGBA8 storage rounds to nearest.
// Expected values are computed here from the window positions, in double, and compared with
// an RGBA32F framebuffer to 1e-5.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Point;
using test::Viewport;

constexpr double kTolerance = 1e-5;

struct Vertex {
  Point window;
  double w;
  std::array<float, 4> rgba;
};

// Screen-space barycentrics of p in the triangle of window positions a, b, c.
std::array<double, 3> barycentrics(Point a, Point b, Point c, Point p) {
  auto cross = [](Point o, Point u, Point v) {
    return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
  };
  const double area = cross(a, b, c);
  return {cross(p, b, c) / area, cross(a, p, c) / area, cross(a, b, p) / area};
}

std::array<double, 4> expected_color(const std::array<Vertex, 3>& t, Point p, Interpolation mode) {
  const auto b = barycentrics(t[0].window, t[1].window, t[2].window, p);
  std::array<double, 4> out{};
  for (int c = 0; c < 4; ++c) {
    double num = 0, den = 0;
    for (int i = 0; i < 3; ++i) {
      const double weight = mode == Interpolation::kPerspective ? b[i] / t[i].w : b[i];
      num += weight * t[i].rgba[c];
      den += weight;
    }
    out[c] = num / den;
  }
  return out;
}

// Draws the triangle into a cleared (0, 0, 0, 0) RGBA32F framebuffer and returns the colours.
std::vector<float> render(const Viewport& v, const std::array<Vertex, 3>& t, Interpolation mode,
                          Counters* counters = nullptr) {
  std::vector<Float4> positions;
  std::vector<float> rgba;
  for (const Vertex& vertex : t) {
    positions.push_back(v.at(vertex.window, 0.5, vertex.w));
    rgba.insert(rgba.end(), vertex.rgba.begin(), vertex.rgba.end());
  }
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({v.width, v.height, 1, ColorFormat::kRGBA32F});
  PipelineState pipeline;
  pipeline.interpolation = mode;
  test::draw(renderer, fb, pipeline, positions, rgba);
  if (counters != nullptr) *counters = renderer.counters();
  return fb.read_rgba32f();
}

// Compares every pixel the triangle covers (alpha 1; the clear has alpha 0) with the formula.
// Returns the number of pixels compared.
int expect_matches_formula(const Viewport& v, const std::array<Vertex, 3>& t, Interpolation mode,
                           const std::vector<float>& image) {
  int compared = 0;
  for (uint32_t j = 0; j < v.height; ++j) {
    for (uint32_t i = 0; i < v.width; ++i) {
      const float* px = &image[(j * v.width + i) * 4];
      if (px[3] == 0.0f) continue;
      const auto expected = expected_color(t, {i + 0.5, j + 0.5}, mode);
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(px[c], expected[c], kTolerance)
            << "pixel (" << i << ", " << j << ") channel " << c;
      }
      ++compared;
    }
  }
  return compared;
}

// --- Worked by hand ---------------------------------------------------------------------------
// Window vertices (0, 0), (16, 0), (1, 9) with w = 1, 3, 1. Pixel (4, 4) has its centre
// (4.5, 4.5) = 1/4 (0, 0) + 1/4 (16, 0) + 1/2 (1, 9): barycentrics (1/4, 1/4, 1/2).
// Red 0, 1, 0:  perspective (1/4 * 1/3) / (1/4 + 1/4 * 1/3 + 1/2) = (1/12) / (10/12) = 0.1,
//               affine 1/4.
// Green 0, 0, 1: perspective (1/2) / (10/12) = 0.6, affine 1/2.
// Blue 1, 0, 0:  perspective (1/4) / (10/12) = 0.3, affine 1/4.

const std::array<Vertex, 3> kHandTriangle = {Vertex{{0, 0}, 1.0, {0, 0, 1, 1}},
                                             Vertex{{16, 0}, 3.0, {1, 0, 0, 1}},
                                             Vertex{{1, 9}, 1.0, {0, 1, 0, 1}}};

TEST(ReferenceInterpolation, PerspectiveCorrectColourAtAPixelCentreMatchesTheHandValue) {
  const Viewport v{16, 16};
  const std::vector<float> image = render(v, kHandTriangle, Interpolation::kPerspective);
  const float* px = &image[(4 * 16 + 4) * 4];
  EXPECT_NEAR(px[0], 0.1, kTolerance);
  EXPECT_NEAR(px[1], 0.6, kTolerance);
  EXPECT_NEAR(px[2], 0.3, kTolerance);
  EXPECT_EQ(px[3], 1.0f);
}

TEST(ReferenceInterpolation, AffineColourAtAPixelCentreMatchesTheHandValue) {
  const Viewport v{16, 16};
  const std::vector<float> image = render(v, kHandTriangle, Interpolation::kAffine);
  const float* px = &image[(4 * 16 + 4) * 4];
  EXPECT_NEAR(px[0], 0.25, kTolerance);
  EXPECT_NEAR(px[1], 0.5, kTolerance);
  EXPECT_NEAR(px[2], 0.25, kTolerance);
  EXPECT_EQ(px[3], 1.0f);
}

// --- Every covered pixel ----------------------------------------------------------------------

const std::array<Vertex, 3> kPerspectiveTriangle = {
    Vertex{{1.25, 0.75}, 1.0, {1.0f, 0.0f, 0.25f, 1.0f}},
    Vertex{{31.5, 6.0}, 2.5, {0.0f, 1.0f, 0.5f, 1.0f}},
    Vertex{{5.0, 30.25}, 4.0, {0.5f, 0.25f, 1.0f, 1.0f}}};

TEST(ReferenceInterpolation, PerspectiveCorrectColourMatchesTheFormulaAtEveryPixelCentre) {
  const Viewport v{32, 32};
  const std::vector<float> image = render(v, kPerspectiveTriangle, Interpolation::kPerspective);
  EXPECT_GT(expect_matches_formula(v, kPerspectiveTriangle, Interpolation::kPerspective, image),
            300);
}

TEST(ReferenceInterpolation, AffineColourMatchesTheFormulaAtEveryPixelCentre) {
  const Viewport v{32, 32};
  const std::vector<float> image = render(v, kPerspectiveTriangle, Interpolation::kAffine);
  EXPECT_GT(expect_matches_formula(v, kPerspectiveTriangle, Interpolation::kAffine, image), 300);
}

TEST(ReferenceInterpolation, PerspectiveAndAffineAgreeWhenAllWAreEqual) {
  std::array<Vertex, 3> t = kPerspectiveTriangle;
  for (Vertex& vertex : t) {
    vertex.w = 2.0;
  }
  const Viewport v{32, 32};
  const std::vector<float> perspective = render(v, t, Interpolation::kPerspective);
  const std::vector<float> affine = render(v, t, Interpolation::kAffine);
  for (size_t i = 0; i < affine.size(); ++i) {
    ASSERT_NEAR(perspective[i], affine[i], 1e-6);
  }
  EXPECT_GT(expect_matches_formula(v, t, Interpolation::kAffine, affine), 300);
}

TEST(ReferenceInterpolation, MissingColourComponentsReadAsZeroZeroZeroOne) {
  const Viewport v{8, 8};
  const std::vector<Float4> tri = {v.at(0, 0), v.at(16, 0), v.at(0, 16)};
  const std::vector<float> rg = {0.25f, 0.5f, 0.25f, 0.5f, 0.25f, 0.5f};
  Renderer renderer = test::reference_renderer();
  Framebuffer fb({8, 8, 1, ColorFormat::kRGBA32F});
  DrawInput input;
  input.positions = tri;
  input.attributes = rg;
  input.attribute_count = 2;
  renderer.draw(fb, {}, input);
  const std::vector<float> image = fb.read_rgba32f();
  for (size_t p = 0; p < image.size() / 4; ++p) {
    EXPECT_NEAR(image[p * 4 + 0], 0.25f, 1e-6);
    EXPECT_NEAR(image[p * 4 + 1], 0.5f, 1e-6);
    EXPECT_EQ(image[p * 4 + 2], 0.0f);
    EXPECT_EQ(image[p * 4 + 3], 1.0f);
  }
}

// --- Guard-band clipping does not change interpolation -----------------------------------------
// A triangle reaching ~100000 pixels out of a 16x16 viewport, far past the guard band (32768
// pixels from the centre), with a different w per vertex. Its colours must be those of the
// uncut triangle, from the formula above with the original window positions.

std::array<Vertex, 3> huge_triangle(std::array<float, 3> red) {
  return {Vertex{{-100000, -50000}, 1.0, {red[0], 0.0f, 1.0f, 1.0f}},
          Vertex{{120000, 8}, 2.0, {red[1], 1.0f, 0.0f, 1.0f}},
          Vertex{{8, 90000}, 4.0, {red[2], 0.5f, 0.5f, 1.0f}}};
}

TEST(ReferenceInterpolation, PerspectiveColourIsUnchangedByGuardBandClipping) {
  const Viewport v{16, 16};
  Counters counters;
  const std::array<Vertex, 3> t = huge_triangle({0.25f, 1.0f, 0.0f});
  const std::vector<float> image = render(v, t, Interpolation::kPerspective, &counters);
  EXPECT_EQ(counters.triangles_clipped, 1u);
  EXPECT_EQ(expect_matches_formula(v, t, Interpolation::kPerspective, image), 16 * 16);
}

// Red is (x + 2y) / 1024 at each vertex, exact in float, so affine red is that linear function
// at every pixel centre. The cut vertices are snapped to 1/256 pixel, which moves the red plane
// by at most (3 / 1024) / 512 < 6e-6 there.

TEST(ReferenceInterpolation, AffineColourIsUnchangedByGuardBandClipping) {
  const Viewport v{16, 16};
  Counters counters;
  auto red = [](double x, double y) { return static_cast<float>((x + 2 * y) / 1024); };
  const std::array<Vertex, 3> t =
      huge_triangle({red(-100000, -50000), red(120000, 8), red(8, 90000)});
  const std::vector<float> image = render(v, t, Interpolation::kAffine, &counters);
  EXPECT_EQ(counters.triangles_clipped, 1u);
  EXPECT_EQ(expect_matches_formula(v, t, Interpolation::kAffine, image), 16 * 16);
  // Affine red is the linear function it was sampled from.
  for (uint32_t j = 0; j < 16; ++j) {
    for (uint32_t i = 0; i < 16; ++i) {
      EXPECT_NEAR(image[(j * 16 + i) * 4], ((i + 0.5) + 2 * (j + 0.5)) / 1024, kTolerance)
          << "pixel (" << i << ", " << j << ")";
    }
  }
}

// --- RGBA8 storage ----------------------------------------------------------------------------

TEST(ReferenceInterpolation, Rgba8StoresTheNearestUnorm8Value) {
  // Constant colours 0.4 and 0.6 of a step past k: they round to k and k + 1 (not down, not
  // up); 0.49 and 0.51 of a step to k and k + 1 as well.
  const Viewport v{8, 8};
  const std::vector<Float4> quad = {v.at(0, 0), v.at(8, 0), v.at(8, 8),
                                    v.at(0, 0), v.at(8, 8), v.at(0, 8)};
  for (int k : {0, 17, 100, 127, 200, 254}) {
    SCOPED_TRACE(k);
    const std::array<float, 4> color = {
        static_cast<float>((k + 0.4) / 255), static_cast<float>((k + 0.6) / 255),
        static_cast<float>((k + 0.49) / 255), static_cast<float>((k + 0.51) / 255)};
    std::vector<float> rgba;
    for (int i = 0; i < 6; ++i) {
      rgba.insert(rgba.end(), color.begin(), color.end());
    }
    Renderer renderer = test::reference_renderer();
    Framebuffer fb({8, 8, 1, ColorFormat::kRGBA8});
    test::draw(renderer, fb, {}, quad, rgba);
    const std::vector<uint8_t> px = fb.read_rgba8();
    for (size_t p = 0; p < px.size() / 4; ++p) {
      ASSERT_EQ(px[p * 4 + 0], k);
      ASSERT_EQ(px[p * 4 + 1], k + 1);
      ASSERT_EQ(px[p * 4 + 2], k);
      ASSERT_EQ(px[p * 4 + 3], k + 1);
    }
  }
}

TEST(ReferenceInterpolation, Rgba8IsTheRgba32fColourRoundedToNearest) {
  const Viewport v{32, 32};
  std::vector<Float4> positions;
  std::vector<float> rgba;
  for (const Vertex& vertex : kPerspectiveTriangle) {
    positions.push_back(v.at(vertex.window, 0.5, vertex.w));
    rgba.insert(rgba.end(), vertex.rgba.begin(), vertex.rgba.end());
  }
  Renderer renderer = test::reference_renderer();
  Framebuffer f32({32, 32, 1, ColorFormat::kRGBA32F});
  Framebuffer u8({32, 32, 1, ColorFormat::kRGBA8});
  test::draw(renderer, f32, {}, positions, rgba);
  test::draw(renderer, u8, {}, positions, rgba);
  const std::vector<float> exact = f32.read_rgba32f();
  const std::vector<uint8_t> stored = u8.read_rgba8();
  int checked = 0;
  for (size_t i = 0; i < exact.size(); ++i) {
    const double scaled = exact[i] * 255.0;
    if (std::abs(scaled - std::floor(scaled) - 0.5) < 1e-3) continue;  // too close to a tie
    ASSERT_EQ(stored[i], static_cast<int>(std::lround(scaled))) << "value " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace tessera
