// Depth bias (PipelineState::depth_bias_*, engine/src/depth_bias.hpp): the unit r of each depth
// format, hand-computed biased depths of flat and sloped triangles with and without the clamp
// in both backends, a decal drawn over its coplanar base winning everywhere only with a bias,
// the fast engine's depth within the reference's tolerance on every target, and bad values
// rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "engine/src/depth_bias.hpp"
#include "tessera/tessera.hpp"
#include "tests/expect_error.hpp"
#include "tests/simd_targets.hpp"

namespace tessera {
namespace {

TEST(DepthBias, TheUnitIsTheFormatsSmallestStepAtTheTrianglesDepth) {
  EXPECT_EQ(depth_bias_unit(DepthFormat::kUnorm16, 0.7), std::ldexp(1.0, -16));
  EXPECT_EQ(depth_bias_unit(DepthFormat::kUnorm24, 0.7), std::ldexp(1.0, -24));
  // Float: 2^(e - 23) with 2^e <= |z| < 2^(e + 1).
  EXPECT_EQ(depth_bias_unit(DepthFormat::kFloat32, 0.7), std::ldexp(1.0, -1 - 23));
  EXPECT_EQ(depth_bias_unit(DepthFormat::kFloat32, 0.5), std::ldexp(1.0, -1 - 23));
  EXPECT_EQ(depth_bias_unit(DepthFormat::kFloat32, 0.49), std::ldexp(1.0, -2 - 23));
  EXPECT_EQ(depth_bias_unit(DepthFormat::kFloat32, 0.0), 0.0);
  PipelineState p;
  p.depth_bias_constant = 3;
  p.depth_bias_slope = 2;
  EXPECT_DOUBLE_EQ(depth_bias(p, 0.001, 0.01, -0.03), 0.003 + 0.06);
  p.depth_bias_clamp = 0.02f;
  EXPECT_DOUBLE_EQ(depth_bias(p, 0.001, 0.01, -0.03), double{0.02f});
  p.depth_bias_constant = -3;
  p.depth_bias_slope = 0;
  p.depth_bias_clamp = -0.002f;
  EXPECT_DOUBLE_EQ(depth_bias(p, 0.001, 0.01, -0.03), double{-0.002f});
}

// A 64x48 framebuffer covered by two triangles whose depth runs from z_left at x = 0 to
// z_right at x = 64 (window x): depth of each pixel's first sample, in `format`.
std::vector<float> ramp(Backend backend, DepthFormat format, const PipelineState& p, float z_left,
                        float z_right, SimdTarget simd = SimdTarget::kAuto) {
  RendererOptions options;
  options.backend = backend;
  options.simd = simd;
  Renderer renderer(options);
  Framebuffer fb({64, 48, 1, ColorFormat::kRGBA8, format});
  const std::vector<Float4> positions = {{-1, -1, z_left, 1}, {1, -1, z_right, 1},
                                         {1, 1, z_right, 1},  {-1, -1, z_left, 1},
                                         {1, 1, z_right, 1},  {-1, 1, z_left, 1}};
  PipelineState q = p;
  q.depth_compare = CompareOp::kAlways;
  renderer.draw(fb, q, {positions, {}, 0, {}});
  return fb.read_depth();
}

TEST(DepthBias, FlatAndSlopedTrianglesTakeTheHandComputedBias) {
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    SCOPED_TRACE(backend == Backend::kFast ? "fast" : "reference");
    PipelineState p;
    p.depth_bias_constant = 5;
    // Flat at 0.5: unorm16 adds 5 * 2^-16 (stored in 1/65535 steps), float 5 * 2^-24.
    const std::vector<float> u16 = ramp(backend, DepthFormat::kUnorm16, p, 0.5f, 0.5f);
    EXPECT_FLOAT_EQ(u16[100],
                    static_cast<float>(std::nearbyint((0.5 + 5.0 / 65536) * 65535) / 65535.0));
    const std::vector<float> f32 = ramp(backend, DepthFormat::kFloat32, p, 0.5f, 0.5f);
    EXPECT_EQ(f32[100], static_cast<float>(0.5 + 5 * std::ldexp(1.0, -24)));
    // A slope of 0.25 over 64 pixels: dz/dx = 1/256 per pixel; slope 2 adds 1/128.
    PipelineState s;
    s.depth_bias_slope = 2;
    const std::vector<float> plain =
        ramp(backend, DepthFormat::kFloat32, PipelineState{}, 0.25f, 0.5f);
    const std::vector<float> sloped = ramp(backend, DepthFormat::kFloat32, s, 0.25f, 0.5f);
    for (size_t i : {size_t{0}, size_t{777}, sloped.size() - 1})
      EXPECT_NEAR(sloped[i] - plain[i], 1.0 / 128, 1e-6) << i;
    // Clamped to 1/1000.
    s.depth_bias_clamp = 0.001f;
    const std::vector<float> clamped = ramp(backend, DepthFormat::kFloat32, s, 0.25f, 0.5f);
    EXPECT_NEAR(clamped[777] - plain[777], 0.001, 1e-6);
  }
}

TEST(DepthBias, ADecalWinsOverItsCoplanarBaseOnlyWithABias) {
  // A sloped soup drawn red, then the same triangles drawn green with LESS: without a bias the
  // equal depths fail; with a constant bias of -8 steps every green sample passes (one step
  // would not do: the fast engine rounds its planes to float, to within 4 units of 2^-24).
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Float4> positions;
  for (int i = 0; i < 300; ++i)
    positions.push_back({u(rng), u(rng), 0.5f + 0.4f * u(rng), 1.0f});
  std::vector<float> red, green;
  for (size_t i = 0; i < positions.size(); ++i) {
    red.insert(red.end(), {1, 0, 0, 1});
    green.insert(green.end(), {0, 1, 0, 1});
  }
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    for (DepthFormat format :
         {DepthFormat::kFloat32, DepthFormat::kUnorm24, DepthFormat::kUnorm16}) {
      for (float bias : {0.0f, -8.0f}) {
        RendererOptions options;
        options.backend = backend;
        options.threads = 2;
        Renderer renderer(options);
        Framebuffer fb({96, 64, 1, ColorFormat::kRGBA8, format});
        PipelineState p;
        renderer.draw(fb, p, {positions, red, 4, {}});
        p.depth_bias_constant = bias;
        renderer.draw(fb, p, {positions, green, 4, {}});
        const std::vector<uint8_t> image = fb.read_rgba8();
        size_t red_pixels = 0, green_pixels = 0;
        for (size_t i = 0; i < image.size(); i += 4) {
          red_pixels += image[i] == 255;
          green_pixels += image[i + 1] == 255;
        }
        const std::string what = std::string(backend == Backend::kFast ? "fast" : "reference") +
                                 ", format " + std::to_string(static_cast<int>(format)) +
                                 ", bias " + std::to_string(bias);
        if (bias == 0.0f) {
          EXPECT_EQ(green_pixels, 0u) << what;
          EXPECT_GT(red_pixels, 1000u) << what;
        } else {
          EXPECT_EQ(red_pixels, 0u) << what;
          EXPECT_GT(green_pixels, 1000u) << what;
        }
      }
    }
  }
}

TEST(DepthBias, TheFastEnginesBiasedDepthIsWithinItsToleranceOfTheReferencesOnEveryTarget) {
  // Perspective triangles of about 60 and 600 pixels (well shaped: the fast engine's float
  // planes are within 4 units of 2^-24 of the reference's depth there, fast_engine_test.cpp's
  // DepthWithinToleranceOfReference; slivers' steep planes round further), biased by constant
  // and slope: every sample within those 4 units of the reference's while the bias moves each
  // sample by 40 units or more, and the same samples covered.
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Float4> positions;
  for (int i = 0; i < 3000; ++i) {
    const float cx = u(rng) * 150.0f - 7.0f, cy = u(rng) * 80.0f - 4.0f;
    const float radius = i % 4 == 0 ? 22.0f : 7.0f;
    const float turn = u(rng) * 6.2832f;
    for (int k = 0; k < 3; ++k) {
      const float angle = turn + static_cast<float>(k) * 2.0944f + (u(rng) - 0.5f) * 0.7f;
      const float x = cx + radius * std::cos(angle), y = cy + radius * std::sin(angle);
      const float w = 0.25f + 4.0f * u(rng);
      positions.push_back({(2.0f * x / 136.0f - 1.0f) * w, (1.0f - 2.0f * y / 72.0f) * w,
                           (0.2f + 0.6f * u(rng)) * w, w});
    }
  }
  PipelineState biased;
  biased.depth_compare = CompareOp::kAlways;
  biased.depth_bias_constant = 40;
  biased.depth_bias_slope = 0.75f;
  biased.depth_bias_clamp = 0.01f;
  PipelineState plain;
  plain.depth_compare = CompareOp::kAlways;
  for (uint32_t samples : {1u, 4u}) {
    const auto render = [&](const PipelineState& p, Backend backend, SimdTarget simd,
                            uint32_t threads) {
      RendererOptions options;
      options.backend = backend;
      options.simd = simd;
      options.threads = threads;
      options.hiz = false;
      options.raster_counters = true;
      Renderer renderer(options);
      Framebuffer fb({136, 72, samples, ColorFormat::kRGBA8});
      renderer.draw(fb, p, {positions, {}, 0, {}});
      return std::make_pair(fb.read_sample_depth(), renderer.counters().samples_covered);
    };
    const auto ref = render(biased, Backend::kReference, SimdTarget::kAuto, 1);
    const auto ref_plain = render(plain, Backend::kReference, SimdTarget::kAuto, 1);
    double least_bias = 1e9;
    for (size_t i = 0; i < ref.first.size(); ++i) {
      if (ref_plain.first[i] == 1.0f) continue;  // not covered (cleared to 1)
      least_bias =
          std::min(least_bias, std::ldexp(double{ref.first[i]} - double{ref_plain.first[i]}, 24));
    }
    EXPECT_GE(least_bias, 39.0);
    for (SimdTarget simd : test::runnable_simd_targets()) {
      for (uint32_t threads : {1u, 2u}) {
        const auto fast = render(biased, Backend::kFast, simd, threads);
        EXPECT_EQ(fast.second, ref.second);
        double worst = 0;
        for (size_t i = 0; i < ref.first.size(); ++i) {
          worst = std::max(worst,
                           std::ldexp(std::abs(double{fast.first[i]} - double{ref.first[i]}), 24));
        }
        EXPECT_LE(worst, 4.0) << samples << " samples, target " << static_cast<int>(simd) << ", "
                              << threads << " threads";
      }
    }
  }
}

TEST(DepthBias, NonFiniteValuesAreErrorsNamingTheField) {
  Renderer renderer;
  Framebuffer fb({16, 16});
  const std::vector<Float4> positions = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {0, 1, 0.5f, 1}};
  PipelineState p;
  p.depth_bias_slope = std::nanf("");
  test::expect_error(
      [&] {
        renderer.draw(fb, p, {positions, {}, 0, {}});
      },
      ErrorCode::kInvalidArgument, "depth_bias_slope");
  p = PipelineState{};
  p.depth_bias_clamp = INFINITY;
  test::expect_error(
      [&] {
        renderer.draw(fb, p, {positions, {}, 0, {}});
      },
      ErrorCode::kInvalidArgument, "depth_bias_clamp");
}

}  // namespace
}  // namespace tessera
