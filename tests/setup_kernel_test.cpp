// The vectorized setup's instances, one per compiled Highway target, against each other: every
// instance this machine runs, the one-lane HWY_SCALAR instance (which sizeless-vector targets
// such as SVE use) included, must write the same setups, pixel and sample records, bins and
// counters, byte for byte (a record's pixels: see same_pixels). The renderer's own tests reach
// only the best instance of each target family; HWY_SCALAR is reached here alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <hwy/targets.h>

#include "binning/bins.hpp"
#include "engine/src/fast/setup_kernel.hpp"
#include "engine/src/sample_positions.hpp"
#include "simd/target_list.hpp"

namespace tessera::fast {
namespace {

constexpr uint32_t kWidth = 136, kHeight = 72;  // three bin tiles across, two down
constexpr float kWidthF = 136.0f, kHeightF = 72.0f;
constexpr uint32_t kTileLog2 = 6;

// Random triangles in clip space: half tiny (about 0.5 to 4 px), the rest up to about 600 px,
// some with w varying per vertex, and a few crossing the near plane (the scalar clipper's).
struct Draw {
  std::vector<Float4> positions;
  std::vector<float> colors;
};

// With `wide_w`, every vertex's w lies anywhere from 2^-24 to 2^24 with a random significand
// instead, so that x / w, y / w and z / w take every kind of rounding, and none is clipped.
Draw random_draw(uint32_t seed, int count, bool wide_w = false) {
  Draw d;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < count; ++i) {
    const float side = i % 2 ? 1.0f + 2.0f * u(rng) : 1.0f + 40.0f * u(rng) * u(rng);
    const float cx = (u(rng) * 1.2f - 0.1f) * kWidthF, cy = (u(rng) * 1.2f - 0.1f) * kHeightF;
    const float rot = u(rng) * 2.0f * std::numbers::pi_v<float>;
    const bool perspective = i % 3 == 0;
    for (int k = 0; k < 3; ++k) {
      const float a = rot + static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / 3.0f +
                      (u(rng) - 0.5f) * 0.7f;
      const float x = cx + side / std::sqrt(3.0f) * std::cos(a);
      const float y = cy + side / std::sqrt(3.0f) * std::sin(a);
      float w = perspective ? 0.25f + 4.0f * u(rng) : 1.0f;
      if (wide_w) w = std::ldexp(1.0f + u(rng), static_cast<int>(u(rng) * 48.0f) - 24);
      // Every 50th triangle has a vertex behind the near plane (z / w < -1).
      const float z = i % 50 == 0 && k == 0 && !wide_w ? -2.0f : u(rng);
      d.positions.push_back(
          {(2.0f * x / kWidthF - 1.0f) * w, (1.0f - 2.0f * y / kHeightF) * w, z * w, w});
      // Every fifth triangle's colours reach beyond [0, 1] (TriangleSetup::unit_colour 0).
      for (int c = 0; c < 4; ++c)
        d.colors.push_back(i % 5 == 0 ? 1.5f * u(rng) - 0.25f : u(rng));
    }
  }
  return d;
}

// Thin triangles about three pixels tall and one or two wide (boxes of up to 3x4 pixels with
// the samples' reach), w varying per vertex, appended to `d`.
void add_tall_triangles(Draw& d, uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < count; ++i) {
    const float cx = u(rng) * kWidthF, cy = u(rng) * kHeightF;
    const float height = 2.4f + 1.0f * u(rng), width = 0.4f + 1.6f * u(rng);
    const float ys[3] = {cy - 0.5f * height, cy + (u(rng) - 0.5f) * height, cy + 0.5f * height};
    for (int k = 0; k < 3; ++k) {
      const float x = cx + (u(rng) - 0.5f) * width, w = 0.25f + 4.0f * u(rng);
      d.positions.push_back(
          {(2.0f * x / kWidthF - 1.0f) * w, (1.0f - 2.0f * ys[k] / kHeightF) * w, u(rng) * w, w});
      for (int c = 0; c < 4; ++c)
        d.colors.push_back(u(rng));
    }
  }
}

// The context of a draw of kWidth x kHeight with four colour values per vertex.
SetupContext draw_context(const PipelineState& pipeline, uint32_t samples, bool records) {
  SetupContext ctx;
  ctx.width = kWidth;
  ctx.height = kHeight;
  ctx.subpixel_bits = 8;
  ctx.attribute_count = 4;
  ctx.pipeline = &pipeline;
  ctx.guard_band = GuardBand::for_viewport(kWidth, kHeight);
  ctx.bin_tile_log2 = kTileLog2;
  ctx.set_sample_pattern(sample_pattern(samples));
  ctx.pixel_records = records && samples == 1;
  ctx.sample_records = records && samples > 1;
  return ctx;
}

struct Output {
  SetupList setups;
  PixelList pixels;
  SampleList samples;
  binning::Bins bins;
  Counters counters;
};

Output set_up(SetupRangeFn setup, const SetupContext& ctx, const DrawInput& input,
              size_t triangles) {
  Output out;
  const uint32_t tiles_x = (kWidth + 63) >> kTileLog2, tiles_y = (kHeight + 63) >> kTileLog2;
  out.bins.reset(tiles_x * tiles_y, tiles_x);
  // In batches, as the renderer calls it.
  for (size_t t = 0; t < triangles; t += 256)
    EXPECT_TRUE(setup(ctx, input, t, std::min(triangles, t + 256), out.setups, out.pixels,
                      out.samples, out.bins, out.counters));
  out.bins.place();
  return out;
}

bool same_bytes(const SetupList& a, const SetupList& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// Records hold up to three or four pixels; the slots past a record's pixel count are never
// read, and hold whatever its vector computed there for other lanes (so they depend on the
// vector width). The pixels a record holds must be the same bytes.
bool same_pixels(const PixelRecord& a, const PixelRecord& b) {
  const uint32_t n = a.pixels();
  bool same = a.x0 == b.x0 && a.y0 == b.y0 && a.shape == b.shape;
  for (uint32_t i = 0; i < n; ++i) {
    same = same && a.offset[i] == b.offset[i] &&
           std::memcmp(&a.z[i], &b.z[i], sizeof(float)) == 0 && a.rgba8[i] == b.rgba8[i];
  }
  return same;
}

bool same_pixels(const SampleRecord& a, const SampleRecord& b) {
  const uint32_t n = a.pixels();
  const uint32_t nibbles = (1u << (4 * n)) - 1;
  bool same = a.x0 == b.x0 && a.y0 == b.y0 &&
              (a.shape_places & 0xFFu) == (b.shape_places & 0xFFu) &&
              ((a.shape_places >> 8) & nibbles) == ((b.shape_places >> 8) & nibbles) &&
              (a.coverage & nibbles) == (b.coverage & nibbles) &&
              std::memcmp(&a.z_dx, &b.z_dx, sizeof(float)) == 0 &&
              std::memcmp(&a.z_dy, &b.z_dy, sizeof(float)) == 0;
  for (uint32_t i = 0; i < n; ++i) {
    same = same && std::memcmp(&a.z_base[i], &b.z_base[i], sizeof(float)) == 0 &&
           a.rgba8[i] == b.rgba8[i];
  }
  return same;
}

template <class List>
size_t first_difference(const List& a, const List& b) {
  if (a.size() != b.size()) return 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (!same_pixels(a[i], b[i])) return i;
  return a.size();
}

// The compiled targets this machine runs, HWY_SCALAR among them.
std::vector<int64_t> runnable_targets() {
  std::vector<int64_t> targets;
#define TESSERA_ADD_TARGET(bit, ns) targets.push_back(bit);
  TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_ADD_TARGET)
#undef TESSERA_ADD_TARGET
  std::erase_if(targets, [](int64_t bit) { return (hwy::SupportedTargets() & bit) == 0; });
  return targets;
}

// Sets `draw` up with every compiled target this machine runs, at 1, 2 and 4 samples, with and
// without records, and expects the same bytes from each as from the first. With
// `expect_clipped`, the draw must have triangles the scalar clipper takes.
void expect_same_bytes_on_every_target(const Draw& draw, bool expect_clipped) {
  const std::vector<int64_t> targets = runnable_targets();
  ASSERT_NE(std::find(targets.begin(), targets.end(), int64_t{HWY_SCALAR}), targets.end())
      << "HWY_SCALAR is not compiled into this build";
  ASSERT_GE(targets.size(), 2u);

  DrawInput input;
  input.positions = draw.positions;
  input.attributes = draw.colors;
  input.attribute_count = 4;
  const size_t triangles = draw.positions.size() / 3;
  PipelineState pipeline;
  for (uint32_t samples : {1u, 2u, 4u}) {
    for (bool records : {false, true}) {
      SCOPED_TRACE(std::to_string(samples) + " samples, records " + (records ? "on" : "off"));
      const SetupContext ctx = draw_context(pipeline, samples, records);
      const Output first = set_up(setup_kernel(targets[0]), ctx, input, triangles);
      // The draw exercises what it should: clipped triangles, setups and records.
      if (expect_clipped) {
        EXPECT_GT(first.counters.triangles_clipped, 0u);
      }
      EXPECT_GT(first.setups.size(), 1000u);
      if (records) {
        EXPECT_GT(first.pixels.size() + first.samples.size(), 1000u);
      }
      for (size_t i = 1; i < targets.size(); ++i) {
        SCOPED_TRACE(hwy::TargetName(targets[i]) + std::string(" against ") +
                     hwy::TargetName(targets[0]));
        const Output other = set_up(setup_kernel(targets[i]), ctx, input, triangles);
        EXPECT_TRUE(same_bytes(other.setups, first.setups));
        EXPECT_EQ(first_difference(other.pixels, first.pixels), first.pixels.size());
        EXPECT_EQ(first_difference(other.samples, first.samples), first.samples.size());
        EXPECT_EQ(other.bins.references(), first.bins.references());
        for (uint32_t tile = 0; tile < 6; ++tile) {
          const auto a = other.bins.tile(tile), b = first.bins.tile(tile);
          EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "tile " << tile;
        }
        EXPECT_EQ(other.counters.triangles_submitted, first.counters.triangles_submitted);
        EXPECT_EQ(other.counters.triangles_culled, first.counters.triangles_culled);
        EXPECT_EQ(other.counters.triangles_clipped, first.counters.triangles_clipped);
        EXPECT_EQ(other.counters.triangles_rasterized, first.counters.triangles_rasterized);
      }
    }
  }
}

TEST(SetupKernel, EveryCompiledTargetWritesTheSameBytes) {
  expect_same_bytes_on_every_target(random_draw(4242, 6000), true);
}

// Sample records of boxes four pixels high: made on every target alike (with the rest of
// random_draw), and common among thin triangles three pixels tall.
TEST(SetupKernel, FourRowBoxesBecomeSampleRecords) {
  Draw draw = random_draw(4343, 4000);
  add_tall_triangles(draw, 4444, 4000);
  expect_same_bytes_on_every_target(draw, true);

  DrawInput input;
  input.positions = draw.positions;
  input.attributes = draw.colors;
  input.attribute_count = 4;
  PipelineState pipeline;
  for (uint32_t samples : {2u, 4u}) {
    SCOPED_TRACE(std::to_string(samples) + " samples");
    const SetupContext ctx = draw_context(pipeline, samples, true);
    const Output out = set_up(setup_kernel(hwy::SupportedTargets() & -hwy::SupportedTargets()), ctx,
                              input, draw.positions.size() / 3);
    size_t four_rows = 0;
    for (const SampleRecord& r : out.samples) {
      const uint32_t height = static_cast<uint32_t>(r.last_y()) + 1;
      four_rows += height == 4;
      // Every pixel a record holds lies in its box.
      for (uint32_t i = 0; i < r.pixels(); ++i) {
        const uint32_t place = r.place(i);
        EXPECT_LE(place & 3u, static_cast<uint32_t>(r.last_x()));
        EXPECT_LT(place >> 2, height);
        EXPECT_NE(r.samples(i), 0u);
      }
    }
    EXPECT_GT(four_rows, 500u);
  }
}

// Small triangles at w = 1 (flat q) in window pixels, about 4 to 7 pixels across, placed well
// inside the screen; `colour(i, k, c)` gives triangle i's vertex k's channel c, and `width` (1
// for the usual shape) scales the triangles in x.
template <class Colour>
Draw small_flat_draw(uint32_t seed, int count, float width, Colour colour) {
  Draw d;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < count; ++i) {
    const float cx = 10.0f + u(rng) * (kWidthF - 20.0f), cy = 10.0f + u(rng) * (kHeightF - 20.0f);
    const float side = 4.0f + 3.0f * u(rng);
    const float xs[3] = {cx - 0.5f * side * width, cx + 0.5f * side * width,
                         cx + (u(rng) - 0.5f) * side * width};
    const float ys[3] = {cy - 0.4f * side, cy - 0.3f * side, cy + 0.5f * side};
    for (int k = 0; k < 3; ++k) {
      d.positions.push_back(
          {2.0f * xs[k] / kWidthF - 1.0f, 1.0f - 2.0f * ys[k] / kHeightF, 0.5f, 1.0f});
      for (int c = 0; c < 4; ++c)
        d.colors.push_back(colour(i, k, c));
    }
  }
  return d;
}

// TriangleSetup::unit_colour on every target: 1 for flat-q triangles whose vertices' channels
// lie in [0, 1] and whose largest gradient times the box's reach is at most kUnitColourReach, at
// one sample only; 0 when a channel reaches beyond [0, 1], when a gradient is steeper, when q
// is not flat.
TEST(SetupKernel, UnitColourMarksFlatTrianglesWithColoursInTheUnitRange) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> values(4000 * 12);
  for (float& v : values)
    v = u(rng);
  const auto in_unit = [&](int i, int k, int c) {
    return c == 3 && i % 2 ? 1.0f : values[static_cast<size_t>((i * 3 + k) * 4 + c)];
  };
  // One channel of one vertex just past 0 or 1.
  const auto beyond = [&](int i, int k, int c) {
    if (k == i % 3 && c == i % 4) return i % 2 ? 1.0f + 1.0f / 1024.0f : -1.0f / 1024.0f;
    return in_unit(i, k, c);
  };
  // 0 and 1 across triangles 1/256 as wide: gradients of about 40 to 64 per pixel, against a
  // reach of about 20.
  const auto steep = [&](int, int k, int c) { return c == 0 && k == 1 ? 1.0f : 0.0f; };
  struct Case {
    const char* name;
    Draw draw;
    bool expected;
  };
  Case cases[] = {{"in [0, 1]", small_flat_draw(1, 4000, 1.0f, in_unit), true},
                  {"beyond [0, 1]", small_flat_draw(2, 4000, 1.0f, beyond), false},
                  {"steep", small_flat_draw(3, 12000, 1.0f / 256.0f, steep), false}};
  PipelineState pipeline;
  for (const Case& c : cases) {
    DrawInput input;
    input.positions = c.draw.positions;
    input.attributes = c.draw.colors;
    input.attribute_count = 4;
    for (const int64_t target : runnable_targets()) {
      for (uint32_t samples : {1u, 4u}) {
        SCOPED_TRACE(std::string(c.name) + ", " + hwy::TargetName(target) + ", " +
                     std::to_string(samples) + " samples");
        const Output out = set_up(setup_kernel(target), draw_context(pipeline, samples, false),
                                  input, c.draw.positions.size() / 3);
        EXPECT_GT(out.setups.size(), 100u);
        size_t flagged = 0;
        for (const TriangleSetup& t : out.setups)
          flagged += t.unit_colour;
        EXPECT_EQ(flagged, c.expected && samples == 1 ? out.setups.size() : 0u);
      }
    }
  }
  // Not flat: w varies per vertex under perspective interpolation.
  Draw perspective = small_flat_draw(4, 4000, 1.0f, in_unit);
  for (size_t v = 0; v < perspective.positions.size(); ++v) {
    const float w = 1.0f + static_cast<float>(v % 3);
    Float4& p = perspective.positions[v];
    p = {p.x * w, p.y * w, p.z * w, w};
  }
  DrawInput input;
  input.positions = perspective.positions;
  input.attributes = perspective.colors;
  input.attribute_count = 4;
  const Output out = set_up(setup_kernel(hwy::SupportedTargets() & -hwy::SupportedTargets()),
                            draw_context(pipeline, 1, false), input, 4000);
  EXPECT_GT(out.setups.size(), 100u);
  for (const TriangleSetup& t : out.setups)
    EXPECT_EQ(t.unit_colour, 0u);
}

// Targets with a fused multiply-add divide by w once per vertex and correct the products
// (setup_kernel.cpp's quotient); the others divide. Both must give the same bits.
TEST(SetupKernel, EveryCompiledTargetWritesTheSameBytesForWOverManyOctaves) {
  expect_same_bytes_on_every_target(random_draw(777, 8000, true), false);
}

}  // namespace
}  // namespace tessera::fast
