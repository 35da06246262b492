// Blending and colour write masks (tessera/pipeline.hpp's BlendState): the formulas against
// values computed by hand, the reference's images against hand-computed bytes, and the fast
// engine against the reference byte for byte on every SIMD target and thread count, for every
// factor and operation, RGBA8 and RGBA32F targets, one and four samples, through every
// raster path (pixel-by-pixel, windows, blocks, shaded kernels, points and lines).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "engine/src/blend/blend.hpp"
#include "tessera/tessera.hpp"
#include "tests/expect_error.hpp"
#include "tests/simd_targets.hpp"

namespace tessera {
namespace {

using blend::Rgba;

TEST(BlendFormulas, EveryFactorAndOperationGivesTheHandComputedValue) {
  const Rgba s = {0.8f, 0.4f, 0.2f, 0.6f};
  const Rgba d = {0.1f, 0.5f, 0.9f, 0.3f};
  const Rgba k = {0.25f, 0.5f, 0.75f, 0.2f};
  struct Expect {
    BlendFactor f;
    Rgba value;  // the factor for R, G, B, A
  };
  const Expect expects[] = {
      {BlendFactor::kZero, {0, 0, 0, 0}},
      {BlendFactor::kOne, {1, 1, 1, 1}},
      {BlendFactor::kSrcColor, {0.8f, 0.4f, 0.2f, 0.6f}},
      {BlendFactor::kOneMinusSrcColor, {1 - 0.8f, 1 - 0.4f, 1 - 0.2f, 1 - 0.6f}},
      {BlendFactor::kDstColor, {0.1f, 0.5f, 0.9f, 0.3f}},
      {BlendFactor::kOneMinusDstColor, {1 - 0.1f, 1 - 0.5f, 1 - 0.9f, 1 - 0.3f}},
      {BlendFactor::kSrcAlpha, {0.6f, 0.6f, 0.6f, 0.6f}},
      {BlendFactor::kOneMinusSrcAlpha, {1 - 0.6f, 1 - 0.6f, 1 - 0.6f, 1 - 0.6f}},
      {BlendFactor::kDstAlpha, {0.3f, 0.3f, 0.3f, 0.3f}},
      {BlendFactor::kOneMinusDstAlpha, {1 - 0.3f, 1 - 0.3f, 1 - 0.3f, 1 - 0.3f}},
      {BlendFactor::kConstantColor, {0.25f, 0.5f, 0.75f, 0.2f}},
      {BlendFactor::kOneMinusConstantColor, {0.75f, 0.5f, 0.25f, 1 - 0.2f}},
      {BlendFactor::kConstantAlpha, {0.2f, 0.2f, 0.2f, 0.2f}},
      {BlendFactor::kOneMinusConstantAlpha, {1 - 0.2f, 1 - 0.2f, 1 - 0.2f, 1 - 0.2f}},
      // min(0.6, 1 - 0.3) for colour, 1 for alpha.
      {BlendFactor::kSrcAlphaSaturate, {0.6f, 0.6f, 0.6f, 1}},
  };
  for (const Expect& e : expects) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_FLOAT_EQ(blend::factor(e.f, c, s, d, k), e.value[c])
          << "factor " << static_cast<int>(e.f) << " channel " << c;
    }
  }
  // Saturate takes 1 - dst alpha where that is smaller.
  EXPECT_FLOAT_EQ(blend::factor(BlendFactor::kSrcAlphaSaturate, 0, s, {0, 0, 0, 0.9f}, k), 0.1f);

  EXPECT_FLOAT_EQ(blend::combine(BlendOp::kAdd, 0.5f, 0.5f, 0.25f, 2.0f), 0.75f);
  EXPECT_FLOAT_EQ(blend::combine(BlendOp::kSubtract, 0.5f, 0.5f, 0.25f, 0.5f), 0.125f);
  EXPECT_FLOAT_EQ(blend::combine(BlendOp::kReverseSubtract, 0.5f, 0.5f, 0.25f, 0.5f), -0.125f);
  EXPECT_FLOAT_EQ(blend::combine(BlendOp::kMin, 0.5f, 0.0f, 0.25f, 0.0f), 0.25f);  // no factors
  EXPECT_FLOAT_EQ(blend::combine(BlendOp::kMax, 0.5f, 0.0f, 0.25f, 0.0f), 0.5f);
}

TEST(BlendFormulas, Rgba8ClampsSourceAndConstantAndRoundsTheResult) {
  BlendState b = BlendState::additive();
  uint8_t bytes[4] = {100, 200, 0, 255};
  // Source 1.5 is 1 for a unorm target: 100 + 255 saturates; 0.5 * 255 + 200 saturates;
  // -0.5 is 0; alpha 0.2 * 255 + 255 saturates.
  blend::write_rgba8(b, {0, 0, 0, 0}, {1.5f, 0.5f, -0.5f, 0.2f}, bytes);
  EXPECT_EQ(bytes[0], 255);
  EXPECT_EQ(bytes[1], 255);
  EXPECT_EQ(bytes[2], 0);
  EXPECT_EQ(bytes[3], 255);

  // Over: 0.6 * 1 + (1 - 0.6) * 51/255 = 0.68 -> 173.4 -> 173; alpha 0.6 + 0.4 * 1 = 1.
  b = BlendState::over();
  uint8_t over[4] = {51, 0, 255, 255};
  blend::write_rgba8(b, {0, 0, 0, 0}, {1.0f, 0.0f, 0.0f, 0.6f}, over);
  EXPECT_EQ(over[0], 173);
  EXPECT_EQ(over[1], 0);
  EXPECT_EQ(over[2], 102);  // 0.4 * 255 = 102
  EXPECT_EQ(over[3], 255);

  // A constant past 1 is clamped for unorm targets: ONE_MINUS_CONSTANT_COLOR with 2 is 0.
  b = BlendState{};
  b.enable = true;
  b.src_color = BlendFactor::kConstantColor;
  b.dst_color = BlendFactor::kOneMinusConstantColor;
  uint8_t constant[4] = {10, 20, 30, 40};
  blend::write_rgba8(b, {2.0f, 2.0f, 2.0f, 2.0f}, {0.5f, 0.5f, 0.5f, 0.5f}, constant);
  EXPECT_EQ(constant[0], 128);  // 0.5 * 1 + 10/255 * 0 = 0.5 -> 128
  EXPECT_EQ(constant[3], 128);  // alpha (ONE, ZERO): the source

  // The write mask keeps the channels it leaves out, blending or not.
  BlendState masked;
  masked.write_mask = kWriteRed | kWriteAlpha;
  uint8_t kept[4] = {1, 2, 3, 4};
  blend::write_rgba8(masked, {0, 0, 0, 0}, {1.0f, 1.0f, 1.0f, 1.0f}, kept);
  EXPECT_EQ(kept[0], 255);
  EXPECT_EQ(kept[1], 2);
  EXPECT_EQ(kept[2], 3);
  EXPECT_EQ(kept[3], 255);
}

TEST(BlendFormulas, FloatTargetsBlendWithNothingClamped) {
  BlendState b = BlendState::additive();
  float values[4] = {2.0f, -1.0f, 0.5f, 3.0f};
  blend::write_rgba32f(b, {0, 0, 0, 0}, {1.5f, -0.5f, 0.25f, 0.5f}, values);
  EXPECT_EQ(values[0], 3.5f);
  EXPECT_EQ(values[1], -1.5f);
  EXPECT_EQ(values[2], 0.75f);
  EXPECT_EQ(values[3], 3.5f);
  b.color_op = BlendOp::kReverseSubtract;
  b.alpha_op = BlendOp::kMin;
  float rev[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  blend::write_rgba32f(b, {0, 0, 0, 0}, {0.25f, 2.0f, -1.0f, 0.5f}, rev);
  EXPECT_EQ(rev[0], 0.75f);
  EXPECT_EQ(rev[1], -1.0f);
  EXPECT_EQ(rev[2], 2.0f);
  EXPECT_EQ(rev[3], 0.5f);
}

// A draw of triangles in window pixels, each of one colour.
struct Scene {
  uint32_t width = 136;  // three tiles across, the last one partial
  uint32_t height = 72;  // two tiles down
  std::vector<Float4> positions;
  std::vector<float> colors;

  void add(const float (&x)[3], const float (&y)[3], float z, const Rgba& rgba) {
    for (int k = 0; k < 3; ++k) {
      positions.push_back({2.0f * x[k] / static_cast<float>(width) - 1.0f,
                           1.0f - 2.0f * y[k] / static_cast<float>(height), z, 1.0f});
      colors.insert(colors.end(), rgba.begin(), rgba.end());
    }
  }
};

// Overlapping triangles of every size class (a few pixels to larger than the screen), each of
// one colour, so both backends blend the same source values; colours past [0, 1] included.
Scene soup(uint32_t seed) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float sizes[] = {1.5f, 3.0f, 6.0f, 12.0f, 40.0f, 150.0f};
  for (int i = 0; i < 600; ++i) {
    const float size = sizes[i % 6];
    const float cx = (u(rng) * 1.2f - 0.1f) * static_cast<float>(s.width);
    const float cy = (u(rng) * 1.2f - 0.1f) * static_cast<float>(s.height);
    float x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      x[k] = cx + (u(rng) - 0.5f) * size;
      y[k] = cy + (u(rng) - 0.5f) * size;
    }
    Rgba c;
    for (int ch = 0; ch < 4; ++ch)
      c[ch] = i % 7 == 0 ? u(rng) * 1.6f - 0.3f : u(rng);
    s.add(x, y, u(rng), c);
  }
  return s;
}

struct Image {
  std::vector<uint8_t> rgba8;
  std::vector<float> rgba32f;  // resolved
  std::vector<float> depth;
};

enum class Draw { kTriangles, kShadedTriangles, kPoints, kLines, kSmoothLines };

Image render(const Scene& scene, const PipelineState& pipeline, ColorFormat format,
             uint32_t samples, Backend backend, SimdTarget simd = SimdTarget::kAuto,
             uint32_t threads = 1, Draw draw = Draw::kTriangles) {
  RendererOptions options;
  options.backend = backend;
  options.simd = simd;
  options.threads = threads;
  Renderer renderer(options);
  Framebuffer fb({scene.width, scene.height, samples, format});
  fb.clear_color({0.2f, 0.4f, 0.6f, 0.5f});
  DrawInput input;
  input.positions = scene.positions;
  input.attributes = scene.colors;
  input.attribute_count = 4;
  PipelineState p = pipeline;
  if (draw == Draw::kShadedTriangles) {
    for (uint32_t i = 0; i < 4; ++i)
      p.varying_modes[i] = VaryingMode::kFlat;
  }
  switch (draw) {
    case Draw::kTriangles:
    case Draw::kShadedTriangles:
      renderer.draw(fb, p, input);
      break;
    case Draw::kPoints: {
      PointState points;
      points.size = 3.0f;
      points.shape = PointShape::kRound;
      renderer.draw_points(fb, p, points, input);
      break;
    }
    case Draw::kLines:
    case Draw::kSmoothLines: {
      LineState lines;
      lines.width = draw == Draw::kSmoothLines ? 2.5f : 1.0f;
      lines.antialiased = draw == Draw::kSmoothLines;
      const size_t vertices = scene.positions.size() / 2 * 2;  // pairs
      input.positions = input.positions.first(vertices);
      input.attributes = input.attributes.first(vertices * 4);
      renderer.draw_lines(fb, p, lines, input);
      break;
    }
  }
  Image image;
  if (format == ColorFormat::kRGBA8) {
    image.rgba8 = fb.read_rgba8();
  } else {
    image.rgba32f = fb.read_rgba32f();
  }
  image.depth = fb.read_sample_depth();
  return image;
}

struct State {
  std::string name;
  PipelineState pipeline;
};

std::vector<State> states() {
  std::vector<State> out;
  const auto add = [&](std::string name, BlendState b, bool depth = false) {
    State s;
    s.name = std::move(name);
    s.pipeline.blend[0] = b;
    s.pipeline.blend_constant = {0.3f, 0.6f, 0.9f, 0.45f};
    // Transparent geometry usually tests depth without writing it.
    s.pipeline.depth_test = depth;
    s.pipeline.depth_write = false;
    out.push_back(s);
  };
  add("over", BlendState::over());
  add("over, depth tested", BlendState::over(), true);
  add("additive", BlendState::additive());
  add("multiply", BlendState::multiply());
  add("premultiplied over", BlendState::premultiplied_over());
  BlendState b;
  b.enable = true;
  b.src_color = BlendFactor::kConstantColor;
  b.dst_color = BlendFactor::kOneMinusDstColor;
  b.color_op = BlendOp::kReverseSubtract;
  b.src_alpha = BlendFactor::kSrcAlphaSaturate;
  b.dst_alpha = BlendFactor::kOneMinusConstantAlpha;
  b.alpha_op = BlendOp::kSubtract;
  add("constant, saturate, subtract", b);
  b = BlendState{};
  b.enable = true;
  b.src_color = BlendFactor::kOneMinusSrcColor;
  b.dst_color = BlendFactor::kDstAlpha;
  b.src_alpha = BlendFactor::kOneMinusDstAlpha;
  b.dst_alpha = BlendFactor::kConstantAlpha;
  b.write_mask = kWriteRed | kWriteBlue | kWriteAlpha;
  add("colour factors, masked green", b);
  b = BlendState{};
  b.enable = true;
  b.color_op = BlendOp::kMin;
  b.alpha_op = BlendOp::kMax;
  add("min and max", b);
  b = BlendState{};
  b.src_color = BlendFactor::kOneMinusConstantColor;  // ignored: blending is off
  b.write_mask = kWriteGreen | kWriteAlpha;
  add("write mask only", b, true);
  return out;
}

template <typename T>
size_t first_difference(const std::vector<T>& a, const std::vector<T>& b) {
  for (size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return i;
  return a.size();
}

void expect_same(const Image& fast, const Image& ref, const std::string& what) {
  ASSERT_EQ(fast.rgba8.size(), ref.rgba8.size()) << what;
  ASSERT_EQ(fast.rgba32f.size(), ref.rgba32f.size()) << what;
  const size_t b = first_difference(fast.rgba8, ref.rgba8);
  EXPECT_EQ(b, ref.rgba8.size()) << what << ": byte " << b << " fast " << int{fast.rgba8[b]}
                                 << " reference " << int{ref.rgba8[b]};
  const size_t f = first_difference(fast.rgba32f, ref.rgba32f);
  EXPECT_EQ(f, ref.rgba32f.size())
      << what << ": value " << f << " fast " << (f < fast.rgba32f.size() ? fast.rgba32f[f] : 0.0f)
      << " reference " << (f < ref.rgba32f.size() ? ref.rgba32f[f] : 0.0f);
  EXPECT_EQ(first_difference(fast.depth, ref.depth), ref.depth.size()) << what << ": depth";
}

void expect_fast_equals_reference(Draw draw, const std::vector<uint32_t>& thread_counts) {
  const Scene scene = soup(7);
  for (const State& state : states()) {
    for (ColorFormat format : {ColorFormat::kRGBA8, ColorFormat::kRGBA32F}) {
      for (uint32_t samples : {1u, 4u}) {
        const std::string what = state.name +
                                 (format == ColorFormat::kRGBA8 ? ", RGBA8" : ", F32") + ", " +
                                 std::to_string(samples) + " samples";
        const Image ref = render(scene, state.pipeline, format, samples, Backend::kReference,
                                 SimdTarget::kAuto, 1, draw);
        // The blend changed the image: the state is not a no-op.
        const Image plain = render(scene, PipelineState{}, format, samples, Backend::kReference,
                                   SimdTarget::kAuto, 1, draw);
        EXPECT_TRUE(ref.rgba8 != plain.rgba8 || ref.rgba32f != plain.rgba32f) << what;
        for (SimdTarget simd : test::runnable_simd_targets()) {
          for (uint32_t threads : thread_counts) {
            const Image fast =
                render(scene, state.pipeline, format, samples, Backend::kFast, simd, threads, draw);
            expect_same(fast, ref,
                        what + ", target " + std::to_string(static_cast<int>(simd)) + ", " +
                            std::to_string(threads) + " threads");
          }
        }
      }
    }
  }
}

TEST(Blend, TrianglesBlendAsTheReferenceOnEveryTargetAndThreadCount) {
  expect_fast_equals_reference(Draw::kTriangles, {1, 2, 3});
}

TEST(Blend, ShadedTrianglesBlendAsTheReferenceOnEveryTarget) {
  expect_fast_equals_reference(Draw::kShadedTriangles, {1, 2});
}

TEST(Blend, PointsAndLinesBlendAsTheReferenceOnEveryTarget) {
  expect_fast_equals_reference(Draw::kPoints, {1, 2});
  expect_fast_equals_reference(Draw::kLines, {1, 2});
  expect_fast_equals_reference(Draw::kSmoothLines, {1, 2});
}

TEST(Blend, HalfTransparentRedOverBlueGivesTheHandComputedBytes) {
  // Two screen-covering triangles of (1, 0, 0, 0.5) over the clear colour (0.2, 0.4, 0.6, 0.5),
  // stored as bytes (51, 102, 153, 128), drawn twice: 0.5 + 0.5 * 51/255 = 0.6 (153),
  // 0.5 * 102/255 = 0.2 (51), 0.5 * 153/255 = 0.3 (76.5 -> 77), alpha 0.5 + 0.5 * 128/255
  // (191.5 -> 192); then 0.5 + 0.5 * 153/255 = 0.8 (204), 0.1 (25.5 -> 26), 0.5 * 77/255
  // (38.5 -> 39), 0.5 + 0.5 * 192/255 (223.5 -> 224).
  Scene s;
  s.width = 80;
  s.height = 40;
  s.add({-1, 200, -1}, {-1, -1, 100}, 0.5f, {1.0f, 0.0f, 0.0f, 0.5f});
  s.add({200, 200, -1}, {-1, 100, 100}, 0.5f, {1.0f, 0.0f, 0.0f, 0.5f});
  PipelineState p;
  p.depth_test = false;
  p.blend[0] = BlendState::over();
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb({s.width, s.height, 1, ColorFormat::kRGBA8});
    fb.clear_color({0.2f, 0.4f, 0.6f, 0.5f});
    DrawInput input;
    input.positions = s.positions;
    input.attributes = s.colors;
    input.attribute_count = 4;
    renderer.draw(fb, p, input);
    std::vector<uint8_t> once = fb.read_rgba8();
    for (size_t i = 0; i < once.size(); i += 4) {
      ASSERT_EQ(once[i + 0], 153) << i;
      ASSERT_EQ(once[i + 1], 51) << i;
      ASSERT_EQ(once[i + 2], 77) << i;
      ASSERT_EQ(once[i + 3], 192) << i;
    }
    renderer.draw(fb, p, input);
    std::vector<uint8_t> twice = fb.read_rgba8();
    for (size_t i = 0; i < twice.size(); i += 4) {
      ASSERT_EQ(twice[i + 0], 204) << i;
      ASSERT_EQ(twice[i + 1], 26) << i;
      ASSERT_EQ(twice[i + 2], 39) << i;
      ASSERT_EQ(twice[i + 3], 224) << i;
    }
  }
}

TEST(BlendValidation, BadBlendStateIsAnErrorNamingTheField) {
  Renderer renderer;
  Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
  const std::vector<Float4> positions = {{-1, -1, 0.5f, 1}, {1, -1, 0.5f, 1}, {0, 1, 0.5f, 1}};
  DrawInput input;
  input.positions = positions;
  const auto expect = [&](const PipelineState& p, const std::string& text) {
    test::expect_error([&] { renderer.draw(fb, p, input); }, ErrorCode::kInvalidArgument, text);
  };
  PipelineState p;
  p.blend[0].src_color = static_cast<BlendFactor>(99);
  expect(p, "blend[0].src_color has the invalid value 99");
  p = PipelineState{};
  p.blend[0].alpha_op = static_cast<BlendOp>(7);
  expect(p, "blend[0].alpha_op has the invalid value 7");
  p = PipelineState{};
  p.blend[0].write_mask = 16;
  expect(p, "blend[0].write_mask 16");
  p = PipelineState{};
  p.blend[1] = BlendState::over();
  expect(p, "blend[1] blends or masks channels");
  p = PipelineState{};
  p.blend_constant[2] = std::nanf("");
  expect(p, "blend_constant[2] is not finite");
}

}  // namespace
}  // namespace tessera
