// Stability at the extremes (issue 4) for the fast engine, on every SIMD target this machine
// runs and with 1, 2 and 3 threads: every case of extremes_support.hpp covers exactly the
// samples it states, each once, with the same triangle winning each sample as in the
// reference; non-finite input is rejected; ten million triangles in one draw render in passes
// under a small bin budget, identically to the default budget, within the budget's memory.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
// From the sanitizer runtime (sanitizer/allocator_interface.h, which GCC does not install).
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#else
#include <malloc.h>
#endif

#include "tests/extremes_support.hpp"

namespace tessera::extremes {
namespace {

void expect_fast_exact(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Outcome ref = run(c, reference_options());
    for (const FastConfig& config : fast_configs()) {
      SCOPED_TRACE(config.name());
      const Outcome fast = run(c, config.options());
      expect_covers_exactly(c, fast);
      expect_same_as_reference(c, fast, ref);
    }
  }
}

TEST(ExtremesFast, RectanglesAtAndPastTheGuardBandUpTo1e30CoverEverySampleOnce) {
  expect_fast_exact(guard_band_cases());
}

TEST(ExtremesFast, FansReachingTo1e30WithWSpreadOverFourteenDecadesCoverEverySampleOnce) {
  expect_fast_exact(huge_fan_cases());
}

TEST(ExtremesFast, FansCrossingTheNearPlaneAndWZeroCoverEverySampleOnce) {
  expect_fast_exact(near_plane_fan_cases());
}

TEST(ExtremesFast, FramebuffersFromOnePixelToRowsAndColumnsOf16384AreExact) {
  expect_fast_exact(framebuffer_size_cases());
}

TEST(ExtremesFast, Framebuffer16384SquaredIsCoveredOnceAndExactlyAtItsCorners) {
  Framebuffer fb({kMaxFramebufferSize, kMaxFramebufferSize, 1, ColorFormat::kRGBA8});
  for (const FastConfig& config : fast_configs({2})) {
    SCOPED_TRACE(config.name());
    expect_largest_framebuffer_exact(fb, config.options());
  }
}

TEST(ExtremesFast, TrianglesOfATenThousandthPixelSnapOrAreCulledAsZeroArea) {
  expect_fast_exact(tiny_triangle_cases());
}

TEST(ExtremesFast, SliversOfAspectRatio1e6TileTheirBandOnce) {
  expect_fast_exact(sliver_cases());
}

TEST(ExtremesFast, WFromTenToTheMinusSevenToTenToTheSevenKeepsTheWindowTrianglesCoverage) {
  expect_fast_exact(w_range_cases());
}

TEST(ExtremesFast, VertexExactlyOnWZeroDrawsTheRegionOutToInfinity) {
  expect_fast_exact(w_zero_cases());
}

TEST(ExtremesFast, DenormalCoordinatesDrawOrAreCulledAndDenormalDepthIsKept) {
  const std::vector<Case> cases = denormal_cases();
  expect_fast_exact(cases);
  const float tiny = std::numeric_limits<float>::denorm_min();
  for (const FastConfig& config : fast_configs()) {
    SCOPED_TRACE(config.name());
    const Outcome o = run(cases[0], config.options());
    EXPECT_GT(o.counters.samples_covered, 0u);
    for (float d : o.depth)
      ASSERT_TRUE(d == kUncovered || d == tiny) << d;
  }
}

TEST(ExtremesFast, SingleSampleCasesCoverTheSameWithTheDepthTestOff) {
  const std::vector<std::vector<uint8_t>> ref =
      expect_cases_exact_without_depth(reference_options());
  for (const FastConfig& config : fast_configs({2})) {
    SCOPED_TRACE(config.name());
    const std::vector<std::vector<uint8_t>> fast =
        expect_cases_exact_without_depth(config.options());
    ASSERT_EQ(fast.size(), ref.size());
    for (size_t i = 0; i < ref.size(); ++i)
      EXPECT_EQ(fast[i], ref[i]) << "case " << i << ": the image differs from the reference's";
  }
}

TEST(ExtremesFast, NearFarRatioOf1e7ResolvesPlanesOnePercentApartAndHitsZeroAndOne) {
  for (const FastConfig& config : fast_configs()) {
    SCOPED_TRACE(config.name());
    expect_near_far_ratio_1e7_resolved(config.options());
  }
}

TEST(ExtremesFast, NaNAndInfInAnyCoordinateAreRejectedNamingTheVertex) {
  for (const FastConfig& config : fast_configs({2})) {
    SCOPED_TRACE(config.name());
    expect_non_finite_rejected(config.options());
  }
}

TEST(ExtremesFast, NaNAndInfVerticesAreCulledAndCountedWhenAsked) {
  for (const FastConfig& config : fast_configs({2})) {
    SCOPED_TRACE(config.name());
    expect_non_finite_culled(config.options());
  }
}

// Bytes the process's heap holds in live allocations (all malloc arenas and mmapped blocks;
// under AddressSanitizer, its allocator's count).
size_t heap_in_use() {
#if defined(__SANITIZE_ADDRESS__)
  return __sanitizer_get_current_allocated_bytes();
#else
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
#endif
}

// A regular grid of 4000 x 1250 cells, two triangles each: exactly 10,000,000 triangles over a
// 256 x 128 screen, each cell 0.064 x 0.1024 px, so no cell snaps empty and the grid covers
// every sample once. Depth varies across the grid (not a plane) and w with x (perspective).
struct TenMillion {
  static constexpr uint32_t kWidth = 256, kHeight = 128, kCellsX = 4000, kCellsY = 1250;
  std::vector<Float4> vertices;
  std::vector<uint32_t> indices;
  TenMillion() {
    vertices.reserve(size_t{kCellsX + 1} * (kCellsY + 1));
    for (uint32_t j = 0; j <= kCellsY; ++j) {
      for (uint32_t i = 0; i <= kCellsX; ++i) {
        const double fx = static_cast<double>(i) / kCellsX, fy = static_cast<double>(j) / kCellsY;
        vertices.push_back(clip(2 * fx - 1, 1 - 2 * fy, 0.2 + 0.6 * fx * fy, 1 + fx));
      }
    }
    indices.reserve(size_t{kCellsX} * kCellsY * 6);
    for (uint32_t j = 0; j < kCellsY; ++j) {
      for (uint32_t i = 0; i < kCellsX; ++i) {
        const uint32_t a = j * (kCellsX + 1) + i, b = a + 1, c = a + kCellsX + 1, d = c + 1;
        indices.insert(indices.end(), {a, b, d, a, d, c});
      }
    }
  }
  size_t triangles() const { return indices.size() / 3; }
};

// A NaN anywhere rejects the ten million triangles with the framebuffer untouched. Every
// target draws them under a 1 MiB budget with one thread, in over a thousand passes, and the
// best target also with two threads (eight setup chunks); each image is the same bytes as one drawn
// under the default budget (in a few passes), and every sample is covered and passes exactly once.
// The renderer's heap growth over each draw (the bins and setups it keeps for the next draw) stays
// within the budget and is recorded as a test property.
TEST(ExtremesFast, TenMillionTrianglesUnderASmallBinBudgetRenderInPassesLikeTheDefaultBudget) {
  TenMillion grid;
  ASSERT_EQ(grid.triangles(), 10000000u);
  const uint64_t samples = uint64_t{TenMillion::kWidth} * TenMillion::kHeight;
  constexpr uint64_t kSmallBudget = uint64_t{1} << 20;
  Framebuffer fb({TenMillion::kWidth, TenMillion::kHeight, 1, ColorFormat::kRGBA8});

  // A NaN in the last of the five million vertices rejects the whole draw before any pass.
  {
    RendererOptions options = FastConfig{available_targets().back(), 2}.options();
    options.bin_memory_budget = kSmallBudget;
    Renderer renderer(options);
    const size_t last = grid.vertices.size() - 1;
    const Float4 kept = grid.vertices[last];
    grid.vertices[last].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(renderer.draw(fb, PipelineState{}, {grid.vertices, {}, 0, grid.indices}), Error);
    grid.vertices[last] = kept;
    EXPECT_EQ(renderer.counters().bin_passes, 0u);
    EXPECT_EQ(renderer.counters().triangles_submitted, 0u);
    const std::vector<float> depth = fb.read_depth();
    EXPECT_EQ(std::count(depth.begin(), depth.end(), 1.0f), static_cast<std::ptrdiff_t>(samples));
  }

  auto draw = [&](const FastConfig& config, uint64_t budget) {
    RendererOptions options = config.options();
    options.bin_memory_budget = budget;
    Renderer renderer(options);
    fb.clear_depth(1.0f);
    const size_t before = heap_in_use();
    renderer.draw(fb, PipelineState{}, {grid.vertices, {}, 0, grid.indices});
    const size_t growth = heap_in_use() - before;
    ::testing::Test::RecordProperty(
        config.name() + ", budget " + std::to_string(budget) + ": heap growth bytes",
        std::to_string(growth));
    // What the renderer keeps for its next draw (bins and setups) stays within the budget.
    EXPECT_LE(growth, budget);
    const Counters& c = renderer.counters();
    EXPECT_EQ(c.triangles_submitted, grid.triangles());
    EXPECT_EQ(c.samples_covered, samples);
    EXPECT_EQ(c.samples_passed, samples);
    return std::pair{c.bin_passes, fb.read_depth()};
  };

  const SimdTarget best = available_targets().back();
  const auto [whole_passes, whole] = draw({best, 1}, kDefaultBinMemoryBudget);
  EXPECT_EQ(std::count(whole.begin(), whole.end(), 1.0f), 0) << "every sample is covered";
  std::vector<FastConfig> configs;
  for (SimdTarget target : available_targets())
    configs.push_back({target, 1});
  configs.push_back({best, 2});
  for (const FastConfig& config : configs) {
    SCOPED_TRACE(config.name());
    const auto [passes, depth] = draw(config, kSmallBudget);
    EXPECT_GT(passes, 1000u);
    EXPECT_GT(passes, whole_passes);
    EXPECT_EQ(0, std::memcmp(depth.data(), whole.data(), whole.size() * sizeof(float)));
  }
}

// The budget holds on a larger grid too (more tiles: more per-tile memory per chunk) and at
// the smallest budget the renderer accepts, for one and two threads.
TEST(ExtremesFast, BinnedTrianglesAndReferencesStayWithinTheBinMemoryBudget) {
  const TenMillion grid;
  struct Case {
    uint32_t width, height;
    uint64_t budget;
  };
  for (const Case& k :
       {Case{TenMillion::kWidth, TenMillion::kHeight, uint64_t{1} << 20},
        Case{TenMillion::kWidth, TenMillion::kHeight, uint64_t{16} << 20},
        Case{2048, 1024, uint64_t{1} << 20}, Case{2048, 1024, uint64_t{64} << 10}}) {
    for (uint32_t threads : {1u, 2u}) {
      SCOPED_TRACE(std::to_string(k.width) + "x" + std::to_string(k.height) + ", " +
                   std::to_string(threads) + " threads, budget " + std::to_string(k.budget));
      RendererOptions options;
      options.threads = threads;
      options.bin_memory_budget = k.budget;
      Renderer renderer(options);
      Framebuffer fb({k.width, k.height, 1, ColorFormat::kRGBA8});
      // Only the first million triangles: enough for many passes at these budgets.
      const std::span<const uint32_t> indices(grid.indices.data(), 3000000);
      const size_t before = heap_in_use();
      renderer.draw(fb, PipelineState{}, {grid.vertices, {}, 0, indices});
      const size_t growth = heap_in_use() - before;
      EXPECT_GT(renderer.counters().bin_passes, 1u);
      EXPECT_EQ(renderer.counters().triangles_submitted, 1000000u);
      EXPECT_LE(growth, k.budget);
    }
  }
}

}  // namespace
}  // namespace tessera::extremes
