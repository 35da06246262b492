// Points, lines and polygons on the fast engine against the reference rasterizer, for every
// SIMD target this machine runs and 1, 2 and 3 threads: thousands of random one-pixel lines
// (each algorithm, stippled), antialiased lines, wide lines with joins, square points and
// tessellated polygons. Each primitive has its own depth under CompareOp::kAlways, so a
// sample's final depth names the last primitive that covered it: equal depths mean equal
// coverage and equal submission order. One-pixel and antialiased lines are the same bytes in
// colour too; the triangle-drawn shapes' colour is within one 8-bit step, as for triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace tessera {
namespace {

struct Config {
  SimdTarget target;
  uint32_t threads;
};

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

constexpr uint32_t kWidth = 200, kHeight = 136;  // 4 x 3 tiles, the last ones partial

struct Image {
  std::vector<uint8_t> rgba8;
  std::vector<float> rgba32f;
  std::vector<float> depth;
  Counters counters;
};

using Draw = std::function<void(Renderer&, Framebuffer&)>;

Image render(const Draw& draw, Backend backend, Config config, uint32_t samples = 1,
             ColorFormat format = ColorFormat::kRGBA8) {
  RendererOptions options;
  options.backend = backend;
  options.threads = config.threads;
  options.simd = config.target;
  Renderer renderer(options);
  Framebuffer fb({kWidth, kHeight, samples, format});
  fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
  fb.clear_depth(1.0f);
  draw(renderer, fb);
  Image image;
  image.rgba8 = fb.read_rgba8();
  if (format == ColorFormat::kRGBA32F) image.rgba32f = fb.read_rgba32f();
  image.depth = fb.read_sample_depth();
  image.counters = renderer.counters();
  return image;
}

// Random vertices: window positions a little beyond the screen, one depth per primitive.
struct Soup {
  std::vector<Float4> positions;
  std::vector<float> colors;
  std::mt19937 rng;
  std::uniform_real_distribution<float> u{0.0f, 1.0f};
  explicit Soup(uint32_t seed) : rng(seed) {}

  void vertex(float x, float y, float z, float w = 1.0f) {
    positions.push_back(
        {(2.0f * x / kWidth - 1.0f) * w, (1.0f - 2.0f * y / kHeight) * w, z * w, w});
    for (int c = 0; c < 4; ++c)
      colors.push_back(u(rng));
  }
  float x() { return (u(rng) * 1.3f - 0.15f) * kWidth; }
  float y() { return (u(rng) * 1.3f - 0.15f) * kHeight; }
  DrawInput input() const { return {positions, colors, 4, {}}; }
};

float depth_of(int i) {
  return static_cast<float>(i + 1) / 32768.0f;
}

PipelineState always() {
  PipelineState p;
  p.depth_compare = CompareOp::kAlways;
  return p;
}

// n random segments as a list: mostly short, some across the screen, some with perspective.
// Every other one has its ends on the half-pixel grid (snapping recovers the grid exactly),
// where lines cross diamond corners and midpoints tie: the rules' tie-breaking is exercised.
Soup random_segments(uint32_t seed, int n) {
  Soup s(seed);
  for (int i = 0; i < n; ++i) {
    float x0 = s.x(), y0 = s.y();
    const bool long_line = i % 7 == 0;
    const float len = long_line ? 300.0f : 2.0f + 40.0f * s.u(s.rng);
    const float a = s.u(s.rng) * 2.0f * std::numbers::pi_v<float>;
    float x1 = x0 + len * std::cos(a), y1 = y0 + len * std::sin(a);
    float w0 = i % 5 == 0 ? 0.5f + 3.0f * s.u(s.rng) : 1.0f;
    float w1 = i % 5 == 0 ? 0.5f + 3.0f * s.u(s.rng) : 1.0f;
    if (i % 2 == 0) {
      auto grid = [](float v) { return std::round(v * 2.0f) / 2.0f; };
      x0 = grid(x0), y0 = grid(y0), x1 = grid(x1), y1 = grid(y1);
      w0 = w1 = 1.0f;
    }
    s.vertex(x0, y0, depth_of(i), w0);
    s.vertex(x1, y1, depth_of(i), w1);
  }
  return s;
}

int max_color_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i)
    worst = std::max(worst, std::abs(int{a.rgba8[i]} - int{b.rgba8[i]}));
  return worst;
}

size_t depth_mismatches(const Image& a, const Image& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.depth.size(); ++i)
    n += std::memcmp(&a.depth[i], &b.depth[i], sizeof(float)) != 0;
  return n;
}

// Compares the fast engine on every configuration with the reference.
// Counters are compared unless the draw has triangles the fast engine's Hi-Z may reject
// whole blocks of (those samples count as covered only in the reference).
void expect_engine_matches(const Draw& draw, bool exact_color, uint32_t samples = 1,
                           ColorFormat format = ColorFormat::kRGBA8, bool compare_counters = true) {
  const Image ref = render(draw, Backend::kReference, {SimdTarget::kAuto, 1}, samples, format);
  const Image* first = nullptr;
  std::vector<Image> images;
  images.reserve(all_configs().size());
  for (const Config& config : all_configs()) {
    images.push_back(render(draw, Backend::kFast, config, samples, format));
    const Image& fast = images.back();
    const char* names[] = {"auto", "scalar", "sse4", "avx2", "avx512", "neon", "sve"};
    const std::string what = std::string(names[static_cast<int>(config.target)]) + ", " +
                             std::to_string(config.threads) + " threads";
    EXPECT_EQ(depth_mismatches(fast, ref), 0u) << what;
    if (compare_counters) {
      EXPECT_EQ(fast.counters.samples_covered, ref.counters.samples_covered) << what;
    }
    if (exact_color) {
      EXPECT_EQ(fast.rgba8, ref.rgba8) << what;
      EXPECT_TRUE(fast.rgba32f == ref.rgba32f) << what;
    } else {
      EXPECT_LE(max_color_difference(fast, ref), 1) << what;
    }
    // The fast engine's own images are the same bytes on every target and thread count.
    if (!first) first = &images.front();
    EXPECT_EQ(fast.rgba8, first->rgba8) << what;
    EXPECT_EQ(depth_mismatches(fast, *first), 0u) << what;
  }
  EXPECT_GT(ref.counters.samples_passed, 1000u);
}

TEST(PrimitiveEngine, OnePixelLinesMatchTheReferenceForEveryAlgorithm) {
  const Soup soup = random_segments(1, 3000);
  for (LineAlgorithm alg :
       {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
    SCOPED_TRACE(static_cast<int>(alg));
    LineState state;
    state.algorithm = alg;
    expect_engine_matches(
        [&](Renderer& r, Framebuffer& fb) { r.draw_lines(fb, always(), state, soup.input()); },
        true);
  }
}

TEST(PrimitiveEngine, StippledStripsAndDepthTestedLinesMatchTheReference) {
  Soup soup(2);
  for (int i = 0; i < 2000; ++i)
    soup.vertex(soup.x(), soup.y(), soup.u(soup.rng));
  LineState state;
  state.topology = LineTopology::kStrip;
  state.stipple = {0x0C0F, 3};
  for (LineAlgorithm alg :
       {LineAlgorithm::kDiamondExit, LineAlgorithm::kBresenham, LineAlgorithm::kDDA}) {
    state.algorithm = alg;
    for (uint32_t samples : {1u, 4u}) {
      SCOPED_TRACE(testing::Message()
                   << "algorithm " << static_cast<int>(alg) << ", samples " << samples);
      expect_engine_matches(
          [&](Renderer& r, Framebuffer& fb) {
            r.draw_lines(fb, {}, state, soup.input());  // depth LESS against the line's own depth
          },
          true, samples);
    }
  }
}

// One-sample lines under every depth state: each compare op with and without depth writes,
// colour writes off, perspective-interpolated colour, drawn twice over the same framebuffer
// so that the second draw tests against the first's depth.
TEST(PrimitiveEngine, OneSampleLinesUnderEveryDepthStateMatchTheReference) {
  const Soup soup = random_segments(8, 1500);
  for (CompareOp op : {CompareOp::kLess, CompareOp::kLessEqual, CompareOp::kGreater,
                       CompareOp::kEqual, CompareOp::kNotEqual, CompareOp::kNever}) {
    for (bool depth_write : {true, false}) {
      for (bool color_write : {true, false}) {
        SCOPED_TRACE(testing::Message() << "op " << static_cast<int>(op) << ", depth write "
                                        << depth_write << ", colour write " << color_write);
        PipelineState p;
        p.depth_compare = op;
        p.depth_write = depth_write;
        p.color_write = color_write;
        expect_engine_matches(
            [&](Renderer& r, Framebuffer& fb) {
              r.draw_lines(fb, always(), {}, soup.input());
              r.draw_lines(fb, p, {}, soup.input());
            },
            true);
      }
    }
  }
}

// Lines that write depth between triangle draws: the triangles after them must see that depth
// (the fast engine's Hi-Z bounds of the blocks the lines wrote are marked stale).
TEST(PrimitiveEngine, TrianglesAfterLinesSeeTheLinesDepth) {
  Soup tris(4);
  for (int i = 0; i < 300; ++i) {
    // Flat depth per triangle: the fast engine's triangle depth is then exact (a plane's
    // rounding is the only difference from the reference's, and a flat plane has none).
    const float cx = tris.x(), cy = tris.y(), z = 0.3f + 0.4f * tris.u(tris.rng);
    for (int k = 0; k < 3; ++k) {
      const float a = static_cast<float>(k) * 2.1f + tris.u(tris.rng);
      tris.vertex(cx + 30.0f * std::cos(a), cy + 30.0f * std::sin(a), z);
    }
  }
  Soup lines(5);
  for (int i = 0; i < 3000; ++i)
    lines.vertex(lines.x(), lines.y(), 0.1f + 0.8f * lines.u(lines.rng));
  const DrawInput first{
      std::span(tris.positions).first(450), std::span(tris.colors).first(1800), 4, {}};
  const DrawInput second{
      std::span(tris.positions).subspan(450), std::span(tris.colors).subspan(1800), 4, {}};
  LineState state;
  state.topology = LineTopology::kStrip;
  expect_engine_matches(
      [&](Renderer& r, Framebuffer& fb) {
        r.draw(fb, {}, first);
        r.draw_lines(fb, {}, state, lines.input());
        r.draw(fb, {}, second);
      },
      false, 1, ColorFormat::kRGBA8, /*compare_counters=*/false);
}

// Per-pixel primitives store depth in the framebuffer's format, as triangles do.
TEST(PrimitiveEngine, PerPixelPrimitivesStoreDepthInTheFramebuffersFormat) {
  Soup soup(6);
  for (int i = 0; i < 40; ++i)
    soup.vertex(soup.x(), soup.y(), 0.3f);
  for (DepthFormat format : {DepthFormat::kUnorm16, DepthFormat::kUnorm24}) {
    const double scale = format == DepthFormat::kUnorm16 ? 65535.0 : 16777215.0;
    const float expected = static_cast<float>(std::nearbyint(double{0.3f} * scale) / scale);
    for (Backend backend : {Backend::kReference, Backend::kFast}) {
      Renderer r(RendererOptions{1, backend});
      FramebufferDesc desc{kWidth, kHeight, 1, ColorFormat::kRGBA8};
      desc.depth_format = format;
      Framebuffer fb(desc);
      LineState lines;
      lines.topology = LineTopology::kStrip;
      r.draw_lines(fb, {}, lines, soup.input());
      r.draw_points(fb, {}, {4.0f, PointShape::kRound}, soup.input());
      r.draw_polygon(fb, {}, {}, soup.input());
      size_t written = 0;
      for (float d : fb.read_depth()) {
        if (d == 1.0f) continue;
        EXPECT_EQ(d, expected);
        ++written;
      }
      EXPECT_GT(written, 1000u);
    }
  }
}

TEST(PrimitiveEngine, AntialiasedLinesMatchTheReference) {
  const Soup soup = random_segments(3, 400);
  LineState state;
  state.antialiased = true;
  state.width = 2.5f;
  expect_engine_matches(
      [&](Renderer& r, Framebuffer& fb) { r.draw_lines(fb, always(), state, soup.input()); }, true,
      1, ColorFormat::kRGBA32F);
}

// Long antialiased lines at every angle over a target of 8 x 6 line tiles, where a diagonal
// line's tiles are a band through its bounding box: the fast engine visits only the tiles
// near each line and draws the reference's bytes.
TEST(PrimitiveEngine, LongAntialiasedLinesOverManyTilesMatchTheReference) {
  constexpr uint32_t kW = 1000, kH = 760;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Float4> positions;
  std::vector<float> colors;
  for (int i = 0; i < 600; ++i) {
    const float x = u(rng) * 1200.0f - 100.0f, y = u(rng) * 960.0f - 100.0f;
    positions.push_back({2.0f * x / kW - 1.0f, 1.0f - 2.0f * y / kH, depth_of(i / 2), 1.0f});
    for (int c = 0; c < 4; ++c)
      colors.push_back(u(rng));
  }
  const DrawInput input{positions, colors, 4, {}};
  for (float width : {1.0f, 4.5f}) {
    SCOPED_TRACE(testing::Message() << "width " << width);
    LineState state;
    state.antialiased = true;
    state.width = width;
    auto draw = [&](Backend backend, Config config) {
      RendererOptions options;
      options.backend = backend;
      options.threads = config.threads;
      options.simd = config.target;
      Renderer renderer(options);
      Framebuffer fb({kW, kH, 1, ColorFormat::kRGBA32F});
      fb.clear_color({0.1f, 0.2f, 0.3f, 1.0f});
      renderer.draw_lines(fb, always(), state, input);
      return std::make_pair(fb.read_rgba32f(), fb.read_depth());
    };
    const auto ref = draw(Backend::kReference, {SimdTarget::kAuto, 1});
    for (const Config& config : all_configs()) {
      SCOPED_TRACE(testing::Message()
                   << static_cast<int>(config.target) << ", " << config.threads << " threads");
      const auto fast = draw(Backend::kFast, config);
      EXPECT_TRUE(fast.first == ref.first);
      EXPECT_TRUE(fast.second == ref.second);
    }
  }
}

// Antialiased lines into RGBA8 (blended over what earlier lines wrote, the bytes rounded as the
// reference rounds them) at one and four samples, without and with a depth test against the
// lines' own depth, at two widths.
TEST(PrimitiveEngine, AntialiasedLinesIntoRgba8MatchTheReference) {
  const Soup soup = random_segments(9, 600);
  for (float width : {1.0f, 2.5f}) {
    for (bool depth_test : {false, true}) {
      for (uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE(testing::Message() << "width " << width << ", depth test " << depth_test
                                        << ", samples " << samples);
        LineState state;
        state.antialiased = true;
        state.width = width;
        PipelineState p = always();
        if (depth_test) p.depth_compare = CompareOp::kLessEqual;
        expect_engine_matches(
            [&](Renderer& r, Framebuffer& fb) { r.draw_lines(fb, p, state, soup.input()); }, true,
            samples);
      }
    }
  }
}

// Antialiased lines with colour writes off write depth only, into RGBA8 and RGBA32F targets
// alike (an RGBA32F target has no 8-bit colour for the blend to read).
TEST(PrimitiveEngine, AntialiasedLinesWithoutColourWritesWriteTheReferencesDepth) {
  const Soup soup = random_segments(13, 400);
  for (ColorFormat format : {ColorFormat::kRGBA8, ColorFormat::kRGBA32F}) {
    SCOPED_TRACE(format == ColorFormat::kRGBA8 ? "rgba8" : "rgba32f");
    LineState state;
    state.antialiased = true;
    state.width = 2.5f;
    PipelineState p = always();
    p.color_write = false;
    expect_engine_matches(
        [&](Renderer& r, Framebuffer& fb) { r.draw_lines(fb, p, state, soup.input()); }, true, 1,
        format);
  }
}

TEST(PrimitiveEngine, WideLinesWithJoinsMatchTheReference) {
  for (LineJoin join : {LineJoin::kMiter, LineJoin::kRound, LineJoin::kBevel}) {
    SCOPED_TRACE(static_cast<int>(join));
    // One strip per draw call, each with its own depth.
    std::vector<Soup> strips;
    for (int k = 0; k < 40; ++k) {
      Soup s(100 + k);
      for (int i = 0; i < 12; ++i)
        s.vertex(s.x(), s.y(), depth_of(k));
      strips.push_back(std::move(s));
    }
    LineState state;
    state.topology = LineTopology::kStrip;
    state.width = 1.5f + 0.5f * static_cast<float>(join);
    state.join = join;
    expect_engine_matches(
        [&](Renderer& r, Framebuffer& fb) {
          for (const Soup& s : strips)
            r.draw_lines(fb, always(), state, s.input());
        },
        false, 4);
  }
}

// Wide lines and a miter join whose ends lie near the guard band's reach at w = 2^127, where
// the clip coordinates of a rectangle's corner or a miter's tip pass the largest float: each
// backend draws the same bytes as at w = 1, and the fast engine the reference's. (Converted back to
// clip space as they were, those corners became infinite, their clipped vertices NaN, and NaN
// reached the conversions to fixed point.)
TEST(PrimitiveEngine, WideLinesNearTheLargestWDrawAsAtWOne) {
  const float far_x = 1.5f * kWidth - 1.0f, far_y = 1.5f * kHeight - 1.0f;
  auto scene = [&](float w) {
    std::vector<Soup> draws(2, Soup(5));
    Soup& lines = draws[0];
    for (int i = 0; i < 8; ++i) {
      const float x = 20.0f + 20.0f * static_cast<float>(i),
                  y = 10.0f + 12.0f * static_cast<float>(i);
      lines.vertex(x, y, depth_of(i), w);
      lines.vertex(i % 2 ? far_x : -0.5f * kWidth + 1.0f, i % 2 ? far_y : -0.5f * kHeight + 1.0f,
                   depth_of(i), w);
    }
    Soup& strip = draws[1];  // turns back sharply beyond the bottom right corner
    strip.vertex(30.0f, 100.0f, depth_of(20), w);
    strip.vertex(far_x, far_y, depth_of(20), w);
    strip.vertex(60.0f, 110.0f, depth_of(20), w);
    return draws;
  };
  const std::vector<Soup> at_one = scene(1.0f), at_largest = scene(0x1p127f);
  auto draw = [](const std::vector<Soup>& draws) {
    return [&draws](Renderer& r, Framebuffer& fb) {
      LineState state;
      state.width = 8.0f;
      r.draw_lines(fb, always(), state, draws[0].input());
      state.topology = LineTopology::kStrip;
      state.join = LineJoin::kMiter;
      state.miter_limit = 100.0f;
      r.draw_lines(fb, always(), state, draws[1].input());
    };
  };
  std::vector<std::pair<Backend, Config>> configs = {{Backend::kReference, {SimdTarget::kAuto, 1}}};
  for (const Config& config : all_configs())
    configs.push_back({Backend::kFast, config});
  for (const auto& [backend, config] : configs) {
    SCOPED_TRACE(testing::Message()
                 << (backend == Backend::kFast ? "fast " : "reference ")
                 << static_cast<int>(config.target) << ", " << config.threads << " threads");
    const Image one = render(draw(at_one), backend, config);
    const Image largest = render(draw(at_largest), backend, config);
    EXPECT_GT(one.counters.samples_passed, 1000u);
    EXPECT_EQ(largest.rgba8, one.rgba8);
    EXPECT_EQ(depth_mismatches(largest, one), 0u);
  }
  expect_engine_matches(draw(at_largest), false);
}

TEST(PrimitiveEngine, SquarePointsMatchTheReference) {
  for (int size : {1, 3, 8}) {
    Soup soup(7);
    for (int i = 0; i < 2000; ++i)
      soup.vertex(soup.x(), soup.y(), depth_of(i));
    expect_engine_matches(
        [&](Renderer& r, Framebuffer& fb) {
          r.draw_points(fb, always(), {static_cast<float>(size), PointShape::kSquare},
                        soup.input());
        },
        false, size == 3 ? 4 : 1);
  }
}

TEST(PrimitiveEngine, RoundPointsMatchTheReference) {
  Soup soup(9);
  for (int i = 0; i < 5000; ++i)
    soup.vertex(soup.x(), soup.y(), soup.u(soup.rng));
  for (float size : {3.0f, 9.5f}) {
    for (uint32_t samples : {1u, 4u}) {
      expect_engine_matches(
          [&](Renderer& r, Framebuffer& fb) {
            r.draw_points(fb, {}, {size, PointShape::kRound}, soup.input());  // depth LESS
          },
          true, samples);
    }
  }
}

TEST(PrimitiveEngine, RoundPointsAndScanlinePolygonsMatchTheReference) {
  Soup soup(8);
  for (int i = 0; i < 500; ++i)
    soup.vertex(soup.x(), soup.y(), depth_of(i));
  expect_engine_matches(
      [&](Renderer& r, Framebuffer& fb) {
        r.draw_points(fb, always(), {5.0f, PointShape::kRound}, soup.input());
        r.draw_polygon(fb, always(), {FillRule::kNonZero, PolygonMethod::kScanline}, soup.input());
      },
      true);
}

TEST(PrimitiveEngine, ScanlinePolygonsMatchTheReference) {
  // Self-intersecting polygons of 3 to 40 random vertices across several tiles, some with a
  // second contour, each with its own tilted depth plane, drawn with depth LESS.
  std::vector<Soup> polygons;
  std::vector<std::vector<uint32_t>> sizes;
  for (int k = 0; k < 40; ++k) {
    Soup s(300 + k);
    const float cx = s.x(), cy = s.y(), r = 10.0f + 80.0f * s.u(s.rng);
    const float z0 = 0.2f + 0.5f * s.u(s.rng), zx = 0.002f * (s.u(s.rng) - 0.5f);
    const uint32_t n = 3 + static_cast<uint32_t>(k % 38);
    std::vector<uint32_t> sz = {n};
    if (k % 3 == 0) sz.push_back(4);
    for (uint32_t c : sz) {
      for (uint32_t i = 0; i < c; ++i) {
        const float x = cx + r * (2.0f * s.u(s.rng) - 1.0f),
                    y = cy + r * (2.0f * s.u(s.rng) - 1.0f);
        s.vertex(x, y, z0 + zx * (x - cx));
      }
    }
    polygons.push_back(std::move(s));
    sizes.push_back(sz);
  }
  for (FillRule rule : {FillRule::kEvenOdd, FillRule::kNonZero}) {
    for (uint32_t samples : {1u, 4u}) {
      expect_engine_matches(
          [&](Renderer& r, Framebuffer& fb) {
            for (size_t k = 0; k < polygons.size(); ++k) {
              r.draw_polygon(fb, {}, {rule, PolygonMethod::kScanline}, polygons[k].input(),
                             sizes[k]);
            }
          },
          true, samples);
    }
  }
}

TEST(PrimitiveEngine, TessellatedPolygonsMatchTheReference) {
  std::vector<Soup> polygons;
  std::vector<std::vector<uint32_t>> sizes;
  for (int k = 0; k < 60; ++k) {
    Soup s(200 + k);
    const float cx = s.x(), cy = s.y(), r = 5.0f + 40.0f * s.u(s.rng);
    const int n = 5 + k % 20;
    for (int i = 0; i < n; ++i) {
      const float a = (static_cast<float>(i) + 0.9f * s.u(s.rng)) * 2.0f *
                      std::numbers::pi_v<float> / static_cast<float>(n);
      const float rr = r * (0.5f + 0.5f * s.u(s.rng));
      s.vertex(cx + rr * std::cos(a), cy + rr * std::sin(a), depth_of(k));
    }
    std::vector<uint32_t> sz = {static_cast<uint32_t>(n)};
    if (k % 2 == 0) {  // a hole inside the outline's inner radius
      for (int i = 0; i < 4; ++i) {
        const float a = static_cast<float>(i) * std::numbers::pi_v<float> / 2.0f;
        s.vertex(cx + 0.15f * r * std::cos(a), cy + 0.15f * r * std::sin(a), depth_of(k));
      }
      sz.push_back(4);
    }
    polygons.push_back(std::move(s));
    sizes.push_back(sz);
  }
  for (FillRule rule : {FillRule::kEvenOdd, FillRule::kNonZero}) {
    expect_engine_matches(
        [&](Renderer& r, Framebuffer& fb) {
          for (size_t k = 0; k < polygons.size(); ++k) {
            r.draw_polygon(fb, always(), {rule, PolygonMethod::kTessellation}, polygons[k].input(),
                           sizes[k]);
          }
        },
        false, 4);
  }
}

}  // namespace
}  // namespace tessera
