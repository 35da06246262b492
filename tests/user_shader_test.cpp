// User fragment shaders (FragmentShader::kUser, tessera/shading.hpp): both backends hand the
// function the same fragments in 2x2 quads, with helper fragments, varyings and derivatives
// that agree within the tolerances of docs/SHADING.md; every SIMD target and thread count
// gives the same bytes; discarded fragments write neither depth nor colour; and bad state is
// an error.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"
#include "tests/shading_scene.hpp"

namespace tessera {
namespace {

using shading_scene::Image;
using shading_scene::kClear;
using shading_scene::kHeight;
using shading_scene::kWidth;
using shading_scene::Mesh;
using shading_scene::render;
using shading_scene::Target;
using shading_scene::test_mesh;

constexpr uint32_t kStride = kFragmentBatchStride;

// Writes four of the fragment's inputs, chosen by `channel`, as its colour.
PipelineState user_pipeline(std::array<int, 4> channel) {
  PipelineState p;
  p.shader = FragmentShader::kUser;
  p.fragment_function = [channel](const FragmentBatch& b, const FragmentOutput& out) {
    for (uint32_t c = 0; c < 4; ++c) {
      // channel: 0..31 a varying, 100 + v its x derivative, 200 + v its y derivative.
      const int k = channel[c];
      const float* from = k >= 200   ? b.ddy + (k - 200) * kStride
                          : k >= 100 ? b.ddx + (k - 100) * kStride
                                     : b.varyings + k * kStride;
      for (uint32_t i = 0; i < b.count; ++i)
        out.color[c * kStride + i] = from[i];
    }
  };
  return p;
}

// Depth from the fast engine's float planes and the reference's double ones: the same samples
// written (the clear, 1, left alone), values within a few float steps.
void expect_same_depth(const std::vector<float>& want, const std::vector<float>& got,
                       const std::string& where) {
  ASSERT_EQ(want.size(), got.size());
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(want[i] == 1.0f, got[i] == 1.0f) << where << ": sample " << i;
    ASSERT_LE(std::abs(want[i] - got[i]), 1e-6f) << where << ": sample " << i;
  }
}

// The fast engine against the reference: same bytes on every target and thread count, the
// reference's coverage exactly, values within `absolute` + `relative` x |value|.
void expect_matches_reference(const std::string& what, const PipelineState& pipeline,
                              double absolute, double relative) {
  const Mesh mesh = test_mesh();
  const std::vector<Target> targets = shading_scene::fast_targets();
  ASSERT_FALSE(targets.empty());
  for (ColorFormat format : {ColorFormat::kRGBA32F, ColorFormat::kRGBA8}) {
    for (uint32_t samples : {1u, 4u}) {
      const std::string where = what +
                                (format == ColorFormat::kRGBA8 ? ", RGBA8, " : ", RGBA32F, ") +
                                std::to_string(samples) + " samples";
      const Image want = render(mesh, pipeline, format, samples, Backend::kReference);
      const Image first = render(mesh, pipeline, format, samples, Backend::kFast, targets[0]);
      for (const Target& t : targets) {
        const Image got = render(mesh, pipeline, format, samples, Backend::kFast, t);
        ASSERT_EQ(got.rgba32f, first.rgba32f)
            << where << ", target " << int(t.simd) << ", " << t.threads << " threads";
        ASSERT_EQ(got.rgba8, first.rgba8) << where << ", target " << int(t.simd);
      }
      expect_same_depth(want.depth, first.depth, where);
      size_t covered = 0;
      double worst = 0;
      if (format == ColorFormat::kRGBA32F) {
        for (size_t i = 0; i < want.rgba32f.size(); ++i) {
          const float w = want.rgba32f[i], g = first.rgba32f[i];
          ASSERT_EQ(w == kClear, g == kClear) << where << ": coverage differs at value " << i;
          if (w == kClear) continue;
          covered += i % 4 == 3;
          const double error = std::abs(double{g} - w);
          worst = std::max(worst, error / (absolute + relative * std::abs(w)));
          ASSERT_LE(error, absolute + relative * std::abs(w))
              << where << ": value " << i << " (pixel " << i / 4 << ") " << g << " against " << w;
        }
      } else {
        for (size_t i = 0; i < want.rgba8.size(); ++i) {
          ASSERT_LE(std::abs(int{want.rgba8[i]} - first.rgba8[i]), 1) << where << ": byte " << i;
          covered += i % 4 == 3 && want.rgba8[i] != 0;
        }
      }
      EXPECT_GT(covered, size_t{kWidth * kHeight / 2}) << where;
      if (format == ColorFormat::kRGBA32F) {
        // The worst error as a fraction of the tolerance.
        ::testing::Test::RecordProperty(where, std::to_string(worst));
        std::printf("%s: worst error %.3f of the tolerance\n", where.c_str(), worst);
      }
    }
  }
}

TEST(UserShader, VaryingsMatchTheReferenceOnEveryTargetAndThreadCount) {
  // The colour varyings as they come: alpha is never 0, so alpha 0 in RGBA8 is uncovered.
  expect_matches_reference("colour varyings", user_pipeline({0, 1, 2, 3}), 2e-6, 0);
  PipelineState mixed = user_pipeline({0, 1, 2, 3});
  mixed.varying_modes[0] = VaryingMode::kAffine;
  mixed.varying_modes[1] = VaryingMode::kFlat;
  mixed.interpolation = Interpolation::kAffine;  // varyings 2 and 3 (kDefault) affine
  expect_matches_reference("colour varyings, affine and flat", mixed, 2e-6, 0);
  expect_matches_reference("positions", user_pipeline({7, 8, 9, 3}), 2e-6, 1e-6);
}

TEST(UserShader, DerivativesMatchTheReference) {
  // Perspective-correct colour and position derivatives (alpha stays the colour's, never 0).
  expect_matches_reference("d/dx and d/dy of colour 0 and 1", user_pipeline({100, 200, 101, 3}),
                           1e-7, 1e-6);
  expect_matches_reference("d/dx and d/dy of position z", user_pipeline({109, 209, 108, 3}), 1e-7,
                           1e-6);
  PipelineState affine = user_pipeline({100, 200, 101, 3});
  affine.interpolation = Interpolation::kAffine;
  expect_matches_reference("affine derivatives", affine, 1e-7, 1e-6);
}

// A varying equal to the window x coordinate: its value at each fragment is the fragment's x,
// its derivatives 1 and 0, on both backends.
TEST(UserShader, AScreenLinearVaryingHasItsAnalyticValueAndDerivatives) {
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    // Two triangles covering the view, w = 1 (perspective-correct is then affine too).
    const std::vector<Float4> positions = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {1, 1, 0.5f, 1},
                                           {-1, -1, 0.5f, 1}, {1, 1, 0.5f, 1},  {-1, 1, 0.5f, 1}};
    std::vector<float> varyings;
    for (const Float4& p : positions) {
      varyings.push_back((p.x + 1) * 0.5f * kWidth);   // window x
      varyings.push_back((1 - p.y) * 0.5f * kHeight);  // window y (down)
    }
    std::mutex m;
    size_t live = 0, helpers = 0, batches = 0;
    double worst_value = 0, worst_slope = 0;
    PipelineState p;
    p.shader = FragmentShader::kUser;
    p.fragment_function = [&](const FragmentBatch& b, const FragmentOutput& out) {
      std::lock_guard lock(m);
      ++batches;
      EXPECT_EQ(b.count % 4, 0u);
      EXPECT_LE(b.count, kStride);
      EXPECT_EQ(b.varying_count, 2u);
      for (uint32_t i = 0; i < b.count; ++i) {
        // Quads: pixels (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1), x and y even.
        const uint32_t q = i & ~3u, k = i & 3u;
        EXPECT_EQ(b.x[i], b.x[q] + float(k & 1)) << i;
        EXPECT_EQ(b.y[i], b.y[q] + float(k >> 1)) << i;
        EXPECT_EQ(std::fmod(b.x[q] - 0.5f, 2.0f), 0.0f);
        EXPECT_EQ(std::fmod(b.y[q] - 0.5f, 2.0f), 0.0f);
        (b.sample_mask[i] != 0 ? live : helpers) += 1;
        worst_value = std::max({worst_value, double(std::abs(b.varyings[i] - b.x[i])),
                                double(std::abs(b.varyings[kStride + i] - b.y[i]))});
        worst_slope = std::max({worst_slope, double(std::abs(b.ddx[i] - 1)),
                                double(std::abs(b.ddy[i])), double(std::abs(b.ddx[kStride + i])),
                                double(std::abs(b.ddy[kStride + i] - 1))});
        for (uint32_t c = 0; c < 4; ++c)
          out.color[c * kStride + i] = 1;
      }
    };
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb({kWidth, kHeight, 1, ColorFormat::kRGBA8});
    renderer.draw(fb, p, {positions, varyings, 2, {}});
    // Every pixel once (the two triangles share their diagonal), and the diagonal's quads have
    // helpers; snapping moves vertices by at most 1/512 pixel.
    EXPECT_EQ(live, size_t{kWidth} * kHeight) << int(backend);
    EXPECT_GT(helpers, 0u) << int(backend);
    EXPECT_LT(worst_value, 1e-2) << int(backend);
    EXPECT_LT(worst_slope, 1e-3) << int(backend);
    const std::vector<uint8_t> image = fb.read_rgba8();
    EXPECT_TRUE(std::all_of(image.begin(), image.end(), [](uint8_t v) { return v == 255; }));
  }
}

// Both backends give the function the same live fragments (pixel, mask, triangle), each once.
TEST(UserShader, BothBackendsShadeTheSameFragments) {
  const Mesh mesh = test_mesh();
  for (uint32_t samples : {1u, 4u}) {
    std::multiset<std::tuple<float, float, uint32_t, uint32_t>> seen[2];
    for (Backend backend : {Backend::kReference, Backend::kFast}) {
      std::mutex m;
      auto& set = seen[backend == Backend::kFast ? 1 : 0];
      PipelineState p;
      p.shader = FragmentShader::kUser;
      p.fragment_function = [&](const FragmentBatch& b, const FragmentOutput& out) {
        std::lock_guard lock(m);
        for (uint32_t i = 0; i < b.count; ++i) {
          if (b.sample_mask[i] != 0)
            set.insert({b.x[i], b.y[i], b.sample_mask[i], b.primitive_id[i]});
          for (uint32_t c = 0; c < 4; ++c)
            out.color[c * kStride + i] = 0.5f;
        }
      };
      RendererOptions options;
      options.backend = backend;
      options.threads = 2;
      Renderer renderer(options);
      Framebuffer fb({kWidth, kHeight, samples, ColorFormat::kRGBA8});
      renderer.draw(fb, p, mesh.input());
    }
    EXPECT_GT(seen[0].size(), size_t{kWidth * kHeight / 2}) << samples;
    EXPECT_TRUE(seen[0] == seen[1]) << samples << " samples: " << seen[0].size() << " against "
                                    << seen[1].size() << " fragments";
  }
}

TEST(UserShader, PrimitiveIdsAreTheBuiltInOutputs) {
  const Mesh mesh = test_mesh();
  PipelineState user;
  user.shader = FragmentShader::kUser;
  user.fragment_function = [](const FragmentBatch& b, const FragmentOutput& out) {
    for (uint32_t i = 0; i < b.count; ++i) {
      out.color[i] = out.color[kStride + i] = out.color[2 * kStride + i] =
          static_cast<float>(b.primitive_id[i]);
      out.color[3 * kStride + i] = 1;
    }
  };
  PipelineState ids;
  ids.output = TargetOutput::kPrimitiveId;
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    EXPECT_EQ(render(mesh, user, ColorFormat::kRGBA32F, 4, backend).rgba32f,
              render(mesh, ids, ColorFormat::kRGBA32F, 4, backend).rgba32f);
  }
}

// A checkerboard of discarded pixels: they keep the clear colour and depth, on both backends,
// and everything the function keeps is drawn as without discards.
TEST(UserShader, DiscardedFragmentsWriteNeitherDepthNorColour) {
  const Mesh mesh = test_mesh();
  PipelineState keep = user_pipeline({0, 1, 2, 3});
  PipelineState discard = keep;
  const FragmentFunction colour = keep.fragment_function;
  discard.fragment_function = [colour](const FragmentBatch& b, const FragmentOutput& out) {
    colour(b, out);
    for (uint32_t i = 0; i < b.count; ++i) {
      out.discard[i] = (static_cast<int>(b.x[i]) + static_cast<int>(b.y[i])) % 2 == 0;
    }
  };
  for (uint32_t samples : {1u, 4u}) {
    for (Backend backend : {Backend::kReference, Backend::kFast}) {
      // One sheet alone: no triangle hides another, so a kept pixel has the same value with
      // and without the discards.
      Mesh sheet;
      shading_scene::add_sheet(sheet, 6, -1.5, -1.2, 2.6, -4.0);
      const Image all = render(sheet, keep, ColorFormat::kRGBA32F, samples, backend);
      const Image some = render(sheet, discard, ColorFormat::kRGBA32F, samples, backend);
      size_t dropped = 0, kept = 0;
      for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
          const size_t pixel = size_t{y} * kWidth + x;
          const bool discarded = (x + y) % 2 == 0;
          for (uint32_t s = 0; s < samples; ++s) {
            const float d = some.depth[pixel * samples + s];
            EXPECT_EQ(d, discarded ? 1.0f : all.depth[pixel * samples + s]) << x << "," << y;
          }
          for (uint32_t c = 0; c < 4; ++c) {
            const float v = some.rgba32f[pixel * 4 + c];
            EXPECT_EQ(v, discarded ? kClear : all.rgba32f[pixel * 4 + c]) << x << "," << y;
          }
          if (all.rgba32f[pixel * 4 + 3] != kClear) (discarded ? dropped : kept) += 1;
        }
      }
      EXPECT_GT(dropped, 500u);
      EXPECT_GT(kept, 500u);
    }
    // With occlusion, both backends agree on depth exactly (a discarded front fragment lets
    // the one behind it through).
    const Image want = render(mesh, discard, ColorFormat::kRGBA32F, samples, Backend::kReference);
    const Image got = render(mesh, discard, ColorFormat::kRGBA32F, samples, Backend::kFast);
    expect_same_depth(want.depth, got.depth, std::to_string(samples) + " samples");
  }
}

TEST(UserShader, AnEmptyFunctionIsAnError) {
  const Mesh mesh = test_mesh();
  PipelineState p;
  p.shader = FragmentShader::kUser;
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb({kWidth, kHeight, 1, ColorFormat::kRGBA8});
    try {
      renderer.draw(fb, p, mesh.input());
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
      EXPECT_NE(std::string(e.what()).find("fragment_function"), std::string::npos) << e.what();
    }
    EXPECT_EQ(fb.read_depth(), std::vector<float>(kWidth * kHeight, 1.0f));
  }
}

TEST(UserShader, AnExceptionFromTheFunctionReachesTheCaller) {
  const Mesh mesh = test_mesh();
  PipelineState p;
  p.shader = FragmentShader::kUser;
  p.fragment_function = [](const FragmentBatch&, const FragmentOutput&) {
    throw std::runtime_error("shader failed");
  };
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    options.threads = 2;
    Renderer renderer(options);
    Framebuffer fb({kWidth, kHeight, 1, ColorFormat::kRGBA8});
    EXPECT_THROW(renderer.draw(fb, p, mesh.input()), std::runtime_error);
    // The renderer still draws.
    renderer.draw(fb, user_pipeline({0, 1, 2, 3}), mesh.input());
  }
}

}  // namespace
}  // namespace tessera
