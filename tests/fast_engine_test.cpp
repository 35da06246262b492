// The fast engine against the reference rasterizer, for every SIMD target this machine runs
// and for 1, 2 and 3 threads: coverage identical bit for bit, depth within kDepthTolerance, colour
// within one 8-bit step, and images byte-identical across thread counts, runs and targets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/sample_positions.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace tessera {
namespace {

// Largest difference between the fast engine's depth and the reference's, in units of 2^-24
// (one float ulp just below 1.0, the top of the depth range). The reference evaluates z/w in
// double at each sample; the fast engine evaluates the depth plane in float from the corner of
// each 8x8 block, a few roundings of terms bounded by the depth range, so its error is absolute
// rather than relative to the (possibly tiny) depth value. The worst seen in these tests is 2.
constexpr double kDepthTolerance = 4.0;

struct Config {
  SimdTarget target;
  uint32_t threads;
};

std::string config_name(const Config& config) {
  const char* names[] = {"auto", "scalar", "sse4", "avx2", "avx512", "neon", "sve"};
  return std::string(names[static_cast<int>(config.target)]) + ", " +
         std::to_string(config.threads) + " threads";
}

std::vector<Config> all_configs() {
  std::vector<Config> configs;
  for (SimdTarget t : {SimdTarget::kScalar, SimdTarget::kSSE4, SimdTarget::kAVX2,
                       SimdTarget::kAVX512, SimdTarget::kNEON, SimdTarget::kSVE}) {
    if (!simd::is_available(t)) continue;
    for (uint32_t threads : {1u, 2u, 3u})
      configs.push_back({t, threads});
  }
  return configs;
}

// A draw: clip-space positions (three per triangle), four colour floats per vertex.
struct Scene {
  uint32_t width = 136;  // three tiles across, the last one partial
  uint32_t height = 72;  // two tiles down
  uint32_t samples = 1;
  ColorFormat format = ColorFormat::kRGBA8;
  DepthFormat depth_format = DepthFormat::kFloat32;
  PipelineState pipeline;
  std::vector<Float4> positions;
  std::vector<float> colors;

  // Appends a triangle given in window pixels (y down) with depth z/w and clip w per vertex.
  void add(const float (&x)[3], const float (&y)[3], const float (&z)[3], const float (&w)[3],
           const float (&rgba)[3][4]) {
    for (int k = 0; k < 3; ++k) {
      positions.push_back({(2.0f * x[k] / static_cast<float>(width) - 1.0f) * w[k],
                           (1.0f - 2.0f * y[k] / static_cast<float>(height)) * w[k], z[k] * w[k],
                           w[k]});
      colors.insert(colors.end(), rgba[k], rgba[k] + 4);
    }
  }
};

struct Result {
  std::vector<uint8_t> rgba8;
  std::vector<float> rgba32f;
  std::vector<float> depth;  // every sample
  Counters counters;
};

Result render(const Scene& scene, Backend backend, const Config& config = {SimdTarget::kAuto, 1},
              uint64_t budget = kDefaultBinMemoryBudget, bool raster_counters = true,
              bool hiz = true, uint32_t bin_tile_size = 64, uint32_t block_size = 8,
              bool sub_blocks = false, bool records = true) {
  RendererOptions options;
  options.tiny_triangle_records = records;
  options.sub_block_tests = sub_blocks;
  options.bin_tile_size = bin_tile_size;
  options.block_size = block_size;
  options.raster_counters = raster_counters;
  options.hiz = hiz;
  options.backend = backend;
  options.threads = config.threads;
  options.simd = config.target;
  options.bin_memory_budget = budget;
  Renderer renderer(options);
  Framebuffer fb({scene.width, scene.height, scene.samples, scene.format, scene.depth_format});
  fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
  DrawInput input;
  input.positions = scene.positions;
  input.attributes = scene.colors;
  input.attribute_count = 4;
  renderer.draw(fb, scene.pipeline, input);
  Result r;
  r.rgba8 = fb.read_rgba8();
  if (scene.format == ColorFormat::kRGBA32F) r.rgba32f = fb.read_rgba32f();
  r.depth = fb.read_sample_depth();
  r.counters = renderer.counters();
  return r;
}

// Random triangles of about `area` pixels, centred anywhere on the screen or a little beyond.
// With flat_depth, triangle i has the constant depth (i + 1) / 2^15, so a sample's final depth
// under CompareOp::kAlways names the last triangle that covered it.
Scene soup(uint32_t seed, int count, float area, bool flat_depth, bool perspective = false) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float side = std::sqrt(4.0f * area / std::sqrt(3.0f));
  for (int i = 0; i < count; ++i) {
    const float cx = (u(rng) * 1.2f - 0.1f) * static_cast<float>(s.width);
    const float cy = (u(rng) * 1.2f - 0.1f) * static_cast<float>(s.height);
    const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
    float x[3], y[3], z[3], w[3], c[3][4];
    for (int k = 0; k < 3; ++k) {
      const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f +
                      (u(rng) - 0.5f) * 0.7f;
      const float r = side / std::sqrt(3.0f) * (0.8f + 0.4f * u(rng));
      x[k] = cx + r * std::cos(a);
      y[k] = cy + r * std::sin(a);
      z[k] = flat_depth ? static_cast<float>(i + 1) / 32768.0f : u(rng);
      w[k] = perspective ? 0.25f + 4.0f * u(rng) : 1.0f;
      for (int ch = 0; ch < 4; ++ch)
        c[k][ch] = u(rng);
    }
    if (i % 2) std::swap(x[1], x[2]), std::swap(y[1], y[2]);  // both windings
    s.add(x, y, z, w, c);
  }
  if (flat_depth) s.pipeline.depth_compare = CompareOp::kAlways;
  return s;
}

// Thin triangles about three pixels tall and one or two wide, at random places, depths and
// colours, w varying per vertex: with the samples' reach their bounding boxes are up to 3 pixels
// wide and 4 high, the boxes of the largest sample records. With flat_depth, depth and w as
// soup's.
Scene tall_soup(uint32_t seed, int count, bool flat_depth) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < count; ++i) {
    const float cx = (u(rng) * 1.1f - 0.05f) * static_cast<float>(s.width);
    const float cy = (u(rng) * 1.1f - 0.05f) * static_cast<float>(s.height);
    const float height = 2.4f + 1.0f * u(rng), width = 0.4f + 1.6f * u(rng);
    const float x[3] = {cx + (u(rng) - 0.5f) * width, cx + (u(rng) - 0.5f) * width,
                        cx + (u(rng) - 0.5f) * width};
    const float y[3] = {cy - 0.5f * height, cy + (u(rng) - 0.5f) * height, cy + 0.5f * height};
    float z[3], w[3], c[3][4];
    for (int k = 0; k < 3; ++k) {
      z[k] = flat_depth ? static_cast<float>(i + 1) / 32768.0f : u(rng);
      w[k] = flat_depth ? 1.0f : 0.25f + 4.0f * u(rng);
      for (int ch = 0; ch < 4; ++ch)
        c[k][ch] = u(rng);
    }
    s.add(x, y, z, w, c);
  }
  if (flat_depth) s.pipeline.depth_compare = CompareOp::kAlways;
  return s;
}

void expect_same_coverage(const Result& fast, const Result& ref, const std::string& what) {
  ASSERT_EQ(fast.depth.size(), ref.depth.size());
  size_t mismatches = 0, first = 0;
  for (size_t i = 0; i < ref.depth.size(); ++i) {
    if (std::memcmp(&fast.depth[i], &ref.depth[i], sizeof(float)) != 0 && mismatches++ == 0) {
      first = i;
    }
  }
  EXPECT_EQ(mismatches, 0u) << what << ": first differing sample " << first << " fast "
                            << fast.depth[first] << " reference " << ref.depth[first];
  EXPECT_EQ(fast.counters.samples_covered, ref.counters.samples_covered) << what;
}

// |a - b| in units of 2^-24.
double depth_error(float a, float b) {
  return std::ldexp(std::abs(double{a} - double{b}), 24);
}

// Every test renders the reference once and compares it with the fast engine under every
// configuration (the reference is the slow part; ctest runs each test in its own process).
template <typename Fn>
void for_each_config(Fn&& fn) {
  for (const Config& config : all_configs()) {
    SCOPED_TRACE(config_name(config));
    fn(config);
  }
}

TEST(FastEngine, CoverageMatchesReferenceInEverySizeClass) {
  // Sub-pixel to larger than the 136x72 screen.
  const float areas[] = {0.2f, 2.0f, 16.0f, 128.0f, 2048.0f, 20000.0f};
  for (size_t c = 0; c < std::size(areas); ++c) {
    const Scene s = soup(100 + static_cast<uint32_t>(c), 10000, areas[c], true);
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      expect_same_coverage(render(s, Backend::kFast, config), ref,
                           "area " + std::to_string(areas[c]));
    });
  }
}

TEST(FastEngine, CoverageMatchesReferenceForEveryMsaaCount) {
  for (uint32_t samples : {2u, 4u, 8u, 16u}) {
    Scene s = soup(200 + samples, 2000, 24.0f, true);
    s.samples = samples;
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      expect_same_coverage(render(s, Backend::kFast, config), ref,
                           std::to_string(samples) + " samples");
    });
  }
}

TEST(FastEngine, CoverageMatchesReferenceForEverySubpixelPrecision) {
  for (uint32_t bits = kMinSubpixelBits; bits <= kMaxSubpixelBits; ++bits) {
    Scene s = soup(300 + bits, 3000, 10.0f, true);
    s.pipeline.subpixel_bits = bits;
    s.samples = bits % 2 ? 4 : 1;
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      expect_same_coverage(render(s, Backend::kFast, config), ref,
                           std::to_string(bits) + " subpixel bits");
    });
  }
}

TEST(FastEngine, CoverageMatchesReferenceOnPixelCentresAndTileAndBlockBoundaries) {
  Scene s;
  std::mt19937 rng(7);
  // Vertices on pixel centres, pixel corners, block (8 px) and tile (64 px) lines.
  const float grid[] = {0.0f,  0.5f,  7.5f,  8.0f,  8.5f,   15.5f,  16.0f,  63.5f,
                        64.0f, 64.5f, 71.5f, 72.0f, 100.5f, 128.0f, 135.5f, 136.0f};
  std::uniform_int_distribution<size_t> pick(0, std::size(grid) - 1);
  for (int i = 0; i < 6000; ++i) {
    float x[3], y[3], z[3], w[3] = {1, 1, 1}, c[3][4] = {};
    for (int k = 0; k < 3; ++k) {
      x[k] = grid[pick(rng)];
      y[k] = std::min(grid[pick(rng)], 72.0f);
      z[k] = static_cast<float>(i + 1) / 32768.0f;
    }
    s.add(x, y, z, w, c);
  }
  s.pipeline.depth_compare = CompareOp::kAlways;
  for (uint32_t samples : {1u, 4u}) {
    s.samples = samples;
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      expect_same_coverage(render(s, Backend::kFast, config), ref,
                           std::to_string(samples) + " samples");
    });
  }
}

TEST(FastEngine, TrianglesBetweenSamplesAreRasterizedWithoutBinning) {
  // A triangle's bounding box holds only the pixels with a sample inside its vertices' box,
  // and at one sample a box of at most 2x2 pixels is drawn only if a pixel centre is inside.
  // Neither triangle here covers a pixel centre: at one sample each is counted as rasterized
  // (not culled) and is not binned. The first lies between four centres (an empty box); the
  // second's box is pixels (10, 10) and (11, 10), whose centres lie outside it. At four
  // samples each covers two, (10.625, 10.875) of pixel (10, 10) and (11.125, 10.625) of pixel
  // (11, 10): both are binned and drawn there.
  struct Case {
    float x[3], y[3];
    uint64_t covered_at_4;
  };
  const Case cases[] = {{{10.6f, 11.4f, 10.6f}, {10.6f, 10.6f, 11.4f}, 2},
                        {{10.4f, 11.0f, 11.6f}, {11.0f, 10.4f, 11.0f}, 2}};
  for (const Case& t : cases) {
    Scene s;
    const float z[3] = {0.5f, 0.5f, 0.5f}, w[3] = {1, 1, 1}, c[3][4] = {};
    s.add(t.x, t.y, z, w, c);
    for (uint32_t samples : {1u, 4u}) {
      SCOPED_TRACE(std::to_string(t.x[0]) + ", " + std::to_string(samples) + " samples");
      s.samples = samples;
      const Result ref = render(s, Backend::kReference);
      EXPECT_EQ(ref.counters.samples_covered, samples == 1 ? 0u : t.covered_at_4);
      for_each_config([&](const Config& config) {
        const Result fast = render(s, Backend::kFast, config);
        expect_same_coverage(fast, ref, "");
        EXPECT_EQ(fast.counters.triangles_rasterized, 1u);
        EXPECT_EQ(fast.counters.triangles_culled, 0u);
        EXPECT_EQ(fast.counters.bin_references, samples == 1 ? 0u : 1u);
        EXPECT_EQ(fast.counters.triangles_binned, samples == 1 ? 0u : 1u);
      });
    }
  }
}

TEST(FastEngine, MultisampleTrianglesBetweenSamplesAreNotBinned) {
  // At four samples this triangle's box is pixel (10, 10), whose first sample (10.375, 10.125)
  // lies inside the vertices' box but not inside the triangle, and no other sample of the
  // pixel is in the box: the setup finds no covered sample (TriangleSetup::sample_bits), so
  // the triangle is rasterized (not culled) and not binned.
  Scene s;
  const float x[3] = {10.45f, 10.3f, 10.45f}, y[3] = {10.2f, 10.2f, 10.1f};
  const float z[3] = {0.5f, 0.5f, 0.5f}, w[3] = {1, 1, 1}, c[3][4] = {};
  s.add(x, y, z, w, c);
  s.samples = 4;
  const Result ref = render(s, Backend::kReference);
  EXPECT_EQ(ref.counters.samples_covered, 0u);
  for_each_config([&](const Config& config) {
    const Result fast = render(s, Backend::kFast, config);
    expect_same_coverage(fast, ref, "");
    EXPECT_EQ(fast.counters.triangles_rasterized, 1u);
    EXPECT_EQ(fast.counters.bin_references, 0u);
  });
}

TEST(FastEngine, LargeTrianglesCutToAFewPixelsMatchReference) {
  // The setup tests the samples of boxes of at most 3x3 pixels itself (sample_bits, pixel and
  // sample records) in 32-bit lanes, which are exact only for small triangles (edges under 32
  // px). On screens of 1x1 to 3x3 pixels every box is that small, whatever the triangle: here
  // triangles with edges from about 3 to 3,000 px (most under 32), centred on the screen or a
  // little beyond, drawn at every sample count the setup tests (1, 2, 4) and at 8 and 16.
  const uint32_t sizes[][2] = {{1, 1}, {2, 2}, {3, 3}, {3, 2}, {2, 3}};
  std::mt19937 rng(717);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const auto& size : sizes) {
    Scene s;
    s.width = size[0];
    s.height = size[1];
    for (int i = 0; i < 600; ++i) {
      const float side = 3.0f + 3000.0f * u(rng) * u(rng) * u(rng);
      const float cx = (u(rng) * 3.0f - 1.0f) * static_cast<float>(s.width);
      const float cy = (u(rng) * 3.0f - 1.0f) * static_cast<float>(s.height);
      const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
      float x[3], y[3], z[3], w[3] = {1, 1, 1}, c[3][4];
      for (int k = 0; k < 3; ++k) {
        const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f +
                        (u(rng) - 0.5f) * 1.5f;
        x[k] = cx + side / std::sqrt(3.0f) * std::cos(a);
        y[k] = cy + side / std::sqrt(3.0f) * std::sin(a);
        z[k] = static_cast<float>(i + 1) / 32768.0f;
        for (int ch = 0; ch < 4; ++ch)
          c[k][ch] = u(rng);
      }
      s.add(x, y, z, w, c);
    }
    s.pipeline.depth_compare = CompareOp::kAlways;
    for (uint32_t samples : {1u, 2u, 4u, 8u, 16u}) {
      SCOPED_TRACE(std::to_string(s.width) + "x" + std::to_string(s.height) + ", " +
                   std::to_string(samples) + " samples");
      s.samples = samples;
      const Result ref = render(s, Backend::kReference);
      EXPECT_GT(ref.counters.samples_covered, 0u);
      for_each_config([&](const Config& config) {
        const Result fast = render(s, Backend::kFast, config);
        expect_same_coverage(fast, ref, "");
        EXPECT_EQ(fast.rgba8, render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, true,
                                     64, 8, false, false)
                                  .rgba8);
      });
    }
  }
}

TEST(FastEngine, TinyTrianglesMatchReferenceInEveryDrawState) {
  // Triangles of about 1.5 pixels, at one, two and four samples: most have a box of at most
  // 2x2 pixels, whose covered pixel centres (one sample: TriangleSetup::centres) or samples
  // (two and four: TriangleSetup::sample_bits) the setup finds and the kernel draws one by one.
  // Each triangle has its own constant depth, increasing with submission by
  // 2^-15, far more than the depth tolerance, so every depth decision is the reference's and
  // each sample's depth names the triangle that wrote it. (The depths are not bit for bit the
  // reference's: z / w of a perspective vertex is not exactly z, and the planes round in
  // float.) Float colour at one sample only, as in ColorWithinOneStepOfReference: with several
  // samples, a pixel centre outside a tiny perspective triangle extrapolates colour far outside
  // [0, 1], where the float planes' error is relative to the value.
  struct State {
    const char* name;
    bool depth_test, depth_write;
    ColorFormat format;
    DepthFormat depth_format;
    Interpolation interpolation;
  };
  const State states[] = {
      {"test+write", true, true, ColorFormat::kRGBA8, DepthFormat::kFloat32,
       Interpolation::kPerspective},
      {"test only", true, false, ColorFormat::kRGBA8, DepthFormat::kFloat32,
       Interpolation::kPerspective},
      {"no depth", false, false, ColorFormat::kRGBA8, DepthFormat::kFloat32,
       Interpolation::kPerspective},
      {"float colour", true, true, ColorFormat::kRGBA32F, DepthFormat::kFloat32,
       Interpolation::kPerspective},
      {"affine", true, true, ColorFormat::kRGBA8, DepthFormat::kFloat32, Interpolation::kAffine},
      {"unorm16", true, true, ColorFormat::kRGBA8, DepthFormat::kUnorm16,
       Interpolation::kPerspective},
      {"unorm24", true, true, ColorFormat::kRGBA8, DepthFormat::kUnorm24,
       Interpolation::kPerspective},
  };
  for (const State& state : states) {
    for (uint32_t samples : {1u, 2u, 4u}) {
      if (state.format == ColorFormat::kRGBA32F && samples > 1) continue;
      SCOPED_TRACE(std::string(state.name) + ", " + std::to_string(samples) + " samples");
      Scene s = soup(650, 6000, 1.5f, true, true);
      s.samples = samples;
      s.format = state.format;
      s.depth_format = state.depth_format;
      s.pipeline.depth_test = state.depth_test;
      s.pipeline.depth_write = state.depth_write;
      // Depth increases with submission and the depth buffer is cleared to the far plane:
      // under kLess, with depth writes each sample keeps the first triangle covering it;
      // without, every covered sample passes and keeps the last.
      s.pipeline.depth_compare = CompareOp::kLess;
      s.pipeline.interpolation = state.interpolation;
      const Result ref = render(s, Backend::kReference);
      ASSERT_GT(ref.counters.samples_covered, 5000u);
      ASSERT_GT(ref.counters.samples_passed, 4000u);
      for_each_config([&](const Config& config) {
        const Result fast = render(s, Backend::kFast, config);
        EXPECT_EQ(fast.counters.samples_covered, ref.counters.samples_covered);
        EXPECT_EQ(fast.counters.samples_passed, ref.counters.samples_passed);
        ASSERT_EQ(fast.depth.size(), ref.depth.size());
        for (size_t i = 0; i < ref.depth.size(); ++i) {
          ASSERT_LE(depth_error(fast.depth[i], ref.depth[i]), kDepthTolerance) << "sample " << i;
        }
        for (size_t i = 0; i < ref.rgba8.size(); ++i) {
          ASSERT_LE(std::abs(int{fast.rgba8[i]} - int{ref.rgba8[i]}), 1) << "byte " << i;
        }
        for (size_t i = 0; i < ref.rgba32f.size(); ++i) {
          ASSERT_NEAR(fast.rgba32f[i], ref.rgba32f[i], 1.0f / 255.0f) << "value " << i;
        }
      });
    }
  }
}

TEST(FastEngine, EveryCompareOpMatchesTheReferenceOnTinyAndSmallTriangles) {
  // The paths that specialise their depth test for kLess (pixel and sample records, the
  // window path of boxes up to 8 pixels wide) and their general form for every other op. A
  // first draw lays down depth under kAlways; a second tests against it under the op. Every
  // triangle's depth is flat and one of seven values, so the two engines compare the same
  // floats and ties (kEqual, kLessEqual, kGreaterEqual) occur; each sample's final depth and
  // the counts of passing samples must be the reference's exactly.
  const auto flat_depths = [](Scene s, uint32_t seed) {
    std::mt19937 rng(seed);
    for (size_t v = 0; v < s.positions.size(); v += 3) {
      const float z = static_cast<float>(rng() % 7 + 1) / 8.0f;
      for (size_t k = 0; k < 3; ++k)
        s.positions[v + k].z = z;  // w is 1
    }
    return s;
  };
  const auto draw_two = [](const Scene& first, const Scene& second, Backend backend,
                           const Config& config) {
    RendererOptions options;
    options.backend = backend;
    options.threads = config.threads;
    options.simd = config.target;
    Renderer renderer(options);
    Framebuffer fb({second.width, second.height, second.samples, second.format});
    fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
    fb.clear_depth(0.5f);
    const auto draw = [&](const Scene& scene) {
      renderer.draw(fb, scene.pipeline, {scene.positions, scene.colors, 4, {}});
    };
    draw(first);
    const uint64_t passed_before = renderer.counters().samples_passed;
    draw(second);
    Result r;
    r.rgba8 = fb.read_rgba8();
    r.depth = fb.read_sample_depth();
    r.counters = renderer.counters();
    r.counters.samples_passed -= passed_before;
    return r;
  };
  const CompareOp ops[] = {CompareOp::kLess,         CompareOp::kLessEqual, CompareOp::kGreater,
                           CompareOp::kGreaterEqual, CompareOp::kEqual,     CompareOp::kNotEqual,
                           CompareOp::kNever,        CompareOp::kAlways};
  for (float area : {1.5f, 12.0f}) {
    for (uint32_t samples : {1u, 2u, 4u}) {
      Scene first = flat_depths(soup(660, 1500, area, false), 661);
      first.samples = samples;
      first.pipeline.depth_compare = CompareOp::kAlways;
      for (CompareOp op : ops) {
        SCOPED_TRACE(testing::Message() << "area " << area << ", " << samples << " samples, op "
                                        << static_cast<int>(op));
        Scene second = flat_depths(soup(662, 1500, area, false), 663);
        second.samples = samples;
        second.pipeline.depth_compare = op;
        const Result ref = draw_two(first, second, Backend::kReference, {SimdTarget::kAuto, 1});
        if (op == CompareOp::kNever) {
          ASSERT_EQ(ref.counters.samples_passed, 0u);
        } else {
          ASSERT_GT(ref.counters.samples_passed, 100u * samples);  // kEqual's ties are the fewest
        }
        for_each_config([&](const Config& config) {
          const Result fast = draw_two(first, second, Backend::kFast, config);
          EXPECT_EQ(fast.counters.samples_covered, ref.counters.samples_covered);
          EXPECT_EQ(fast.counters.samples_passed, ref.counters.samples_passed);
          ASSERT_EQ(fast.depth.size(), ref.depth.size());
          EXPECT_EQ(0, std::memcmp(fast.depth.data(), ref.depth.data(),
                                   ref.depth.size() * sizeof(float)));
          for (size_t i = 0; i < ref.rgba8.size(); ++i) {
            ASSERT_LE(std::abs(int{fast.rgba8[i]} - int{ref.rgba8[i]}), 1) << "byte " << i;
          }
        });
      }
    }
  }
}

// A draw with records against the same draw with full setups for every triangle: the same
// sample counters, depth bits and colour bytes.
void expect_same_draw(const Result& records, const Result& setups) {
  EXPECT_EQ(records.counters.samples_covered, setups.counters.samples_covered);
  EXPECT_EQ(records.counters.samples_passed, setups.counters.samples_passed);
  EXPECT_EQ(records.counters.pixels_shaded, setups.counters.pixels_shaded);
  ASSERT_EQ(records.depth.size(), setups.depth.size());
  EXPECT_EQ(
      std::memcmp(records.depth.data(), setups.depth.data(), records.depth.size() * sizeof(float)),
      0);
  EXPECT_EQ(records.rgba8, setups.rgba8);
}

TEST(FastEngine, SampleRecordsOfFourRowBoxesMatchTheReferenceAndTheFullSetups) {
  // Boxes up to 3 pixels wide and 4 high (tall_soup) become sample records when at most five
  // of their pixels have a covered sample: coverage as the reference's, and the same depth
  // bits, colour bytes and sample counters as full setups for every triangle.
  for (uint32_t samples : {2u, 4u}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    Scene flat = tall_soup(90 + samples, 6000, true);
    flat.samples = samples;
    const Result ref = render(flat, Backend::kReference);
    Scene s = tall_soup(90 + samples, 6000, false);
    s.samples = samples;
    for_each_config([&](const Config& config) {
      expect_same_coverage(render(flat, Backend::kFast, config), ref, "records");
      const Result records = render(s, Backend::kFast, config);
      const Result setups = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, true,
                                   64, 8, false, /*records=*/false);
      ASSERT_GT(records.counters.samples_passed, 2000u * samples);
      EXPECT_EQ(records.counters.bin_references, setups.counters.bin_references);
      expect_same_draw(records, setups);
    });
  }
}

TEST(FastEngine, SmallTrianglesReachingTheEndsOfTheDepthRangeStoreTheSameBitsOnEveryTarget) {
  // Triangles of about 15 px (the vector targets' window path) with a vertex on or within a
  // rounding of the near or far plane (depth 0 or 1), placed on a sample: the kernels' float
  // sums from the block's corner may land a rounding beyond the range there, which the clamp
  // must catch on every target. Every covered sample is written (kAlways), so each lands in the
  // buffer; the scalar target, whose path always clamps, is the baseline.
  // The ends, and depths within a rounding of them (2^-26 above 0, one float step below 1):
  const float kEnds[4] = {0.0f, std::ldexp(1.0f, -26), 1.0f - std::ldexp(1.0f, -24), 1.0f};
  for (uint32_t samples : {1u, 4u}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const auto pattern = sample_pattern(samples);
    Scene s;
    s.samples = samples;
    s.pipeline.depth_compare = CompareOp::kAlways;
    std::mt19937 rng(70 + samples);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 4000; ++i) {
      const float cx = std::floor(u(rng) * static_cast<float>(s.width));
      const float cy = std::floor(u(rng) * static_cast<float>(s.height));
      const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
      float x[3], y[3], z[3], c[3][4];
      const float w[3] = {1.0f, 1.0f, 1.0f};
      for (int k = 0; k < 3; ++k) {
        const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f;
        // Each vertex on a sample of its pixel, one of them at depth 0 or 1 and the others
        // anywhere in the range, so the depth plane is steep.
        const SampleOffset on = pattern[rng() % samples];
        x[k] = cx + std::round(3.5f * std::cos(a)) + 0.5f + static_cast<float>(on.dx) / 16.0f;
        y[k] = cy + std::round(3.5f * std::sin(a)) + 0.5f + static_cast<float>(on.dy) / 16.0f;
        z[k] = k == 0 ? kEnds[i % 4] : u(rng);
        for (int ch = 0; ch < 4; ++ch)
          c[k][ch] = u(rng);
      }
      s.add(x, y, z, w, c);
    }
    const Result baseline = render(s, Backend::kFast, {SimdTarget::kScalar, 1});
    for (float d : baseline.depth) {
      ASSERT_GE(d, 0.0f);
      ASSERT_LE(d, 1.0f);
    }
    for_each_config([&](const Config& config) {
      const Result r = render(s, Backend::kFast, config);
      EXPECT_EQ(0, std::memcmp(r.depth.data(), baseline.depth.data(), r.depth.size() * 4));
      EXPECT_EQ(r.rgba8, baseline.rgba8);
    });
  }
}

TEST(FastEngine, TrianglesWithColoursAtTheEndsOfTheUnitRangeStoreTheSameBytesOnEveryTarget) {
  // Triangles up to 7 px across (the vector targets' window path) and up to 25 (the block path),
  // every vertex on a pixel centre, with colour channels at 0 or 1, within a rounding of them,
  // or anywhere between. Where the setup bounds a triangle's colour to [0, 1]
  // (TriangleSetup::unit_colour), one-sample kernels pack RGBA8 without the clamp, so a sum a
  // rounding beyond the range must give the clamp's byte there. In one triangle in four some
  // channels lie 1/64 beyond the range, where packing without the clamp gives other bytes, and
  // slivers take gradients up to about 8 per pixel. The scalar target, whose path always
  // clamps, is the baseline; every covered pixel is written (kAlways).
  const float kValues[6] = {0.0f, std::ldexp(1.0f, -26), 1.0f - std::ldexp(1.0f, -24),
                            1.0f, -1.0f / 64.0f,         1.0f + 1.0f / 64.0f};
  Scene s;
  s.pipeline.depth_compare = CompareOp::kAlways;
  std::mt19937 rng(91);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 6000; ++i) {
    const float radius = i % 3 == 1 ? 12.0f : 3.0f;
    const float cx = std::floor(u(rng) * (static_cast<float>(s.width) - 2.0f * radius - 2.0f));
    const float cy = std::floor(u(rng) * (static_cast<float>(s.height) - 2.0f * radius - 2.0f));
    float x[3], y[3], c[3][4];
    const float z[3] = {0.5f, 0.5f, 0.5f}, w[3] = {1.0f, 1.0f, 1.0f};
    if (i % 3 == 0) {
      // A sliver from (0, 0) to (1, n), its third vertex at (0, m): the distance from it to
      // the long edge, m / sqrt(1 + n^2), is 0.12 px and up, so a channel that is 1 there and
      // 0 at the others has a gradient of up to about 8 per pixel.
      const float n = static_cast<float>(5 + rng() % 5), m = static_cast<float>(1 + rng() % 3);
      const float xs[3] = {cx + 0.5f, cx + 1.5f, cx + 0.5f};
      const float ys[3] = {cy + 0.5f, cy + 0.5f + n, cy + 0.5f + m};
      for (int k = 0; k < 3; ++k) {
        x[k] = xs[k];
        y[k] = ys[k];
        for (int ch = 0; ch < 4; ++ch)
          c[k][ch] = k == 2 && ch == i % 4 ? 1.0f : 0.0f;
      }
    } else {
      const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
      for (int k = 0; k < 3; ++k) {
        const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f;
        x[k] = cx + 0.5f + radius + std::round(radius * std::cos(a));
        y[k] = cy + 0.5f + radius + std::round(radius * std::sin(a));
        for (int ch = 0; ch < 4; ++ch) {
          const uint32_t pick = rng() % 8;
          // Just beyond the range in one triangle in four.
          c[k][ch] = pick < 4 || (pick < 6 && i % 4 == 1) ? kValues[pick] : u(rng);
        }
      }
    }
    s.add(x, y, z, w, c);
  }
  const Result baseline = render(s, Backend::kFast, {SimdTarget::kScalar, 1});
  for_each_config([&](const Config& config) {
    const Result r = render(s, Backend::kFast, config);
    ASSERT_EQ(r.rgba8.size(), baseline.rgba8.size());
    const auto [a, b] = std::mismatch(r.rgba8.begin(), r.rgba8.end(), baseline.rgba8.begin());
    EXPECT_EQ(a, r.rgba8.end()) << "first differing byte " << (a - r.rgba8.begin()) << ": "
                                << int{*a} << " against " << int{*b};
  });
}

TEST(FastEngine, TinyTriangleRecordsDrawTheSameBytesAsTheFullSetups) {
  // Pixel records (one sample) and sample records (two and four) against full setups for
  // every triangle (RendererOptions::tiny_triangle_records off): the same depth bits, colour
  // bytes and counters in every draw state, with random depths so that the depth tests decide
  // with values the setup computed, and w varying so that colour is divided by q. At one
  // sample, a float colour target (which takes no records) gives the same RGBA8 image too.
  struct State {
    const char* name;
    bool depth_test, depth_write, color_write;
    CompareOp compare;
    DepthFormat depth_format;
    Interpolation interpolation;
    bool perspective;
  };
  const State states[] = {
      {"perspective", true, true, true, CompareOp::kLess, DepthFormat::kFloat32,
       Interpolation::kPerspective, true},
      {"affine", true, true, true, CompareOp::kLessEqual, DepthFormat::kFloat32,
       Interpolation::kAffine, true},
      {"unit w", true, true, true, CompareOp::kNotEqual, DepthFormat::kFloat32,
       Interpolation::kPerspective, false},
      {"test only", true, false, true, CompareOp::kLess, DepthFormat::kFloat32,
       Interpolation::kPerspective, true},
      {"no depth", false, false, true, CompareOp::kLess, DepthFormat::kFloat32,
       Interpolation::kPerspective, true},
      {"depth only", true, true, false, CompareOp::kLess, DepthFormat::kFloat32,
       Interpolation::kPerspective, true},
      {"unorm16", true, true, true, CompareOp::kLess, DepthFormat::kUnorm16,
       Interpolation::kPerspective, true},
      {"unorm24", true, true, true, CompareOp::kLess, DepthFormat::kUnorm24,
       Interpolation::kPerspective, true},
  };
  for (const State& state : states) {
    for (uint32_t samples : {1u, 2u, 4u}) {
      SCOPED_TRACE(std::string(state.name) + ", " + std::to_string(samples) + " samples");
      Scene s = soup(651, 8000, 1.5f, false, state.perspective);
      s.samples = samples;
      s.depth_format = state.depth_format;
      s.pipeline.depth_test = state.depth_test;
      s.pipeline.depth_write = state.depth_write;
      s.pipeline.color_write = state.color_write;
      s.pipeline.depth_compare = state.compare;
      s.pipeline.interpolation = state.interpolation;
      for_each_config([&](const Config& config) {
        const Result records = render(s, Backend::kFast, config);
        const Result setups = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, true,
                                     64, 8, false, /*records=*/false);
        ASSERT_GT(records.counters.samples_passed, 3000u * samples);
        const Counters &on = records.counters, &off = setups.counters;
        if (samples == 1) {
          // Boxes of 3x3 pixels covering no centre are not binned with pixel records; the
          // kernels reject their blocks.
          EXPECT_LT(on.bin_references, off.bin_references);
          EXPECT_LE(on.blocks_rejected, off.blocks_rejected);
          EXPECT_EQ(on.blocks_partial, off.blocks_partial);
        } else {
          // The same blocks are visited. A record counts a block partial when it has a
          // covered sample there; the kernels of 3x3 boxes at four samples, when no edge
          // misses the whole block.
          EXPECT_EQ(on.bin_references, off.bin_references);
          EXPECT_EQ(on.blocks_partial + on.blocks_rejected,
                    off.blocks_partial + off.blocks_rejected);
          EXPECT_LE(on.blocks_partial, off.blocks_partial);
        }
        expect_same_draw(records, setups);
        if (samples == 1 && state.color_write) {
          Scene float_target = s;
          float_target.format = ColorFormat::kRGBA32F;
          const Result full = render(float_target, Backend::kFast, config);
          EXPECT_EQ(std::memcmp(records.depth.data(), full.depth.data(),
                                records.depth.size() * sizeof(float)),
                    0);
          EXPECT_EQ(records.rgba8, full.rgba8);
        }
      });
    }
  }
}

TEST(FastEngine, CoverageMatchesReferenceOnLongSlivers) {
  Scene s;
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    // A long edge across the screen and a third vertex a fraction of a pixel off it.
    const float x0 = u(rng) * 200 - 30, y0 = u(rng) * 120 - 20;
    const float x1 = u(rng) * 200 - 30, y1 = u(rng) * 120 - 20;
    const float t = u(rng), off = (u(rng) - 0.5f) * 0.6f;
    const float len = std::hypot(x1 - x0, y1 - y0) + 1e-3f;
    const float x[3] = {x0, x1, x0 + t * (x1 - x0) - off * (y1 - y0) / len};
    const float y[3] = {y0, y1, y0 + t * (y1 - y0) + off * (x1 - x0) / len};
    const float zi = static_cast<float>(i + 1) / 32768.0f;
    const float z[3] = {zi, zi, zi};
    const float w[3] = {1, 1, 1}, c[3][4] = {};
    s.add(x, y, z, w, c);
  }
  s.pipeline.depth_compare = CompareOp::kAlways;
  const Result ref = render(s, Backend::kReference);
  for_each_config([&](const Config& config) {
    expect_same_coverage(render(s, Backend::kFast, config), ref, "slivers");
  });
}

// Triangles whose first edge has |dx| + |dy| = `span` px (the sum that narrow_edge_limit
// bounds), across the small screen and far into the guard band, or past it, for spans of
// thousands of pixels: level, or with `diagonal` at 45 degrees (a span twice as long inside the
// band). Each is shifted by each offset and has a depth of its own, drawn with
// CompareOp::kAlways: a sample's depth names the last triangle that covered it.
void add_spanning_triangles(Scene& s, std::initializer_list<float> spans,
                            std::initializer_list<float> offsets, bool diagonal = false) {
  int i = static_cast<int>(s.positions.size() / 3);
  for (float span : spans) {
    for (float offset : offsets) {
      const float h = diagonal ? span / 4 : span / 2, v = diagonal ? span / 4 : 0.0f;
      const float x[3] = {68.0f - h + offset, 68.0f + h + offset, 70.0f};
      const float y[3] = {diagonal ? 36.0f - v : 10.0f + offset / 4, diagonal ? 36.0f + v : 30.0f,
                          60.0f - offset / 8};
      const float z = static_cast<float>(++i) / 32768.0f;
      const float zz[3] = {z, z, z}, w[3] = {1, 1, 1}, c[3][4] = {};
      s.add(x, y, zz, w, c);
    }
  }
  s.pipeline.depth_compare = CompareOp::kAlways;
}

TEST(FastEngine, CoverageMatchesReferenceAtAndPastTheThirtyTwoBitStepLimit) {
  // Edge steps |a| + |b| just below, at and above narrow_edge_limit, 2^(28 - 2 bits) px: 4096
  // px at 8 subpixel bits, 16384 at 7, 65536 at 6, by level and by diagonal edges. Inside the
  // guard band (32768 px each way from the screen's centre) |dx| + |dy| reaches 131072 px on a
  // diagonal: 6 bits is the last precision whose limit an unclipped edge can reach. Spans past
  // the band are clipped first.
  for (uint32_t bits : {8u, 7u, 6u}) {
    Scene s;
    s.pipeline.subpixel_bits = bits;
    const float limit_px =
        static_cast<float>(fast::narrow_edge_limit(bits)) / static_cast<float>(1u << bits);
    const float unit = 1.0f / static_cast<float>(1u << bits);
    for (bool diagonal : {false, true}) {
      add_spanning_triangles(
          s, {limit_px - 1.0f, limit_px - unit, limit_px, limit_px + 3.0f, 3.0f * limit_px},
          {-0.3f, 0.0f, 17.25f, 40.5f}, diagonal);
    }
    for (uint32_t samples : {1u, 8u}) {
      s.samples = samples;
      const Result ref = render(s, Backend::kReference);
      for_each_config([&](const Config& config) {
        expect_same_coverage(
            render(s, Backend::kFast, config), ref,
            std::to_string(bits) + " bits, " + std::to_string(samples) + " samples");
      });
    }
  }
}

TEST(FastEngine, NearPlaneCrossingsMatchReference) {
  for (Interpolation interpolation : {Interpolation::kPerspective, Interpolation::kAffine}) {
    Scene s;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 3000; ++i) {
      const float z = static_cast<float>(i + 1) / 32768.0f;
      for (int k = 0; k < 3; ++k) {
        // w and z (0..w convention) chosen so that some vertices lie behind the eye or in front
        // of the near plane.
        const float w = u(rng) * 3.0f;
        s.positions.push_back({u(rng) * 2.0f, u(rng) * 2.0f, w < 0 ? -0.5f : z * w, w});
        for (int ch = 0; ch < 4; ++ch)
          s.colors.push_back(0.5f + 0.5f * u(rng));
      }
    }
    s.pipeline.depth_compare = CompareOp::kAlways;
    s.pipeline.interpolation = interpolation;
    const Result ref = render(s, Backend::kReference);
    EXPECT_GT(ref.counters.triangles_clipped, 100u);
    for_each_config([&](const Config& config) {
      const Result fast = render(s, Backend::kFast, config);
      EXPECT_EQ(fast.counters.triangles_clipped, ref.counters.triangles_clipped);
      // Depth is not flat here (clipping moves vertices): compare it by tolerance.
      for (size_t i = 0; i < ref.rgba8.size(); ++i) {
        ASSERT_LE(std::abs(int{fast.rgba8[i]} - int{ref.rgba8[i]}), 1) << "byte " << i;
      }
      for (size_t i = 0; i < ref.depth.size(); ++i) {
        ASSERT_LE(depth_error(fast.depth[i], ref.depth[i]), kDepthTolerance) << "sample " << i;
      }
    });
  }
}

TEST(FastEngine, DepthWithinToleranceOfReference) {
  for (bool perspective : {false, true}) {
    for (uint32_t samples : {1u, 4u}) {
      Scene s = soup(400 + samples, 4000, 60.0f, false, perspective);
      s.samples = samples;
      const Result ref = render(s, Backend::kReference);
      for_each_config([&](const Config& config) {
        const Result fast = render(s, Backend::kFast, config);
        double worst = 0;
        for (size_t i = 0; i < ref.depth.size(); ++i) {
          worst = std::max(worst, depth_error(fast.depth[i], ref.depth[i]));
        }
        EXPECT_LE(worst, kDepthTolerance) << samples << " samples, perspective " << perspective;
      });
    }
  }
}

TEST(FastEngine, FixedPointDepthFormatsMatchReference) {
  // Every triangle writes (compare kAlways), so no decision hangs on a rounded depth: the
  // stored steps differ from the reference's by at most the float tolerance in steps plus one
  // for rounding to a step, plus one for the float read-back of two 24-bit steps.
  struct Case {
    DepthFormat format;
    double steps;
  };
  for (const Case c :
       {Case{DepthFormat::kUnorm16, 65535.0}, Case{DepthFormat::kUnorm24, 16777215.0}}) {
    Scene s = soup(450, 3000, 60.0f, false, true);
    s.depth_format = c.format;
    s.pipeline.depth_compare = CompareOp::kAlways;
    const Result ref = render(s, Backend::kReference);
    const double tolerance = std::ceil(std::ldexp(kDepthTolerance, -24) * c.steps) + 1.0 +
                             (c.format == DepthFormat::kUnorm24 ? 1.0 : 0.0);
    for_each_config([&](const Config& config) {
      // Coverage too: an uncovered sample keeps the far plane, a step apart from any triangle.
      const Result fast = render(s, Backend::kFast, config);
      double worst = 0;
      for (size_t i = 0; i < ref.depth.size(); ++i) {
        const double fast_step = double{fast.depth[i]} * c.steps;
        const double ref_step = double{ref.depth[i]} * c.steps;
        if (c.format == DepthFormat::kUnorm16) {
          // Stored on a step: the float read-back k / 65535 is off by at most 65535 * 2^-24
          // (under 0.004) steps, far from the half step between two.
          ASSERT_LT(std::abs(fast_step - std::nearbyint(fast_step)), 0.004) << "sample " << i;
        }
        worst = std::max(worst, std::abs(fast_step - ref_step));
      }
      EXPECT_LE(worst, tolerance) << "format " << static_cast<int>(c.format);
    });
  }
}

TEST(FastEngine, ColorWithinOneStepOfReference) {
  for (ColorFormat format : {ColorFormat::kRGBA8, ColorFormat::kRGBA32F}) {
    for (Interpolation interpolation : {Interpolation::kPerspective, Interpolation::kAffine}) {
      Scene s = soup(500, 3000, 80.0f, true, true);
      s.format = format;
      s.samples = format == ColorFormat::kRGBA8 ? 4 : 1;
      s.pipeline.interpolation = interpolation;
      const Result ref = render(s, Backend::kReference);
      for_each_config([&](const Config& config) {
        const Result fast = render(s, Backend::kFast, config);
        for (size_t i = 0; i < ref.rgba8.size(); ++i) {
          ASSERT_LE(std::abs(int{fast.rgba8[i]} - int{ref.rgba8[i]}), 1) << "byte " << i;
        }
        for (size_t i = 0; i < ref.rgba32f.size(); ++i) {
          ASSERT_NEAR(fast.rgba32f[i], ref.rgba32f[i], 1.0f / 255.0f) << "value " << i;
        }
      });
    }
  }
}

TEST(FastEngine, WatertightGridCoversEverySampleExactlyOnce) {
  // A jittered grid of 1,002,528 triangles (708 x 708 cells, two triangles each) over a
  // 4-sample framebuffer: the samples covered add up to exactly the samples of the screen and
  // none is left uncovered, so each is covered exactly once.
  const uint32_t width = 320, height = 200, samples = 4;
  const int n = 709;  // vertices per side
  std::mt19937 rng(10);
  // Each vertex moves at most 0.2 cells per axis: a triangle's vertex stays at least
  // 0.707 - 2 * 0.283 > 0 cells from its opposite edge, so no triangle folds over.
  std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
  std::vector<Float4> v(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const bool border = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      const float fx = (static_cast<float>(i) + (border ? 0.0f : jitter(rng))) / (n - 1);
      const float fy = (static_cast<float>(j) + (border ? 0.0f : jitter(rng))) / (n - 1);
      // Slight perspective: w varies across the grid, positions stay on the same screen spot.
      const float w = 1.0f + fx;
      v[static_cast<size_t>(j) * n + i] = {(2 * fx - 1) * w, (1 - 2 * fy) * w, 0.5f * w, w};
    }
  }
  std::vector<uint32_t> indices;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
  }
  ASSERT_GE(indices.size() / 3, 1000000u);
  for_each_config([&](const Config& config) {
    RendererOptions options;
    options.backend = Backend::kFast;
    options.threads = config.threads;
    options.simd = config.target;
    Renderer renderer(options);
    Framebuffer fb({width, height, samples, ColorFormat::kRGBA8});
    PipelineState p;
    p.depth_compare = CompareOp::kAlways;
    renderer.draw(fb, p, {v, {}, 0, indices});
    EXPECT_EQ(renderer.counters().samples_covered, uint64_t{width} * height * samples);
    const std::vector<float> depth = fb.read_sample_depth();
    EXPECT_EQ(std::count(depth.begin(), depth.end(), 1.0f), 0);
  });
}

TEST(FastEngine, ImagesAreByteIdenticalAcrossThreadsRunsAndTargets) {
  Scene s = soup(600, 20000, 40.0f, false, true);
  s.samples = 4;
  const Result baseline = render(s, Backend::kFast, {SimdTarget::kScalar, 1});
  for_each_config([&](const Config& config) {
    for (int run = 0; run < 2; ++run) {
      const Result r = render(s, Backend::kFast, config);
      EXPECT_EQ(r.rgba8, baseline.rgba8) << "run " << run;
      EXPECT_EQ(0, std::memcmp(r.depth.data(), baseline.depth.data(), r.depth.size() * 4))
          << "run " << run;
    }
  });
}

TEST(FastEngine, SmallTrianglesNearTheirHorizonDrawTheSameBytesOnEveryTarget) {
  // Triangles of a few pixels take lane windows on targets with 8 or 16 lanes and blocks on
  // the others (scalar, SSE4). Vertex w from 0.002 to 10 leaves q = 1/w at some pixel centres
  // next to a triangle at or below zero, where the kernels shade at the first passing sample
  // instead; both paths must write the same bytes there too, at one sample and several.
  for (uint32_t samples : {1u, 4u}) {
    Scene s = soup(660 + samples, 20000, 12.0f, true);
    s.samples = samples;
    std::mt19937 rng(661);
    std::uniform_real_distribution<float> log_w(std::log(0.002f), std::log(10.0f));
    for (Float4& p : s.positions) {
      const float w = std::exp(log_w(rng));
      p = {p.x * w, p.y * w, p.z * w, p.w * w};
    }
    const Result baseline = render(s, Backend::kFast, {SimdTarget::kScalar, 1});
    // (Depth is z * w / w here, not exactly flat: the reference's differs in the last bits.)
    EXPECT_EQ(baseline.counters.samples_covered,
              render(s, Backend::kReference).counters.samples_covered);
    for_each_config([&](const Config& config) {
      const Result r = render(s, Backend::kFast, config);
      EXPECT_EQ(r.rgba8, baseline.rgba8) << samples << " samples";
      EXPECT_EQ(0, std::memcmp(r.depth.data(), baseline.depth.data(), r.depth.size() * 4))
          << samples << " samples";
    });
  }
}

TEST(FastEngine, VerticesAtUnitWDrawTheSameBytesAsAnyOtherW) {
  // The setup skips the divisions by w for a vector of triangles whose vertices all have w = 1
  // (orthographic and 2D draws). Scaling a triangle's clip coordinates by 2 is exact and leaves
  // its window coordinates, depth and (flat) q the same, so the same scene with every third
  // triangle scaled (no vector of triangles all at w = 1, wherever vectors start) must draw the
  // same bytes, at one and four samples, and both must match the reference's coverage.
  for (uint32_t samples : {1u, 4u}) {
    Scene unit = soup(650 + samples, 6000, 6.0f, true);
    unit.samples = samples;
    Scene scaled = unit;
    for (size_t i = 0; i < scaled.positions.size(); ++i) {
      if ((i / 3) % 3 != 0) continue;
      Float4& p = scaled.positions[i];
      p = {p.x * 2.0f, p.y * 2.0f, p.z * 2.0f, p.w * 2.0f};
    }
    const Result ref = render(unit, Backend::kReference);
    for_each_config([&](const Config& config) {
      const Result a = render(unit, Backend::kFast, config);
      const Result b = render(scaled, Backend::kFast, config);
      expect_same_coverage(a, ref, "w = 1");
      EXPECT_EQ(a.rgba8, b.rgba8) << samples << " samples";
      EXPECT_EQ(0, std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)))
          << samples << " samples";
    });
  }
}

TEST(FastEngine, EveryBinTileSizeDrawsTheSameImage) {
  // 32-pixel bin tiles split storage tiles, 128-pixel ones span 2x2 of them (and the screen's
  // partial last column and row); the image is the same bytes for every size.
  Scene s = soup(720, 8000, 50.0f, false, true);
  s.samples = 4;
  for_each_config([&](const Config& config) {
    const Result standard = render(s, Backend::kFast, config);
    for (uint32_t size : {32u, 128u}) {
      const Result r = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, true, size);
      EXPECT_EQ(r.rgba8, standard.rgba8) << "bin tiles of " << size;
      EXPECT_EQ(0, std::memcmp(r.depth.data(), standard.depth.data(), r.depth.size() * 4))
          << "bin tiles of " << size;
      EXPECT_EQ(r.counters.samples_passed, standard.counters.samples_passed);
      if (size == 32) {
        EXPECT_GT(r.counters.bin_references, standard.counters.bin_references);
      } else {
        EXPECT_LT(r.counters.bin_references, standard.counters.bin_references);
      }
    }
  });
}

// The counters that must not depend on the block size: a 16 or 32-pixel block rejected or
// accepted as a whole stands for exactly the 8x8 blocks inside it, each counted as its own test
// would count it.
void expect_same_block_counts(const Counters& c, const Counters& standard, uint32_t size) {
  EXPECT_EQ(c.blocks_rejected, standard.blocks_rejected) << "blocks of " << size;
  EXPECT_EQ(c.blocks_accepted, standard.blocks_accepted) << "blocks of " << size;
  EXPECT_EQ(c.blocks_partial, standard.blocks_partial) << "blocks of " << size;
  EXPECT_EQ(c.subblocks_rejected, standard.subblocks_rejected) << "blocks of " << size;
  EXPECT_EQ(c.subblocks_accepted, standard.subblocks_accepted) << "blocks of " << size;
  EXPECT_EQ(c.subblocks_partial, standard.subblocks_partial) << "blocks of " << size;
  EXPECT_EQ(c.hiz_rejected, standard.hiz_rejected) << "blocks of " << size;
  EXPECT_EQ(c.hiz_accepted, standard.hiz_accepted) << "blocks of " << size;
  EXPECT_EQ(c.samples_covered, standard.samples_covered) << "blocks of " << size;
  EXPECT_EQ(c.samples_passed, standard.samples_passed) << "blocks of " << size;
  EXPECT_EQ(c.pixels_shaded, standard.pixels_shaded) << "blocks of " << size;
}

TEST(FastEngine, EveryBlockSizeDrawsTheSameImageAndCountsTheSameBlocks) {
  // Random triangles from a few pixels (the small-triangle path) to larger than the screen
  // (16 and 32-pixel blocks accepted whole), depth tested and written, perspective colour, with
  // and without MSAA, in both colour formats: the bytes and the counters at block sizes 16 and
  // 32 are those at 8.
  struct Case {
    float area;
    uint32_t samples;
    ColorFormat format;
  };
  const Case cases[] = {{6.0f, 4, ColorFormat::kRGBA8},      {90.0f, 1, ColorFormat::kRGBA8},
                        {400.0f, 4, ColorFormat::kRGBA8},    {2500.0f, 8, ColorFormat::kRGBA8},
                        {2500.0f, 1, ColorFormat::kRGBA32F}, {20000.0f, 4, ColorFormat::kRGBA8}};
  for (size_t c = 0; c < std::size(cases); ++c) {
    Scene s = soup(730 + static_cast<uint32_t>(c), cases[c].area > 1000.0f ? 400 : 4000,
                   cases[c].area, false, true);
    s.samples = cases[c].samples;
    s.format = cases[c].format;
    SCOPED_TRACE("area " + std::to_string(cases[c].area));
    for_each_config([&](const Config& config) {
      const Result standard = render(s, Backend::kFast, config);
      EXPECT_GT(standard.counters.blocks_rejected + standard.counters.blocks_partial, 0u);
      for (uint32_t size : {16u, 32u}) {
        const Result r =
            render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, true, 64, size);
        EXPECT_EQ(r.rgba8, standard.rgba8) << "blocks of " << size;
        EXPECT_EQ(r.rgba32f, standard.rgba32f) << "blocks of " << size;
        EXPECT_EQ(0, std::memcmp(r.depth.data(), standard.depth.data(), r.depth.size() * 4))
            << "blocks of " << size;
        expect_same_block_counts(r.counters, standard.counters, size);
      }
    });
  }
}

TEST(FastEngine, EveryBlockSizeMatchesTheReferenceCoverage) {
  // Coverage bit for bit against the reference (flat depths, compare always: a sample's depth
  // names the last triangle that covered it) at block sizes 16 and 32, in every size class, with
  // MSAA, in every bin tile size, and for triangles past the 32-bit step limit (the wide path's
  // int64 coverage inside partly covered 16 and 32-pixel blocks).
  std::vector<Scene> scenes;
  const float areas[] = {2.0f, 16.0f, 128.0f, 2048.0f, 20000.0f};
  for (size_t c = 0; c < std::size(areas); ++c) {
    scenes.push_back(soup(760 + static_cast<uint32_t>(c), 3000, areas[c], true));
    scenes.back().samples = c % 2 ? 4 : 1;
  }
  Scene wide;
  const float limit_px = static_cast<float>(fast::narrow_edge_limit(8)) / 256.0f;
  add_spanning_triangles(wide, {limit_px - 1.0f, limit_px + 3.0f, 3.0f * limit_px},
                         {-0.3f, 17.25f, 40.5f});
  wide.samples = 8;
  scenes.push_back(wide);
  for (size_t n = 0; n < scenes.size(); ++n) {
    SCOPED_TRACE("scene " + std::to_string(n));
    const Result ref = render(scenes[n], Backend::kReference);
    for_each_config([&](const Config& config) {
      for (uint32_t size : {16u, 32u}) {
        for (uint32_t tile : {32u, 64u, 128u}) {
          expect_same_coverage(
              render(scenes[n], Backend::kFast, config, kDefaultBinMemoryBudget, true, true, tile,
                     size),
              ref, "blocks of " + std::to_string(size) + ", bin tiles of " + std::to_string(tile));
        }
      }
    });
  }
}

TEST(FastEngineOptions, AnUnsupportedBlockSizeIsAnErrorNamingIt) {
  for (uint32_t size : {0u, 4u, 12u, 24u, 64u}) {
    RendererOptions options;
    options.block_size = size;
    try {
      Renderer renderer(options);
      ADD_FAILURE() << "block size " << size << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
      EXPECT_NE(std::string(e.what()).find("block size " + std::to_string(size)), std::string::npos)
          << e.what();
    }
  }
}

TEST(FastEngineOptions, AnUnsupportedBinTileSizeIsAnError) {
  for (uint32_t size : {0u, 16u, 48u, 256u}) {
    RendererOptions options;
    options.bin_tile_size = size;
    EXPECT_THROW(Renderer renderer(options), Error) << size;
  }
}

TEST(FastEngine, SmallBinBudgetRendersInPassesWithTheSameImage) {
  Scene s = soup(700, 20000, 30.0f, false);
  for_each_config([&](const Config& config) {
    const Result whole = render(s, Backend::kFast, config);
    const Result passes = render(s, Backend::kFast, config, 64 << 10);
    EXPECT_EQ(whole.counters.bin_passes, 1u);
    EXPECT_GT(passes.counters.bin_passes, 4u);
    EXPECT_EQ(passes.rgba8, whole.rgba8);
    EXPECT_EQ(0, std::memcmp(passes.depth.data(), whole.depth.data(), whole.depth.size() * 4));
    EXPECT_EQ(passes.counters.samples_passed, whole.counters.samples_passed);
    // Each triangle is binned in exactly one pass.
    EXPECT_EQ(passes.counters.triangles_binned, whole.counters.triangles_binned);
    EXPECT_GT(whole.counters.triangles_binned, 0u);
  });
}

TEST(FastEngine, RasterCountersOffDrawTheSameImageAndCountNoRasterWork) {
  Scene s = soup(710, 5000, 60.0f, false, true);
  s.samples = 4;
  for_each_config([&](const Config& config) {
    const Result counted = render(s, Backend::kFast, config);
    const Result quiet = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, false);
    EXPECT_GT(counted.counters.blocks_partial, 0u);
    EXPECT_GT(counted.counters.samples_covered, 0u);
    EXPECT_GT(counted.counters.pixels_shaded, 0u);
    EXPECT_EQ(quiet.rgba8, counted.rgba8);
    EXPECT_EQ(0, std::memcmp(quiet.depth.data(), counted.depth.data(), counted.depth.size() * 4));
    const Counters& c = quiet.counters;
    EXPECT_EQ(c.blocks_rejected + c.blocks_accepted + c.blocks_partial, 0u);
    EXPECT_EQ(c.subblocks_rejected + c.subblocks_accepted + c.subblocks_partial, 0u);
    EXPECT_EQ(c.hiz_rejected + c.hiz_accepted, 0u);
    EXPECT_EQ(c.samples_covered + c.samples_passed + c.pixels_shaded, 0u);
    // The triangle and bin counts are kept either way.
    EXPECT_EQ(c.triangles_rasterized, counted.counters.triangles_rasterized);
    EXPECT_EQ(c.bin_references, counted.counters.bin_references);
    EXPECT_EQ(c.triangles_binned, counted.counters.triangles_binned);
  });
  // Triangles of ~80 px sides over one another, through the general path, whose kernels
  // without counters drop a triangle that Hi-Z finds hidden at every block of its box in a
  // tile before the blocks' own tests: the same image and depth, in every depth format.
  Scene large = soup(712, 600, 3000.0f, false, true);
  for (const uint32_t samples : {1u, 4u}) {
    for (const DepthFormat format : {DepthFormat::kFloat32, DepthFormat::kUnorm16}) {
      large.samples = samples;
      large.depth_format = format;
      for_each_config([&](const Config& config) {
        const Result counted = render(large, Backend::kFast, config);
        const Result quiet = render(large, Backend::kFast, config, kDefaultBinMemoryBudget, false);
        EXPECT_GT(counted.counters.hiz_rejected, 1000u);
        EXPECT_EQ(quiet.rgba8, counted.rgba8);
        EXPECT_EQ(0,
                  std::memcmp(quiet.depth.data(), counted.depth.data(), counted.depth.size() * 4));
      });
    }
  }
}

TEST(FastEngine, SubBlocksSkipLaneGroupsOutsideAnEdgeAndTestOnlyTheEdgesCrossingThem) {
  // Triangles of about 1000 px (the general path): a partial block's lane groups are rejected,
  // accepted or partial by their corner pixels' edge values against the samples' thresholds.
  // Coverage stays the reference's (flat depth per triangle, compare always: every sample's
  // depth names the last triangle covering it). A triangle's bounding box holds the pixels with
  // a sample inside its vertices' box, so at 4 samples, which lie around the pixel centre, it
  // holds the 1-sample box: every sub-block tested at 1 sample is tested at 4 (Hi-Z is off so
  // none is skipped); 4 samples lie off the pixel centre, so a sub-block wholly inside or
  // outside at 4 samples is so at 1, and some that are at 1 are not at 4.
  Scene s = soup(760, 1500, 1000.0f, true);
  Scene multi = s;
  multi.samples = 4;
  const Result ref1 = render(s, Backend::kReference);
  const Result ref4 = render(multi, Backend::kReference);
  for_each_config([&](const Config& config) {
    const auto draw = [&](const Scene& scene, bool sub_blocks) {
      return render(scene, Backend::kFast, config, kDefaultBinMemoryBudget, true, false, 64, 8,
                    sub_blocks);
    };
    const Result one = draw(s, true), four = draw(multi, true);
    expect_same_coverage(one, ref1, "1 sample");
    expect_same_coverage(four, ref4, "4 samples");
    // Off (the default): the same bytes, no sub-block counted.
    const Result plain = draw(multi, false);
    EXPECT_EQ(plain.rgba8, four.rgba8);
    EXPECT_EQ(0, std::memcmp(plain.depth.data(), four.depth.data(), four.depth.size() * 4));
    EXPECT_EQ(plain.counters.subblocks_rejected + plain.counters.subblocks_accepted +
                  plain.counters.subblocks_partial,
              0u);
    const Counters& a = one.counters;
    const Counters& b = four.counters;
    EXPECT_GT(a.subblocks_rejected, 1000u);
    EXPECT_GT(a.subblocks_accepted, 1000u);
    EXPECT_GT(b.subblocks_partial, 1000u);  // at 1 sample, none with one lane (scalar)
    EXPECT_LE(a.subblocks_rejected + a.subblocks_accepted + a.subblocks_partial,
              b.subblocks_rejected + b.subblocks_accepted + b.subblocks_partial);
    EXPECT_LT(b.subblocks_rejected, a.subblocks_rejected);
    EXPECT_LT(b.subblocks_accepted, a.subblocks_accepted);
  });
}

TEST(FastEngine, ClearsTakeEffectWhereverTheFramebufferIsNextUsed) {
  // Clears are recorded and written per tile when the fast engine next draws the tile, or
  // before any other use; tiles a draw does not touch keep them. A sequence of clears, draws
  // (one without triangles, two covering only part of the screen, the second drawing tiles the
  // first left pending) and reads in between must leave the same bytes as the same
  // sequence with every clear written at once (a read right after each clear forces it), for
  // every bin tile size (32-pixel bin tiles share a storage tile), sample count and colour
  // format; in RGBA8 they are also the reference's bytes.
  // Flat depth per triangle (exact in both engines), tested with <.
  Scene first = soup(770, 300, 40.0f, true);
  Scene second = soup(771, 300, 40.0f, true);
  Scene third = soup(772, 300, 40.0f, true);
  first.pipeline.depth_compare = second.pipeline.depth_compare = CompareOp::kLess;
  third.pipeline.depth_compare = CompareOp::kLess;
  for (Float4& p : second.positions)
    p.x = std::min(p.x, 0.0f);  // the left half of the screen only
  for (Float4& p : third.positions)
    p.x = std::max(p.x, 0.0f);  // the right half only: tiles the draw before left pending
  for (const uint32_t samples : {1u, 4u}) {
    for (const ColorFormat format : {ColorFormat::kRGBA8, ColorFormat::kRGBA32F}) {
      SCOPED_TRACE("samples " + std::to_string(samples) +
                   (format == ColorFormat::kRGBA8 ? ", RGBA8" : ", RGBA32F"));
      const auto run = [&](Backend backend, const Config& config, uint32_t bin_tile, bool eager) {
        RendererOptions options;
        options.backend = backend;
        options.threads = config.threads;
        options.simd = config.target;
        options.bin_tile_size = bin_tile;
        Renderer renderer(options);
        Framebuffer fb({first.width, first.height, samples, format, DepthFormat::kFloat32});
        const auto draw = [&](const Scene& s) {
          DrawInput input;
          input.positions = s.positions;
          input.attributes = s.colors;
          input.attribute_count = 4;
          renderer.draw(fb, s.pipeline, input);
        };
        const auto written = [&] {
          if (eager) (void)fb.read_sample_depth();
        };
        std::vector<std::vector<float>> seen;
        fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
        fb.clear_depth(1.0f);
        written();
        draw(Scene{});  // no triangles: the clears stay pending
        seen.push_back(fb.read_rgba32f());
        draw(first);
        fb.clear_color({0.9f, 0.8f, 0.7f, 0.5f});  // colour only: the depth of `first` stays
        written();
        draw(second);
        draw(third);
        seen.push_back(fb.read_rgba32f());
        seen.push_back(fb.read_sample_depth());
        fb.clear_depth(0.5f);
        written();
        seen.push_back(fb.read_sample_depth());
        draw(first);
        seen.push_back(fb.read_rgba32f());
        return seen;
      };
      const auto expect_same = [](const std::vector<std::vector<float>>& a,
                                  const std::vector<std::vector<float>>& b, const char* what) {
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
          EXPECT_EQ(0, std::memcmp(a[i].data(), b[i].data(), a[i].size() * 4))
              << what << ": read " << i;
        }
      };
      const auto ref = run(Backend::kReference, {SimdTarget::kAuto, 1}, 64, false);
      for_each_config([&](const Config& config) {
        for (const uint32_t bin_tile : {32u, 64u, 128u}) {
          SCOPED_TRACE("bin tile " + std::to_string(bin_tile));
          const auto fast = run(Backend::kFast, config, bin_tile, false);
          expect_same(fast, run(Backend::kFast, config, bin_tile, true), "written at once");
          if (format == ColorFormat::kRGBA8) expect_same(fast, ref, "reference");
        }
      });
    }
  }
}

TEST(FastEngine, HiZRejectsHiddenBlocksWithoutChangingTheImage) {
  Scene s;
  // A screen-filling pair of triangles in front, then many triangles behind it, large enough
  // (a bounding box over 16 px across) to take a Hi-Z test: ~30 px sides, most through the
  // small-triangle path, and ~80 px, through the general path.
  const float c[3][4] = {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}};
  const float w[3] = {1, 1, 1}, zf[3] = {0.1f, 0.1f, 0.1f};
  s.add({0, 136, 0}, {0, 0, 72}, zf, w, c);
  s.add({136, 136, 0}, {0, 72, 72}, zf, w, c);
  for (const Scene& behind : {soup(800, 2000, 400.0f, false), soup(802, 200, 3000.0f, false)}) {
    for (size_t i = 0; i < behind.positions.size(); ++i) {
      Float4 p = behind.positions[i];
      p.z = 0.2f + 0.7f * p.z;  // every depth behind the front quad
      s.positions.push_back(p);
    }
    s.colors.insert(s.colors.end(), behind.colors.begin(), behind.colors.end());
  }
  for (DepthFormat format : {DepthFormat::kFloat32, DepthFormat::kUnorm16}) {
    s.depth_format = format;
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      const Result fast = render(s, Backend::kFast, config);
      EXPECT_GT(fast.counters.hiz_rejected, 10000u);
      EXPECT_EQ(fast.rgba8, ref.rgba8);
      EXPECT_EQ(0, std::memcmp(fast.depth.data(), ref.depth.data(), ref.depth.size() * 4));
      // The kernels without counters, which drop a triangle hidden at every block of its box
      // in a tile before the blocks' tests: the same image.
      const Result quiet = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, false);
      EXPECT_EQ(quiet.rgba8, ref.rgba8);
      EXPECT_EQ(0, std::memcmp(quiet.depth.data(), ref.depth.data(), ref.depth.size() * 4));
      // Hi-Z switched off: the same image from per-sample tests alone.
      const Result plain = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, false);
      EXPECT_EQ(plain.counters.hiz_rejected + plain.counters.hiz_accepted, 0u);
      EXPECT_GT(plain.counters.samples_covered, fast.counters.samples_covered);
      EXPECT_EQ(plain.rgba8, ref.rgba8);
      EXPECT_EQ(0, std::memcmp(plain.depth.data(), ref.depth.data(), ref.depth.size() * 4));
    });
  }
}

// Two screen-filling quads, the far one first, each in front of everything drawn before it:
// every block a quad's triangle covers whole is accepted by Hi-Z (written without its depth
// read), and the image is the reference's.
TEST(FastEngine, HiZAcceptsBlocksCoveredInFrontOfEverythingWithoutChangingTheImage) {
  Scene s;
  const float w[3] = {1, 1, 1};
  // One colour a quad (as the depth): the two backends' bytes are then equal, not within a step.
  const float far_c[3][4] = {{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}};
  const float near_c[3][4] = {{1, 1, 0, 1}, {1, 1, 0, 1}, {1, 1, 0, 1}};
  for (float z : {0.9f, 0.1f}) {
    const float zz[3] = {z, z, z};
    const auto& c = z > 0.5f ? far_c : near_c;
    s.add({0, 136, 0}, {0, 0, 72}, zz, w, c);
    s.add({136, 136, 0}, {0, 72, 72}, zz, w, c);
  }
  // 17 x 9 blocks; a quad's diagonal crosses 17 + 9 - 1 of them (17 and 9 have no common
  // factor, so it meets no block corner inside the screen), and every other block lies inside
  // one of its triangles: 128 accepted per quad.
  constexpr uint64_t kAccepted = 2 * (17 * 9 - (17 + 9 - 1));
  for (uint32_t samples : {1u, 4u}) {
    s.samples = samples;
    const Result ref = render(s, Backend::kReference);
    for_each_config([&](const Config& config) {
      const Result fast = render(s, Backend::kFast, config);
      EXPECT_EQ(fast.counters.hiz_accepted, kAccepted) << config_name(config);
      EXPECT_EQ(fast.counters.hiz_rejected, 0u) << config_name(config);
      EXPECT_EQ(fast.rgba8, ref.rgba8) << config_name(config);
      EXPECT_EQ(0, std::memcmp(fast.depth.data(), ref.depth.data(), ref.depth.size() * 4));
      const Result plain = render(s, Backend::kFast, config, kDefaultBinMemoryBudget, true, false);
      EXPECT_EQ(plain.counters.hiz_accepted, 0u);
      EXPECT_EQ(plain.rgba8, fast.rgba8);
    });
  }
}

// A depth buffer cleared to NaN, one block of it then written in part: a NaN sample fails
// every ordering compare, so a triangle in front of the written samples must not be accepted
// over the whole block by Hi-Z (whose bounds are computed from the block's samples).
TEST(FastEngine, HiZAcceptsNoBlockThatHoldsNaNDepth) {
  const auto draw = [](Backend backend, const Config& config, DepthFormat format, CompareOp op) {
    RendererOptions options;
    options.backend = backend;
    options.simd = config.target;
    options.threads = config.threads;
    Renderer renderer(options);
    Framebuffer fb({64, 64, 1, ColorFormat::kRGBA8, format});
    fb.clear_color({0.0f, 0.0f, 0.0f, 1.0f});
    fb.clear_depth(std::numeric_limits<float>::quiet_NaN());
    const auto x = [](float px) { return px / 32.0f - 1.0f; };
    const auto y = [](float py) { return 1.0f - py / 32.0f; };
    // Depth 0.4375 over the first four columns of block (0, 0), whatever is there.
    const std::vector<Float4> rect = {{x(0), y(0), 0.4375f, 1}, {x(4), y(0), 0.4375f, 1},
                                      {x(0), y(8), 0.4375f, 1}, {x(4), y(0), 0.4375f, 1},
                                      {x(4), y(8), 0.4375f, 1}, {x(0), y(8), 0.4375f, 1}};
    const std::vector<float> grey(rect.size() * 4, 0.5f);
    PipelineState always;
    always.depth_compare = CompareOp::kAlways;
    renderer.draw(fb, always, {rect, grey, 4, {}});
    // Red over the whole screen, in front of the rectangle under `op`. (Depths whose 16-bit
    // steps lie far from a tie, so that both engines round them alike.)
    const float z = op == CompareOp::kLess || op == CompareOp::kLessEqual ? 0.125f : 0.875f;
    const std::vector<Float4> screen = {{-1, -1, z, 1}, {3, -1, z, 1}, {-1, 3, z, 1}};
    const std::vector<float> red = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    PipelineState tested;
    tested.depth_compare = op;
    renderer.draw(fb, tested, {screen, red, 4, {}});
    return std::make_pair(fb.read_rgba8(), fb.read_depth());
  };
  for (DepthFormat format : {DepthFormat::kFloat32, DepthFormat::kUnorm16}) {
    for (CompareOp op :
         {CompareOp::kLess, CompareOp::kLessEqual, CompareOp::kGreater, CompareOp::kGreaterEqual}) {
      SCOPED_TRACE(testing::Message() << "depth format " << static_cast<int>(format) << ", compare "
                                      << static_cast<int>(op));
      const auto ref = draw(Backend::kReference, {SimdTarget::kAuto, 1}, format, op);
      EXPECT_EQ(ref.first[4 * 4], 0);  // pixel (4, 0) held NaN: still the clear colour
      EXPECT_EQ(ref.first[0], 255);    // pixel (0, 0) held 0.4375: red
      for_each_config([&](const Config& config) {
        const auto fast = draw(Backend::kFast, config, format, op);
        EXPECT_EQ(fast.first, ref.first);
        EXPECT_EQ(0, std::memcmp(fast.second.data(), ref.second.data(), ref.second.size() * 4));
      });
    }
  }
}

// Ties at Hi-Z's bounds: a depth buffer cleared to 0.5, part of it then written at 0.25, and
// triangles of every size class at exactly 0.5 or 0.25 (flat planes at w = 1, 0.5 or 2, whose
// window depth is the value exactly) under each ordering compare op. A block's bounds then equal
// a triangle's depth, where Hi-Z must neither reject what LEQUAL or GEQUAL draws nor accept what
// LESS or GREATER does not: the reference's depth bits and colour, with and without raster counters
// (without them whole hidden triangles are dropped per tile), at one and four samples and in
// each depth format.
TEST(FastEngine, HiZAtTiedDepthsMatchesTheReference) {
  std::mt19937 rng(71);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float ws[] = {1.0f, 0.5f, 2.0f};
  Scene first, second;
  const auto add = [&](Scene& s, float cx, float cy, float r, float z, int i) {
    float x[3], y[3], zs[3], w[3], c[3][4];
    const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
    for (int k = 0; k < 3; ++k) {
      const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f;
      x[k] = cx + r * std::cos(a);
      y[k] = cy + r * std::sin(a);
      zs[k] = z;
      w[k] = ws[(i + k) % 3];
      for (int ch = 0; ch < 4; ++ch)
        c[k][ch] = u(rng);
    }
    s.add(x, y, zs, w, c);
  };
  // The first draw: depth 0.25 over scattered patches, so that blocks hold 0.25 and 0.5.
  for (int i = 0; i < 60; ++i)
    add(first, u(rng) * 136.0f, u(rng) * 72.0f, 3.0f + 12.0f * u(rng), 0.25f, i);
  // The second: radii from under a pixel to past the screen, at the two tied depths.
  const float radii[] = {0.7f, 2.0f, 5.0f, 12.0f, 30.0f, 200.0f};
  for (int i = 0; i < 600; ++i) {
    add(second, u(rng) * 150.0f - 7.0f, u(rng) * 86.0f - 7.0f,
        radii[i % 6] * (0.8f + 0.4f * u(rng)), i % 2 ? 0.5f : 0.25f, i);
  }
  const auto draw = [&](Backend backend, const Config& config, uint32_t samples, DepthFormat format,
                        CompareOp op, bool counters) {
    RendererOptions options;
    options.backend = backend;
    options.simd = config.target;
    options.threads = config.threads;
    options.raster_counters = counters;
    Renderer renderer(options);
    Framebuffer fb({136, 72, samples, ColorFormat::kRGBA8, format});
    fb.clear_color({0.0f, 0.0f, 0.0f, 1.0f});
    fb.clear_depth(0.5f);
    PipelineState always;
    always.depth_compare = CompareOp::kAlways;
    renderer.draw(fb, always, {first.positions, first.colors, 4, {}});
    PipelineState tested;
    tested.depth_compare = op;
    renderer.draw(fb, tested, {second.positions, second.colors, 4, {}});
    return std::make_pair(fb.read_rgba8(), fb.read_sample_depth());
  };
  for (DepthFormat format : {DepthFormat::kFloat32, DepthFormat::kUnorm24, DepthFormat::kUnorm16}) {
    for (uint32_t samples : {1u, 4u}) {
      std::vector<uint8_t> strict;  // the reference's image under LESS, then GREATER
      for (CompareOp op : {CompareOp::kLess, CompareOp::kLessEqual, CompareOp::kGreater,
                           CompareOp::kGreaterEqual}) {
        SCOPED_TRACE(testing::Message()
                     << "depth format " << static_cast<int>(format) << ", samples " << samples
                     << ", compare " << static_cast<int>(op));
        const auto ref =
            draw(Backend::kReference, {SimdTarget::kAuto, 1}, samples, format, op, true);
        // The ties decide: the inclusive op draws what the strict one does not.
        if (op == CompareOp::kLess || op == CompareOp::kGreater) {
          strict = ref.first;
        } else {
          size_t differ = 0;
          for (size_t i = 0; i < strict.size(); i += 4)
            differ += std::memcmp(&strict[i], &ref.first[i], 4) != 0;
          EXPECT_GT(differ, 2000u);
        }
        for_each_config([&](const Config& config) {
          for (bool counters : {true, false}) {
            const auto fast = draw(Backend::kFast, config, samples, format, op, counters);
            int worst = 0;  // colour: within one 8-bit step, as for every triangle
            for (size_t i = 0; i < ref.first.size(); ++i)
              worst = std::max(worst, std::abs(int{fast.first[i]} - int{ref.first[i]}));
            EXPECT_LE(worst, 1) << "counters " << counters;
            EXPECT_EQ(0, std::memcmp(fast.second.data(), ref.second.data(), ref.second.size() * 4))
                << "counters " << counters;
          }
        });
      }
    }
  }
}

TEST(FastEngine, DepthOnlyDrawWritesNoColourAndCulledTrianglesDrawNothing) {
  Scene s = soup(900, 2000, 50.0f, false);
  s.pipeline.color_write = false;
  const Result ref = render(s, Backend::kReference);
  std::vector<std::pair<Scene, Result>> culled;
  for (CullMode cull : {CullMode::kBack, CullMode::kFront}) {
    for (FrontFace front : {FrontFace::kCounterClockwise, FrontFace::kClockwise}) {
      Scene c = soup(901, 2000, 50.0f, true);
      c.pipeline.cull = cull;
      c.pipeline.front_face = front;
      culled.emplace_back(c, render(c, Backend::kReference));
    }
  }
  for_each_config([&](const Config& config) {
    const Result depth_only = render(s, Backend::kFast, config);
    EXPECT_EQ(depth_only.counters.pixels_shaded, 0u);
    for (size_t i = 0; i < depth_only.rgba8.size(); i += 4) {
      ASSERT_EQ(depth_only.rgba8[i], 26);  // the clear colour 0.1 * 255, rounded
    }
    for (size_t i = 0; i < ref.depth.size(); ++i) {
      ASSERT_LE(depth_error(depth_only.depth[i], ref.depth[i]), kDepthTolerance);
    }
    for (const auto& [scene, reference] : culled) {
      const Result f = render(scene, Backend::kFast, config);
      expect_same_coverage(f, reference, "culling");
      EXPECT_GT(f.counters.triangles_culled, 900u);
    }
  });
}

TEST(FastEngineOptions, ForcingAnUnsupportedOrUnknownTargetIsAnError) {
  for (SimdTarget t : {SimdTarget::kScalar, SimdTarget::kSSE4, SimdTarget::kAVX2,
                       SimdTarget::kAVX512, SimdTarget::kNEON, SimdTarget::kSVE}) {
    RendererOptions o;
    o.backend = Backend::kFast;
    o.simd = t;
    if (simd::is_available(t)) {
      EXPECT_NO_THROW(Renderer{o});
    } else {
      EXPECT_THROW(Renderer{o}, Error);
    }
  }
  RendererOptions tiny_budget;
  tiny_budget.bin_memory_budget = 1000;
  EXPECT_THROW(Renderer{tiny_budget}, Error);
}

// Every kernel this build compiles for this CPU can be forced, so the suites that loop over
// the forcible targets test each of them: a compiled target no SimdTarget reaches would run
// (as the automatic choice on some CPU) without ever being compared with the others.
TEST(FastEngineOptions, EveryCompiledTargetThisCpuRunsCanBeForced) {
  int64_t reached = 0;
  for (SimdTarget t : {SimdTarget::kScalar, SimdTarget::kSSE4, SimdTarget::kAVX2,
                       SimdTarget::kAVX512, SimdTarget::kNEON, SimdTarget::kSVE}) {
    if (simd::is_available(t)) reached |= simd::resolve_target(t);
  }
  const int64_t runnable = simd::runnable_target_bits();
  for (int64_t rest = runnable & ~reached; rest != 0; rest &= rest - 1) {
    ADD_FAILURE() << "compiled target " << simd::target_name(rest & -rest)
                  << " runs here but no SimdTarget forces it";
  }
  EXPECT_NE(runnable & reached, 0);
}

// Sets TESSERA_SIMD for its lifetime and puts back what was there, also when a test fails.
class SimdVariable {
 public:
  SimdVariable() : had_(std::getenv("TESSERA_SIMD") != nullptr) {
    if (had_) old_ = std::getenv("TESSERA_SIMD");
  }
  ~SimdVariable() {
    if (had_) {
      setenv("TESSERA_SIMD", old_.c_str(), 1);
    } else {
      unsetenv("TESSERA_SIMD");
    }
  }
  SimdVariable(const SimdVariable&) = delete;
  SimdVariable& operator=(const SimdVariable&) = delete;
  void set(const char* value) { ASSERT_EQ(setenv("TESSERA_SIMD", value, 1), 0); }

 private:
  bool had_;
  std::string old_;
};

// TESSERA_SIMD forces the target of renderers left at SimdTarget::kAuto; a target named in
// RendererOptions::simd wins over it; an unknown or unsupported value is an error naming it.
TEST(FastEngineOptions, TheTesseraSimdVariableForcesTheTargetOfAutomaticRenderers) {
  SimdVariable variable;
  RendererOptions automatic;
  automatic.backend = Backend::kFast;
  struct Named {
    SimdTarget target;
    const char* name;
  };
  const Named named_targets[] = {{SimdTarget::kScalar, "scalar"},
                                 {SimdTarget::kSSE4, "sse4"},
                                 {SimdTarget::kAVX2, "avx2"},
                                 {SimdTarget::kAVX512, "avx512"},
                                 {SimdTarget::kNEON, "neon"}};
  int forced = 0;
  const Named* vector_target = nullptr;  // one available target other than scalar
  for (const Named& n : named_targets) {
    variable.set(n.name);
    if (simd::is_available(n.target)) {
      EXPECT_EQ(std::string(Renderer(automatic).simd_target()), n.name);
      ++forced;
      if (n.target != SimdTarget::kScalar) vector_target = &n;
    } else {
      try {
        Renderer r(automatic);
        ADD_FAILURE() << "TESSERA_SIMD=" << n.name << " accepted on a CPU without it";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(std::string("TESSERA_SIMD=") + n.name),
                  std::string::npos)
            << e.what();
      }
    }
  }
  EXPECT_GE(forced, 1);  // scalar at least
  if (vector_target != nullptr) {
    variable.set("scalar");
    RendererOptions named = automatic;
    named.simd = vector_target->target;
    EXPECT_EQ(std::string(Renderer(named).simd_target()), vector_target->name);
  }
  variable.set("avx1024");
  try {
    Renderer r(automatic);
    ADD_FAILURE() << "TESSERA_SIMD=avx1024 accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("TESSERA_SIMD=avx1024"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
