// Multiple render targets (FramebufferDesc::extra_targets, PipelineState::extra_outputs): one
// draw writes colour, normals, eye depth and IDs into up to four targets, each equal to what a
// draw of that output alone writes; the fast engine matches the reference on every SIMD target
// and thread count; a user shader feeds the extra targets; discards drop a fragment from all of
// them; and bad targets, formats and reads are errors naming what was wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/expect_error.hpp"
#include "tests/shading_scene.hpp"

namespace tessera {
namespace {

using shading_scene::kClear;
using shading_scene::kHeight;
using shading_scene::kWidth;
using shading_scene::Mesh;
using shading_scene::Target;
using shading_scene::test_mesh;

constexpr uint32_t kStride = kFragmentBatchStride;
constexpr uint32_t kNoId = 0xFFFFFFFFu;

// Every target of a framebuffer read back: floats (RGBA: 4 per pixel, R32F: 1) or, for R32UI,
// unsigned integers; and every sample's depth.
struct Targets {
  std::vector<std::vector<float>> floats;
  std::vector<std::vector<uint32_t>> uints;
  std::vector<float> depth;
};

FramebufferDesc mrt_desc(uint32_t samples, std::vector<ColorFormat> extra,
                         ColorFormat first = ColorFormat::kRGBA32F) {
  FramebufferDesc d{kWidth, kHeight, samples, first};
  d.extra_targets = static_cast<uint32_t>(extra.size());
  std::copy(extra.begin(), extra.end(), d.extra_formats.begin());
  return d;
}

Targets read_all(const Framebuffer& fb) {
  Targets out;
  out.floats.resize(fb.target_count());
  out.uints.resize(fb.target_count());
  for (uint32_t t = 0; t < fb.target_count(); ++t) {
    if (fb.target_format(t) == ColorFormat::kR32UI) {
      out.uints[t] = fb.read_target_uint(t);
    } else {
      out.floats[t] = fb.read_target(t);
    }
  }
  out.depth = fb.read_sample_depth();
  return out;
}

// Clears every target to values no draw writes, then draws.
void clear_all(Framebuffer& fb) {
  for (uint32_t t = 0; t < fb.target_count(); ++t) {
    if (fb.target_format(t) == ColorFormat::kR32UI) {
      fb.clear_target_uint(t, kNoId);
    } else {
      fb.clear_target(t, {kClear, kClear, kClear, kClear});
    }
  }
}

Targets render(const FramebufferDesc& desc, const PipelineState& pipeline, const DrawInput& input,
               Backend backend, Target target = {SimdTarget::kAuto, 1}) {
  RendererOptions options;
  options.backend = backend;
  options.simd = target.simd;
  options.threads = target.threads;
  Renderer renderer(options);
  Framebuffer fb(desc);
  clear_all(fb);
  renderer.draw(fb, pipeline, input);
  return read_all(fb);
}

// Gouraud colour in target 0, normals (RGBA32F), eye depth (R32F) and primitive IDs (R32UI).
PipelineState vision_pipeline() {
  PipelineState p;
  p.extra_outputs = {TargetOutput::kNormal, TargetOutput::kEyeDepth, TargetOutput::kPrimitiveId};
  return p;
}

const std::vector<ColorFormat> kVisionFormats = {ColorFormat::kRGBA32F, ColorFormat::kR32F,
                                                 ColorFormat::kR32UI};

// Target t of `mrt` against `single`'s RGBA32F colour: every channel, or (one-channel targets)
// red only; within absolute + relative x |value|, and the same pixels covered.
void expect_target_matches(const std::vector<float>& single, const std::vector<float>& mrt,
                           uint32_t channels, double absolute, double relative,
                           const std::string& where) {
  ASSERT_EQ(mrt.size(), single.size() / 4 * channels) << where;
  size_t covered = 0;
  for (size_t p = 0; p < single.size() / 4; ++p) {
    for (uint32_t c = 0; c < channels; ++c) {
      const float want = single[p * 4 + c], got = mrt[p * channels + c];
      ASSERT_EQ(want == kClear, got == kClear) << where << ": pixel " << p << " channel " << c;
      ASSERT_LE(std::abs(double{got} - want), absolute + relative * std::abs(want))
          << where << ": pixel " << p << " channel " << c << ": " << got << " against " << want;
      covered += c == 0 && want != kClear;
    }
  }
  EXPECT_GT(covered, size_t{kWidth * kHeight / 2}) << where;
}

// The IDs of an R32UI target against a draw of the same output into an RGBA32F target.
void expect_ids_match(const std::vector<float>& single, const std::vector<uint32_t>& ids,
                      const std::string& where) {
  ASSERT_EQ(ids.size(), single.size() / 4) << where;
  for (size_t p = 0; p < ids.size(); ++p) {
    const float want = single[p * 4];
    ASSERT_EQ(ids[p], want == kClear ? kNoId : static_cast<uint32_t>(want))
        << where << ": pixel " << p;
  }
}

// Each target of one draw holds what a draw of that output alone holds, on both backends (one
// sample: the R32UI target's sample 0 is then the pixel).
TEST(MultipleTargets, EachTargetHoldsWhatADrawOfItsOutputAloneHolds) {
  const Mesh mesh = test_mesh();
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    const std::string where = backend == Backend::kFast ? "fast" : "reference";
    const FramebufferDesc one{kWidth, kHeight, 1, ColorFormat::kRGBA32F};
    const Targets mrt =
        render(mrt_desc(1, kVisionFormats), vision_pipeline(), mesh.input(), backend);
    const auto single = [&](TargetOutput output) {
      PipelineState p;
      p.output = output;
      return render(one, p, mesh.input(), backend);
    };
    const Targets colour = single(TargetOutput::kColor);
    EXPECT_EQ(mrt.depth, colour.depth) << where;
    // The reference computes every output with the same code alone or together; the fast
    // engine may shade a target through a different kernel, within the shaders' tolerances.
    const bool exact = backend == Backend::kReference;
    expect_target_matches(colour.floats[0], mrt.floats[0], 4, exact ? 0 : 2e-6, 0,
                          where + " colour");
    expect_target_matches(single(TargetOutput::kNormal).floats[0], mrt.floats[1], 4,
                          exact ? 0 : 2e-6, 0, where + " normals");
    expect_target_matches(single(TargetOutput::kEyeDepth).floats[0], mrt.floats[2], 1, 0,
                          exact ? 0 : 2e-6, where + " eye depth");
    expect_ids_match(single(TargetOutput::kPrimitiveId).floats[0], mrt.uints[3],
                     where + " primitive IDs");
  }
}

// The fast engine against the reference, all four targets at once: identical bytes on every
// SIMD target and thread count, the reference's coverage and IDs exactly, values within the
// shaders' tolerances; with one and four samples and target 0 in both formats.
TEST(MultipleTargets, FastMatchesTheReferenceOnEveryTargetAndThreadCount) {
  const Mesh mesh = test_mesh();
  const std::vector<Target> targets = shading_scene::fast_targets();
  ASSERT_FALSE(targets.empty());
  PipelineState phong = vision_pipeline();
  phong.shader = FragmentShader::kPhong;
  phong.phong.light_count = 1;
  phong.phong.lights[0].position = {1.0f, 2.0f, 1.0f};
  for (const PipelineState& pipeline : {vision_pipeline(), phong}) {
    const bool is_phong = pipeline.shader == FragmentShader::kPhong;
    for (ColorFormat first : {ColorFormat::kRGBA32F, ColorFormat::kRGBA8}) {
      for (uint32_t samples : {1u, 4u}) {
        const std::string where = std::string(is_phong ? "phong, " : "gouraud, ") +
                                  (first == ColorFormat::kRGBA8 ? "RGBA8, " : "RGBA32F, ") +
                                  std::to_string(samples) + " samples";
        const FramebufferDesc desc = mrt_desc(samples, kVisionFormats, first);
        const Targets want = render(desc, pipeline, mesh.input(), Backend::kReference);
        const Targets got = render(desc, pipeline, mesh.input(), Backend::kFast, targets[0]);
        for (const Target& t : targets) {
          const Targets again = render(desc, pipeline, mesh.input(), Backend::kFast, t);
          ASSERT_EQ(again.floats, got.floats)
              << where << ", target " << int(t.simd) << ", " << t.threads << " threads";
          ASSERT_EQ(again.uints, got.uints) << where << ", target " << int(t.simd);
          ASSERT_EQ(again.depth, got.depth) << where << ", target " << int(t.simd);
        }
        // Target 0: RGBA8 bytes (as floats / 255) within one step, RGBA32F within the shader's
        // tolerance; the clear is kClear in RGBA32F and 0 in RGBA8.
        const float clear0 = first == ColorFormat::kRGBA8 ? 0.0f : kClear;
        const double tolerance0 = first == ColorFormat::kRGBA8 ? 1.0 / 255 + 1e-7
                                  : is_phong                   ? 2e-5
                                                               : 2e-6;
        for (size_t i = 0; i < want.floats[0].size(); ++i) {
          const float w = want.floats[0][i], g = got.floats[0][i];
          if (first == ColorFormat::kRGBA32F) {
            ASSERT_EQ(w == clear0, g == clear0) << where << ": target 0 value " << i;
          }
          ASSERT_LE(std::abs(w - g), tolerance0) << where << ": target 0 value " << i;
        }
        size_t covered = 0;
        for (size_t i = 0; i < want.floats[1].size(); ++i) {
          const float w = want.floats[1][i], g = got.floats[1][i];
          ASSERT_EQ(w == kClear, g == kClear) << where << ": normals value " << i;
          ASSERT_LE(std::abs(w - g), 2e-6) << where << ": normals value " << i;
          covered += w != kClear;
        }
        EXPECT_GT(covered, size_t{kWidth * kHeight * 2}) << where;
        for (size_t i = 0; i < want.floats[2].size(); ++i) {
          const float w = want.floats[2][i], g = got.floats[2][i];
          ASSERT_EQ(w == kClear, g == kClear) << where << ": eye depth pixel " << i;
          ASSERT_LE(std::abs(w - g), 2e-6 * std::abs(w)) << where << ": eye depth pixel " << i;
        }
        EXPECT_EQ(want.uints[3], got.uints[3]) << where << ": primitive IDs";
        // Resolved float targets of partly covered pixels mix kClear in, so a 4-sample target's
        // coverage is that of depth: the samples both backends wrote.
        const size_t ids = static_cast<size_t>(std::count_if(
            got.uints[3].begin(), got.uints[3].end(), [](uint32_t v) { return v != kNoId; }));
        EXPECT_GT(ids, size_t{kWidth * kHeight / 2}) << where;
        EXPECT_LT(*std::max_element(got.uints[3].begin(), got.uints[3].end(),
                                    [](uint32_t a, uint32_t b) {
                                      return (a == kNoId ? 0 : a) < (b == kNoId ? 0 : b);
                                    }),
                  mesh.positions.size() / 3)
            << where;
      }
    }
  }
}

// An R32UI target keeps IDs beyond 2^24 exactly, which a float target cannot.
TEST(MultipleTargets, AnIntegerTargetKeepsLargeObjectIdsExactly) {
  const Mesh mesh = test_mesh();
  PipelineState p;
  p.object_id = (1u << 24) + 3;
  p.extra_outputs[0] = TargetOutput::kObjectId;
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    const Targets got = render(mrt_desc(4, {ColorFormat::kR32UI}), p, mesh.input(), backend);
    size_t hit = 0;
    for (uint32_t v : got.uints[1]) {
      ASSERT_TRUE(v == kNoId || v == p.object_id) << v;
      hit += v == p.object_id;
    }
    EXPECT_GT(hit, size_t{kWidth * kHeight / 2});
  }
  // The same ID in a float target is an error.
  p.extra_outputs[0] = TargetOutput::kObjectId;
  Renderer renderer;
  Framebuffer fb(mrt_desc(1, {ColorFormat::kR32F}));
  try {
    renderer.draw(fb, p, mesh.input());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("object_id"), std::string::npos) << e.what();
  }
}

// A user shader writes target 0 and two extra targets (an RGBA8 one and an R32UI one); the
// engine computes a built-in output for the third; both backends agree.
TEST(MultipleTargets, AUserShaderFeedsTheExtraTargets) {
  const Mesh mesh = test_mesh();
  PipelineState p;
  p.shader = FragmentShader::kUser;
  p.extra_outputs = {TargetOutput::kColor, TargetOutput::kColor, TargetOutput::kEyeDepth};
  p.fragment_function = [](const FragmentBatch& b, const FragmentOutput& out) {
    EXPECT_NE(out.extra[0], nullptr);
    EXPECT_EQ(out.extra[1], nullptr);
    EXPECT_NE(out.extra_uint[1], nullptr);
    EXPECT_NE(out.extra[2], nullptr);  // computed by the engine; the shader's values are dropped
    for (uint32_t i = 0; i < b.count; ++i) {
      for (uint32_t c = 0; c < 4; ++c) {
        out.color[c * kStride + i] = b.varyings[c * kStride + i];
        // Target 1: the normal mapped to 0..1, alpha 1.
        out.extra[0][c * kStride + i] =
            c < 3 ? 0.5f + 0.5f * b.varyings[(4 + c) * kStride + i] : 1.0f;
      }
      out.extra_uint[1][i] = b.primitive_id[i] * 10 + 7;
      out.extra[2][i] = 123.0f;
    }
  };
  const std::vector<ColorFormat> formats = {ColorFormat::kRGBA8, ColorFormat::kR32UI,
                                            ColorFormat::kR32F};
  for (uint32_t samples : {1u, 4u}) {
    const FramebufferDesc desc = mrt_desc(samples, formats);
    const Targets want = render(desc, p, mesh.input(), Backend::kReference);
    const Targets got = render(desc, p, mesh.input(), Backend::kFast, {SimdTarget::kAuto, 2});
    const std::string where = std::to_string(samples) + " samples";
    // Depth from the fast engine's float planes and the reference's double ones: the same
    // samples written, values within a few float steps.
    ASSERT_EQ(want.depth.size(), got.depth.size());
    for (size_t i = 0; i < want.depth.size(); ++i) {
      ASSERT_EQ(want.depth[i] == 1.0f, got.depth[i] == 1.0f) << where << ": sample " << i;
      ASSERT_LE(std::abs(want.depth[i] - got.depth[i]), 1e-6f) << where << ": sample " << i;
    }
    for (size_t i = 0; i < want.floats[0].size(); ++i)
      ASSERT_LE(std::abs(want.floats[0][i] - got.floats[0][i]), 2e-6) << where << ": " << i;
    for (size_t i = 0; i < want.floats[1].size(); ++i)
      ASSERT_LE(std::abs(want.floats[1][i] - got.floats[1][i]), 1.0 / 255 + 1e-7) << where;
    EXPECT_EQ(want.uints[2], got.uints[2]) << where;
    size_t covered = 0;
    for (size_t i = 0; i < got.uints[2].size(); ++i) {
      const uint32_t v = got.uints[2][i];
      ASSERT_TRUE(v == kNoId || v % 10 == 7) << where << ": pixel " << i << " holds " << v;
      covered += v != kNoId;
      // The eye depth is the engine's, never the 123 the shader wrote.
      ASSERT_NE(got.floats[3][i], 123.0f) << where;
      if (samples == 1) {
        ASSERT_EQ(v == kNoId, got.floats[3][i] == kClear) << where;
      }
    }
    EXPECT_GT(covered, size_t{kWidth * kHeight / 2}) << where;
    for (size_t i = 0; i < want.floats[3].size(); ++i)
      ASSERT_LE(std::abs(want.floats[3][i] - got.floats[3][i]), 2e-6 * std::abs(want.floats[3][i]))
          << where;
  }
}

// A discarded fragment writes no target: the checkerboard of discarded pixels keeps every
// target's clear value, and the kept pixels hold what they hold without discards.
TEST(MultipleTargets, ADiscardedFragmentWritesNoTarget) {
  Mesh sheet;
  shading_scene::add_sheet(sheet, 6, -1.5, -1.2, 2.6, -4.0);
  const auto pipeline = [](bool discard) {
    PipelineState p;
    p.shader = FragmentShader::kUser;
    p.extra_outputs = {TargetOutput::kNormal, TargetOutput::kEyeDepth, TargetOutput::kPrimitiveId};
    p.fragment_function = [discard](const FragmentBatch& b, const FragmentOutput& out) {
      for (uint32_t i = 0; i < b.count; ++i) {
        for (uint32_t c = 0; c < 4; ++c)
          out.color[c * kStride + i] = b.varyings[c * kStride + i];
        out.discard[i] = discard && (static_cast<int>(b.x[i]) + static_cast<int>(b.y[i])) % 2 == 0;
      }
    };
    return p;
  };
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    const FramebufferDesc desc = mrt_desc(1, kVisionFormats);
    const Targets all = render(desc, pipeline(false), sheet.input(), backend);
    const Targets some = render(desc, pipeline(true), sheet.input(), backend);
    size_t dropped = 0, kept = 0;
    for (uint32_t y = 0; y < kHeight; ++y) {
      for (uint32_t x = 0; x < kWidth; ++x) {
        const size_t p = size_t{y} * kWidth + x;
        const bool discarded = (x + y) % 2 == 0;
        for (uint32_t c = 0; c < 4; ++c) {
          ASSERT_EQ(some.floats[0][p * 4 + c], discarded ? kClear : all.floats[0][p * 4 + c]);
          ASSERT_EQ(some.floats[1][p * 4 + c], discarded ? kClear : all.floats[1][p * 4 + c]);
        }
        ASSERT_EQ(some.floats[2][p], discarded ? kClear : all.floats[2][p]);
        ASSERT_EQ(some.uints[3][p], discarded ? kNoId : all.uints[3][p]);
        if (all.uints[3][p] != kNoId) (discarded ? dropped : kept) += 1;
      }
    }
    EXPECT_GT(dropped, 500u);
    EXPECT_GT(kept, 500u);
  }
}

// Points, lines and polygons draw into target 0 only; the extra targets keep their clear.
TEST(MultipleTargets, PointsLinesAndPolygonsWriteTargetZeroOnly) {
  const std::vector<Float4> positions = {
      {-0.5f, -0.5f, 0.5f, 1}, {0.5f, 0.4f, 0.5f, 1}, {0.2f, -0.6f, 0.5f, 1}};
  const std::vector<float> colours(12, 1.0f);
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb(mrt_desc(1, {ColorFormat::kRGBA32F, ColorFormat::kR32UI}));
    clear_all(fb);
    PipelineState p;
    p.extra_outputs = {TargetOutput::kNormal, TargetOutput::kPrimitiveId};
    LineState lines;
    lines.topology = LineTopology::kStrip;
    lines.width = 3.0f;
    PointState points;
    points.size = 5.0f;
    const DrawInput input{positions, colours, 4, {}};
    renderer.draw_lines(fb, p, lines, input);
    renderer.draw_points(fb, p, points, input);
    renderer.draw_polygon(fb, p, PolygonState{}, input);
    const std::vector<float> colour = fb.read_target(0);
    EXPECT_GT(std::count(colour.begin(), colour.end(), 1.0f), 100) << int(backend);
    const std::vector<float> normals = fb.read_target(1);
    EXPECT_TRUE(std::all_of(normals.begin(), normals.end(), [](float v) { return v == kClear; }));
    const std::vector<uint32_t> ids = fb.read_target_uint(2);
    EXPECT_TRUE(std::all_of(ids.begin(), ids.end(), [](uint32_t v) { return v == kNoId; }));
  }
}

// Clear and read: each target keeps its own clear; RGBA8 targets read as bytes / 255, R32F as
// its red channel; extra targets start at 0.
TEST(MultipleTargets, TargetsClearAndReadInTheirFormats) {
  Framebuffer fb(mrt_desc(2, {ColorFormat::kRGBA8, ColorFormat::kR32F, ColorFormat::kR32UI},
                          ColorFormat::kRGBA8));
  ASSERT_EQ(fb.target_count(), 4u);
  EXPECT_EQ(fb.target_format(0), ColorFormat::kRGBA8);
  EXPECT_EQ(fb.target_format(3), ColorFormat::kR32UI);
  const size_t pixels = size_t{kWidth} * kHeight;
  EXPECT_EQ(fb.read_target(1), std::vector<float>(pixels * 4, 0.0f));
  EXPECT_EQ(fb.read_target(2), std::vector<float>(pixels, 0.0f));
  EXPECT_EQ(fb.read_target_uint(3), std::vector<uint32_t>(pixels, 0u));
  fb.clear_target(0, {1.0f, 0.0f, 0.0f, 1.0f});
  fb.clear_target(1, {0.2f, 0.4f, 2.0f, -1.0f});
  fb.clear_target(2, {0.25f, 9.0f, 9.0f, 9.0f});
  fb.clear_target_uint(3, 42);
  EXPECT_EQ(fb.read_rgba8()[0], 255);
  const std::vector<float> one = fb.read_target(1);
  EXPECT_EQ(one[0], 51.0f / 255);  // 0.2 rounds to byte 51
  EXPECT_EQ(one[1], 102.0f / 255);
  EXPECT_EQ(one[2], 1.0f);  // clamped
  EXPECT_EQ(one[3], 0.0f);
  EXPECT_EQ(fb.read_target(2), std::vector<float>(pixels, 0.25f));
  EXPECT_EQ(fb.read_target_uint(3), std::vector<uint32_t>(pixels, 42u));
}

using test::expect_error;

TEST(MultipleTargets, BadTargetsFormatsAndReadsAreErrors) {
  FramebufferDesc d = mrt_desc(1, {});
  d.extra_targets = 4;
  expect_error([&] { Framebuffer fb(d); }, ErrorCode::kInvalidArgument, "extra_targets 4");
  d = mrt_desc(1, {}, ColorFormat::kR32F);
  expect_error([&] { Framebuffer fb(d); }, ErrorCode::kInvalidArgument, "target 0");
  d = mrt_desc(1, {ColorFormat::kRGBA8});
  d.extra_formats[0] = static_cast<ColorFormat>(9);
  expect_error([&] { Framebuffer fb(d); }, ErrorCode::kInvalidArgument, "extra_formats[0]");

  Framebuffer fb(mrt_desc(1, {ColorFormat::kR32F, ColorFormat::kR32UI}));
  expect_error([&] { fb.read_target(3); }, ErrorCode::kInvalidArgument, "target 3 does not exist");
  expect_error([&] { fb.read_target(2); }, ErrorCode::kInvalidArgument, "read_target_uint");
  expect_error([&] { fb.read_target_uint(1); }, ErrorCode::kInvalidArgument, "R32F, not R32UI");
  expect_error([&] { fb.read_target_uint(0); }, ErrorCode::kInvalidArgument, "not R32UI");
  expect_error(
      [&] {
        fb.clear_target(2, {1, 1, 1, 1});
      },
      ErrorCode::kInvalidArgument, "clear_target_uint");
  expect_error([&] { fb.clear_target_uint(1, 3); }, ErrorCode::kInvalidArgument, "not R32UI");
  expect_error([&] { fb.target_format(7); }, ErrorCode::kInvalidArgument, "target 7");

  // Draws: an R32UI target takes IDs or a user shader's integers, never a float output; IDs
  // never go to an RGBA8 target; every extra output is checked like `output`.
  const Mesh mesh = test_mesh();
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    const auto draw_error = [&](const FramebufferDesc& desc, const PipelineState& p,
                                const std::string& words) {
      Framebuffer target(desc);
      expect_error([&] { renderer.draw(target, p, mesh.input()); }, ErrorCode::kInvalidArgument,
                   words);
      // Nothing was drawn.
      EXPECT_EQ(target.read_depth(), std::vector<float>(kWidth * kHeight, 1.0f));
    };
    PipelineState p;
    p.extra_outputs[0] = TargetOutput::kNormal;
    draw_error(mrt_desc(1, {ColorFormat::kR32UI}), p, "extra_outputs[0] kNormal");
    p.extra_outputs[0] = TargetOutput::kPrimitiveId;
    draw_error(mrt_desc(1, {ColorFormat::kRGBA8}), p, "target 1 is RGBA8");
    p.extra_outputs = {TargetOutput::kColor, TargetOutput::kPosition};
    p.roles.position = 8;  // 8..10 of 10 varyings
    draw_error(mrt_desc(1, {ColorFormat::kR32F, ColorFormat::kRGBA32F}), p, "extra_outputs[1]");
    p = PipelineState{};
    p.extra_outputs[2] = static_cast<TargetOutput>(40);
    draw_error(mrt_desc(1, {ColorFormat::kR32F, ColorFormat::kR32F, ColorFormat::kR32F}), p,
               "extra_outputs[2]");
  }
}

}  // namespace
}  // namespace tessera
