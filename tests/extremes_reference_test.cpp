// Stability at the extremes (issue 4) for the scalar reference rasterizer: every case of
// extremes_support.hpp covers exactly the samples it states, each once, and the draws that
// cannot be drawn are rejected before anything is touched.
#include <gtest/gtest.h>

#include <vector>

#include "tests/extremes_support.hpp"

namespace tessera::extremes {
namespace {

void expect_reference_exact(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    expect_covers_exactly(c, run(c, reference_options()));
  }
}

TEST(ExtremesReference, RectanglesAtAndPastTheGuardBandUpTo1e30CoverEverySampleOnce) {
  expect_reference_exact(guard_band_cases());
}

TEST(ExtremesReference, FansReachingTo1e30WithWSpreadOverFourteenDecadesCoverEverySampleOnce) {
  expect_reference_exact(huge_fan_cases());
}

TEST(ExtremesReference, FansCrossingTheNearPlaneAndWZeroCoverEverySampleOnce) {
  expect_reference_exact(near_plane_fan_cases());
}

TEST(ExtremesReference, FramebuffersFromOnePixelToRowsAndColumnsOf16384AreExact) {
  expect_reference_exact(framebuffer_size_cases());
}

TEST(ExtremesReference, Framebuffer16384SquaredIsCoveredOnceAndExactlyAtItsCorners) {
  Framebuffer fb({kMaxFramebufferSize, kMaxFramebufferSize, 1, ColorFormat::kRGBA8});
  expect_largest_framebuffer_exact(fb, reference_options());
}

TEST(ExtremesReference, TrianglesOfATenThousandthPixelSnapOrAreCulledAsZeroArea) {
  expect_reference_exact(tiny_triangle_cases());
}

TEST(ExtremesReference, SliversOfAspectRatio1e6TileTheirBandOnce) {
  expect_reference_exact(sliver_cases());
}

TEST(ExtremesReference, WFromTenToTheMinusSevenToTenToTheSevenKeepsTheWindowTrianglesCoverage) {
  expect_reference_exact(w_range_cases());
}

TEST(ExtremesReference, VertexExactlyOnWZeroDrawsTheRegionOutToInfinity) {
  expect_reference_exact(w_zero_cases());
}

TEST(ExtremesReference, DenormalCoordinatesDrawOrAreCulledAndDenormalDepthIsKept) {
  const std::vector<Case> cases = denormal_cases();
  expect_reference_exact(cases);
  const Outcome o = run(cases[0], reference_options());
  const float tiny = std::numeric_limits<float>::denorm_min();
  EXPECT_GT(o.counters.samples_covered, 0u);
  for (float d : o.depth)
    ASSERT_TRUE(d == kUncovered || d == tiny) << d;
}

TEST(ExtremesReference, SingleSampleCasesCoverTheSameWithTheDepthTestOff) {
  expect_cases_exact_without_depth(reference_options());
}

TEST(ExtremesReference, NearFarRatioOf1e7ResolvesPlanesOnePercentApartAndHitsZeroAndOne) {
  expect_near_far_ratio_1e7_resolved(reference_options());
}

TEST(ExtremesReference, NaNAndInfInAnyCoordinateAreRejectedNamingTheVertex) {
  expect_non_finite_rejected(reference_options());
}

TEST(ExtremesReference, NaNAndInfVerticesAreCulledAndCountedWhenAsked) {
  expect_non_finite_culled(reference_options());
}

}  // namespace
}  // namespace tessera::extremes
