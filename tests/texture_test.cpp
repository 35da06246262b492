// Textures and samplers (tessera/texture.hpp): mip chains by the stated box filter, every wrap
// mode and filter against hand-computed texels, the level of detail of OpenGL 4.6 section
// 8.14, sRGB decoding, the float sampler against the double reference on random coordinates,
// defined results for NaN, infinite and huge coordinates, errors for bad textures, and
// sampling from a user fragment shader on both backends.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "engine/src/reference/reference_sampler.hpp"
#include "engine/src/texture/sample_batch.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace tessera {
namespace {

std::span<const std::byte> bytes_of(const std::vector<uint8_t>& v) {
  return std::as_bytes(std::span(v));
}
std::span<const std::byte> bytes_of(const std::vector<float>& v) {
  return std::as_bytes(std::span(v));
}

// A w x h RGBA8 texture whose texel (x, y) is (x * 10 + 1, y * 10 + 2, x + y, 255 - x).
std::vector<uint8_t> ramp(uint32_t w, uint32_t h) {
  std::vector<uint8_t> p;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      p.push_back(static_cast<uint8_t>(x * 10 + 1));
      p.push_back(static_cast<uint8_t>(y * 10 + 2));
      p.push_back(static_cast<uint8_t>(x + y));
      p.push_back(static_cast<uint8_t>(255 - x));
    }
  }
  return p;
}

std::array<float, 4> unorm(int r, int g, int b, int a) {
  return {float(r) / 255.0f, float(g) / 255.0f, float(b) / 255.0f, float(a) / 255.0f};
}

TEST(Texture, MipChainSizesAndBoxFilterFollowTheStatedRule) {
  // 5x3: levels 5x3, 2x1, 1x1. Level 1's texel (x, 0) averages (2x..2x+1, 0..1) of level 0.
  const std::vector<uint8_t> p = ramp(5, 3);
  const Texture t({5, 3, TextureFormat::kRGBA8}, bytes_of(p), true);
  ASSERT_EQ(t.levels(), 3u);
  EXPECT_EQ(t.width(1), 2u);
  EXPECT_EQ(t.height(1), 1u);
  EXPECT_EQ(t.width(2), 1u);
  EXPECT_EQ(t.height(2), 1u);
  // Level 1 texel 1: level 0 texels x 2..3, y 0..1: R (21 + 31 + 21 + 31 + 2) / 4 = 26,
  // G (2 + 2 + 12 + 12 + 2) / 4 = 7, B (2 + 3 + 3 + 4 + 2) / 4 = 3, A (253 + 252 + 253 + 252 +
  // 2) / 4 = 253 (the mean 252.5 rounded up).
  EXPECT_EQ(t.texel(1, 1, 0), unorm(26, 7, 3, 253));
  // Level 2 (1x1) from level 1 (2x1): the row counted twice. Level 1 texel 0 is
  // R (1 + 11 + 1 + 11 + 2) / 4 = 6, G 7, B (0 + 1 + 1 + 2 + 2) / 4 = 1, A (255 + 254 + 255 +
  // 254 + 2) / 4 = 255; texel 1 as above; the mean R (6 + 26 + 6 + 26 + 2) / 4 = 16.
  EXPECT_EQ(t.texel(1, 0, 0), unorm(6, 7, 1, 255));
  EXPECT_EQ(t.texel(2, 0, 0), unorm(16, 7, 2, 254));
  // Without mipmaps: one level.
  EXPECT_EQ(Texture({5, 3, TextureFormat::kRGBA8}, bytes_of(p), false).levels(), 1u);
  // 16384 x 1: 15 levels down to 1x1.
  const std::vector<float> wide(16384, 0.5f);
  const Texture w({16384, 1, TextureFormat::kR32F}, bytes_of(wide), true);
  EXPECT_EQ(w.levels(), 15u);
  EXPECT_EQ(w.texel(14, 0, 0), (std::array<float, 4>{0.5f, 0, 0, 1}));
}

TEST(Texture, SrgbTexelsAreDecodedAndAveragedInLinearSpace) {
  // sRGB 188 is linear 0.50289...; 0 and 255 average to linear 0.5, which encodes as 188.
  const std::vector<uint8_t> p = {188, 188, 188, 128, 0, 0, 0, 0, 255, 255, 255, 255};
  const Texture t({3, 1, TextureFormat::kRGBA8Srgb}, bytes_of(p), true);
  const double linear = std::pow((188 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_EQ(t.texel(0, 0, 0)[0], static_cast<float>(linear));
  EXPECT_EQ(t.texel(0, 0, 0)[3], 128 / 255.0f);  // alpha is linear
  // Level 1 (1x1): texels 0 and 1 (linear 0.50289 and 0) averaged twice: 0.2514, sRGB 137.
  const std::vector<uint8_t> q = {0, 0, 0, 0, 255, 255, 255, 255};
  const Texture u({2, 1, TextureFormat::kRGBA8Srgb}, bytes_of(q), true);
  EXPECT_EQ(std::to_integer<int>(u.level_bytes(1)[0]), 188);
  EXPECT_EQ(std::to_integer<int>(u.level_bytes(1)[3]), 128);  // alpha (0 + 255 + 0 + 255 + 2)/4
}

TEST(Texture, NearestSamplesTheTexelHoldingThePointUnderEveryWrapMode) {
  const std::vector<uint8_t> p = ramp(3, 2);
  const Texture t({3, 2, TextureFormat::kRGBA8}, bytes_of(p), false);
  Sampler s;
  s.mag_filter = s.min_filter = Filter::kNearest;
  s.border_color = {0.25f, 0.5f, 0.75f, 1.0f};
  const auto at = [&](Wrap wrap, float u, float v) {
    s.wrap_u = s.wrap_v = wrap;
    return sample(t, s, u, v, 0.0f);
  };
  const auto texel = [&](uint32_t x, uint32_t y) { return t.texel(0, x, y); };
  // Inside: texel (1, 1) holds u in [1/3, 2/3), v in [1/2, 1).
  EXPECT_EQ(at(Wrap::kRepeat, 0.5f, 0.75f), texel(1, 1));
  // u = -0.1 is texel -1 (u w = -0.3); v = 1.2 is texel 2 (v h = 2.4).
  EXPECT_EQ(at(Wrap::kRepeat, -0.1f, 1.2f), texel(2, 0));
  EXPECT_EQ(at(Wrap::kClampToEdge, -0.1f, 1.2f), texel(0, 1));
  EXPECT_EQ(at(Wrap::kMirroredRepeat, -0.1f, 1.2f), texel(0, 1));  // -1 -> 0, 2 -> 1
  EXPECT_EQ(at(Wrap::kMirroredRepeat, 1.5f, 2.6f), texel(1, 1));   // x 4 -> 1; y 5 -> 1
  EXPECT_EQ(at(Wrap::kClampToBorder, -0.1f, 0.5f), (std::array<float, 4>{0.25f, 0.5f, 0.75f, 1}));
  EXPECT_EQ(at(Wrap::kClampToBorder, 0.9f, 0.9f), texel(2, 1));
}

TEST(Texture, LinearWeighsTheFourTexelsAroundThePoint) {
  const std::vector<float> p = {0, 1, 2, 3};  // 2x2 R32F
  const Texture t({2, 2, TextureFormat::kR32F}, bytes_of(p), false);
  Sampler s;
  s.wrap_u = s.wrap_v = Wrap::kClampToEdge;
  // (u w - 1/2, v h - 1/2) = (0.25, 0.5): 0.75 * 0.5 * 0 + 0.25 * 0.5 * 1 + 0.75 * 0.5 * 2 +
  // 0.25 * 0.5 * 3 = 1.25.
  EXPECT_FLOAT_EQ(sample(t, s, 0.375f, 0.5f, 0.0f)[0], 1.25f);
  // Repeat: at u = 0 the left neighbour is the last column.
  s.wrap_u = Wrap::kRepeat;
  // (u w - 1/2) = -0.5: texels -1 (= 1) and 0 with weights 1/2; v at texel row 0's centre.
  EXPECT_FLOAT_EQ(sample(t, s, 0.0f, 0.25f, 0.0f)[0], 0.5f);
}

TEST(Texture, LevelOfDetailFollowsTheSpecification) {
  const std::vector<uint8_t> p(64 * 32 * 4, 0);
  const Texture t({64, 32, TextureFormat::kRGBA8}, bytes_of(p), true);
  Sampler s;
  // du/dx = 4/64: 4 texels per pixel in x; dv/dy = 2/32: 2 texels in y. rho = 4, lambda = 2.
  EXPECT_FLOAT_EQ(texture_lod(t, s, 4.0f / 64, 0, 0, 2.0f / 32), 2.0f);
  // The longer axis of a rotated footprint: (3, 4) texels in x is 5.
  EXPECT_FLOAT_EQ(texture_lod(t, s, 3.0f / 64, 4.0f / 32, 0, 0), std::log2(5.0f));
  s.lod_bias = 0.5f;
  s.max_lod = 2.25f;
  EXPECT_FLOAT_EQ(texture_lod(t, s, 4.0f / 64, 0, 0, 0), 2.25f);
  s = {};
  s.min_lod = -2;
  EXPECT_FLOAT_EQ(texture_lod(t, s, 0, 0, 0, 0), -2.0f);  // no change: magnified
}

TEST(Texture, MipFiltersPickAndBlendTheLevelsTheLodSays) {
  // An R32F 8x8 texture whose levels are set by hand to constants 0, 10, 20, 30.
  std::vector<float> p(64, 0.0f);
  Texture t({8, 8, TextureFormat::kR32F}, bytes_of(p), true);
  ASSERT_EQ(t.levels(), 4u);
  for (uint32_t l = 1; l < 4; ++l) {
    const std::vector<float> level(size_t{t.width(l)} * t.height(l), 10.0f * float(l));
    t.set_level(l, bytes_of(level));
  }
  Sampler s;
  s.mip_filter = MipFilter::kNearest;
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 0.5f)[0], 0.0f);    // up to 1/2: level 0
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 0.51f)[0], 10.0f);  // ceil(1.01) - 1 = 1
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 1.5f)[0], 10.0f);   // ceil(2) - 1 = 1
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 1.6f)[0], 20.0f);
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 9.0f)[0], 30.0f);  // past the chain: the last level
  s.mip_filter = MipFilter::kLinear;
  EXPECT_FLOAT_EQ(sample(t, s, 0.3f, 0.6f, 1.25f)[0], 12.5f);
  EXPECT_FLOAT_EQ(sample(t, s, 0.3f, 0.6f, 2.5f)[0], 25.0f);
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 3.5f)[0], 30.0f);
  s.mip_filter = MipFilter::kNone;
  EXPECT_EQ(sample(t, s, 0.3f, 0.6f, 2.5f)[0], 0.0f);
}

TEST(Texture, TheFloatSamplerMatchesTheDoubleReference) {
  // A non-power-of-two RGBA8 texture of noise, every filter and wrap mode, random coordinates
  // over [-3, 4] and footprints from magnified to past the chain.
  std::mt19937 rng(7);
  std::vector<uint8_t> p(37 * 23 * 4);
  for (uint8_t& b : p)
    b = static_cast<uint8_t>(rng());
  const Texture t({37, 23, TextureFormat::kRGBA8}, bytes_of(p), true);
  std::uniform_real_distribution<float> coord(-3.0f, 4.0f), scale(-6.0f, 6.0f);
  int near_edges = 0, checked = 0;
  for (Filter filter : {Filter::kNearest, Filter::kLinear}) {
    for (MipFilter mip : {MipFilter::kNone, MipFilter::kNearest, MipFilter::kLinear}) {
      for (Wrap wrap :
           {Wrap::kRepeat, Wrap::kClampToEdge, Wrap::kMirroredRepeat, Wrap::kClampToBorder}) {
        Sampler s;
        s.mag_filter = s.min_filter = filter;
        s.mip_filter = mip;
        s.wrap_u = s.wrap_v = wrap;
        s.border_color = {0.1f, 0.2f, 0.3f, 0.4f};
        for (int k = 0; k < 2000; ++k) {
          const float u = coord(rng), v = coord(rng);
          const float d = std::exp2(scale(rng)) / 37.0f;
          const float lod = texture_lod(t, s, d, 0.3f * d, -0.2f * d, d);
          const double want_lod = reference::texture_lod(t, s, d, 0.3 * d, -0.2 * d, d);
          ASSERT_NEAR(lod, want_lod, 1e-5) << k;
          const auto got = sample(t, s, u, v, lod);
          const auto want = reference::sample(t, s, u, v, want_lod);
          // Nearest: the same texel, unless the point lies within 1e-5 texel of a texel edge
          // or the LOD within 1e-5 of a level switch, where float and double may round apart.
          bool edge = false;
          for (uint32_t l = 0; l < t.levels(); ++l) {
            for (double x : {double(u) * t.width(l), double(v) * t.height(l)}) {
              const double f = x - std::floor(x);
              edge |=
                  filter == Filter::kNearest ? std::min(f, 1 - f) < 1e-5 : std::abs(f - 0.5) < 1e-5;
            }
          }
          edge |= std::abs(want_lod - std::round(want_lod)) < 1e-5 ||
                  std::abs(want_lod - 0.5 - std::round(want_lod - 0.5)) < 1e-5;
          ++checked;
          if (edge) {
            ++near_edges;
            continue;
          }
          for (int c = 0; c < 4; ++c) {
            // Linear: the fraction of a position of up to 150 texels, rounded to float.
            ASSERT_LE(std::abs(got[c] - want[c]), filter == Filter::kNearest ? 1e-7 : 1e-4)
                << "filter " << int(filter) << ", mip " << int(mip) << ", wrap " << int(wrap)
                << " at (" << u << ", " << v << ") lod " << lod;
          }
        }
      }
    }
  }
  // Those near an edge are rare.
  EXPECT_LT(near_edges, checked / 100);
}

// One-texel stripes across v (white rows at even y, black at odd) under a footprint 8 texels
// long in u (or, transposed, in v) and 1 texel across: the isotropic LOD, log2 8 = 3, reads a
// level where the stripes have averaged to grey; 8 anisotropic samples read level 0, where the
// point on a white row's centre stays white. Fewer allowed samples give lambda = log2(8 / N):
// grey down to level 1. More than the footprint's ratio take only 8 (ceil(8 / 1)).
TEST(Texture, AnisotropicFilteringSamplesAlongTheLongerAxisAtTheShorterAxissLevel) {
  for (bool transposed : {false, true}) {
    std::vector<uint8_t> p;
    for (uint32_t y = 0; y < 64; ++y) {
      for (uint32_t x = 0; x < 64; ++x) {
        const uint8_t c = ((transposed ? x : y) % 2 == 0) ? 255 : 0;
        p.insert(p.end(), {c, c, c, 255});
      }
    }
    const Texture t({64, 64, TextureFormat::kRGBA8}, bytes_of(p), true);
    Sampler s;  // trilinear, repeat
    // (u, v) on white texel (21, 10)'s centre; 8 texels per pixel step along the stripes.
    float u = 21.5f / 64, v = 10.5f / 64;
    float du_dx = 8.0f / 64, dv_dx = 0, du_dy = 0, dv_dy = 1.0f / 64;
    if (transposed) {
      std::swap(u, v);
      std::swap(du_dx, dv_dx);
      std::swap(du_dy, dv_dy);
    }
    const auto red = [&](float max_anisotropy) {
      s.max_anisotropy = max_anisotropy;
      return sample(t, s, u, v, du_dx, dv_dx, du_dy, dv_dy)[0];
    };
    const float grey = 128.0f / 255;              // 8-bit means round 127.5 up
    EXPECT_FLOAT_EQ(red(1), grey) << transposed;  // level 3
    EXPECT_FLOAT_EQ(red(2), grey) << transposed;  // level 2
    EXPECT_FLOAT_EQ(red(4), grey) << transposed;  // level 1
    EXPECT_FLOAT_EQ(red(8), 1.0f) << transposed;  // level 0, every sample on the white row
    EXPECT_FLOAT_EQ(red(8.9f), 1.0f) << transposed;
    EXPECT_FLOAT_EQ(red(16), 1.0f) << transposed;
    // max_anisotropy 1 is the isotropic sample at texture_lod.
    s.max_anisotropy = 1;
    EXPECT_EQ(sample(t, s, u, v, du_dx, dv_dx, du_dy, dv_dy),
              sample(t, s, u, v, texture_lod(t, s, du_dx, dv_dx, du_dy, dv_dy)));
  }
  // The samples spread along the longer axis: across a black/white edge in u (level 0 only,
  // nearest), 4 samples at offsets -0.3, -0.1, 0.1, 0.3 of 10 texels: two on each side.
  std::vector<uint8_t> half;
  for (uint32_t y = 0; y < 16; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      const uint8_t c = x < 32 ? 0 : 255;
      half.insert(half.end(), {c, c, c, 255});
    }
  }
  const Texture edge({64, 16, TextureFormat::kRGBA8}, bytes_of(half), false);
  Sampler s;
  s.mag_filter = s.min_filter = Filter::kNearest;
  s.mip_filter = MipFilter::kNone;
  s.max_anisotropy = 4;
  EXPECT_FLOAT_EQ(sample(edge, s, 32.0f / 64, 0.5f, 10.0f / 64, 0, 0, 2.5f / 16)[0], 0.5f);
  EXPECT_FLOAT_EQ(sample(edge, s, 34.5f / 64, 0.5f, 10.0f / 64, 0, 0, 2.5f / 16)[0], 0.75f);
}

// The anisotropic float sampler against the double reference: random footprints stretched up to
// 40:1 in any direction, linear filters (within 1e-4) and nearest ones (the same texel but where
// a sample point lies near a texel edge or the LOD near a level switch: counted, rare).
TEST(Texture, TheAnisotropicFloatSamplerMatchesTheDoubleReference) {
  std::mt19937 rng(17);
  std::vector<uint8_t> p(64 * 32 * 4);
  for (uint8_t& b : p)
    b = static_cast<uint8_t>(rng());
  const Texture t({64, 32, TextureFormat::kRGBA8}, bytes_of(p), true);
  std::uniform_real_distribution<float> coord(-2.0f, 3.0f), scale(-5.0f, 5.0f), ratio(0.0f, 5.3f),
      angle(0.0f, 6.2831853f);
  int differing = 0, checked = 0;
  for (Filter filter : {Filter::kNearest, Filter::kLinear}) {
    for (MipFilter mip : {MipFilter::kNone, MipFilter::kNearest, MipFilter::kLinear}) {
      for (float max_anisotropy : {2.0f, 5.5f, 16.0f}) {
        Sampler s;
        s.mag_filter = s.min_filter = filter;
        s.mip_filter = mip;
        s.wrap_u = Wrap::kRepeat;
        s.wrap_v = Wrap::kClampToBorder;
        s.border_color = {0.1f, 0.2f, 0.3f, 0.4f};
        s.max_anisotropy = max_anisotropy;
        for (int k = 0; k < 1000; ++k) {
          const float u = coord(rng), v = coord(rng);
          // Axes of lengths l and l / 2^r texels at angle a and a + 90 degrees.
          const float l = std::exp2(scale(rng)), r = std::exp2(-ratio(rng)), a = angle(rng);
          const float du_dx = l * std::cos(a) / 64, dv_dx = l * std::sin(a) / 32;
          const float du_dy = -l * r * std::sin(a) / 64, dv_dy = l * r * std::cos(a) / 32;
          const auto got = sample(t, s, u, v, du_dx, dv_dx, du_dy, dv_dy);
          const auto want = reference::sample(t, s, u, v, du_dx, dv_dx, du_dy, dv_dy);
          ++checked;
          float worst = 0;
          for (int c = 0; c < 4; ++c)
            worst = std::max(worst, static_cast<float>(std::abs(got[c] - want[c])));
          if (filter == Filter::kLinear && mip != MipFilter::kNearest) {
            ASSERT_LE(worst, 1e-4f) << "mip " << int(mip) << ", anisotropy " << max_anisotropy
                                    << " at (" << u << ", " << v << ")";
          } else {
            differing += worst > 1e-4f;
          }
        }
      }
    }
  }
  EXPECT_LT(differing, checked / 100);
  std::printf("%d of %d nearest samples differ from the reference\n", differing, checked);
}

TEST(Texture, TheBatchSamplerGivesTheScalarSamplersBitsOnEveryTarget) {
  // Power-of-two RGBA8 and sRGB textures (sampled in lanes), a non-power-of-two one (in lanes
  // when clamped, fragment by fragment when repeated or mirrored) and a float one (fragment by
  // fragment); batches of quads sharing derivatives from magnified to past the chain, stretched
  // up to 45:1 in any direction (some empty, infinite or NaN), with NaN, infinite and huge
  // coordinates among them; every filter pairing, mip filter and wrap, isotropic and with up to
  // 3 and 16 anisotropic samples.
  std::mt19937 rng(11);
  const auto noise = [&](size_t n) {
    std::vector<uint8_t> p(n);
    for (uint8_t& b : p)
      b = static_cast<uint8_t>(rng());
    return p;
  };
  std::vector<float> f(16 * 8 * 4);
  for (float& x : f)
    x = static_cast<float>(rng() % 1000) / 250.0f - 1.0f;
  const Texture textures[] = {
      Texture({64, 32, TextureFormat::kRGBA8}, bytes_of(noise(64 * 32 * 4)), true),
      Texture({32, 64, TextureFormat::kRGBA8Srgb}, bytes_of(noise(32 * 64 * 4)), true),
      Texture({37, 23, TextureFormat::kRGBA8}, bytes_of(noise(37 * 23 * 4)), true),
      Texture({16, 8, TextureFormat::kRGBA32F}, bytes_of(f), true)};
  constexpr uint32_t kStride = kFragmentBatchStride;
  std::uniform_real_distribution<float> coord(-3.0f, 4.0f), scale(-7.0f, 7.0f), ratio(0.0f, 5.5f),
      angle(0.0f, 6.2831853f);
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(),
                            1e7f,
                            -1e9f,
                            0.5f};
  const int64_t runnable = simd::runnable_target_bits();
  int batches = 0;
  for (const Texture& t : textures) {
    for (const auto& [mag, min] :
         {std::pair{Filter::kNearest, Filter::kNearest},
          std::pair{Filter::kLinear, Filter::kLinear}, std::pair{Filter::kNearest, Filter::kLinear},
          std::pair{Filter::kLinear, Filter::kNearest}}) {
      for (MipFilter mip : {MipFilter::kNone, MipFilter::kNearest, MipFilter::kLinear}) {
        for (const auto& [wrap, max_anisotropy] : {std::pair{Wrap::kRepeat, 1.0f},
                                                   {Wrap::kClampToEdge, 1.0f},
                                                   {Wrap::kMirroredRepeat, 1.0f},
                                                   {Wrap::kClampToBorder, 1.0f},
                                                   {Wrap::kRepeat, 3.0f},
                                                   {Wrap::kClampToBorder, 3.0f},
                                                   {Wrap::kMirroredRepeat, 16.0f},
                                                   {Wrap::kClampToEdge, 16.0f}}) {
          Sampler s;
          s.max_anisotropy = max_anisotropy;
          s.mag_filter = mag;
          s.min_filter = min;
          s.mip_filter = mip;
          s.wrap_u = wrap;
          s.wrap_v = wrap == Wrap::kClampToBorder ? Wrap::kRepeat : Wrap::kClampToBorder;
          s.border_color = {0.1f, -0.0f, 0.3f, 0.4f};
          s.lod_bias = 0.25f;
          std::array<std::vector<float>, 6> in;  // u, v, du/dx, dv/dx, du/dy, dv/dy
          for (std::vector<float>& a : in)
            a.resize(kStride);
          const uint32_t count = 1 + static_cast<uint32_t>(rng() % kStride);
          for (uint32_t i = 0; i < kStride; i += 4) {
            // Axes of d and d / 2^ratio texels-ish at angle a and a + 90 degrees.
            const float d = std::exp2(scale(rng)) / 37.0f, r = std::exp2(-ratio(rng)),
                        a = angle(rng);
            std::array<float, 4> deriv = {d * std::cos(a), d * std::sin(a), -d * r * std::sin(a),
                                          d * r * std::cos(a)};
            if (rng() % 16 == 0) deriv[rng() % 4] = specials[rng() % 3];
            if (rng() % 32 == 0) deriv = {0, 0, 0, 0};
            for (uint32_t k = i; k < i + 4; ++k) {
              in[0][k] = rng() % 16 == 0 ? specials[rng() % 6] : coord(rng);
              in[1][k] = rng() % 16 == 0 ? specials[rng() % 6] : coord(rng);
              for (uint32_t c = 0; c < 4; ++c)
                in[2 + c][k] = deriv[c];
            }
          }
          const texture::BatchCoordinates batch{in[0].data(), in[1].data(), in[2].data(),
                                                in[3].data(), in[4].data(), in[5].data(),
                                                count};
          for (int64_t bits = runnable; bits != 0; bits &= bits - 1) {
            const int64_t target = bits & -bits;
            std::vector<float> rgba(4 * kStride, 7.0f);
            const Texture::Storage& storage = detail::TextureAccess::storage(t);
            texture::LaneTexture lanes;
            const bool in_lanes = texture::lanes_apply(storage, s, lanes);
            texture::sample_batch(target, storage, s, in_lanes ? &lanes : nullptr, batch,
                                  rgba.data());
            for (uint32_t i = 0; i < kStride; ++i) {
              const std::array<float, 4> want =
                  sample(t, s, in[0][i], in[1][i], in[2][i], in[3][i], in[4][i], in[5][i]);
              for (uint32_t c = 0; c < 4; ++c) {
                const float got = rgba[c * kStride + i];
                if (i >= count) {
                  ASSERT_EQ(got, 7.0f) << "fragment " << i << " past the batch was written";
                  continue;
                }
                ASSERT_EQ(std::memcmp(&got, &want[c], sizeof got), 0)
                    << simd::target_name(target) << ": format " << int(t.desc().format)
                    << ", filters " << int(mag) << "/" << int(min) << ", mip " << int(mip)
                    << ", wrap " << int(wrap) << ", anisotropy " << max_anisotropy << ", fragment "
                    << i << " at (" << in[0][i] << ", " << in[1][i] << ") derivatives " << in[2][i]
                    << " " << in[3][i] << " " << in[4][i] << " " << in[5][i] << ", channel " << c
                    << ": " << got << " against " << want[c];
              }
            }
          }
          ++batches;
        }
      }
    }
  }
  EXPECT_EQ(batches, 4 * 4 * 3 * 8);
}

TEST(Texture, NanInfiniteAndHugeCoordinatesHaveDefinedResults) {
  const std::vector<uint8_t> p = ramp(4, 4);
  const Texture t({4, 4, TextureFormat::kRGBA8}, bytes_of(p), true);
  Sampler s;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // NaN samples as 0; a NaN LOD as 0 (magnified).
  EXPECT_EQ(sample(t, s, nan, 0.3f, 0.0f), sample(t, s, 0.0f, 0.3f, 0.0f));
  EXPECT_EQ(sample(t, s, 0.3f, 0.2f, nan), sample(t, s, 0.3f, 0.2f, 0.0f));
  EXPECT_EQ(texture_lod(t, s, nan, 0, 0, 0), 0.0f);
  // Infinities are clamped to 2^30 texels: finite, in range.
  for (float x : {inf, -inf}) {
    for (Wrap wrap : {Wrap::kRepeat, Wrap::kMirroredRepeat, Wrap::kClampToEdge}) {
      s.wrap_u = s.wrap_v = wrap;
      for (float c : sample(t, s, x, x, 0.0f)) {
        EXPECT_TRUE(c >= 0.0f && c <= 1.0f) << x << " " << int(wrap);
      }
    }
  }
  EXPECT_EQ(texture_lod(t, s, inf, 0, 0, 0), s.max_lod);
  // Anisotropic footprints with NaN or infinite derivatives, or none: in range.
  s = {};
  s.max_anisotropy = 16;
  for (const auto& d : {std::array<float, 4>{nan, 0, 0, 0},
                        {inf, 0.1f, 0, 0},
                        {0, 0, 0, 0},
                        {0.5f, 0, 0, 0},
                        {inf, inf, inf, inf},
                        {nan, nan, 0.5f, 0}}) {
    for (float c : sample(t, s, 0.3f, 0.6f, d[0], d[1], d[2], d[3])) {
      EXPECT_TRUE(c >= 0.0f && c <= 1.0f) << d[0] << " " << d[1] << " " << d[2] << " " << d[3];
    }
  }
  // A million texels out, exactly representable: u w = 1000000.5 is texel 1000000 = 0 mod 4.
  s = {};
  s.mag_filter = Filter::kNearest;
  EXPECT_EQ(sample(t, s, 250000.125f, 0.375f, 0.0f), t.texel(0, 0, 1));
  s.wrap_u = Wrap::kMirroredRepeat;  // 1000000 mod 8 = 0: texel 0
  EXPECT_EQ(sample(t, s, 250000.125f, 0.375f, 0.0f), t.texel(0, 0, 1));
}

TEST(Texture, BadTexturesAreErrors) {
  const std::vector<uint8_t> p = ramp(4, 4);
  const auto code = [&](const TextureDesc& d, size_t bytes) {
    std::vector<uint8_t> data(bytes);
    try {
      Texture t(d, bytes_of(data), true);
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::kUnsupported;  // no error: not what any case expects
  };
  EXPECT_EQ(code({0, 4, TextureFormat::kRGBA8}, 0), ErrorCode::kInvalidArgument);
  EXPECT_EQ(code({16385, 1, TextureFormat::kRGBA8}, 16385 * 4), ErrorCode::kInvalidArgument);
  EXPECT_EQ(code({4, 4, TextureFormat::kRGBA8}, 63), ErrorCode::kInvalidArgument);
  EXPECT_EQ(code({4, 4, static_cast<TextureFormat>(9)}, 64), ErrorCode::kInvalidArgument);
  Texture t({4, 4, TextureFormat::kRGBA8}, bytes_of(p), true);
  EXPECT_THROW(t.set_level(3, bytes_of(p)), Error);  // levels 0..2
  EXPECT_THROW(t.set_level(1, bytes_of(p)), Error);  // 2x2 needs 16 bytes
  EXPECT_THROW(t.texel(0, 4, 0), Error);
  // The caller's pixels are copied: changing them afterwards changes nothing.
  std::vector<uint8_t> mine = ramp(4, 4);
  const Texture copy({4, 4, TextureFormat::kRGBA8}, bytes_of(mine), false);
  mine[0] = 99;
  EXPECT_EQ(copy.texel(0, 0, 0), unorm(1, 2, 0, 255));
}

// A textured square drawn through a user fragment shader that samples with the batch's
// varyings and derivatives: both backends give the same image within 1/255 (their varyings and
// derivatives agree within docs/SHADING.md's tolerances), and the magnified texels show.
TEST(Texture, UserShadersSampleWithTheirDerivativesOnBothBackends) {
  std::vector<uint8_t> checker;
  for (uint32_t y = 0; y < 8; ++y) {
    for (uint32_t x = 0; x < 8; ++x) {
      const uint8_t c = (x + y) % 2 ? 230 : 20;
      checker.insert(checker.end(), {c, c, c, 255});
    }
  }
  const Texture t({8, 8, TextureFormat::kRGBA8}, bytes_of(checker), true);
  Sampler s;
  s.wrap_u = s.wrap_v = Wrap::kRepeat;
  // A square tilted away (w from 1 to 3), u, v over [0, 4] x [0, 4]: minified at the far end.
  const std::vector<Float4> positions = {
      {-1, -1, 0.5f, 1}, {3, -3, 1.5f, 3}, {3, 3, 1.5f, 3}, {-1, 1, 0.5f, 1}};
  const std::vector<float> uv = {0, 4, 4, 4, 4, 0, 0, 0};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  PipelineState p;
  p.shader = FragmentShader::kUser;
  p.fragment_function = [&](const FragmentBatch& b, const FragmentOutput& out) {
    sample(t, s, b, 0, 1, out.color);
  };
  std::vector<uint8_t> images[2];
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    options.threads = 2;
    Renderer renderer(options);
    Framebuffer fb({96, 64, 1, ColorFormat::kRGBA8});
    renderer.draw(fb, p, {positions, uv, 2, indices});
    images[backend == Backend::kFast] = fb.read_rgba8();
  }
  int worst = 0, dark = 0, light = 0, grey = 0;
  for (size_t i = 0; i < images[0].size(); ++i) {
    worst = std::max(worst, std::abs(int{images[0][i]} - images[1][i]));
    if (i % 4 == 0) {
      dark += images[1][i] < 60;
      light += images[1][i] > 190;
      grey += images[1][i] > 110 && images[1][i] < 140;
    }
  }
  EXPECT_LE(worst, 1);
  EXPECT_GT(dark, 150);  // checks of about 3 pixels a texel near the viewer
  EXPECT_GT(light, 150);
  EXPECT_GT(grey, 50);  // minified far away: the mip chain's mean
}

}  // namespace
}  // namespace tessera
