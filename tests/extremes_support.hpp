// The extreme cases of issue 4 ("stability at the extremes"), shared by the reference suite
// (extremes_reference_test.cpp) and the fast-engine suite (extremes_fast_test.cpp): draws at
// the guard-band limit and far past it (to 1e30), framebuffers from 1x1 to 16384x16384,
// triangles from 1e-4 px to larger than the screen, slivers of aspect ratio 1e6, w from 1e-7
// to 1e7, vertices exactly on w = 0 and on the near plane, and denormal coordinates.
//
// Every case states its exact expectation as the set of samples it covers and how often: a
// case either covers every sample of the framebuffer exactly once (watertight meshes whose
// outline lies beyond the screen) or exactly the samples the fill rule gives a polygon whose
// vertices the test snaps itself (tessera::test::polygon_covers). Hits per sample are counted
// in one draw: depth is cleared to -1, a value no draw can write (depth lies in [0, 1]), and
// drawn with compare ALWAYS (no Hi-Z), so a sample is covered exactly when its depth no longer
// reads -1; the covered samples must be exactly the expected ones, and counters.samples_covered
// (every hit of every triangle) must equal their number, so none is hit twice.
//
// Each triangle has its own flat colour whose channels are 0, 1 or a power of two no larger
// than 1/4 (1/2 is avoided: 127.5 is a rounding tie). Interpolating such a colour, perspective
// correct or affine, scales every term by a power of two, so the colour comes out exact on both
// backends whatever the w of the vertices; the resolved images of the two backends must then be
// the same bytes, which says that every sample was won by the same triangle.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/src/clip.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"
#include "tests/simd_targets.hpp"

namespace tessera::extremes {

using test::Point;

// The depth a cleared sample reads until a triangle covers it: outside [0, 1], so no draw can
// write it.
inline constexpr float kUncovered = -1.0f;

// Per-triangle colours (see the file comment). Channel values: 0, 1, 1/4 .. 1/128.
inline std::array<float, 4> id_color(size_t triangle) {
  static constexpr float kLevels[8] = {0.0f,    1.0f,     0.25f,     0.125f,
                                       0.0625f, 0.03125f, 0.015625f, 0.0078125f};
  return {kLevels[triangle % 8], kLevels[(triangle / 8) % 8], kLevels[(triangle / 64) % 8], 1.0f};
}

// One draw and what it must cover.
struct Case {
  std::string name;
  FramebufferDesc desc{64, 48, 1, ColorFormat::kRGBA8};
  PipelineState pipeline = test::coverage_pipeline();
  std::vector<Float4> positions;  // three per triangle
  std::vector<float> colors;      // four per vertex: the triangle's id_color

  // The samples covered exactly once; every other sample is not covered. Empty: every sample
  // of the framebuffer.
  std::function<bool(uint32_t x, uint32_t y, uint32_t s)> covers;
  // When set, samples for which this is true but `covers` false may be covered or not (still
  // at most once): a boundary whose position the test knows only to within a margin.
  std::function<bool(uint32_t x, uint32_t y, uint32_t s)> may_cover;
  // Counters the case pins down, when it does.
  std::optional<uint64_t> triangles_clipped;
  std::optional<uint64_t> triangles_culled;

  size_t triangle_count() const { return positions.size() / 3; }

  void add_triangle(const Float4& a, const Float4& b, const Float4& c) {
    const std::array<float, 4> rgba = id_color(triangle_count());
    for (const Float4& p : {a, b, c}) {
      positions.push_back(p);
      colors.insert(colors.end(), rgba.begin(), rgba.end());
    }
  }
};

// What a draw left behind.
struct Outcome {
  std::vector<float> depth;   // every sample: (y * width + x) * samples + s
  std::vector<uint8_t> rgba;  // resolved
  Counters counters;
};

inline RendererOptions reference_options() {
  return test::reference_options();
}

// The fast-engine configurations: every SIMD target this machine runs, each with 1, 2 and 3
// threads.
struct FastConfig {
  SimdTarget target;
  uint32_t threads;
  std::string name() const {
    static const char* kNames[] = {"auto", "scalar", "sse4", "avx2", "avx512", "neon", "sve"};
    return std::string(kNames[static_cast<int>(target)]) + ", " + std::to_string(threads) +
           " threads";
  }
  RendererOptions options() const {
    RendererOptions o;
    o.backend = Backend::kFast;
    o.simd = target;
    o.threads = threads;
    return o;
  }
};

inline std::vector<SimdTarget> available_targets() {
  return test::runnable_simd_targets();
}

inline std::vector<FastConfig> fast_configs(std::initializer_list<uint32_t> threads = {1, 2, 3}) {
  std::vector<FastConfig> configs;
  for (SimdTarget t : available_targets()) {
    for (uint32_t n : threads)
      configs.push_back({t, n});
  }
  return configs;
}

inline Outcome run(const Case& c, const RendererOptions& options, bool read_color = true) {
  Renderer renderer(options);
  Framebuffer fb(c.desc);
  fb.clear_depth(kUncovered);
  DrawInput input;
  input.positions = c.positions;
  input.attributes = c.colors;
  input.attribute_count = c.colors.empty() ? 0 : 4;
  renderer.draw(fb, c.pipeline, input);
  Outcome o;
  o.depth = fb.read_sample_depth();
  if (read_color) o.rgba = fb.read_rgba8();
  o.counters = renderer.counters();
  return o;
}

// The case's expectation, exactly: the covered samples are the expected ones and each is hit
// once. Also no covered sample has a depth outside [0, 1].
inline void expect_covers_exactly(const Case& c, const Outcome& o) {
  const FramebufferDesc& d = c.desc;
  uint64_t expected = 0, wrong = 0, outside_range = 0;
  std::string first_wrong;
  size_t i = 0;
  for (uint32_t y = 0; y < d.height; ++y) {
    for (uint32_t x = 0; x < d.width; ++x) {
      for (uint32_t s = 0; s < d.samples; ++s, ++i) {
        const bool got = o.depth[i] != kUncovered;
        bool want = !c.covers || c.covers(x, y, s);
        if (!want && got && c.may_cover && c.may_cover(x, y, s)) want = true;
        expected += want ? 1 : 0;
        if (got && !(o.depth[i] >= 0.0f && o.depth[i] <= 1.0f)) ++outside_range;
        if (want != got && wrong++ == 0) {
          first_wrong = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") sample " +
                        std::to_string(s) + (want ? " not covered" : " covered");
        }
      }
    }
  }
  EXPECT_EQ(wrong, 0u) << c.name << ": first wrong sample: " << first_wrong;
  EXPECT_EQ(o.counters.samples_covered, expected) << c.name << ": hits other than one per sample";
  EXPECT_EQ(outside_range, 0u) << c.name << ": depth outside [0, 1]";
  if (c.triangles_clipped) {
    EXPECT_EQ(o.counters.triangles_clipped, *c.triangles_clipped) << c.name;
  }
  if (c.triangles_culled) {
    EXPECT_EQ(o.counters.triangles_culled, *c.triangles_culled) << c.name;
  }
}

// The fast engine drew what the reference drew: the same samples, won by the same triangles.
inline void expect_same_as_reference(const Case& c, const Outcome& fast, const Outcome& ref) {
  ASSERT_EQ(fast.depth.size(), ref.depth.size());
  size_t differ = 0, first = 0;
  for (size_t i = 0; i < ref.depth.size(); ++i) {
    if ((fast.depth[i] != kUncovered) != (ref.depth[i] != kUncovered) && differ++ == 0) first = i;
  }
  EXPECT_EQ(differ, 0u) << c.name << ": coverage differs first at sample index " << first;
  EXPECT_EQ(fast.counters.samples_covered, ref.counters.samples_covered) << c.name;
  EXPECT_EQ(fast.counters.triangles_clipped, ref.counters.triangles_clipped) << c.name;
  size_t bytes = 0, first_byte = 0;
  for (size_t i = 0; i < ref.rgba.size(); ++i) {
    if (fast.rgba[i] != ref.rgba[i] && bytes++ == 0) first_byte = i;
  }
  EXPECT_EQ(bytes, 0u) << c.name << ": resolved colour differs first at byte " << first_byte
                       << " (pixel " << first_byte / 4 << ")";
}

// --- Building cases -------------------------------------------------------------------------

// The fill rule's expectation for a convex polygon given in window pixels, snapped to 8 bits.
inline std::function<bool(uint32_t, uint32_t, uint32_t)> polygon(std::vector<Point> outline,
                                                                 uint32_t samples) {
  return [outline = std::move(outline), samples](uint32_t x, uint32_t y, uint32_t s) {
    return test::polygon_covers(outline, test::sample_position(samples, x, y, s));
  };
}

// Clip-space position of NDC point (x, y) at depth z/w = z, scaled to homogeneous w, computed
// in double and rounded once.
inline Float4 clip(double x, double y, double z, double w) {
  return {static_cast<float>(x * w), static_cast<float>(y * w), static_cast<float>(z * w),
          static_cast<float>(w)};
}

// A closed fan: triangles (centre, ring[i], ring[i+1]) around the whole ring, which must go
// once around the centre in angular order. Its outline is the ring, so when the ring's
// projection encloses the screen the fan covers every sample exactly once.
inline void add_fan(Case& c, const Float4& centre, const std::vector<Float4>& ring) {
  for (size_t i = 0; i < ring.size(); ++i)
    c.add_triangle(centre, ring[i], ring[(i + 1) % ring.size()]);
}

// w for vertex k of a spread: powers of ten from 1e-7 to 1e7 in a scrambled order.
inline double spread_w(size_t k) {
  return std::pow(10.0, static_cast<double>(static_cast<int>((k * 5) % 15) - 7));
}

// The guard band's half-extent in clip units per unit of w (clip.hpp: 32768 px from the
// viewport centre).
inline double guard_x(const FramebufferDesc& d) {
  return GuardBand::for_viewport(d.width, d.height).x;
}
inline double guard_y(const FramebufferDesc& d) {
  return GuardBand::for_viewport(d.width, d.height).y;
}

// Two triangles making the clip-space rectangle [-x, x] x [-y, y] at depth 0.5, w = 1, sharing
// a diagonal.
inline void add_rectangle(Case& c, float x, float y) {
  const Float4 a{-x, -y, 0.5f, 1}, b{x, -y, 0.5f, 1}, cc{x, y, 0.5f, 1}, d{-x, y, 0.5f, 1};
  c.add_triangle(a, b, cc);
  c.add_triangle(a, cc, d);
}

// A regular ring of n vertices of NDC radius r around the NDC origin, starting at `phase`
// radians, each scaled to its own w by w_of(k).
inline std::vector<Float4> ring(int n, double r, double phase,
                                const std::function<double(size_t)>& w_of) {
  std::vector<Float4> v;
  for (int k = 0; k < n; ++k) {
    const double a = phase + 2.0 * std::numbers::pi * k / n;
    v.push_back(clip(r * std::cos(a), r * std::sin(a), 0.5, w_of(static_cast<size_t>(k))));
  }
  return v;
}

// Window coordinates of a clip-space vertex with w > 0, by the convention's formula
// (ARCHITECTURE.md section 2) in double: what both rasterizers snap.
inline Point window_of(const Float4& v, const FramebufferDesc& d) {
  return {(double{v.x} / v.w + 1.0) * (0.5 * d.width),
          (1.0 - double{v.y} / v.w) * (0.5 * d.height)};
}

// Clip-space vertex at window point p, NDC depth z, homogeneous w.
inline Float4 at_window(const FramebufferDesc& d, Point p, double z = 0.5, double w = 1.0) {
  return test::Viewport{d.width, d.height}.at(p, z, w);
}

// Whether three window points snap (8 bits) to a triangle of zero area.
inline bool snaps_to_zero_area(Point a, Point b, Point c) {
  auto f = [](double v) { return static_cast<int64_t>(std::nearbyint(v * 256.0)); };
  return (f(b.x) - f(a.x)) * (f(c.y) - f(a.y)) - (f(b.y) - f(a.y)) * (f(c.x) - f(a.x)) == 0;
}

// A per-sample expectation stored as a mask.
class Mask {
 public:
  explicit Mask(const FramebufferDesc& d)
      : d_(d),
        bits_(std::make_shared<std::vector<uint8_t>>(size_t{d.width} * d.height * d.samples)) {}
  void add_polygon(const std::vector<Point>& outline) {
    size_t i = 0;
    for (uint32_t y = 0; y < d_.height; ++y) {
      for (uint32_t x = 0; x < d_.width; ++x) {
        for (uint32_t s = 0; s < d_.samples; ++s, ++i) {
          if (test::polygon_covers(outline, test::sample_position(d_.samples, x, y, s))) {
            ++(*bits_)[i];
          }
        }
      }
    }
  }
  // Whether no sample is claimed by two polygons (the expectation is "once").
  bool disjoint() const {
    return std::all_of(bits_->begin(), bits_->end(), [](uint8_t b) { return b <= 1; });
  }
  std::function<bool(uint32_t, uint32_t, uint32_t)> covers() const {
    return [bits = bits_, d = d_](uint32_t x, uint32_t y, uint32_t s) {
      return (*bits)[(size_t{y} * d.width + x) * d.samples + s] != 0;
    };
  }

 private:
  FramebufferDesc d_;
  std::shared_ptr<std::vector<uint8_t>> bits_;
};

// Rectangles at, just inside and past the guard-band limit, and far beyond it up to 1e30 in
// clip space and in window space: every sample exactly once; clipped exactly when past.
inline std::vector<Case> guard_band_cases() {
  std::vector<Case> cases;
  const FramebufferDesc descs[] = {{64, 48, 1, ColorFormat::kRGBA8},
                                   {64, 48, 4, ColorFormat::kRGBA8},
                                   {200, 136, 4, ColorFormat::kRGBA8}};
  for (const FramebufferDesc& d : descs) {
    const uint32_t samples = d.samples;
    const double gx = guard_x(d), gy = guard_y(d);  // 64x48: 1024 (a float) and 1365.33...
    // The float at the limit or below it is inside, the one above it outside.
    float x_at = static_cast<float>(gx);
    if (x_at > gx) x_at = std::nextafter(x_at, 0.0f);
    const float x_past = std::nextafter(x_at, std::numeric_limits<float>::infinity());
    // gy is not a float: the float below it is inside, the one above it outside.
    float y_in = static_cast<float>(gy);
    if (y_in > gy) y_in = std::nextafter(y_in, 0.0f);
    const float y_past = std::nextafter(y_in, std::numeric_limits<float>::infinity());
    struct Size {
      const char* name;
      float x, y;
      uint64_t clipped;
    };
    const Size sizes[] = {
        {"at or just inside the guard-band limit", x_at, y_in, 0},
        {"one float past the limit in x", x_past, y_in, 2},
        {"one float past the limit in y", x_at, y_past, 2},
        {"twice the limit", 2.0f * x_at, 2.0f * y_in, 2},
        {"1e6", 1e6f, 1e6f, 2},
        {"1e10", 1e10f, 1e10f, 2},
        {"1e20", 1e20f, 1e20f, 2},
        {"1e30", 1e30f, 1e30f, 2},
        {"3e38", 3e38f, 3e38f, 2},
    };
    for (const Size& s : sizes) {
      Case c;
      c.name = std::string("rectangle ") + s.name + ", " + std::to_string(d.width) + "x" +
               std::to_string(d.height) + "x" + std::to_string(samples);
      c.desc = d;
      add_rectangle(c, s.x, s.y);
      c.triangles_clipped = s.clipped;
      cases.push_back(std::move(c));
    }
    // Window coordinates of 1e30 from a tiny w: NDC +-1 at w = 1e-30, and 1e23 at w = 1e-7.
    for (const auto& [x, w] : {std::pair{1.0f, 1e-30f}, std::pair{1e23f, 1e-7f}}) {
      Case c;
      c.name = "rectangle with window coordinates near 1e30 (w = " + std::to_string(w) + "), " +
               std::to_string(samples) + " samples";
      c.desc = d;
      const Float4 a{-x, -x, 0.5f * w, w}, b{x, -x, 0.5f * w, w}, cc{x, x, 0.5f * w, w},
          dd{-x, x, 0.5f * w, w};
      c.add_triangle(a, b, cc);
      c.add_triangle(a, cc, dd);
      c.triangles_clipped = 2;
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

// Closed fans whose ring lies from just inside the guard band to 1e30 (NDC), the ring's w equal
// or spread from 1e-7 to 1e7, on screens whose centre (the fan's centre vertex) is a pixel
// corner (64x48) or a pixel centre (61x47), snapped to 4, 6 and 8 subpixel bits.
inline std::vector<Case> huge_fan_cases() {
  std::vector<Case> cases;
  const FramebufferDesc descs[] = {
      {64, 48, 1, ColorFormat::kRGBA8},   {61, 47, 1, ColorFormat::kRGBA8},
      {61, 47, 4, ColorFormat::kRGBA8},   {64, 48, 16, ColorFormat::kRGBA8},
      {200, 136, 1, ColorFormat::kRGBA8}, {131, 71, 8, ColorFormat::kRGBA8}};
  for (const FramebufferDesc& d : descs) {
    for (double r : {900.0, 1e5, 1e10, 1e20, 1e30}) {
      for (bool spread : {false, true}) {
        // Keep x = r * w a float: r * 1e7 <= 1e37.
        Case c;
        c.name = "fan of radius " + std::to_string(r) + (spread ? ", w spread 1e-7..1e7" : "") +
                 ", " + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
                 std::to_string(d.samples);
        c.desc = d;
        add_fan(c, clip(0, 0, 0.5, 1),
                ring(7, r, 0.3, [spread](size_t k) { return spread ? spread_w(k) : 1.0; }));
        // Every snapping precision: the outline is off screen, so the expectation holds for all.
        for (uint32_t bits = kMinSubpixelBits; bits <= kMaxSubpixelBits; bits += 2) {
          c.pipeline.subpixel_bits = bits;
          cases.push_back(c);
          cases.back().name += ", " + std::to_string(bits) + " subpixel bits";
        }
      }
    }
  }
  return cases;
}

// Closed fans in one plane of clip space that crosses the eye: the fan's parameter (s, t) maps
// to C + s U + t V with C = (0, 0, 0.5, 1), U = (1, 0, 1/8, 1/2), V = (0, 1, 0, 1/4), so
// z = 1/2 + s/8 and w = 1 + s/2 + t/4. The screen's preimage is the quadrilateral with
// corners (4, 4), (4/3, -4/3), (-4/5, 4/5), (-4/7, -4/7), where 0 < z < w; the near plane
// z = 0 is the line s = -4 and w = 0 the line t = -4 - 2 s. Besides a large ring, the ring has
// a vertex exactly on the near plane with w = 1 (-4, 8), one exactly on w = 0 and z = 0
// (-4, 4), one exactly on w = 0 with z > 0 (-2, 0), and two behind the eye. The projections
// of the pieces left after clipping cover every sample once, at 8 and at 4 subpixel bits.
inline std::vector<Case> near_plane_fan_cases() {
  std::vector<Case> cases;
  const FramebufferDesc descs[] = {{64, 48, 1, ColorFormat::kRGBA8},
                                   {61, 47, 4, ColorFormat::kRGBA8},
                                   {200, 136, 1, ColorFormat::kRGBA8}};
  for (const FramebufferDesc& d : descs) {
    for (double r : {1e3, 1e30}) {
      for (bool spread : {false, true}) {
        std::vector<std::pair<double, double>> st = {{-4, 8}, {-4, 4}, {-2, 0}, {-8, -2}, {0, -6}};
        for (int k = 0; k < 9; ++k) {
          const double a = 0.1 + 2.0 * std::numbers::pi * k / 9;
          st.push_back({r * std::cos(a), r * std::sin(a)});
        }
        std::sort(st.begin(), st.end(), [](const auto& p, const auto& q) {
          return std::atan2(p.second, p.first) < std::atan2(q.second, q.first);
        });
        std::vector<Float4> ring;
        for (size_t k = 0; k < st.size(); ++k) {
          const auto [s, t] = st[k];
          // Scaling a vertex by a positive factor keeps its projection and its side of every
          // plane through the eye.
          const double lambda = spread ? spread_w(k) : 1.0;
          ring.push_back({static_cast<float>(s * lambda), static_cast<float>(t * lambda),
                          static_cast<float>((0.5 + s / 8) * lambda),
                          static_cast<float>((1 + s / 2 + t / 4) * lambda)});
        }
        Case c;
        c.name = std::string("near-plane fan, ring radius ") + std::to_string(r) +
                 (spread ? ", w spread" : "") + ", " + std::to_string(d.width) + "x" +
                 std::to_string(d.height) + "x" + std::to_string(d.samples);
        c.desc = d;
        add_fan(c, {0, 0, 0.5f, 1}, ring);
        for (uint32_t bits : {kMaxSubpixelBits, kMinSubpixelBits}) {
          c.pipeline.subpixel_bits = bits;
          cases.push_back(c);
          cases.back().name += ", " + std::to_string(bits) + " subpixel bits";
        }
      }
    }
  }
  return cases;
}

// The smallest framebuffers and the longest rows and columns: a fan to 1e30 covers each sample
// once; in the 16384-long ones a small triangle at the far end covers exactly what the fill
// rule says.
inline std::vector<Case> framebuffer_size_cases() {
  std::vector<Case> cases;
  const FramebufferDesc descs[] = {
      {1, 1, 1, ColorFormat::kRGBA8},     {1, 1, 16, ColorFormat::kRGBA8},
      {2, 1, 4, ColorFormat::kRGBA8},     {16384, 1, 1, ColorFormat::kRGBA8},
      {1, 16384, 1, ColorFormat::kRGBA8}, {16384, 2, 4, ColorFormat::kRGBA8}};
  for (const FramebufferDesc& d : descs) {
    const std::string size =
        std::to_string(d.width) + "x" + std::to_string(d.height) + "x" + std::to_string(d.samples);
    Case fan;
    fan.name = "fan to 1e30 on " + size;
    fan.desc = d;
    add_fan(fan, clip(0, 0, 0.5, 1), ring(5, 1e30, 0.7, [](size_t) { return 1.0; }));
    cases.push_back(std::move(fan));

    if (d.width * d.height < 16384) continue;
    Case corner;
    corner.name = "small triangle at the far end of " + size;
    corner.desc = d;
    const double fx = d.width - 1.4, fy = d.height - 1.3;
    const std::vector<Point> tri = {
        {fx - 2.0, fy - 3.0}, {fx + 1.4, fy + 1.3}, {fx - 3.0, fy + 1.3}};
    corner.add_triangle(at_window(d, tri[0]), at_window(d, tri[1]), at_window(d, tri[2]));
    Mask m(d);
    m.add_polygon({window_of(corner.positions[0], d), window_of(corner.positions[1], d),
                   window_of(corner.positions[2], d)});
    corner.covers = m.covers();
    cases.push_back(std::move(corner));
  }
  return cases;
}

// Triangles of 1e-4 px and 1e-2 px. Regular grids of them: grid vertices snap monotonically,
// so the snapped grid is a grid of possibly empty rectangles, each empty one's two triangles
// culled as zero area, and the rest tile the snapped outline once. Scattered single ones, one
// per pixel near its sample or near a rounding boundary: each either snaps to zero area and is
// culled or covers what the fill rule gives its snapped vertices.
inline std::vector<Case> tiny_triangle_cases() {
  std::vector<Case> cases;
  struct Grid {
    double cell;  // pixels
    int n;        // cells per side
    Point centre;
    uint32_t samples;
    uint32_t width = 5, height = 4;
  };
  // Then on the corner of four tiles, of four 8x8 blocks, and at the far end of a 16384-wide
  // framebuffer, where clip-space floats are 4.9e-4 px apart and the grid's columns collapse.
  for (const Grid& g :
       {Grid{1e-4, 200, {2.5, 1.5}, 1}, Grid{1e-4, 150, {1.3781, 2.6193}, 16},
        Grid{1e-2, 150, {2.0, 2.0}, 4}, Grid{1e-2, 150, {64.0, 64.0}, 4, 72, 72},
        Grid{1e-3, 200, {8.0, 16.0}, 8, 72, 72}, Grid{1e-3, 300, {16383.25, 1.0}, 4, 16384, 2}}) {
    Case c;
    c.name = "grid of " + std::to_string(g.n) + "x" + std::to_string(g.n) + " cells of " +
             std::to_string(g.cell) + " px, " + std::to_string(g.samples) + " samples";
    c.desc = {g.width, g.height, g.samples, ColorFormat::kRGBA8};
    std::vector<Float4> v;
    const double x0 = g.centre.x - g.n * g.cell / 2, y0 = g.centre.y - g.n * g.cell / 2;
    for (int j = 0; j <= g.n; ++j) {
      for (int i = 0; i <= g.n; ++i)
        v.push_back(at_window(c.desc, {x0 + i * g.cell, y0 + j * g.cell}));
    }
    const int n1 = g.n + 1;
    uint64_t culled = 0;
    auto fixed = [](double p) { return std::nearbyint(p * 256.0); };
    for (int j = 0; j < g.n; ++j) {
      for (int i = 0; i < g.n; ++i) {
        const Float4 &a = v[j * n1 + i], &b = v[j * n1 + i + 1], &cc = v[(j + 1) * n1 + i],
                     &dd = v[(j + 1) * n1 + i + 1];
        c.add_triangle(a, b, dd);
        c.add_triangle(a, dd, cc);
        const Point pa = window_of(a, c.desc), pd = window_of(dd, c.desc);
        if (fixed(pa.x) == fixed(pd.x) || fixed(pa.y) == fixed(pd.y)) culled += 2;
      }
    }
    c.triangles_culled = culled;
    Mask m(c.desc);
    m.add_polygon({window_of(v.front(), c.desc), window_of(v[g.n], c.desc),
                   window_of(v.back(), c.desc), window_of(v[g.n * n1], c.desc)});
    c.covers = m.covers();
    cases.push_back(std::move(c));
  }

  for (uint32_t samples : {1u, 4u}) {
    Case c;
    c.name = "scattered 1e-4 px triangles, " + std::to_string(samples) + " samples";
    c.desc = {16, 16, samples, ColorFormat::kRGBA8};
    Mask m(c.desc);
    uint64_t culled = 0;
    for (uint32_t y = 0; y < 16; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        // Centred on the pixel's first sample, or a little off it, or on the midpoint between
        // two fixed-point steps (where rounding splits the vertices), in turn.
        const Point s0 = test::sample_position(samples, x, y, 0);
        const int kind = static_cast<int>((x + 3 * y) % 4);
        const Point centre = kind == 0   ? s0
                             : kind == 1 ? Point{s0.x + 2e-4, s0.y - 1e-4}
                             : kind == 2 ? Point{s0.x + 0.5 / 256, s0.y + 0.5 / 256}
                                         : Point{s0.x - 0.5 / 256 + 3e-5, s0.y + 0.5 / 256};
        const double r = 1e-4 / 2;
        const double rot = 0.37 * (x + 16 * y);
        std::vector<Float4> tri;
        std::vector<Point> win;
        for (int k = 0; k < 3; ++k) {
          const double a = rot + k * 2.0 * std::numbers::pi / 3;
          tri.push_back(
              at_window(c.desc, {centre.x + r * std::cos(a), centre.y + r * std::sin(a)}));
          win.push_back(window_of(tri.back(), c.desc));
        }
        c.add_triangle(tri[0], tri[1], tri[2]);
        if (snaps_to_zero_area(win[0], win[1], win[2])) {
          ++culled;
        } else {
          m.add_polygon(win);
        }
      }
    }
    c.triangles_culled = culled;
    c.covers = m.covers();
    cases.push_back(std::move(c));
  }
  return cases;
}

// Slivers with an aspect ratio of 1e6 and more: a band [y0, y0 + 3) px high, slanted, whose short
// sides are vertical at x = -5000 and x = width + 5000, cut into 300 bands 0.01 px high, each band
// two triangles 10^4 px long: the snapped band is covered once, its interior lines never.
inline std::vector<Case> sliver_cases() {
  std::vector<Case> cases;
  struct Band {
    double slope;
    uint32_t samples;
  };
  for (const Band& b : {Band{0.003, 1}, Band{-0.0007, 4}, Band{1.0, 1}, Band{0.0, 8}}) {
    Case c;
    c.name = "slivers 1e4 x 1e-2 px, slope " + std::to_string(b.slope) + ", " +
             std::to_string(b.samples) + " samples";
    c.desc = {136, 72, b.samples, ColorFormat::kRGBA8};  // 3 x 2 tiles
    const double xl = -5000.0, xr = c.desc.width + 5000.0, y0 = 36.37, pivot = 68.0;
    const int n = 300;
    auto left = [&](int i) {
      return at_window(c.desc, {xl, y0 + i * 0.01 + b.slope * (xl - pivot)});
    };
    auto right = [&](int i) {
      return at_window(c.desc, {xr, y0 + i * 0.01 + b.slope * (xr - pivot)});
    };
    for (int i = 0; i < n; ++i) {
      c.add_triangle(left(i), right(i), right(i + 1));
      c.add_triangle(left(i), right(i + 1), left(i + 1));
    }
    Mask m(c.desc);
    m.add_polygon({window_of(left(0), c.desc), window_of(right(0), c.desc),
                   window_of(right(n), c.desc), window_of(left(n), c.desc)});
    c.covers = m.covers();
    c.triangles_clipped = 0;
    cases.push_back(std::move(c));
  }

  // The same bands 2e6 px long, beyond the guard band on both sides: every triangle is clipped
  // (the interior lines at bit-identical points in both triangles that share them). The band's
  // edges are then known to within the snapping of the clipped vertices, which are on the
  // original lines to ~1e-12 px: samples more than 1/64 px inside the band's edges (the lines
  // through the vertices as floats) are covered, those more than 1/64 px outside are not, and
  // none is covered twice.
  for (const Band& b : {Band{0.003, 1}, Band{-0.0007, 4}, Band{1.0, 1}}) {
    Case c;
    c.name = "slivers 2e6 x 1e-2 px beyond the guard band, slope " + std::to_string(b.slope) +
             ", " + std::to_string(b.samples) + " samples";
    c.desc = {136, 72, b.samples, ColorFormat::kRGBA8};
    const double xl = -1e6, xr = c.desc.width + 1e6, y0 = 36.37, pivot = 68.0;
    const int n = 300;
    auto left = [&](int i) {
      return at_window(c.desc, {xl, y0 + i * 0.01 + b.slope * (xl - pivot)});
    };
    auto right = [&](int i) {
      return at_window(c.desc, {xr, y0 + i * 0.01 + b.slope * (xr - pivot)});
    };
    for (int i = 0; i < n; ++i) {
      c.add_triangle(left(i), right(i), right(i + 1));
      c.add_triangle(left(i), right(i + 1), left(i + 1));
    }
    // Window y of the line through two window points at window x.
    auto line_y = [](Point p, Point q, double x) {
      return p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x);
    };
    const Point tl = window_of(left(0), c.desc), tr = window_of(right(0), c.desc);
    const Point bl = window_of(left(n), c.desc), br = window_of(right(n), c.desc);
    const uint32_t samples = b.samples;
    auto inside_by = [=](uint32_t x, uint32_t y, uint32_t s, double margin) {
      const Point p = test::sample_position(samples, x, y, s);
      return p.y >= line_y(tl, tr, p.x) + margin && p.y <= line_y(bl, br, p.x) - margin;
    };
    constexpr double kMargin = 1.0 / 64;
    c.covers = [=](uint32_t x, uint32_t y, uint32_t s) { return inside_by(x, y, s, kMargin); };
    c.may_cover = [=](uint32_t x, uint32_t y, uint32_t s) { return inside_by(x, y, s, -kMargin); };
    c.triangles_clipped = 2 * n;
    cases.push_back(std::move(c));
  }
  return cases;
}

// The same window triangles at w = 1e-7, 1e7 and with w of 1e-7, 1 and 1e7 at its three
// vertices: coverage is that of the snapped window triangle, whatever w.
inline std::vector<Case> w_range_cases() {
  std::vector<Case> cases;
  const std::vector<std::array<double, 3>> ws = {
      {1e-7, 1e-7, 1e-7}, {1e7, 1e7, 1e7}, {1e-7, 1.0, 1e7}, {1e7, 3e-7, 0.5}};
  for (const auto& w : ws) {
    for (uint32_t samples : {1u, 4u}) {
      Case c;
      c.name = "w " + std::to_string(w[0]) + ", " + std::to_string(w[1]) + ", " +
               std::to_string(w[2]) + ", " + std::to_string(samples) + " samples";
      c.desc = {40, 30, samples, ColorFormat::kRGBA8};
      Mask m(c.desc);
      // Three disjoint triangles: small, screen-sized, and one reaching past the screen.
      const std::vector<std::vector<Point>> tris = {{{3.25, 2.5}, {9.75, 4.125}, {4.0, 11.0}},
                                                    {{38.5, 1.0}, {39.0, 28.5}, {12.0, 27.0}},
                                                    {{-30.0, 12.0}, {20.0, 14.5}, {-10.0, 60.0}}};
      for (const auto& t : tris) {
        std::vector<Float4> v;
        std::vector<Point> win;
        for (int k = 0; k < 3; ++k) {
          v.push_back(at_window(c.desc, t[k], 0.25 + 0.25 * k, w[k]));
          win.push_back(window_of(v.back(), c.desc));
        }
        c.add_triangle(v[0], v[1], v[2]);
        m.add_polygon(win);
      }
      EXPECT_TRUE(m.disjoint());
      c.covers = m.covers();
      c.triangles_clipped = 0;
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

// A vertex exactly on w = 0 is a point at infinity: the triangle (A, B, (1, 0, 0, 0)) is the
// region swept by the segment AB moving right to infinity, bounded by horizontal rays from A
// and B. Clipped at w = kMinClipW (or the far plane) and at the guard band, its pieces cover
// exactly that, at any scale of the vertex from 1e-20 to 1e30. The vertex (0, 0, 0, 0) makes
// the triangle a segment, which covers nothing.
inline std::vector<Case> w_zero_cases() {
  std::vector<Case> cases;
  for (uint32_t samples : {1u, 4u}) {
    for (const Float4 unit : {Float4{1, 0, 0, 0}, Float4{-1, 0, 0.25f, 0}, Float4{0, 1, 0, 0}}) {
      // Homogeneous coordinates name the same point at any positive scale (down to where the
      // w >= kMinClipW plane, 1e-30 from w = 0, cuts the triangle at a finite distance).
      for (float scale : {1.0f, 1e30f, 1e-20f}) {
        const Float4 dir{unit.x * scale, unit.y * scale, unit.z * scale, 0};
        Case c;
        c.name = "vertex at infinity (" + std::to_string(unit.x) + ", " + std::to_string(unit.y) +
                 ", " + std::to_string(unit.z) + ", 0) * " +
                 (scale == 1.0f  ? "1"
                  : scale > 1.0f ? "1e30"
                                 : "1e-20") +
                 ", " + std::to_string(samples) + " samples";
        c.desc = {48, 40, samples, ColorFormat::kRGBA8};
        const Point a{17.25, 9.5}, b{25.5, 30.0};
        c.add_triangle(at_window(c.desc, a), at_window(c.desc, b), dir);
        // NDC +x is window +x, NDC +y is window -y; the far side lies well beyond the screen.
        const double far = 1e4;
        std::vector<Point> outline;
        if (dir.x != 0) {
          const double sx = dir.x > 0 ? far : -far;
          outline = {a, b, {sx, b.y}, {sx, a.y}};
        } else {
          outline = {a, b, {b.x, -far}, {a.x, -far}};
        }
        Mask m(c.desc);
        m.add_polygon(outline);
        c.covers = m.covers();
        c.triangles_clipped = 1;
        cases.push_back(std::move(c));
      }
    }
    // The homogeneous origin is no point at all: the triangle (A, B, 0) is the set of points
    // a A + b B, whose projection is the segment AB. Clipped at w = kMinClipW, the cut points
    // are kMinClipW A and kMinClipW B, which project onto A and B: nothing has any area.
    Case c;
    c.name =
        "vertex at the homogeneous origin (0, 0, 0, 0), " + std::to_string(samples) + " samples";
    c.desc = {48, 40, samples, ColorFormat::kRGBA8};
    c.add_triangle(at_window(c.desc, {17.25, 9.5}), at_window(c.desc, {25.5, 30.0}), {0, 0, 0, 0});
    c.covers = [](uint32_t, uint32_t, uint32_t) { return false; };
    c.triangles_clipped = 1;
    cases.push_back(std::move(c));
  }
  return cases;
}

// Denormal coordinates are valid input. The smallest positive float as an offset changes no
// window coordinate (a triangle with denormal z draws at depth 2^-149, kept, not flushed to 0);
// a triangle made only of denormal offsets snaps to a point and is culled as zero area; one
// whose w is denormal lies before the w >= kMinClipW plane and is culled as outside the view.
inline std::vector<Case> denormal_cases() {
  std::vector<Case> cases;
  constexpr float t = std::numeric_limits<float>::denorm_min();
  const FramebufferDesc d{32, 16, 4, ColorFormat::kRGBA8};
  {
    Case c;
    c.name = "denormal offsets and depth";
    c.desc = d;
    c.pipeline.depth_compare = CompareOp::kAlways;
    const Float4 a{t, t, t, 1}, b{0.5f, -t, t, 1}, cc{-t, -0.75f, t, 1};
    c.add_triangle(a, b, cc);
    Mask m(d);
    m.add_polygon({window_of(a, d), window_of(b, d), window_of(cc, d)});
    c.covers = m.covers();
    c.triangles_culled = 0;
    c.triangles_clipped = 0;
    cases.push_back(std::move(c));
  }
  {
    Case c;
    c.name = "denormal-only triangle";
    c.desc = d;
    c.add_triangle({t, 0, 0.5f, 1}, {2 * t, 3 * t, 0.5f, 1}, {-t, t, 0.5f, 1});
    c.covers = [](uint32_t, uint32_t, uint32_t) { return false; };
    c.triangles_culled = 1;
    c.triangles_clipped = 0;
    cases.push_back(std::move(c));
  }
  {
    Case c;
    c.name = "denormal w";
    c.desc = d;
    c.add_triangle({t, t, 0, t}, {-t, t, 0, t}, {0, -t, 0, 2 * t});
    c.covers = [](uint32_t, uint32_t, uint32_t) { return false; };
    c.triangles_culled = 1;
    c.triangles_clipped = 1;
    cases.push_back(std::move(c));
  }
  return cases;
}

// --- Without the depth test -------------------------------------------------------------------

// Every single-sample case once more with the depth test off (no depth read or written: the
// kernels without depth): coverage is read from alpha, which every triangle writes as 1 over a
// clear of 0. The covered pixels are the case's, the hits add up to their number, and the image
// is returned for comparison with the reference's.
inline std::vector<std::vector<uint8_t>> expect_cases_exact_without_depth(
    const RendererOptions& options) {
  std::vector<std::vector<uint8_t>> images;
  for (const std::vector<Case>& list :
       {guard_band_cases(), huge_fan_cases(), near_plane_fan_cases(), framebuffer_size_cases(),
        tiny_triangle_cases(), sliver_cases(), w_range_cases(), w_zero_cases(), denormal_cases()}) {
    for (Case c : list) {
      if (c.desc.samples != 1) continue;
      SCOPED_TRACE(c.name);
      c.pipeline.depth_test = false;
      Renderer renderer(options);
      Framebuffer fb(c.desc);
      fb.clear_color({0, 0, 0, 0});
      renderer.draw(fb, c.pipeline, {c.positions, c.colors, 4, {}});
      std::vector<uint8_t> rgba = fb.read_rgba8();
      uint64_t covered = 0, wrong = 0;
      for (uint32_t y = 0; y < c.desc.height; ++y) {
        for (uint32_t x = 0; x < c.desc.width; ++x) {
          const bool got = rgba[(size_t{y} * c.desc.width + x) * 4 + 3] != 0;
          bool want = !c.covers || c.covers(x, y, 0);
          if (!want && got && c.may_cover && c.may_cover(x, y, 0)) want = true;
          covered += got ? 1 : 0;
          wrong += got != want ? 1 : 0;
        }
      }
      EXPECT_EQ(wrong, 0u);
      EXPECT_EQ(renderer.counters().samples_covered, covered) << "hits other than one per pixel";
      images.push_back(std::move(rgba));
    }
  }
  EXPECT_GT(images.size(), 100u);
  return images;
}

// --- Depth at a near/far ratio of 1e7 --------------------------------------------------------

// A D3D-style perspective projection with near 1 and far 1e7: z_clip = f / (f - n) (d - n),
// w = d, for a point at NDC (x, y) and view distance d.
inline Float4 project(double x, double y, double d) {
  constexpr double n = 1.0, f = 1e7;
  return {static_cast<float>(x * d), static_cast<float>(y * d),
          static_cast<float>(f / (f - n) * (d - n)), static_cast<float>(d)};
}

// A quad reaching past the screen on every side (NDC +-1.5), at view distance d_left on its
// left edge and d_right on its right edge (a plane in view space: its two edges are parallel).
inline std::vector<Float4> distance_quad(double d_left, double d_right) {
  const Float4 a = project(-1.5, -1.5, d_left), b = project(1.5, -1.5, d_right),
               c = project(1.5, 1.5, d_right), d = project(-1.5, 1.5, d_left);
  return {a, b, c, a, c, d};
}

// Draws the triangle lists one after the other into a fresh framebuffer (depth cleared to 1)
// and returns the renderer's counters and every sample's depth.
inline std::pair<Counters, std::vector<float>> draw_lists(
    const RendererOptions& options, const FramebufferDesc& desc, const PipelineState& pipeline,
    std::initializer_list<std::vector<Float4>> lists) {
  Renderer renderer(options);
  Framebuffer fb(desc);
  for (const std::vector<Float4>& list : lists)
    renderer.draw(fb, pipeline, {list, {}, 0, {}});
  return {renderer.counters(), fb.read_sample_depth()};
}

// With n = 1 and f = 1e7, two planes 1% apart at distances 1e3 to 1e4 differ in depth by at
// least 1e-6 (17 float steps below 1.0): the nearer wins every sample in either drawing order.
// A plane exactly on the near plane (z = 0) has depth exactly 0, one exactly on the far plane
// (z = w) depth exactly 1, which LESS rejects over a depth of 1 and LESS_EQUAL accepts; neither
// is clipped. Drawn again over itself at depth 0, it passes LESS_EQUAL and GREATER_EQUAL and
// fails LESS and GREATER, block by block as sample by sample.
inline void expect_near_far_ratio_1e7_resolved(const RendererOptions& options) {
  const FramebufferDesc desc{72, 40, 4, ColorFormat::kRGBA8};
  const uint64_t n = uint64_t{desc.width} * desc.height * desc.samples;
  PipelineState less;  // LESS, write
  const std::vector<Float4> front = distance_quad(1e3, 1e4), back = distance_quad(1010, 10100);

  auto [c1, d1] = draw_lists(options, desc, less, {back, front});
  EXPECT_EQ(c1.samples_passed, 2 * n) << "back then front: the front must win every sample";
  auto [c2, d2] = draw_lists(options, desc, less, {front, back});
  EXPECT_EQ(c2.samples_passed, n) << "front then back: the back must lose every sample";
  EXPECT_EQ(d1, d2) << "the front's depth is left, whatever the order";

  // On the near plane: z = 0 exactly.
  auto [c3, d3] = draw_lists(options, desc, less, {distance_quad(1.0, 1.0)});
  EXPECT_EQ(c3.samples_passed, n);
  EXPECT_EQ(c3.triangles_clipped, 0u);
  EXPECT_EQ(std::count(d3.begin(), d3.end(), 0.0f), static_cast<std::ptrdiff_t>(n));
  // On the far plane: z = w exactly.
  std::vector<Float4> far = distance_quad(1e7, 1e7);
  for (Float4& v : far)
    v.z = v.w;
  auto [c4, d4] = draw_lists(options, desc, less, {far});
  EXPECT_EQ(c4.samples_passed, 0u) << "depth 1 is not less than 1";
  EXPECT_EQ(c4.triangles_clipped, 0u);
  PipelineState less_equal;
  less_equal.depth_compare = CompareOp::kLessEqual;
  auto [c5, d5] = draw_lists(options, desc, less_equal, {far, far});
  EXPECT_EQ(c5.samples_passed, 2 * n) << "depth 1 is less than or equal to 1, twice";
  EXPECT_EQ(std::count(d5.begin(), d5.end(), 1.0f), static_cast<std::ptrdiff_t>(n));
  // Depth 0 over depth 0, where a block's nearest and farthest depth equal the triangle's: the
  // Hi-Z may decide whole blocks, and must decide them as the per-sample test would.
  const std::vector<Float4> near = distance_quad(1.0, 1.0);
  for (const auto& [op, passes] :
       {std::pair{CompareOp::kLess, 1u}, std::pair{CompareOp::kLessEqual, 3u},
        std::pair{CompareOp::kGreater, 1u}, std::pair{CompareOp::kGreaterEqual, 3u}}) {
    PipelineState p;
    p.depth_compare = CompareOp::kAlways;
    Renderer renderer(options);
    Framebuffer fb(desc);
    renderer.draw(fb, p, {near, {}, 0, {}});  // depth 0 everywhere, n samples pass
    p.depth_compare = op;
    renderer.draw(fb, p, {near, {}, 0, {}});
    renderer.draw(fb, p, {near, {}, 0, {}});
    EXPECT_EQ(renderer.counters().samples_passed, passes * n) << "compare " << static_cast<int>(op);
  }
}

// --- Non-finite coordinates ---------------------------------------------------------------------

// NaN, +Inf and -Inf in x, y, z and w of one vertex, in indexed and non-indexed draws: the
// draw is rejected with Error(kInvalidInput) naming the vertex, before anything is drawn: the
// framebuffer's colour and depth and the counters are as they were, and the renderer draws the
// same mesh without the bad value afterwards.
inline void expect_non_finite_rejected(const RendererOptions& options) {
  const FramebufferDesc desc{40, 24, 4, ColorFormat::kRGBA8};
  Case mesh;
  mesh.desc = desc;
  add_fan(mesh, clip(0.1, -0.2, 0.5, 1), ring(9, 3.0, 0.2, [](size_t k) { return spread_w(k); }));
  const size_t bad_vertex = 13;
  const float values[] = {std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity()};
  for (bool indexed : {false, true}) {
    for (int component = 0; component < 4; ++component) {
      for (float value : values) {
        SCOPED_TRACE(std::string(indexed ? "indexed, " : "") + "component " +
                     std::to_string(component) + " = " + std::to_string(value));
        Renderer renderer(options);
        Framebuffer fb(desc);
        fb.clear_color({0.25f, 0.5f, 0.75f, 1.0f});
        fb.clear_depth(0.625f);
        const std::vector<uint8_t> rgba_before = fb.read_rgba8();
        const std::vector<float> depth_before = fb.read_sample_depth();

        std::vector<Float4> positions = mesh.positions;
        std::vector<uint32_t> indices;
        if (indexed) {
          for (uint32_t i = 0; i < positions.size(); ++i)
            indices.push_back(static_cast<uint32_t>(positions.size()) - 1 - i);
        }
        (&positions[bad_vertex].x)[component] = value;
        DrawInput input{positions, mesh.colors, 4, indices};
        try {
          renderer.draw(fb, PipelineState{}, input);
          ADD_FAILURE() << "the draw was accepted";
        } catch (const Error& e) {
          EXPECT_EQ(e.code(), ErrorCode::kInvalidInput);
          EXPECT_NE(std::string(e.what()).find("position of vertex " + std::to_string(bad_vertex) +
                                               " is not finite"),
                    std::string::npos)
              << e.what();
        }
        EXPECT_EQ(fb.read_rgba8(), rgba_before);
        EXPECT_EQ(fb.read_sample_depth(), depth_before);
        EXPECT_EQ(renderer.counters().triangles_submitted, 0u);
        EXPECT_EQ(renderer.counters().samples_covered, 0u);

        input.positions = mesh.positions;
        renderer.draw(fb, PipelineState{}, input);
        EXPECT_EQ(renderer.counters().triangles_submitted, mesh.triangle_count());
        EXPECT_GT(renderer.counters().samples_passed, 0u);
      }
    }
  }
}

// With NonFiniteVertices::kCull, the triangles that use a vertex holding a NaN or an infinity
// (in its position or its colour) are dropped and counted, and the rest draw exactly what an
// index list without them draws: an indexed fan whose ring vertices are each shared by two
// triangles, one bad value at a time; and a bad centre, which every triangle uses.
inline void expect_non_finite_culled(RendererOptions options) {
  const FramebufferDesc desc{40, 24, 4, ColorFormat::kRGBA8};
  std::vector<Float4> positions = {clip(0.1, -0.2, 0.5, 1)};
  for (const Float4& p : ring(9, 3.0, 0.2, [](size_t k) { return spread_w(k); }))
    positions.push_back(p);
  const uint32_t ring_size = static_cast<uint32_t>(positions.size()) - 1;
  std::vector<uint32_t> indices;
  for (uint32_t i = 0; i < ring_size; ++i)
    indices.insert(indices.end(), {0, 1 + i, 1 + (i + 1) % ring_size});
  std::vector<float> colors;
  for (size_t v = 0; v < positions.size(); ++v) {
    const std::array<float, 4> rgba = id_color(v);
    colors.insert(colors.end(), rgba.begin(), rgba.end());
  }
  const float values[] = {std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity()};
  for (uint32_t bad : {0u, 4u}) {
    for (int component = 0; component < 8; ++component) {  // x, y, z, w, r, g, b, a
      for (float value : values) {
        SCOPED_TRACE("vertex " + std::to_string(bad) + ", component " + std::to_string(component) +
                     " = " + std::to_string(value));
        std::vector<Float4> bad_positions = positions;
        std::vector<float> bad_colors = colors;
        if (component < 4) {
          (&bad_positions[bad].x)[component] = value;
        } else {
          bad_colors[bad * 4 + static_cast<size_t>(component - 4)] = value;
        }
        std::vector<uint32_t> good;
        for (size_t t = 0; t < indices.size(); t += 3) {
          if (indices[t] != bad && indices[t + 1] != bad && indices[t + 2] != bad)
            good.insert(good.end(), indices.begin() + t, indices.begin() + t + 3);
        }
        const uint64_t dropped = (indices.size() - good.size()) / 3;
        EXPECT_EQ(dropped, bad == 0 ? ring_size : 2u);

        options.non_finite = NonFiniteVertices::kCull;
        Renderer culling(options);
        Framebuffer fb(desc);
        fb.clear_color({0.25f, 0.5f, 0.75f, 1.0f});
        culling.draw(fb, PipelineState{}, {bad_positions, bad_colors, 4, indices});
        EXPECT_EQ(culling.counters().triangles_invalid, dropped);

        options.non_finite = NonFiniteVertices::kError;
        Renderer plain(options);
        Framebuffer expected(desc);
        expected.clear_color({0.25f, 0.5f, 0.75f, 1.0f});
        if (!good.empty()) plain.draw(expected, PipelineState{}, {positions, colors, 4, good});
        EXPECT_EQ(plain.counters().triangles_invalid, 0u);
        EXPECT_EQ(culling.counters().triangles_submitted, plain.counters().triangles_submitted);
        EXPECT_EQ(fb.read_rgba8(), expected.read_rgba8());
        EXPECT_EQ(fb.read_sample_depth(), expected.read_sample_depth());
        if (bad != 0) {
          EXPECT_GT(culling.counters().samples_passed, 0u);
        }
      }
    }
  }
}

// --- The largest framebuffer ------------------------------------------------------------------

// 16384 x 16384 with one sample of RGBA8 colour and float depth: 2 GiB of framebuffer, plus
// 1 GiB for the depth read back; colour is neither written nor read. One draw: two triangles
// reaching to 1e30 at depth 1/2 (the guard band is only 4 viewport half-widths here), then
// small triangles at depth 1/4 at the four corners and the centre. Every sample is covered by
// the big ones exactly once; the small ones cover exactly what the fill rule gives them, and
// nothing else is nearer than 3/8; the hits add up to the samples plus those of the small ones.
inline void expect_largest_framebuffer_exact(Framebuffer& fb, const RendererOptions& options) {
  const FramebufferDesc desc = fb.desc();
  EXPECT_EQ(desc.width, kMaxFramebufferSize);
  EXPECT_EQ(desc.height, kMaxFramebufferSize);
  const uint64_t n = uint64_t{desc.width} * desc.height;
  Case c;
  add_rectangle(c, 1e30f, 1e30f);
  const double side = kMaxFramebufferSize;
  const Point anchors[] = {{1.3, 1.7},
                           {side - 1.6, 1.2},
                           {1.1, side - 1.9},
                           {side - 1.5, side - 1.5},
                           {side / 2 + 0.25, side / 2 - 0.5}};
  std::vector<std::vector<Point>> outlines;
  for (const Point& p : anchors) {
    const std::vector<Point> tri = {
        {p.x - 1.3, p.y - 1.7}, {p.x + 1.6, p.y + 0.2}, {p.x - 0.9, p.y + 1.9}};
    std::vector<Point> win;
    for (const Point& q : tri) {
      c.positions.push_back(at_window(desc, q, 0.25));
      win.push_back(window_of(c.positions.back(), desc));
    }
    outlines.push_back(win);
  }

  Renderer renderer(options);
  PipelineState pipeline = test::coverage_pipeline();
  pipeline.color_write = false;
  fb.clear_depth(kUncovered);
  renderer.draw(fb, pipeline, {c.positions, {}, 0, {}});
  const std::vector<float> depth = fb.read_depth();
  const auto uncovered = std::count(depth.begin(), depth.end(), kUncovered);
  const auto near =
      std::count_if(depth.begin(), depth.end(), [](float d) { return d >= 0.0f && d < 0.375f; });
  EXPECT_EQ(uncovered, 0);

  int64_t expected = 0, wrong = 0;
  for (size_t t = 0; t < outlines.size(); ++t) {
    const Point& p = anchors[t];
    for (int64_t y = static_cast<int64_t>(p.y) - 4; y <= static_cast<int64_t>(p.y) + 4; ++y) {
      for (int64_t x = static_cast<int64_t>(p.x) - 4; x <= static_cast<int64_t>(p.x) + 4; ++x) {
        if (x < 0 || y < 0 || x >= desc.width || y >= desc.height) continue;
        const bool want = test::polygon_covers(
            outlines[t], {static_cast<double>(x) + 0.5, static_cast<double>(y) + 0.5});
        const float d = depth[static_cast<size_t>(y) * desc.width + static_cast<size_t>(x)];
        expected += want ? 1 : 0;
        wrong += want != (d >= 0.0f && d < 0.375f) ? 1 : 0;
      }
    }
  }
  EXPECT_GT(expected, 10);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(near, expected) << "samples nearer than the big triangles away from the small ones";
  EXPECT_EQ(renderer.counters().samples_covered, n + static_cast<uint64_t>(expected));
  EXPECT_EQ(renderer.counters().triangles_clipped, 2u);
}

}  // namespace tessera::extremes
