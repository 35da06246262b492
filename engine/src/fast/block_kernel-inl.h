// The raster kernel, written once against Highway. Highway's -inl.h convention: the guard
// below toggles once per target, so a source that sets HWY_TARGET_INCLUDE and includes
// hwy/foreach_target.h compiles this code for every SIMD target (the Embree / Masked Occlusion
// Culling per-ISA pattern). One source per depth mode (block_kernel_depth_*.cpp) instantiates
// it, so the three compile in parallel; block_kernel.cpp gathers them into the kernel table.
//
// For one triangle in one tile it walks the 8x8 blocks under the triangle's bounding box. Each
// block is classified by the edge functions at its corners (Abrash 2009: an edge's extremes over
// a rectangle lie at two corners): outside an edge (rejected), inside all three (accepted: no
// edge tests), or partial; then Hi-Z may reject it or prove every sample passes. A partial
// block's lane groups (its sub-blocks) take the same test from their corner pixels: outside an
// edge (skipped), or inside some edges (not tested there). With a block
// size of 16 or 32 (RendererOptions::block_size) the same test first classifies 2x2 or 4x4
// blocks at once, testing the blocks one by one only where an edge crosses. Lanes are the
// block's pixels in row-major order, only the rows the triangle touches; each sample is a pass
// over the lanes with its own edge and depth offsets. Edge functions step exactly in int32
// (bound in block_kernel.hpp). Planes are evaluated as base + (gx * x + gy * y) from the block
// corner in the same order on every target, and contraction is off, so every target writes the
// same bytes. Small triangles whose box is at most 8 pixels wide take windows of lanes that
// begin at the box's first column instead of a block's (raster_window), with the same values
// per pixel.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "binning/tile_grid.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/hiz.hpp"
#include "engine/src/fast/pixel_record.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"

// Per-target include guard: defined and undefined in turn as foreach_target.h toggles
// HWY_TARGET_TOGGLE, so each target's pass reads the code below once.
#if defined(TESSERA_ENGINE_SRC_FAST_BLOCK_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_FAST_BLOCK_KERNEL_INL_H_
#undef TESSERA_ENGINE_SRC_FAST_BLOCK_KERNEL_INL_H_
#else
#define TESSERA_ENGINE_SRC_FAST_BLOCK_KERNEL_INL_H_
#endif

#include <hwy/highway.h>

#include "engine/src/blend/blend-inl.h"
#include "engine/src/blend/blend.hpp"
#include "engine/src/fast/hiz-inl.h"
#include "engine/src/fast/unorm8-inl.h"
#include "engine/src/shade/shade-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The fragment back end of the user shader's kernels (user_fragments-inl.h, compiled with
// them): block (bx, by) of the tile (8x8 pixels from pixel (8 bx, 8 by); `block` its index in
// the tile's storage) for triangle `t` with planes `planes`. mask[i]: the samples of the
// block's pixel i (row-major) that are covered and passed the depth test. z: null, or the depth
// to write for sample s of pixel i at z[s * 64 + i] (depth writes on).
void shade_user_block(const TileContext& tc, const TriangleSetup& t, const float* planes,
                      int32_t bx, int32_t by, size_t block, const uint32_t* mask, const float* z);

namespace {

using detail::kBlocksPerTileSide;

// Block (bx, by)'s index in the storage tile whose first block is (tile_bx, tile_by), all in
// blocks from the screen's origin.
HWY_INLINE size_t tile_block(int32_t bx, int32_t by, int32_t tile_bx, int32_t tile_by) {
  return static_cast<size_t>((by - tile_by) * kBlocksPerTileSide + (bx - tile_bx));
}

// Pixel coordinates of the 64 lanes of a block, row-major.
struct PixelTables {
  alignas(64) int32_t x[64];
  alignas(64) int32_t y[64];
  alignas(64) float fx[64];
  alignas(64) float fy[64];
  constexpr PixelTables() : x(), y(), fx(), fy() {
    for (int i = 0; i < 64; ++i) {
      x[i] = i & 7;
      y[i] = i >> 3;
      fx[i] = static_cast<float>(i & 7);
      fy[i] = static_cast<float>(i >> 3);
    }
  }
};
constexpr PixelTables kPixels;

template <class D>
HWY_INLINE auto all_lanes(D d) {
  return hn::FirstN(d, hn::Lanes(d));
}

// Masked stores of whole vectors. On x86 without AVX-512 a masked store (AVX2's vmaskmovps and
// vpmaskmovd) is microcoded on AMD's Zen 1 to 3, about a dozen cycles each: there, a load, a
// blend and a store of the whole vector instead (on a Zen 3 host `small` took about 0.75x the
// time at one sample and 0.5x at four, benchmarks/RESULTS.md decision 170). Every vector the
// kernels store this way lies in one block row of the tile being drawn, which only the task
// drawing that tile touches, so the lanes written back unchanged race with nothing.
#if HWY_ARCH_X86 && HWY_TARGET > HWY_AVX3
inline constexpr bool kStoreByBlend = true;
#else
inline constexpr bool kStoreByBlend = false;
#endif

// Stores v's lanes where m is set to p (aligned, a whole vector), whose whole vector `old`
// holds as loaded before (read only with kStoreByBlend).
template <class D, class M, class T>
HWY_INLINE void store_masked(hn::Vec<D> v, M m, D d, T* HWY_RESTRICT p, hn::Vec<D> old) {
  if constexpr (kStoreByBlend) {
    hn::Store(hn::IfThenElse(m, v, old), d, p);
  } else {
    hn::BlendedStore(v, m, d, p);
  }
}

// The same, loading p's vector itself where it needs it.
template <class D, class M, class T>
HWY_INLINE void store_masked(hn::Vec<D> v, M m, D d, T* HWY_RESTRICT p) {
  store_masked(v, m, d, p, kStoreByBlend ? hn::Load(d, p) : v);
}

template <class D, class V>
HWY_INLINE auto depth_passes(D d, CompareOp op, V incoming, V stored) {
  switch (op) {
    case CompareOp::kNever:
      return hn::FirstN(d, 0);
    case CompareOp::kLess:
      return hn::Lt(incoming, stored);
    case CompareOp::kEqual:
      return hn::Eq(incoming, stored);
    case CompareOp::kLessEqual:
      return hn::Le(incoming, stored);
    case CompareOp::kGreater:
      return hn::Gt(incoming, stored);
    case CompareOp::kNotEqual:
      return hn::Ne(incoming, stored);
    case CompareOp::kGreaterEqual:
      return hn::Ge(incoming, stored);
    case CompareOp::kAlways:
      break;
  }
  return all_lanes(d);
}

// The depth test of a loop compiled for one compare op: LessCompare for CompareOp::kLess, the
// default, whose loop then holds no switch over the op (the window path at four samples: small
// about 0.93x the time, benchmarks/RESULTS.md decision 79); AnyCompare for the others.
struct LessCompare {
  template <class D, class V>
  HWY_INLINE auto operator()(D, V incoming, V stored) const {
    return hn::Lt(incoming, stored);
  }
  HWY_INLINE bool operator()(float incoming, float stored) const { return incoming < stored; }
};
struct AnyCompare {
  CompareOp op;
  template <class D, class V>
  HWY_INLINE auto operator()(D d, V incoming, V stored) const {
    return depth_passes(d, op, incoming, stored);
  }
  HWY_INLINE bool operator()(float incoming, float stored) const {
    return detail::depth_passes(op, incoming, stored);
  }
};

// Calls body(LessCompare) when the draw tests depth with kLess, else body(AnyCompare).
template <DepthMode kDepth, class Body>
HWY_INLINE void with_compare(const TileContext& tc, Body&& body) {
  if constexpr (kDepth != DepthMode::kOff) {
    if (tc.compare == CompareOp::kLess) {
      body(LessCompare{});
      return;
    }
  }
  body(AnyCompare{tc.compare});
}

// Whether, at one sample, triangle t's RGBA8 colour may be packed without the clamp to [0, 1]:
// every channel formed at a covered pixel centre then lies in [-0.25 / 255, 1 + 0.25 / 255],
// where the clamp changes no byte (unorm8_low_byte). t.unit_colour says the exact planes lie in
// [0, 1] at such a centre (inside the triangle, so its barycentric weights, from the unbiased
// edge functions, are not negative; the setup's double planes are far closer to them than the
// float error below). A channel's float sum at a pixel of the box (W by H pixels) takes at most
// 11 roundings: the setup's value at the box's first pixel and its two gradients to float, then
// base = qa0 + (gx dx + gy dy) at the block's (or window's) first pixel and base + (gx fx +
// gy fy) at the pixel. Each is under 2^-24 of the sum S of the terms' magnitudes. With G the
// largest gradient: the value at the box's first pixel is within G (W + H) of a covered
// centre's, |dx| <= W + 7 and |dy| <= H + 7, and fx, fy <= 7, so S <= 1 + 2 G (W + H + 13),
// at most 1025 under unit_colour's bound G (W + H + 13) <= 512. The error is then at most
// 11 * 2^-24 * 1025, about 6.7e-4, against 0.25 / 255, 9.8e-4.
HWY_INLINE bool packs_without_clamp(const TriangleSetup& t) {
  static_assert(kUnitColourReach == 512.0f, "the bound above");
  return t.unit_colour != 0;
}

// base + (gx * x + gy * y) at the lanes' pixels.
template <class DF, class VF>
HWY_INLINE VF plane_at(DF df, VF fx, VF fy, float base, float gx, float gy) {
  return hn::Add(hn::Set(df, base),
                 hn::Add(hn::Mul(fx, hn::Set(df, gx)), hn::Mul(fy, hn::Set(df, gy))));
}

// A plane at the lanes' pixels (fx, fy): base + (gx * x + gy * y), or base + offsets (the
// same bits) with kOffsets.
template <bool kOffsets, class DF, class VF>
HWY_INLINE VF plane_of_lanes(DF df, VF fx, VF fy, const float* offsets, float base, float gx,
                             float gy) {
  if constexpr (kOffsets) {
    return hn::Add(hn::Set(df, base), hn::Load(df, offsets));
  } else {
    return plane_at(df, fx, fy, base, gx, gy);
  }
}

// The four colour channels' lanes to and from memory, for the per-lane fallback of pixels
// beyond a triangle's horizon.
template <class DF, class VF>
HWY_INLINE void store_channels(DF df, VF r, VF g, VF b, VF a, float (&channel)[4][64]) {
  hn::Store(r, df, channel[0]);
  hn::Store(g, df, channel[1]);
  hn::Store(b, df, channel[2]);
  hn::Store(a, df, channel[3]);
}
template <class DF, class VF>
HWY_INLINE void load_channels(DF df, const float (&channel)[4][64], VF& r, VF& g, VF& b, VF& a) {
  r = hn::Load(df, channel[0]);
  g = hn::Load(df, channel[1]);
  b = hn::Load(df, channel[2]);
  a = hn::Load(df, channel[3]);
}

// Bit s of a lane set where sample s passed there (passed(s): that sample's mask), for the
// horizon fallback's lane-by-lane loop.
template <class DU, class Passed>
HWY_INLINE hn::Vec<DU> sample_bits(DU du, uint32_t samples, const Passed& passed) {
  auto bits = hn::Zero(du);
  for (uint32_t s = 0; s < samples; ++s) {
    bits = hn::Or(bits, hn::IfThenElseZero(hn::RebindMask(du, passed(s)), hn::Set(du, 1u << s)));
  }
  return bits;
}

// The margin around a triangle's depth plane that covers the kernel's float rounding of it.
inline double hiz_margin(const TriangleSetup& t) {
  return fast::hiz_margin(t.z0, t.z_dx, t.z_dy);
}

// Depth bounds [lo, hi] in the tile's depth encoding (hiz.hpp's hiz_range).
inline void hiz_range(const TileContext& tc, double lo, double hi, float& out_lo, float& out_hi) {
  fast::hiz_range(tc.depth_scale, lo, hi, out_lo, out_hi);
}

// Wide path: exact int64 coverage bits for each pixel of the block (see block_kernel.hpp).
void wide_coverage(const TriangleSetup& t, const TileContext& tc, int32_t bx, int32_t by,
                   uint32_t* coverage) {
  const int shift = static_cast<int>(tc.subpixel_bits) - 4;
  for (int p = 0; p < 64; ++p) {
    const int64_t cx = ((int64_t{bx} * 8 + (p & 7)) * 16 + 8) << shift;
    const int64_t cy = ((int64_t{by} * 8 + (p >> 3)) * 16 + 8) << shift;
    uint32_t mask = 0;
    for (uint32_t s = 0; s < tc.samples; ++s) {
      const int64_t sx = cx + tc.sample_x[s], sy = cy + tc.sample_y[s];
      bool inside = true;
      for (int e = 0; e < 3; ++e)
        inside &= t.a[e] * sx + t.b[e] * sy + t.c[e] >= 0;
      mask |= inside ? 1u << s : 0u;
    }
    coverage[p] = mask;
  }
}

// Hi-Z bounds of a block whose depth changed since they were last computed ("dirty": marked
// by min > max, block_kernel.hpp's mark_hiz_dirty). Writers only mark blocks; a Hi-Z test
// recomputes the bounds from the block's samples when it needs them, so triangles that never
// test Hi-Z never pay for it.
inline bool hiz_dirty(const TileContext& tc, size_t block) {
  return fast::hiz_dirty(tc.hiz_min[block], tc.hiz_max[block]);
}

inline void refresh_hiz(const TileContext& tc, size_t block, uint32_t samples) {
  RefreshHizBlock(tc.depth + block * 64, samples, tc.hiz_min[block], tc.hiz_max[block]);
}

// Hi-Z's verdict on block `block` of the tile for depth bounds [lo, hi] (hiz_range's), with
// `samples` samples per pixel: its bounds are recomputed first when out of date.
inline HizVerdict block_hiz_verdict(const TileContext& tc, size_t block, uint32_t samples, float lo,
                                    float hi) {
  if (hiz_dirty(tc, block)) refresh_hiz(tc, block, samples);
  return hiz_test(tc.compare, lo, hi, tc.hiz_min[block], tc.hiz_max[block]);
}

// A whole triangle's depth bounds for Hi-Z: its vertices' range, widened by the margin that
// covers the kernel's float rounding (as the general path's block ranges are).
inline void triangle_hiz_range(const TileContext& tc, const TriangleSetup& t, float& lo,
                               float& hi) {
  const double margin = hiz_margin(t);
  hiz_range(tc, t.z_min - margin, t.z_max + margin, lo, hi);
}

// Calls f(state) with tc's blend state: for the usual states (blend::Preset) a constant, so
// that once f is inlined the switches over its factors fold away (blended `small` and `medium`
// at one thread about 0.95x the time of the switches, benchmarks/RESULTS.md decision 216), else
// *tc.blend.
template <class F>
HWY_INLINE auto with_blend_state(const TileContext& tc, F&& f) {
  switch (tc.blend_preset) {
    case blend::Preset::kOver:
      return f(blend::kPresetState<blend::Preset::kOver>);
    case blend::Preset::kPremultipliedOver:
      return f(blend::kPresetState<blend::Preset::kPremultipliedOver>);
    case blend::Preset::kAdditive:
      return f(blend::kPresetState<blend::Preset::kAdditive>);
    case blend::Preset::kMultiply:
      return f(blend::kPresetState<blend::Preset::kMultiply>);
    case blend::Preset::kOther:
      break;
  }
  return f(*tc.blend);
}

// RGBA lanes blended into RGBA8 lanes `old` under tc.blend (blend.hpp's blend and write mask,
// the same operations): the packed lanes to store. Out of line: one copy serves every path,
// and draws that do not blend never reach it.
template <class DF, class VF>
HWY_NOINLINE hn::Vec<hn::RebindToUnsigned<DF>> blend_packed(DF df, const TileContext& tc,
                                                            hn::Vec<hn::RebindToUnsigned<DF>> old,
                                                            VF r, VF g, VF b, VF a) {
  const hn::RebindToUnsigned<DF> du;
  const hn::RebindToSigned<DF> di;
  const auto byte = hn::Set(du, 0xFFu);
  const auto unpack = [&](auto bits) {
    return hn::Div(hn::ConvertTo(df, hn::BitCast(di, hn::And(bits, byte))), hn::Set(df, 255.0f));
  };
  return with_blend_state(
      tc, [&](const BlendState& state) __attribute__((always_inline)) {
        VF r2 = r, g2 = g, b2 = b, a2 = a;
        blend::HWY_NAMESPACE::blend(df, state, tc.blend_constant.data(), true, r2, g2, b2, a2,
                                    unpack(old), unpack(hn::ShiftRight<8>(old)),
                                    unpack(hn::ShiftRight<16>(old)),
                                    unpack(hn::ShiftRight<24>(old)));
        const auto packed = pack_unorm8<true>(df, r2, g2, b2, a2);
        uint32_t keep = 0;  // the bytes of channels outside the write mask
        for (int c = 0; c < 4; ++c)
          if (!(state.write_mask & (1u << c))) keep |= 0xFFu << (8 * c);
        if (keep == 0) return packed;
        return hn::Or(hn::AndNot(hn::Set(du, keep), packed), hn::And(hn::Set(du, keep), old));
      });
}

// RGBA lanes blended under tc.blend into the RGBA32F values at `dst` (interleaved, a whole
// vector of pixels) where m is set.
template <class DF, class MF, class VF>
HWY_NOINLINE void blend_rgba32f(DF df, const TileContext& tc, float* HWY_RESTRICT dst, MF m, VF r,
                                VF g, VF b, VF a) {
  VF r0, g0, b0, a0;
  hn::LoadInterleaved4(df, dst, r0, g0, b0, a0);
  with_blend_state(
      tc, [&](const BlendState& state) __attribute__((always_inline)) {
        VF r2 = r, g2 = g, b2 = b, a2 = a;
        blend::HWY_NAMESPACE::blend(df, state, tc.blend_constant.data(), false, r2, g2, b2, a2, r0,
                                    g0, b0, a0);
        const uint8_t mask = state.write_mask;
        const auto pick = [&](int c, VF v, VF stored) {
          return (mask & (1u << c)) ? hn::IfThenElse(m, v, stored) : stored;
        };
        hn::StoreInterleaved4(pick(0, r2, r0), pick(1, g2, g0), pick(2, b2, b0), pick(3, a2, a0),
                              df, dst);
      });
}

// The colour write of lane group i of block `block`: RGBA lanes to the samples that passed
// (passed(s); one sample: `any`), packed to RGBA8 (kClamp as pack_unorm8's) or stored as floats,
// or blended where the draw blends (tc.blend).
template <ColorMode kColor, bool kMulti, bool kClamp, class DF, class VF, class MU, class Passed>
HWY_INLINE void store_colour(DF df, const TileContext& tc, size_t block, size_t i, uint32_t samples,
                             MU any, const Passed& passed, VF r, VF g, VF b, VF a) {
  const hn::RebindToUnsigned<DF> du;
  if (tc.blend != nullptr) {
    for (uint32_t s = 0; s < samples; ++s) {
      const MU m = kMulti ? passed(s) : any;
      if (hn::AllFalse(du, m)) continue;
      if constexpr (kColor == ColorMode::kRGBA8) {
        uint32_t* colour =
            reinterpret_cast<uint32_t*>(tc.rgba8) + block * 64 + s * kSamplePlane + i;
        const auto old = hn::Load(du, colour);
        store_masked(blend_packed(df, tc, old, r, g, b, a), m, du, colour, old);
      } else {
        blend_rgba32f(df, tc, tc.rgba32f + (block * 64 + s * kSamplePlane + i) * 4,
                      hn::RebindMask(df, m), r, g, b, a);
      }
    }
    return;
  }
  if constexpr (kColor == ColorMode::kRGBA8) {
    const auto packed = pack_unorm8<kClamp>(df, r, g, b, a);
    uint32_t* colour = reinterpret_cast<uint32_t*>(tc.rgba8) + block * 64 + i;
    if (samples == 1) {
      store_masked(packed, any, du, colour);
    } else {
      for (uint32_t s = 0; s < samples; ++s) {
        store_masked(packed, passed(s), du, colour + s * kSamplePlane);
      }
    }
  } else {
    for (uint32_t s = 0; s < samples; ++s) {
      const auto m = hn::RebindMask(df, kMulti ? passed(s) : any);
      float* dst = tc.rgba32f + (block * 64 + s * kSamplePlane + i) * 4;
      VF r0, g0, b0, a0;
      hn::LoadInterleaved4(df, dst, r0, g0, b0, a0);
      hn::StoreInterleaved4(hn::IfThenElse(m, r, r0), hn::IfThenElse(m, g, g0),
                            hn::IfThenElse(m, b, b0), hn::IfThenElse(m, a, a0), df, dst);
    }
  }
}

// The planes' change from a block's first pixel centre to each of its pixels, gx * x + gy * y
// (plane_at's inner sum, so base + offset is the same bits): the general path computes them once
// per triangle, at its first covered block, for all its blocks.
struct PlaneOffsets {
  alignas(64) float z[64];
  alignas(64) float q[64];
  alignas(64) float qa[4][64];
  bool ready = false;
};

template <DepthMode kDepth, ColorMode kColor>
HWY_INLINE void compute_plane_offsets(const TriangleSetup& t, PlaneOffsets& po) {
  const hn::ScalableTag<float> df;
  for (size_t i = 0; i < 64; i += hn::Lanes(df)) {
    const auto fx = hn::Load(df, kPixels.fx + i);
    const auto fy = hn::Load(df, kPixels.fy + i);
    const auto offset = [&](float gx, float gy) {
      return hn::Add(hn::Mul(fx, hn::Set(df, gx)), hn::Mul(fy, hn::Set(df, gy)));
    };
    if constexpr (kDepth != DepthMode::kOff) hn::Store(offset(t.z_dx, t.z_dy), df, po.z + i);
    if constexpr (kColor != ColorMode::kOff) {
      if (!t.flat_q) hn::Store(offset(t.q_dx, t.q_dy), df, po.q + i);
      for (int c = 0; c < 4; ++c)
        hn::Store(offset(t.qa_dx[c], t.qa_dy[c]), df, po.qa[c] + i);
    }
  }
  po.ready = true;
}

// What one triangle's blocks share: per-pixel edge steps, the per-sample edge thresholds and
// depth offsets, the pixels it may cover in this tile, and the counts it accumulates. Scalars
// only: vectors travel as arguments (sizeless SIMD types cannot be members).
struct TriangleState {
  int32_t step_x[3], step_y[3];  // edge change per pixel in x and y
  // A sample is inside edge e when E(pixel centre) + offset(sample) >= 0, i.e. when
  // E(pixel centre) > -1 - offset: one compare per edge and sample, no add.
  // (Row s's fourth value is unused: rows of four are formed in vector lanes.)
  alignas(16) int32_t edge_threshold[16][4];
  int32_t threshold_lo[3], threshold_hi[3];  // the smallest and largest over the samples
  // An edge's smallest and largest change from a sub-block's first pixel centre to its others.
  int32_t sub_lo[3], sub_hi[3];
  float z_offset[16];
  PlaneOffsets* offsets = nullptr;  // the general path's (raster_block's kOffsets)
  const float* planes = nullptr;    // a shaded draw's (TileContext::layout)
  uint32_t samples;
  int32_t px0, px1, py0, py1;  // the bounding box inside the tile
  int32_t tile_bx, tile_by;
  uint32_t covered = 0, passed = 0, shaded = 0;
  uint32_t sub_rejected = 0, sub_accepted = 0, sub_partial = 0;
};

// Rasterizes the triangle over block (bx, by) of the tile: coverage of the edges in edge_mask
// (e_block: their values at the centre of the block's first pixel), or the wide path's int64
// coverage bits, then the early depth test, shading once per pixel and the writes. Plane bases
// are computed at the first lane group with coverage, so blocks the triangle misses cost only
// their edge tests.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          bool kSubBlocks, bool kOffsets, class VI>
HWY_INLINE void raster_block(const TileContext& tc, const TriangleSetup& t, TriangleState& st,
                             VI lane_e0, VI lane_e1, VI lane_e2, int32_t bx, int32_t by,
                             const int32_t* e_block, uint32_t edge_mask, bool wide,
                             bool test_depth) {
  const hn::ScalableTag<int32_t> di;
  const hn::ScalableTag<uint32_t> du;
  const hn::ScalableTag<float> df;
  const size_t lanes = hn::Lanes(di);
  const uint32_t samples = kMulti ? st.samples : 1;  // a constant 1 unrolls the sample loop

  const size_t block = tile_block(bx, by, st.tile_bx, st.tile_by);
  // The block's columns and rows inside the region: [col0, cols) and [row0, rows). The region
  // is block-aligned on the left and top except at a scissor rectangle's edges.
  const int32_t cols = std::min<int32_t>(8, tc.x1 + 1 - bx * 8);
  const int32_t rows = std::min<int32_t>(8, tc.y1 + 1 - by * 8);
  const int32_t col0 = std::max<int32_t>(0, tc.x0 - bx * 8);
  const int32_t row0 = std::max<int32_t>(0, tc.y0 - by * 8);
  const bool clipped_block = cols < 8 || rows < 8 || col0 > 0 || row0 > 0;
  alignas(64) uint32_t coverage_bits[64];
  if (wide) wide_coverage(t, tc, bx, by, coverage_bits);

  bool have_bases = false;
  float z_base = 0.0f, q_base = 0.0f, qa_base[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const auto compute_bases = [&] {
    // The planes at the centre of the block's first pixel, relative to the plane origin.
    const double dx = bx * 8.0 - t.x0, dy = by * 8.0 - t.y0;
    z_base = static_cast<float>(t.z0 + t.z_dx * dx + t.z_dy * dy);
    if constexpr (kColor != ColorMode::kOff && kShader == shade::Shader::kGouraud) {
      const float fdx = static_cast<float>(dx), fdy = static_cast<float>(dy);
      q_base = t.q0 + (t.q_dx * fdx + t.q_dy * fdy);
      for (int c = 0; c < 4; ++c)
        qa_base[c] = t.qa0[c] + (t.qa_dx[c] * fdx + t.qa_dy[c] * fdy);
    }
    if constexpr (kOffsets) {
      if (!st.offsets->ready) {
        compute_plane_offsets<kDepth,
                              kShader == shade::Shader::kGouraud ? kColor : ColorMode::kOff>(
            t, *st.offsets);
      }
    }
    have_bases = true;
  };
  float* depth = tc.depth + block * 64;

  // Lane groups covering the rows of the block the triangle's bounding box touches.
  const int32_t row_begin = std::max(st.py0 - by * 8, 0);
  const int32_t row_end = std::min(st.py1 - by * 8 + 1, rows);
  const size_t first = static_cast<size_t>(row_begin) * 8 / lanes * lanes;
  const size_t last =
      std::min<size_t>(64, (static_cast<size_t>(row_end) * 8 + lanes - 1) / lanes * lanes);

  // Copies the compiler can keep in registers across the depth and colour stores of the
  // sample loop (multisample only: at one sample the copies measured 2% slower on tiny).
  const CompareOp compare = tc.compare;
  const float depth_scale = tc.depth_scale;
  bool wrote = false;
  // A user shader's block (shade::Shader::kUser): each pixel's passing samples, and with depth
  // writes each sample's depth, kept for its back end (user_fragments-inl.h), which writes them
  // after the shader, for the fragments it keeps.
  constexpr bool kUser = kShader == shade::Shader::kUser;
  constexpr bool kUserDepth = kUser && kDepth == DepthMode::kTestWrite;
  alignas(64) uint32_t user_mask[kUser ? 64 : 1];
  alignas(64) float user_z[kUserDepth ? (kMulti ? 16 : 1) * 64 : 1];
  bool user_any = false;
  if constexpr (kUser) std::fill_n(user_mask, 64, 0u);
  for (size_t i = first; i < last; i += lanes) {
    auto inside = all_lanes(di);
    if (clipped_block) {
      const auto x = hn::Load(di, kPixels.x + i), y = hn::Load(di, kPixels.y + i);
      inside = hn::And(hn::And(hn::Lt(x, hn::Set(di, cols)), hn::Lt(y, hn::Set(di, rows))),
                       hn::And(hn::Gt(x, hn::Set(di, col0 - 1)), hn::Gt(y, hn::Set(di, row0 - 1))));
    }
    // Edge values at the lanes' pixel centres: the group's first pixel plus lane offsets.
    const int32_t gx = static_cast<int32_t>(i & 7), gy = static_cast<int32_t>(i >> 3);
    uint32_t group_mask = edge_mask;
    if constexpr (kSubBlocks) {
      // The sub-block test: the lane group's pixels as a sub-block of a partial block. An edge
      // crossing the block is exact in int32 at every pixel centre of it (block_kernel.hpp), and
      // eg + sub_hi, eg + sub_lo are its values at two of them. Outside the edge at every
      // sample of every pixel: rejected. Inside at all of them: that edge needs no test here.
      if (edge_mask != 0 && !wide) {
        const int32_t eg[3] = {e_block[0] + st.step_x[0] * gx + st.step_y[0] * gy,
                               e_block[1] + st.step_x[1] * gx + st.step_y[1] * gy,
                               e_block[2] + st.step_x[2] * gx + st.step_y[2] * gy};
        bool outside = false;
        for (int e = 0; e < 3; ++e) {
          if (!(edge_mask & (1u << e))) continue;
          outside |= eg[e] + st.sub_hi[e] <= st.threshold_lo[e];
          if (eg[e] + st.sub_lo[e] > st.threshold_hi[e]) group_mask &= ~(1u << e);
        }
        if (outside) {
          if constexpr (kCount) ++st.sub_rejected;
          continue;
        }
        if constexpr (kCount) {
          if (group_mask == 0) {
            ++st.sub_accepted;
          } else {
            ++st.sub_partial;
          }
        }
      }
    }
    const auto e0 =
        hn::Add(hn::Set(di, e_block[0] + st.step_x[0] * gx + st.step_y[0] * gy), lane_e0);
    const auto e1 =
        hn::Add(hn::Set(di, e_block[1] + st.step_x[1] * gx + st.step_y[1] * gy), lane_e1);
    const auto e2 =
        hn::Add(hn::Set(di, e_block[2] + st.step_x[2] * gx + st.step_y[2] * gy), lane_e2);
    const auto cov_bits = wide ? hn::Load(du, coverage_bits + i) : hn::Zero(du);
    const auto fx = hn::Load(df, kPixels.fx + i);
    const auto fy = hn::Load(df, kPixels.fy + i);
    // The depth plane's change from the block's first pixel, shared by every sample (the
    // same sums plane_at forms, so the bits do not change). Offsets are read in the sample
    // loop, after the bases, with which they are computed.
    const auto z_rel = hn::Add(hn::Mul(fx, hn::Set(df, t.z_dx)), hn::Mul(fy, hn::Set(df, t.z_dy)));
    // Multisample: which lanes each sample passed, kept (keep) and read back (passed) as one
    // mask per sample (medium, large and huge at four samples 0.95x to 0.99x the time of a
    // vector of lane bits). Sizeless-vector targets (SVE), whose masks cannot be array elements,
    // keep the bits.
#if HWY_HAVE_SCALABLE
    auto pass_bits = hn::Zero(du);  // bit s: sample s passed
    const auto keep = [&](uint32_t s, auto pass) {
      pass_bits =
          hn::Or(pass_bits, hn::IfThenElseZero(hn::RebindMask(du, pass), hn::Set(du, 1u << s)));
    };
    const auto passed = [&](uint32_t s) { return hn::TestBit(pass_bits, hn::Set(du, 1u << s)); };
#else
    hn::Mask<decltype(du)> pass_masks[16];
    const auto keep = [&](uint32_t s, auto pass) { pass_masks[s] = hn::RebindMask(du, pass); };
    const auto passed = [&](uint32_t s) { return pass_masks[s]; };
#endif
    // The one sample's passing lanes; multisample: the lanes where any sample passed.
    auto pass_one = hn::FirstN(du, 0);
    for (uint32_t s = 0; s < samples; ++s) {
      auto cov = inside;
      if (wide) {
        cov = hn::And(cov, hn::RebindMask(di, hn::TestBit(cov_bits, hn::Set(du, 1u << s))));
      } else {
        // Inside when E + offset >= 0, i.e. E > -1 - offset (integer lanes have no >=).
        if (group_mask & 1) cov = hn::And(cov, hn::Gt(e0, hn::Set(di, st.edge_threshold[s][0])));
        if (group_mask & 2) cov = hn::And(cov, hn::Gt(e1, hn::Set(di, st.edge_threshold[s][1])));
        if (group_mask & 4) cov = hn::And(cov, hn::Gt(e2, hn::Set(di, st.edge_threshold[s][2])));
      }
      // Multisample and in the general path, each sample goes on whether or not any lane is
      // covered: a branch on it is often mispredicted, and the depth test of an empty mask
      // costs less (4 samples: small 6.5%, medium 3.4% faster; one sample, general path: huge
      // 2-4%). For small triangles at one sample the branch measured faster (tiny 7%, grid 11%).
      if constexpr (!kMulti && !kOffsets) {
        if (hn::AllFalse(di, cov)) continue;
      }
      if (!have_bases) compute_bases();
      if constexpr (kCount) st.covered += static_cast<uint32_t>(hn::CountTrue(di, cov));
      auto pass = hn::RebindMask(df, cov);
      if constexpr (kDepth != DepthMode::kOff) {
        auto z = kMulti
                     ? hn::Add(hn::Set(df, z_base + st.z_offset[s]),
                               (kOffsets ? hn::Load(df, st.offsets->z + i) : z_rel))
                     : plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? st.offsets->z + i : nullptr,
                                                z_base, t.z_dx, t.z_dy);
        z = hn::Min(hn::Max(z, hn::Zero(df)), hn::Set(df, 1.0f));
        // Fixed-point formats: the step nearest z, ties to even (as encode_depth).
        const float scale = kMulti ? depth_scale : tc.depth_scale;
        if (scale > 0.0f) z = hn::Round(hn::Mul(z, hn::Set(df, scale)));
        float* plane = depth + s * kSamplePlane + i;
        if (test_depth) {
          const auto stored = hn::Load(df, plane);
          pass = hn::And(pass, depth_passes(df, kMulti ? compare : tc.compare, z, stored));
        }
        if constexpr (kUserDepth) {
          hn::Store(z, df, user_z + s * 64 + i);
        } else if constexpr (kDepth == DepthMode::kTestWrite) {
          if constexpr (!kOffsets || !kMulti) {
            // Samples are stored unconditionally: whether any lane passes varies from lane
            // group to lane group and sample to sample, a branch on it is often mispredicted,
            // and an empty masked store costs less (small triangles at 4 samples: small 4%,
            // tiny 7% faster; at 1 sample: small 2%; the general path at one sample: huge
            // about 0.96x, large 0.94x to 1.00x, medium the same, benchmarks/RESULTS.md
            // decisions 15, 41 and 160). The general path's multisample blocks keep the branch
            // (without it medium took 1.03x the time at 4 samples).
            store_masked(z, pass, df, plane);
            wrote |= !hn::AllFalse(df, pass);
          } else if (!hn::AllFalse(df, pass)) {
            store_masked(z, pass, df, plane);
            wrote = true;
          }
        }
      }
      if constexpr (kCount) st.passed += static_cast<uint32_t>(hn::CountTrue(df, pass));
      if constexpr (kMulti) {
        keep(s, pass);
        pass_one = hn::Or(pass_one, hn::RebindMask(du, pass));
      } else {
        pass_one = hn::RebindMask(du, pass);
      }
    }

    if constexpr (kUser) {
      const auto any = pass_one;
      if (hn::AllFalse(du, any)) continue;
      if constexpr (kCount) st.shaded += static_cast<uint32_t>(hn::CountTrue(du, any));
      if constexpr (kMulti) {
        hn::Store(sample_bits(du, samples, passed), du, user_mask + i);
      } else {
        hn::Store(hn::IfThenElseZero(any, hn::Set(du, 1u)), du, user_mask + i);
      }
      user_any = true;
    } else if constexpr (kColor != ColorMode::kOff && kShader != shade::Shader::kGouraud) {
      const auto any = pass_one;
      if (hn::AllFalse(du, any)) continue;
      if constexpr (kCount) st.shaded += static_cast<uint32_t>(hn::CountTrue(du, any));
      // The lanes' pixel offsets from the plane origin (the centre of pixel (t.x0, t.y0)), and
      // each lane's first passing sample's offsets for pixels beyond the triangle's horizon.
      const auto x = hn::Add(fx, hn::Set(df, static_cast<float>(bx * 8 - t.x0)));
      const auto y = hn::Add(fy, hn::Set(df, static_cast<float>(by * 8 - t.y0)));
      const auto first_sample = [&](hn::Vec<decltype(df)>& sx, hn::Vec<decltype(df)>& sy) {
        sx = hn::Zero(df);
        sy = hn::Zero(df);
        for (uint32_t s = samples; s-- > 0;) {
          const auto m = hn::RebindMask(df, kMulti ? passed(s) : any);
          sx = hn::IfThenElse(m, hn::Set(df, tc.sample_fx[s]), sx);
          sy = hn::IfThenElse(m, hn::Set(df, tc.sample_fy[s]), sy);
        }
      };
      hn::Vec<decltype(df)> r, g, b, a;
      shade::HWY_NAMESPACE::shade_fragments<kShader>(
          df, *tc.layout, {t.q0, t.q_dx, t.q_dy, t.flat_q != 0, st.planes, t.x0, t.y0}, x, y,
          hn::RebindMask(df, any), first_sample, r, g, b, a);
      store_colour<kColor, kMulti, true>(df, tc, block, i, samples, any, passed, r, g, b, a);
    } else if constexpr (kColor != ColorMode::kOff) {
      // The passing lanes themselves (multisample: of any sample), not a bit set built from
      // them and tested again (a shorter chain ahead of the branch below).
      const auto any = pass_one;
      if (hn::AllFalse(du, any)) continue;
      if constexpr (kCount) st.shaded += static_cast<uint32_t>(hn::CountTrue(du, any));
      PlaneOffsets* const po = st.offsets;
      auto r = plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? po->qa[0] + i : nullptr, qa_base[0],
                                        t.qa_dx[0], t.qa_dy[0]);
      auto g = plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? po->qa[1] + i : nullptr, qa_base[1],
                                        t.qa_dx[1], t.qa_dy[1]);
      auto b = plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? po->qa[2] + i : nullptr, qa_base[2],
                                        t.qa_dx[2], t.qa_dy[2]);
      auto a = plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? po->qa[3] + i : nullptr, qa_base[3],
                                        t.qa_dx[3], t.qa_dy[3]);
      if (!t.flat_q) {
        const auto q = plane_of_lanes<kOffsets>(df, fx, fy, kOffsets ? po->q + i : nullptr, q_base,
                                                t.q_dx, t.q_dy);
        const auto inv_q = hn::Div(hn::Set(df, 1.0f), q);
        r = hn::Mul(r, inv_q);
        g = hn::Mul(g, inv_q);
        b = hn::Mul(b, inv_q);
        a = hn::Mul(a, inv_q);
        const auto beyond = hn::AndNot(hn::Gt(q, hn::Zero(df)), hn::RebindMask(df, any));
        if (!hn::AllFalse(df, beyond)) {
          // The pixel centre lies beyond the triangle's horizon (1/w <= 0 there): evaluate
          // at the pixel's first passing sample instead, which is inside the triangle.
          alignas(64) float channel[4][64];
          alignas(64) uint32_t passing[64];
          store_channels(df, r, g, b, a, channel);
          if constexpr (kMulti) {
            hn::Store(sample_bits(du, samples, passed), du, passing);
          } else {
            hn::Store(hn::IfThenElseZero(any, hn::Set(du, 1u)), du, passing);
          }
          for (size_t l = 0; l < lanes; ++l) {
            const float lx = kPixels.fx[i + l], ly = kPixels.fy[i + l];
            if (passing[l] == 0 || q_base + (t.q_dx * lx + t.q_dy * ly) > 0.0f) continue;
            uint32_t s = 0;
            while (!(passing[l] & (1u << s)))
              ++s;
            const float sx = lx + tc.sample_fx[s], sy = ly + tc.sample_fy[s];
            const float qs = q_base + (t.q_dx * sx + t.q_dy * sy);
            for (int c = 0; c < 4; ++c) {
              channel[c][l] = (qa_base[c] + (t.qa_dx[c] * sx + t.qa_dy[c] * sy)) / qs;
            }
          }
          load_channels(df, channel, r, g, b, a);
        }
      }
      // One sample: RGBA8 without the clamp where packs_without_clamp allows.
      if (!kMulti && packs_without_clamp(t)) {
        store_colour<kColor, kMulti, false>(df, tc, block, i, samples, any, passed, r, g, b, a);
      } else {
        store_colour<kColor, kMulti, true>(df, tc, block, i, samples, any, passed, r, g, b, a);
      }
    }
  }
  if constexpr (kUser) {
    if (user_any) {
      shade_user_block(tc, t, st.planes, bx, by, block, user_mask, kUserDepth ? user_z : nullptr);
    }
  } else if constexpr (kDepth == DepthMode::kTestWrite) {
    // The block's depth changed: its Hi-Z bounds are recomputed when next needed.
    if (wrote) mark_hiz_dirty(tc, block);
  }
}

// raster_block out of line, for the general path: one copy of the block code for all its block
// loops (small triangles inline theirs); next to a block's 64 pixels the call costs little.
// With and without the sub-block tests: a copy of its own for each, as the tests in the lane
// loop, even skipped, cost the loop without them 1-3% (benchmarks/RESULTS.md decision 10).
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          bool kSubBlocks, class VI>
HWY_NOINLINE void raster_block_outlined(const TileContext& tc, const TriangleSetup& t,
                                        TriangleState& st, VI lane_e0, VI lane_e1, VI lane_e2,
                                        int32_t bx, int32_t by, const int32_t* e_block,
                                        uint32_t edge_mask, bool wide, bool test_depth) {
  raster_block<kDepth, kColor, kShader, kMulti, kCount, kSubBlocks, true>(
      tc, t, st, lane_e0, lane_e1, lane_e2, bx, by, e_block, edge_mask, wide, test_depth);
}

// What the general path's block tests share for one triangle.
struct BlockTests {
  // An edge's largest and smallest change over a block's sample area from its corner, and its
  // change from one block to the next in x and y.
  int64_t max_offset[3], min_offset[3], step_bx[3], step_by[3];
  int64_t corner_to_centre;  // from the corner of a pixel's sample area to its centre
  // The depth plane's range over a block's sample area from its corner, and the margin that
  // covers the kernel's float rounding; the plane's change from one block to the next in x and
  // y; the triangle's depth range widened by the margin.
  double z_lo_offset, z_hi_offset, z_margin;
  double z_step_bx, z_step_by;
  double z_floor, z_ceil;
};

// A block that passed the corner test, with the edges crossing it in edge_mask (block_corner:
// the edges' values at the corner of its sample area; z_corner: the depth plane's there):
// counted, then Hi-Z, then rasterized.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          class VI>
HWY_INLINE void visit_block(const TileContext& tc, const TriangleSetup& t, TriangleState& st,
                            const BlockTests& bt, Counters& counters, VI lane_e0, VI lane_e1,
                            VI lane_e2, int32_t bx, int32_t by, const int64_t* block_corner,
                            double z_corner, uint32_t edge_mask) {
  if constexpr (kCount) {
    if (edge_mask == 0) {
      ++counters.blocks_accepted;
    } else {
      ++counters.blocks_partial;
    }
  }

  bool test_depth = kDepth == DepthMode::kTest || kDepth == DepthMode::kTestWrite;
  if (tc.hiz) {
    const size_t block = tile_block(bx, by, st.tile_bx, st.tile_by);
    const bool clipped_block =
        bx * 8 + 7 > tc.x1 || by * 8 + 7 > tc.y1 || bx * 8 < tc.x0 || by * 8 < tc.y0;
    float lo, hi;
    hiz_range(tc, std::max(z_corner + bt.z_lo_offset, bt.z_floor),
              std::min(z_corner + bt.z_hi_offset, bt.z_ceil), lo, hi);
    const HizVerdict verdict = block_hiz_verdict(tc, block, st.samples, lo, hi);
    if (verdict == HizVerdict::kReject) {
      if constexpr (kCount) ++counters.hiz_rejected;
      return;
    }
    if (verdict == HizVerdict::kAccept && edge_mask == 0 && !clipped_block) {
      if constexpr (kCount) ++counters.hiz_accepted;
      test_depth = false;  // every sample passes: write without reading
    }
  }

  const bool wide = edge_mask != 0 && !t.narrow;
  int32_t e_block[3] = {0, 0, 0};  // at the centre of the block's first pixel
  for (int e = 0; e < 3; ++e) {
    // Only edges crossing the block are stepped; they fit 32 bits (block_kernel.hpp).
    if (!wide && (edge_mask & (1u << e))) {
      e_block[e] =
          static_cast<int32_t>(block_corner[e] + (int64_t{t.a[e]} + t.b[e]) * bt.corner_to_centre);
    }
  }
  if (tc.sub_blocks) {
    raster_block_outlined<kDepth, kColor, kShader, kMulti, kCount, true>(
        tc, t, st, lane_e0, lane_e1, lane_e2, bx, by, e_block, edge_mask, wide, test_depth);
  } else {
    raster_block_outlined<kDepth, kColor, kShader, kMulti, kCount, false>(
        tc, t, st, lane_e0, lane_e1, lane_e2, bx, by, e_block, edge_mask, wide, test_depth);
  }
}

// The blocks from (bx_begin, by_begin) to (bx_end, by_end) (inclusive). With `classify`, each
// takes the corner test, stepped from block to block from `corner` (the edges' values at the
// first block's corner): blocks outside an edge are rejected, the others visited. Without, all
// are inside every edge (a coarse block's verdict) and visited untested.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          class VI>
HWY_INLINE void visit_blocks(const TileContext& tc, const TriangleSetup& t, TriangleState& st,
                             const BlockTests& bt, Counters& counters, VI lane_e0, VI lane_e1,
                             VI lane_e2, int32_t bx_begin, int32_t by_begin, int32_t bx_end,
                             int32_t by_end, const int64_t* corner, bool classify) {
  int64_t corner_row[3] = {corner[0], corner[1], corner[2]};
  // The depth plane at the corner of the first block's sample area, stepped like the edges
  // (double: the rounding of a few hundred steps is far below the Hi-Z margin).
  double z_row =
      t.z0 + t.z_dx * (bx_begin * 8.0 - t.x0 - 0.5) + t.z_dy * (by_begin * 8.0 - t.y0 - 0.5);
  for (int32_t by = by_begin; by <= by_end; ++by) {
    int64_t block_corner[3] = {corner_row[0], corner_row[1], corner_row[2]};
    double z_corner = z_row;
    for (int e = 0; e < 3; ++e)
      corner_row[e] += bt.step_by[e];
    z_row += bt.z_step_by;
    for (int32_t bx = bx_begin; bx <= bx_end; ++bx) {
      uint32_t edge_mask = 0;
      bool rejected = false;
      if (classify) {
        for (int e = 0; e < 3; ++e) {
          rejected |= block_corner[e] + bt.max_offset[e] < 0;
          edge_mask |= block_corner[e] + bt.min_offset[e] < 0 ? 1u << e : 0u;
        }
      }
      if (rejected) {
        if constexpr (kCount) ++counters.blocks_rejected;
      } else {
        visit_block<kDepth, kColor, kShader, kMulti, kCount>(tc, t, st, bt, counters, lane_e0,
                                                             lane_e1, lane_e2, bx, by, block_corner,
                                                             z_corner, edge_mask);
      }
      for (int e = 0; e < 3; ++e)
        block_corner[e] += bt.step_bx[e];
      z_corner += bt.z_step_bx;
    }
  }
}

// The general path at block size 16 or 32: coarse blocks of n x n blocks (n = 2 or 4), counted
// from the triangle's first block in this tile and cut at its last, take the same corner test
// first, over their own sample area, which holds their blocks' sample areas: outside an edge
// there, every block inside is outside it (all rejected, none visited); inside all three, every
// block inside is too (all accepted, no test each). Only the blocks of a partial coarse block
// are tested one by one. So every block is rejected, accepted or partial, counted and drawn
// exactly as at block size 8, only in another order, which changes nothing: a triangle's
// blocks are disjoint. Out of line, with one copy of the block loop, which block size 8 does
// not run.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          class VI>
HWY_NOINLINE void raster_coarse(const TileContext& tc, const TriangleSetup& t, TriangleState& st,
                                const BlockTests& bt, Counters& counters, VI lane_e0, VI lane_e1,
                                VI lane_e2, int32_t bx0, int32_t by0, int32_t bx1, int32_t by1,
                                const int64_t* corner) {
  const int shift = static_cast<int>(tc.subpixel_bits) - 4;
  const int32_t n = static_cast<int32_t>(tc.coarse_blocks);
  int64_t coarse_row[3] = {corner[0], corner[1], corner[2]};
  for (int32_t cy = by0; cy <= by1; cy += n) {
    const int32_t cy1 = std::min(cy + n - 1, by1);
    int64_t coarse[3] = {coarse_row[0], coarse_row[1], coarse_row[2]};
    for (int e = 0; e < 3; ++e)
      coarse_row[e] += bt.step_by[e] * n;
    for (int32_t cx = bx0; cx <= bx1; cx += n) {
      const int32_t cx1 = std::min(cx + n - 1, bx1);
      int64_t coarse_corner[3] = {coarse[0], coarse[1], coarse[2]};
      for (int e = 0; e < 3; ++e)
        coarse[e] += bt.step_bx[e] * n;
      // The coarse block's sample area: cx1 - cx + 1 blocks across, cy1 - cy + 1 down.
      const int64_t span_x = (int64_t{cx1 - cx + 1} * 128 - 1) << shift;
      const int64_t span_y = (int64_t{cy1 - cy + 1} * 128 - 1) << shift;
      bool outside = false, inside = true;
      for (int e = 0; e < 3; ++e) {
        const int64_t a_span = t.a[e] * span_x, b_span = t.b[e] * span_y;
        const int64_t c = coarse_corner[e];
        outside |= c + std::max<int64_t>(a_span, 0) + std::max<int64_t>(b_span, 0) < 0;
        inside &= c + std::min<int64_t>(a_span, 0) + std::min<int64_t>(b_span, 0) >= 0;
      }
      if (outside) {
        if constexpr (kCount) {
          counters.blocks_rejected += static_cast<uint64_t>((cx1 - cx + 1) * (cy1 - cy + 1));
        }
        continue;
      }
      // Partial: its blocks take their own tests; inside every edge: none.
      visit_blocks<kDepth, kColor, kShader, kMulti, kCount>(tc, t, st, bt, counters, lane_e0,
                                                            lane_e1, lane_e2, cx, cy, cx1, cy1,
                                                            coarse_corner, !inside);
    }
  }
}

// The triangle's state in this tile, as both paths set it up.
// kSmall: the small path's triangles, all narrow (edges under 32 px: |a| + |b| < 2^(bits + 6),
// within the narrow bound 2^(28 - bits) for 4 to 8 bits): their steps are set without a branch
// on t.narrow (fewer instructions per triangle, measured with callgrind).
template <bool kMulti, bool kSmall>
HWY_INLINE void set_up_state(const TileContext& tc, const TriangleSetup& t, TriangleState& st) {
  const uint32_t bits = tc.subpixel_bits;
  const bool narrow = kSmall || t.narrow;
  st.samples = kMulti ? tc.samples : 1;
  st.px0 = std::max(t.x0, tc.x0);
  st.px1 = std::min(t.x1, tc.x1);
  st.py0 = std::max(t.y0, tc.y0);
  st.py1 = std::min(t.y1, tc.y1);
  st.tile_bx = tc.tile_x0 >> 3;
  st.tile_by = tc.tile_y0 >> 3;
  for (int e = 0; e < 3; ++e) {
    // Only narrow triangles step edges in int32 (|a| << bits < 2^28); the wide path reads
    // coverage bits computed in int64 instead.
    st.step_x[e] = narrow ? t.a[e] * (1 << bits) : 0;
    st.step_y[e] = narrow ? t.b[e] * (1 << bits) : 0;
  }
  const hn::CappedTag<int32_t, 16> di;
  if (kMulti && narrow && hn::Lanes(di) >= 4) {
    // A row of four lanes per sample, edges 0 to 2 and one unused: a's lanes hold a[0..2] and
    // b[0], b's b[0..2] and x0 (the unused lane's value is never read). The same integer
    // products and sums as below (`small` at four samples 0.96x to 0.98x the time).
    static_assert(offsetof(TriangleSetup, b) == offsetof(TriangleSetup, a) + 12 &&
                  offsetof(TriangleSetup, x0) == offsetof(TriangleSetup, b) + 12);
    const auto a = hn::LoadDup128(di, t.a.data());
    const auto b = hn::LoadDup128(di, t.b.data());
    const uint32_t per = static_cast<uint32_t>(hn::Lanes(di) / 4);  // samples per vector
    for (uint32_t s = 0; s < st.samples; s += per) {
      const auto offset = hn::Add(hn::Mul(a, hn::LoadU(di, tc.sample_x4.data() + 4 * s)),
                                  hn::Mul(b, hn::LoadU(di, tc.sample_y4.data() + 4 * s)));
      hn::StoreU(hn::Sub(hn::Set(di, -1), offset), di, &st.edge_threshold[s][0]);
    }
  } else {
    for (uint32_t s = 0; s < st.samples; ++s) {
      for (int e = 0; e < 3; ++e) {
        const int32_t offset =
            kMulti && narrow ? t.a[e] * tc.sample_x[s] + t.b[e] * tc.sample_y[s] : 0;
        st.edge_threshold[s][e] = -1 - offset;
      }
    }
  }
  if constexpr (kMulti) {
    const hn::CappedTag<float, 16> df;
    for (uint32_t s = 0; s < st.samples; s += static_cast<uint32_t>(hn::Lanes(df))) {
      hn::StoreU(hn::Add(hn::Mul(hn::Set(df, t.z_dx), hn::LoadU(df, tc.sample_fx.data() + s)),
                         hn::Mul(hn::Set(df, t.z_dy), hn::LoadU(df, tc.sample_fy.data() + s))),
                 df, st.z_offset + s);
    }
  } else {
    st.z_offset[0] = 0.0f;
  }
}

// What the general path's sub-block tests need (after set_up_state).
HWY_INLINE void set_up_sub_blocks(TriangleState& st) {
  // Sub-blocks are lane groups: lanes / 8 rows of 8 pixels, or the first `lanes` pixels of a
  // row on targets with fewer than 8 lanes.
  const int32_t lanes = static_cast<int32_t>(hn::Lanes(hn::ScalableTag<int32_t>()));
  const int32_t sub_cols = std::min(lanes, 8) - 1, sub_rows = std::max(lanes / 8, 1) - 1;
  for (int e = 0; e < 3; ++e) {
    st.threshold_lo[e] = st.threshold_hi[e] = st.edge_threshold[0][e];
    for (uint32_t s = 1; s < st.samples; ++s) {
      st.threshold_lo[e] = std::min(st.threshold_lo[e], st.edge_threshold[s][e]);
      st.threshold_hi[e] = std::max(st.threshold_hi[e], st.edge_threshold[s][e]);
    }
    const int32_t dx = st.step_x[e] * sub_cols, dy = st.step_y[e] * sub_rows;
    st.sub_lo[e] = std::min(dx, 0) + std::min(dy, 0);
    st.sub_hi[e] = std::max(dx, 0) + std::max(dy, 0);
  }
}

// An edge's change from a lane group's first pixel to each lane's pixel, in column lane_col and
// row kPixels.y of the group.
template <class DI>
HWY_INLINE hn::Vec<DI> lane_steps(DI di, hn::Vec<DI> lane_col, int32_t step_x, int32_t step_y) {
  return hn::Add(hn::Mul(lane_col, hn::Set(di, step_x)),
                 hn::Mul(hn::Load(di, kPixels.y), hn::Set(di, step_y)));
}
// The same for a block's lanes (row-major).
template <class DI>
HWY_INLINE hn::Vec<DI> lane_steps(DI di, int32_t step_x, int32_t step_y) {
  return lane_steps(di, hn::Load(di, kPixels.x), step_x, step_y);
}

// Whether Hi-Z rejects triangle t's whole depth range (triangle_hiz_range) at every block of its
// box in this tile, with `samples` samples per pixel.
HWY_INLINE bool hidden_in_tile(const TileContext& tc, const TriangleSetup& t, uint32_t samples) {
  float lo, hi;
  triangle_hiz_range(tc, t, lo, hi);
  const int32_t bx0 = std::max(t.x0, tc.x0) >> 3, bx1 = std::min(t.x1, tc.x1) >> 3;
  const int32_t by0 = std::max(t.y0, tc.y0) >> 3, by1 = std::min(t.y1, tc.y1) >> 3;
  const int32_t tile_bx = tc.tile_x0 >> 3, tile_by = tc.tile_y0 >> 3;
  for (int32_t by = by0; by <= by1; ++by) {
    for (int32_t bx = bx0; bx <= bx1; ++bx) {
      const size_t block = tile_block(bx, by, tile_bx, tile_by);
      if (block_hiz_verdict(tc, block, samples, lo, hi) != HizVerdict::kReject) return false;
    }
  }
  return true;
}

// RasterTriangle's general path, for triangles that are not small: out of line, with a state of
// its own. In one function with the small-triangle path, sharing its state (whose address the
// general path passes to raster_block_outlined), it made that path, which most triangles of a
// dense mesh take, 3-4% slower.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount>
HWY_NOINLINE void raster_general(const TileContext& tc, const TriangleSetup& t, const float* planes,
                                 Counters& counters) {
  // Without counters: a triangle behind every block of its box in this tile is dropped before
  // any block test. Its depth range over the whole triangle holds each block's range, so each
  // block would have been rejected by its corner test or by Hi-Z, with nothing written (the
  // counting kernels take the block tests, whose counts the early verdict would change).
  if (!kCount && tc.hiz && hidden_in_tile(tc, t, kMulti ? tc.samples : 1)) return;
  const hn::ScalableTag<int32_t> di;
  const int shift = static_cast<int>(tc.subpixel_bits) - 4;
  TriangleState st;
  set_up_state<kMulti, false>(tc, t, st);
  st.planes = planes;
  if (tc.sub_blocks) set_up_sub_blocks(st);
  PlaneOffsets offsets;
  st.offsets = &offsets;
  const auto lane_e0 = lane_steps(di, st.step_x[0], st.step_y[0]);
  const auto lane_e1 = lane_steps(di, st.step_x[1], st.step_y[1]);
  const auto lane_e2 = lane_steps(di, st.step_x[2], st.step_y[2]);
  const int32_t bx0 = st.px0 >> 3, by0 = st.py0 >> 3, bx1 = st.px1 >> 3, by1 = st.py1 >> 3;

  // Block classification, stepped from block to block. A block's sample area spans
  // [x_lo, x_lo + span] in fixed point (pixel x holds samples from x + 0/16 to x + 15/16),
  // so an edge's largest and smallest values over it are E(x_lo, y_lo) plus the positive or
  // negative parts of a * span and b * span (Abrash 2009).
  const int64_t span = int64_t{7 * 16 + 15} << shift;
  const int64_t block_step = int64_t{8 * 16} << shift;
  BlockTests bt;
  int64_t corner[3];  // at the first block
  for (int e = 0; e < 3; ++e) {
    corner[e] = t.a[e] * (bx0 * block_step) + t.b[e] * (by0 * block_step) + t.c[e];
    bt.max_offset[e] = std::max<int64_t>(t.a[e] * span, 0) + std::max<int64_t>(t.b[e] * span, 0);
    bt.min_offset[e] = std::min<int64_t>(t.a[e] * span, 0) + std::min<int64_t>(t.b[e] * span, 0);
    bt.step_bx[e] = t.a[e] * block_step;
    bt.step_by[e] = t.b[e] * block_step;
  }
  bt.corner_to_centre = int64_t{8} << shift;
  // Depth over a block's sample area (pixel coordinates relative to the plane origin, the
  // centre of pixel (x0, y0)), widened by a margin that covers the kernel's float rounding.
  bt.z_margin = hiz_margin(t);
  bt.z_lo_offset = std::min(0.0, 8.0 * t.z_dx) + std::min(0.0, 8.0 * t.z_dy) - bt.z_margin;
  bt.z_hi_offset = std::max(0.0, 8.0 * t.z_dx) + std::max(0.0, 8.0 * t.z_dy) + bt.z_margin;
  bt.z_step_bx = 8.0 * t.z_dx;
  bt.z_step_by = 8.0 * t.z_dy;
  bt.z_floor = t.z_min - bt.z_margin;
  bt.z_ceil = t.z_max + bt.z_margin;

  if (tc.coarse_blocks == 1) {
    visit_blocks<kDepth, kColor, kShader, kMulti, kCount>(
        tc, t, st, bt, counters, lane_e0, lane_e1, lane_e2, bx0, by0, bx1, by1, corner, true);
  } else {
    raster_coarse<kDepth, kColor, kShader, kMulti, kCount>(
        tc, t, st, bt, counters, lane_e0, lane_e1, lane_e2, bx0, by0, bx1, by1, corner);
  }
  if constexpr (kCount) {
    counters.samples_covered += st.covered;
    counters.samples_passed += st.passed;
    counters.pixels_shaded += st.shaded;
    counters.subblocks_rejected += st.sub_rejected;
    counters.subblocks_accepted += st.sub_accepted;
    counters.subblocks_partial += st.sub_partial;
  }
}

// Small triangles (every edge under 32 px across) skip the corner classification: for the
// few blocks they touch, testing every edge costs less. Every sample of those blocks lies
// within 40 px of each vertex and |a|, |b| < 2^(bits+5), so |E| < 2^(2 bits + 12): all
// three edges step exactly in int32 from block to block. A block is skipped when an edge is
// negative at all its samples: its largest value over the block's pixel centres, plus half
// a pixel's change in x and y for the sample offsets (|offset| <= 1/2 px), is below zero.
// Sets each edge's value at the centre of block (bx0, by0)'s first pixel (e_block) and that
// margin (reach): a block is outside edge e when its e_block[e] + reach[e] < 0.
HWY_INLINE void small_block_edges(const TileContext& tc, const TriangleSetup& t,
                                  const TriangleState& st, int32_t bx0, int32_t by0,
                                  int32_t (&e_block)[3], int32_t (&reach)[3]) {
  const int shift = static_cast<int>(tc.subpixel_bits) - 4;
  const int64_t ox = (int64_t{bx0} * 128 + 8) << shift, oy = (int64_t{by0} * 128 + 8) << shift;
  for (int e = 0; e < 3; ++e) {
    e_block[e] = static_cast<int32_t>(t.a[e] * ox + t.b[e] * oy + t.c[e]);
    reach[e] = std::max(st.step_x[e] * 7, 0) + std::max(st.step_y[e] * 7, 0) +
               ((std::abs(st.step_x[e]) + std::abs(st.step_y[e])) >> 1);
  }
}

// The small-triangle path (RasterTriangle's), with kHiz its Hi-Z test per block.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount,
          bool kHiz>
HWY_INLINE void raster_small(const TileContext& tc, const TriangleSetup& t, const float* planes,
                             Counters& counters) {
  const hn::ScalableTag<int32_t> di;
  constexpr bool kTestDepth = kDepth == DepthMode::kTest || kDepth == DepthMode::kTestWrite;
  TriangleState st;
  set_up_state<kMulti, true>(tc, t, st);
  st.planes = planes;
  const auto lane_e0 = lane_steps(di, st.step_x[0], st.step_y[0]);
  const auto lane_e1 = lane_steps(di, st.step_x[1], st.step_y[1]);
  const auto lane_e2 = lane_steps(di, st.step_x[2], st.step_y[2]);
  const int32_t bx0 = st.px0 >> 3, by0 = st.py0 >> 3, bx1 = st.px1 >> 3, by1 = st.py1 >> 3;

  int32_t e_row[3], reach[3];
  small_block_edges(tc, t, st, bx0, by0, e_row, reach);
  // Hi-Z (kHiz): the triangle's whole depth range against each block's bounds.
  float hiz_lo = 0.0f, hiz_hi = 0.0f;
  if constexpr (kHiz) triangle_hiz_range(tc, t, hiz_lo, hiz_hi);
  uint64_t rejected = 0, visited = 0, hiz_rejected = 0;
  for (int32_t by = by0; by <= by1; ++by) {
    int32_t e_block[3] = {e_row[0], e_row[1], e_row[2]};
    for (int e = 0; e < 3; ++e)
      e_row[e] += st.step_y[e] * 8;
    for (int32_t bx = bx0; bx <= bx1; ++bx) {
      const bool outside =
          (e_block[0] + reach[0] < 0) | (e_block[1] + reach[1] < 0) | (e_block[2] + reach[2] < 0);
      ++visited;
      bool hidden = false;
      if (kHiz && !outside) {
        const size_t block = tile_block(bx, by, st.tile_bx, st.tile_by);
        hidden = block_hiz_verdict(tc, block, st.samples, hiz_lo, hiz_hi) == HizVerdict::kReject;
        hiz_rejected += hidden ? 1 : 0;
      }
      if (outside) {
        ++rejected;
      } else if (!hidden) {
        raster_block<kDepth, kColor, kShader, kMulti, kCount, false, false>(
            tc, t, st, lane_e0, lane_e1, lane_e2, bx, by, e_block, 7, false, kTestDepth);
      }
      for (int e = 0; e < 3; ++e)
        e_block[e] += st.step_x[e] * 8;
    }
  }
  if constexpr (kCount) {
    counters.blocks_rejected += rejected;
    counters.blocks_partial += visited - rejected;
    if constexpr (kHiz) counters.hiz_rejected += hiz_rejected;
    counters.samples_covered += st.covered;
    counters.samples_passed += st.passed;
    counters.pixels_shaded += st.shaded;
  }
}

// raster_small with Hi-Z, out of line: in the inlined small path, even skipped, its test made
// the smallest triangles 3-4% slower.
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount>
HWY_NOINLINE void raster_small_hiz(const TileContext& tc, const TriangleSetup& t,
                                   const float* planes, Counters& counters) {
  raster_small<kDepth, kColor, kShader, kMulti, kCount, true>(tc, t, planes, counters);
}

// m & (a > b) for int32 lanes: one compare under a mask on AVX-512 (a compare and a mask AND
// elsewhere).
template <class D>
HWY_INLINE hn::Mask<D> and_greater([[maybe_unused]] D d, hn::Mask<D> m, hn::Vec<D> a,
                                   hn::Vec<D> b) {
  static_assert(std::is_same_v<hn::TFromD<D>, int32_t>);
#if HWY_TARGET <= HWY_AVX3
  if constexpr (hn::MaxLanes(D()) == 16) {
    return hn::Mask<D>{_mm512_mask_cmpgt_epi32_mask(m.raw, a.raw, b.raw)};
  }
#endif
  return hn::And(m, hn::Gt(a, b));
}

// Whether a covered sample's depth may need the clamp to [0, 1] in raster_window. A covered
// sample lies in the triangle, where the depth plane lies between the vertices' depths; the
// lanes' float sums are within hiz_margin of the plane (the block base in double, then offsets
// of under 8 px; the gradients' float rounding over a small triangle's 40 px is below it too).
// With that room inside (0, 1) the clamp changes no covered lane, and is left out (`small` at
// four samples 0.95x to 0.98x the time, benchmarks/RESULTS.md decision 129).
HWY_INLINE bool window_depth_may_clamp(const TriangleSetup& t) {
  const double z_margin = hiz_margin(t);
  return !(t.z_min - z_margin > 0.0 && t.z_max + z_margin < 1.0);
}

// Whether raster_window's windows for triangle t in this tile span two blocks: the box (inside
// the tile) does not begin at a block's first column and reaches the next block.
HWY_INLINE bool window_spans_two_blocks(const TileContext& tc, const TriangleSetup& t) {
  const int32_t px0 = std::max(t.x0, tc.x0), px1 = std::min(t.x1, tc.x1);  // set_up_state's
  return (px0 & 7) != 0 && ((px0 >> 3) + 1) * 8 <= px1;
}

// The small path's lane groups at one sample or several, for an RGBA8 or no colour target:
// windows of 8 pixels across and lanes / 8 rows, at the bounding box's first column (not at a
// block's) and at an even row (every lanes / 8-th), so that a narrow box takes one window per
// row pair instead of one lane group per row pair in each block it touches (in a model of
// `small`'s triangles, 3.4 windows per triangle against 5.4 lane groups). The box is at most 8
// pixels wide (kWindowBox), so one window spans each row pair. A window whose first
// column is not a block's spans two blocks: the lanes in the first (`in_a`) read and write it at
// one address, the others the next block at another, each a masked load and store. Every lane's
// values are raster_block's for its pixel and sample (its own block's plane bases, then the offsets
// to the sample in that block), and the counters are raster_small's, so the bytes and counts are
// the same. Targets with 8 or 16 lanes.
//
// kTwo: the windows span two blocks (window_spans_two_blocks), one copy of the loop for each
// case, so that a box inside one block column reads its depth with one unmasked load of the
// window's aligned line and writes under the pass mask alone, with no per-window choice
// between one block and two (`small` about 0.97x the time at one sample and at four,
// benchmarks/RESULTS.md decision 164).
//
// kSimple: one sample or four, q flat (t.flat_q), the depth buffer float and no covered
// sample's depth needing the clamp (window_depth_may_clamp), so the loop holds no perspective
// division, depth rounding or clamp, and at four samples its sample loops unroll. At one sample
// the colour needs no clamp either (packs_without_clamp), and RGBA8 packs without it. Such
// triangles take this copy: `small` about 0.93x the time at four samples; at one about 0.99x,
// then 0.95x of that without the colour clamp (benchmarks/RESULTS.md decisions 165, 167 and
// 168). Other sample counts do not, as two samples with copies of their own made four samples
// 1.02x to 1.03x slower.
template <DepthMode kDepth, ColorMode kColor, bool kMulti, bool kCount, bool kTwo, bool kSimple,
          class Compare>
HWY_INLINE void raster_window(const TileContext& tc, const TriangleSetup& t, Counters& counters,
                              [[maybe_unused]] Compare compare) {
  static_assert(kColor != ColorMode::kRGBA32F, "windows write RGBA8 colour");
  const hn::ScalableTag<int32_t> di;
  const hn::ScalableTag<uint32_t> du;
  const hn::ScalableTag<float> df;
  const int32_t rows = static_cast<int32_t>(hn::Lanes(di) / 8);  // 1 or 2
  const int shift = static_cast<int>(tc.subpixel_bits) - 4;
  const uint32_t samples = kMulti ? (kSimple ? 4 : tc.samples) : 1;
  TriangleState st;
  set_up_state<kMulti, true>(tc, t, st);
  const int32_t px0 = st.px0, px1 = st.px1, py1 = st.py1;
  const int32_t first_col = px0 & 7;
  // Lane (row k, column c) is the pixel in column c of its block and row wy + k: of block a
  // (the box's first) from column first_col on, of block b (the next) before it. So each
  // block's lanes lie where its two rows lie in memory, in one aligned cache line (lanes in
  // the box's order from its first column made each masked access span two lines). col: a
  // lane's column counted from the box's first, (c - first_col) mod 8.
  const auto col =
      hn::And(hn::Sub(hn::Load(di, kPixels.x), hn::Set(di, first_col)), hn::Set(di, 7));
  const auto row = hn::Load(di, kPixels.y);
  const auto lane_e0 = lane_steps(di, col, st.step_x[0], st.step_y[0]);
  const auto lane_e1 = lane_steps(di, col, st.step_x[1], st.step_y[1]);
  const auto lane_e2 = lane_steps(di, col, st.step_x[2], st.step_y[2]);
  // Multisample: the edges' smallest thresholds over the samples, for a window's first test
  // (whether any sample of it is covered).
  constexpr int32_t kNone = std::numeric_limits<int32_t>::max();
  alignas(64) int32_t threshold_lo[16] = {kNone, kNone, kNone};
  const hn::CappedTag<int32_t, 16> d16;
  if (kMulti && hn::Lanes(d16) >= 4) {
    // set_up_state's rows of four lanes: their minimum, then the minimum of the 128-bit blocks
    // (one row each).
    const uint32_t per = static_cast<uint32_t>(hn::Lanes(d16) / 4);
    auto lo = hn::Set(d16, kNone);
    for (uint32_t s = 0; s < samples; s += per) {
      const auto sample_rows = hn::LoadU(d16, &st.edge_threshold[s][0]);
      lo = hn::Min(
          lo, hn::IfThenElse(hn::FirstN(d16, 4 * (samples - s)), sample_rows, hn::Set(d16, kNone)));
    }
    lo = hn::Min(lo, hn::SwapAdjacentBlocks(lo));
    lo = hn::Min(lo, hn::ReverseBlocks(d16, lo));
    hn::Store(lo, d16, threshold_lo);
  } else {
    for (uint32_t s = 0; s < samples; ++s) {
      for (int e = 0; e < 3; ++e)
        threshold_lo[e] = std::min(threshold_lo[e], st.edge_threshold[s][e]);
    }
  }
  const auto cols_in = hn::Lt(col, hn::Set(di, px1 - px0 + 1));
  const auto in_a = hn::Lt(col, hn::Set(di, 8 - first_col));
  const auto in_a_f = hn::RebindMask(df, in_a);
  const auto in_b_f = hn::Not(in_a_f);
  // The lanes' pixel coordinates in their own block (fy without the window's row in it).
  const auto fx = hn::Load(df, kPixels.fx);
  const auto fy_lane = hn::Load(df, kPixels.fy);

  const int32_t wy0 = st.py0 & ~(rows - 1);
  const int64_t ox = (int64_t{px0} * 16 + 8) << shift, oy = (int64_t{wy0} * 16 + 8) << shift;
  int32_t e_row[3];
  for (int e = 0; e < 3; ++e)
    e_row[e] = static_cast<int32_t>(t.a[e] * ox + t.b[e] * oy + t.c[e]);
  const float depth_scale = kSimple ? 0.0f : tc.depth_scale;
  const bool clamp = !kSimple && window_depth_may_clamp(t);
  // The windows' blocks: a, and b to its right when some lane of the box lies there; their
  // first pixels' offsets from the plane origin in x.
  const int32_t window_bx = px0 >> 3;
  constexpr bool two = kTwo;
  HWY_DASSERT(two == window_spans_two_blocks(tc, t));
  const double dx = window_bx * 8.0 - t.x0;
  // What every window repeats, formed once: the gradients (read here, not through `t` in the
  // loop, where the compiler must assume the depth and colour stores may change them) and
  // their products with the lanes' columns, fx * gx, the first term of each plane's sum
  // (`small` about 0.98x the time at one sample and at four, benchmarks/RESULTS.md decision 153).
  const float z_dx = t.z_dx, z_dy = t.z_dy;
  const auto z_col = hn::Mul(fx, hn::Set(df, z_dx));
  const float qa_gy[4] = {t.qa_dy[0], t.qa_dy[1], t.qa_dy[2], t.qa_dy[3]};
  // (Four vectors, not an array: sizeless vector types cannot be array elements.)
  const auto col_r = hn::Mul(fx, hn::Set(df, t.qa_dx[0]));
  const auto col_g = hn::Mul(fx, hn::Set(df, t.qa_dx[1]));
  const auto col_b = hn::Mul(fx, hn::Set(df, t.qa_dx[2]));
  const auto col_a = hn::Mul(fx, hn::Set(df, t.qa_dx[3]));
  // The planes' bases at the windows' blocks depend only on the block row: formed when a window
  // of a new block row first needs them, and kept for the next windows of that row.
  int32_t z_row = -1, colour_row = -1;  // the block row whose bases are held (none: -1)
  float za = 0.0f, zb = 0.0f;
  float qa_a[4] = {}, qa_b[4] = {}, q_a = 0.0f, q_b = 0.0f;

  for (int32_t wy = wy0; wy <= py1; wy += rows) {
    const auto e0 = hn::Add(hn::Set(di, e_row[0]), lane_e0);
    const auto e1 = hn::Add(hn::Set(di, e_row[1]), lane_e1);
    const auto e2 = hn::Add(hn::Set(di, e_row[2]), lane_e2);
    for (int e = 0; e < 3; ++e)
      e_row[e] += st.step_y[e] * rows;
    const int32_t by = wy >> 3, r = wy & 7;
    const auto fy = hn::Add(fy_lane, hn::Set(df, static_cast<float>(r)));
    // Rows from the box's first (py0: a window may begin a row above it) to its last.
    const auto box = hn::And(cols_in, hn::And(hn::Lt(row, hn::Set(di, py1 - wy + 1)),
                                              hn::Gt(row, hn::Set(di, st.py0 - wy - 1))));
    // Inside edge e at sample s when E > threshold (one sample: the only coverage).
    const auto covered = [&](const int32_t* threshold) {
      auto m = hn::And(box, hn::Gt(e0, hn::Set(di, threshold[0])));
      m = hn::And(m, hn::Gt(e1, hn::Set(di, threshold[1])));
      return hn::And(m, hn::Gt(e2, hn::Set(di, threshold[2])));
    };
    const auto cov_any = covered(threshold_lo);
    // A sample's coverage, inside cov_any: fewer operations, in a longer chain (the samples'
    // chains are independent of one another).
    const auto sample_covered = [&](const int32_t* threshold) {
      auto m = and_greater(di, cov_any, e0, hn::Set(di, threshold[0]));
      m = and_greater(di, m, e1, hn::Set(di, threshold[1]));
      return and_greater(di, m, e2, hn::Set(di, threshold[2]));
    };
    if (hn::AllFalse(di, cov_any)) continue;

    const size_t block_a = tile_block(window_bx, by, st.tile_bx, st.tile_by);
    const size_t block_b = block_a + 1;
    const size_t at_a = block_a * 64 + static_cast<size_t>(r * 8);
    const size_t at_b = block_b * 64 + static_cast<size_t>(r * 8);
    // A plane's bases at the two blocks' first pixels, lane by lane (raster_block's).
    const auto bases = [&](float a_base, float b_base) {
      return two ? hn::IfThenElse(in_a_f, hn::Set(df, a_base), hn::Set(df, b_base))
                 : hn::Set(df, a_base);
    };

    // Multisample: which lanes each sample passed, kept (keep) and read back (passed) as one
    // mask per sample (`small` at four samples 0.95x the time of a vector of lane bits).
    // Sizeless-vector targets (SVE), whose masks cannot be array elements, keep the bits.
#if HWY_HAVE_SCALABLE
    auto pass_bits = hn::Zero(du);  // bit s: sample s passed
    const auto keep = [&](uint32_t s, auto pass) {
      pass_bits =
          hn::Or(pass_bits, hn::IfThenElseZero(hn::RebindMask(du, pass), hn::Set(du, 1u << s)));
    };
    const auto passed = [&](uint32_t s) {
      return hn::RebindMask(df, hn::TestBit(pass_bits, hn::Set(du, 1u << s)));
    };
#else
    hn::Mask<decltype(df)> pass_masks[16];
    const auto keep = [&](uint32_t s, auto pass) { pass_masks[s] = hn::RebindMask(df, pass); };
    const auto passed = [&](uint32_t s) { return pass_masks[s]; };
#endif
    // The one sample's passing lanes (its coverage until the depth test); multisample: the lanes
    // where any sample passed, gathered from none.
    auto pass_one = hn::RebindMask(df, cov_any);
    if constexpr (kMulti) pass_one = hn::FirstN(df, 0);
    if constexpr (kCount && !kMulti)
      st.covered += static_cast<uint32_t>(hn::CountTrue(di, cov_any));
    if constexpr (kDepth != DepthMode::kOff) {
      if (by != z_row) {
        z_row = by;
        const double dy = by * 8.0 - t.y0;
        za = static_cast<float>(t.z0 + t.z_dx * dx + t.z_dy * dy);
        zb = static_cast<float>(t.z0 + t.z_dx * (dx + 8.0) + t.z_dy * dy);
      }
      const auto z_rel = hn::Add(z_col, hn::Mul(fy, hn::Set(df, z_dy)));
      // Sample s's stored values at the lanes' pixels.
      const auto load_plane = [&](uint32_t s) {
        const float* const plane = tc.depth + s * kSamplePlane;
        // One block: the box's lanes are all in it (in_a), in one aligned line.
        if constexpr (!two) return hn::Load(df, plane + at_a);
        const auto v = hn::MaskedLoad(in_a_f, df, plane + at_a);
        return hn::IfThenElse(in_a_f, v, hn::MaskedLoad(in_b_f, df, plane + at_b));
      };
      const auto test_sample = [&](uint32_t s, auto stored) {
        auto pass = pass_one;
        if constexpr (kMulti) {
          pass = hn::RebindMask(df, sample_covered(st.edge_threshold[s]));
          if constexpr (kCount) st.covered += static_cast<uint32_t>(hn::CountTrue(df, pass));
        }
        auto z = hn::Add(kMulti ? bases(za + st.z_offset[s], zb + st.z_offset[s]) : bases(za, zb),
                         z_rel);
        if (clamp) z = hn::Min(hn::Max(z, hn::Zero(df)), hn::Set(df, 1.0f));
        if (depth_scale > 0.0f) z = hn::Round(hn::Mul(z, hn::Set(df, depth_scale)));
        float* const plane = tc.depth + s * kSamplePlane;
        pass = hn::And(pass, compare(df, z, stored));
        if constexpr (kDepth == DepthMode::kTestWrite) {
          if constexpr (two) {
            store_masked(z, hn::And(pass, in_a_f), df, plane + at_a);
            store_masked(z, hn::And(pass, in_b_f), df, plane + at_b);
          } else {
            store_masked(z, pass, df, plane + at_a, stored);  // stored: the whole line
          }
        }
        if constexpr (kCount) st.passed += static_cast<uint32_t>(hn::CountTrue(df, pass));
        if constexpr (kMulti) {
          keep(s, pass);
          pass_one = hn::Or(pass_one, pass);
        } else {
          pass_one = pass;
        }
      };
      // At two and four samples every plane is loaded before the first store: the planes lie
      // 16 KB apart, so a load from plane s + 1 issued after the store to plane s at the same
      // offset matches it in the low 12 address bits (4K aliasing). Measured on small: about
      // 0.88x the time at four samples, 0.95x at two (benchmarks/RESULTS.md decision 83).
      if (kMulti && samples == 2) {
        const auto v0 = load_plane(0), v1 = load_plane(1);
        test_sample(0, v0);
        test_sample(1, v1);
      } else if (kMulti && samples == 4) {
        const auto v0 = load_plane(0), v1 = load_plane(1), v2 = load_plane(2), v3 = load_plane(3);
        test_sample(0, v0);
        test_sample(1, v1);
        test_sample(2, v2);
        test_sample(3, v3);
      } else {
        for (uint32_t s = 0; s < samples; ++s)
          test_sample(s, load_plane(s));
      }
      if constexpr (kDepth == DepthMode::kTestWrite) {
        // Both blocks, whether or not a sample was written: no branch on the depth test (see
        // the colour below). A block marked without a change gets the same bounds when a Hi-Z
        // test recomputes them, so verdicts and counters are unchanged.
        mark_hiz_dirty(tc, block_a);
        if (two) mark_hiz_dirty(tc, block_b);
      }
    } else if constexpr (kMulti) {
      for (uint32_t s = 0; s < samples; ++s) {
        const auto pass = sample_covered(st.edge_threshold[s]);
        if constexpr (kCount) {
          st.covered += static_cast<uint32_t>(hn::CountTrue(di, pass));
          st.passed += static_cast<uint32_t>(hn::CountTrue(di, pass));
        }
        keep(s, pass);
        pass_one = hn::Or(pass_one, hn::RebindMask(df, pass));
      }
    } else if constexpr (kCount) {
      st.passed += static_cast<uint32_t>(hn::CountTrue(di, cov_any));
    }

    if constexpr (kColor == ColorMode::kRGBA8) {
      // Shaded whether or not a sample passed (the stores are then empty), so that no branch
      // waits on the depth test, a late and often mispredicted one. With the Hi-Z marks above,
      // `small` at one sample 0.90x to 0.99x the time at one thread (median about 0.92x) and
      // about 0.95x at two, `tiny` about 0.98x, `grid` within the noise, `medium` about 1.02x
      // (Hi-Z recomputes the bounds of blocks marked with no change; a branch-free select
      // that marks only changed blocks made `small` 1.02x slower). At four samples 0.97x to
      // 1.04x (median about 0.99x in 22 rounds) and 0.94x to 1.02x at two threads. Either
      // alone was slower (one sample: the colour alone 1.15x; four: the colour alone 1.11x to
      // 1.15x, the marks alone 1.01x to 1.03x).
      const auto any = pass_one;
      if constexpr (kCount) st.shaded += static_cast<uint32_t>(hn::CountTrue(df, any));
      if (by != colour_row) {
        colour_row = by;
        const float fdx = static_cast<float>(dx), fdy = static_cast<float>(by * 8.0 - t.y0);
        const float fdx_b = static_cast<float>(dx + 8.0);
        for (int c = 0; c < 4; ++c) {
          qa_a[c] = t.qa0[c] + (t.qa_dx[c] * fdx + t.qa_dy[c] * fdy);
          qa_b[c] = t.qa0[c] + (t.qa_dx[c] * fdx_b + t.qa_dy[c] * fdy);
        }
        if (!(kSimple || t.flat_q)) {
          q_a = t.q0 + (t.q_dx * fdx + t.q_dy * fdy);
          q_b = t.q0 + (t.q_dx * fdx_b + t.q_dy * fdy);
        }
      }
      const auto plane = [&](float a_base, float b_base, float gx, float gy) {
        return hn::Add(bases(a_base, b_base),
                       hn::Add(hn::Mul(fx, hn::Set(df, gx)), hn::Mul(fy, hn::Set(df, gy))));
      };
      const auto channel_plane = [&](int c, auto col_term) {
        return hn::Add(bases(qa_a[c], qa_b[c]),
                       hn::Add(col_term, hn::Mul(fy, hn::Set(df, qa_gy[c]))));
      };
      auto red = channel_plane(0, col_r);
      auto green = channel_plane(1, col_g);
      auto blue = channel_plane(2, col_b);
      auto alpha = channel_plane(3, col_a);
      if (!(kSimple || t.flat_q)) {
        const auto q = plane(q_a, q_b, t.q_dx, t.q_dy);
        const auto inv_q = hn::Div(hn::Set(df, 1.0f), q);
        red = hn::Mul(red, inv_q);
        green = hn::Mul(green, inv_q);
        blue = hn::Mul(blue, inv_q);
        alpha = hn::Mul(alpha, inv_q);
        const auto beyond = hn::AndNot(hn::Gt(q, hn::Zero(df)), any);
        if (!hn::AllFalse(df, beyond)) {
          // The pixel centre lies beyond the triangle's horizon: evaluate at the pixel's
          // first passing sample instead, as raster_block does, in the same order.
          alignas(64) float channel[4][64];
          alignas(64) float lane_fx[64], lane_fy[64];
          alignas(64) int32_t lane_a[64], lane_beyond[64];
          alignas(64) uint32_t passing[64];  // multisample only: bit s, sample s passed
          store_channels(df, red, green, blue, alpha, channel);
          hn::Store(fx, df, lane_fx);
          hn::Store(fy, df, lane_fy);
          hn::Store(hn::VecFromMask(di, in_a), di, lane_a);
          hn::Store(hn::VecFromMask(di, hn::RebindMask(di, beyond)), di, lane_beyond);
          if constexpr (kMulti) hn::Store(sample_bits(du, samples, passed), du, passing);
          for (size_t l = 0; l < hn::Lanes(df); ++l) {
            if (lane_beyond[l] == 0) continue;
            const uint32_t s = kMulti ? static_cast<uint32_t>(std::countr_zero(passing[l])) : 0;
            const bool a = lane_a[l] != 0 || !two;
            const float sx = lane_fx[l] + tc.sample_fx[s], sy = lane_fy[l] + tc.sample_fy[s];
            const float qs = (a ? q_a : q_b) + (t.q_dx * sx + t.q_dy * sy);
            for (int c = 0; c < 4; ++c) {
              channel[c][l] = ((a ? qa_a[c] : qa_b[c]) + (t.qa_dx[c] * sx + t.qa_dy[c] * sy)) / qs;
            }
          }
          load_channels(df, channel, red, green, blue, alpha);
        }
      }
      // One sample, simple: the stored lanes, covered pixel centres, need no clamp
      // (packs_without_clamp).
      uint32_t* const colour = reinterpret_cast<uint32_t*>(tc.rgba8);
      if (tc.blend != nullptr) {
        // Each lane blends with the value it replaces: block a's lanes' at at_a, block b's at
        // at_b.
        for (uint32_t s = 0; s < samples; ++s) {
          const auto m = kMulti ? passed(s) : any;
          if (hn::AllFalse(df, m)) continue;
          uint32_t* const target = colour + s * kSamplePlane;
          const auto old_a = hn::Load(du, target + at_a);
          const auto old_b = two ? hn::Load(du, target + at_b) : old_a;
          const auto old = two ? hn::IfThenElse(hn::RebindMask(du, in_a_f), old_a, old_b) : old_a;
          const auto packed = blend_packed(df, tc, old, red, green, blue, alpha);
          store_masked(packed, hn::RebindMask(du, two ? hn::And(m, in_a_f) : m), du, target + at_a,
                       old_a);
          if (two) {
            store_masked(packed, hn::RebindMask(du, hn::And(m, in_b_f)), du, target + at_b, old_b);
          }
        }
        continue;
      }
      const auto packed = pack_unorm8<!(kSimple && !kMulti)>(df, red, green, blue, alpha);
      for (uint32_t s = 0; s < samples; ++s) {
        const auto m = kMulti ? passed(s) : any;
        uint32_t* const target = colour + s * kSamplePlane;
        store_masked(packed, hn::RebindMask(du, two ? hn::And(m, in_a_f) : m), du, target + at_a);
        if (two) store_masked(packed, hn::RebindMask(du, hn::And(m, in_b_f)), du, target + at_b);
      }
    }
  }
  if constexpr (kCount) {
    // The blocks raster_small visits and the ones its test rejects.
    const int32_t bx0 = px0 >> 3, by0 = st.py0 >> 3, bx1 = px1 >> 3, by1 = py1 >> 3;
    int32_t e_block_row[3], reach[3];
    small_block_edges(tc, t, st, bx0, by0, e_block_row, reach);
    uint64_t rejected = 0, visited = 0;
    for (int32_t by = by0; by <= by1; ++by) {
      int32_t e_block[3] = {e_block_row[0], e_block_row[1], e_block_row[2]};
      for (int e = 0; e < 3; ++e)
        e_block_row[e] += st.step_y[e] * 8;
      for (int32_t bx = bx0; bx <= bx1; ++bx) {
        ++visited;
        rejected +=
            (e_block[0] + reach[0] < 0) | (e_block[1] + reach[1] < 0) | (e_block[2] + reach[2] < 0);
        for (int e = 0; e < 3; ++e)
          e_block[e] += st.step_x[e] * 8;
      }
    }
    counters.blocks_rejected += rejected;
    counters.blocks_partial += visited - rejected;
    counters.samples_covered += st.covered;
    counters.samples_passed += st.passed;
    counters.pixels_shaded += st.shaded;
  }
}

// The widest box, in pixels, that takes the window path: one window per row pair (`small`
// about 0.85x the block path's time; wider boxes measured no faster on `medium`, whose
// blocks outside an edge the block path skips whole).
constexpr int32_t kWindowBox = 8;

// A small triangle whose box is more than this many pixels wide or tall tests Hi-Z (8:
// `medium` about 0.93x the time of 16 at one thread and one sample, 0.97x at four, about 0.94x
// at two threads; `small`, `tiny` and `grid` within the noise; 6: `small` 1.24x).
constexpr int32_t kSmallHizBox = 8;

// The widest and tallest box, in pixels, whose pixel centres the kernel tests one by one
// (3 measured 4% faster than 2 on `tiny` and `grid`; 4 no faster than 3).
constexpr int32_t kCentresBox = 3;

// Which pixel centres of a small triangle's box (at most kCentresBox pixels across and down) are
// inside, bit (y - y0) * 4 + (x - x0): the edge functions there, exact in int32 for small
// triangles (raster_small's bound), inside all three when none is negative.
HWY_INLINE uint32_t centres_inside(const TileContext& tc, const TriangleSetup& t) {
  const int bits = static_cast<int>(tc.subpixel_bits);
  const int64_t cx = (int64_t{t.x0} * 16 + 8) << (bits - 4);
  const int64_t cy = (int64_t{t.y0} * 16 + 8) << (bits - 4);
  int32_t row[3], step_x[3], step_y[3];
  for (int e = 0; e < 3; ++e) {
    row[e] = static_cast<int32_t>(t.a[e] * cx + t.b[e] * cy + t.c[e]);
    step_x[e] = t.a[e] * (1 << bits);
    step_y[e] = t.b[e] * (1 << bits);
  }
  const uint32_t columns = (1u << (t.x1 - t.x0 + 1)) - 1;
  uint32_t inside = 0;
  for (int32_t y = 0; y <= t.y1 - t.y0; ++y) {
    uint32_t line = 0;
    for (int32_t x = 0; x < kCentresBox; ++x) {
      const int32_t e0 = row[0] + step_x[0] * x, e1 = row[1] + step_x[1] * x,
                    e2 = row[2] + step_x[2] * x;
      line |= static_cast<uint32_t>((e0 | e1 | e2) >= 0) << x;
    }
    inside |= (line & columns) << (y * 4);
    for (int e = 0; e < 3; ++e)
      row[e] += step_y[e];
  }
  return inside;
}

// Where pixel (x, y) of this tile lies for a triangle drawn pixel by pixel: its block and
// value index in the tile's storage; block_bit is its block's bit for count_pixels, from the
// block of the box's first pixel (x0, y0).
struct PixelSite {
  PixelSite(const TileContext& tc, int32_t x0, int32_t y0, int32_t x, int32_t y)
      : block(tile_block((x - tc.tile_x0) >> 3, (y - tc.tile_y0) >> 3, 0, 0)),
        index(block * 64 + static_cast<size_t>((y & 7) * 8 + (x & 7))),
        block_bit(1u << ((((y >> 3) - (y0 >> 3)) << 1) + ((x >> 3) - (x0 >> 3)))) {}
  size_t block, index;
  uint32_t block_bit;
};

// Whether a depth value passes against the stored one (and is written with kTestWrite, its
// block's Hi-Z bounds then out of date): z clamped to [0, 1], rounded here to a fixed-point
// format's steps as raster_block rounds its lanes.
template <DepthMode kDepth, class Compare>
HWY_INLINE bool pixel_depth_passes(const TileContext& tc, size_t block, size_t index, float z,
                                   Compare compare) {
  if (tc.depth_scale > 0.0f) z = std::nearbyint(z * tc.depth_scale);
  float& stored = tc.depth[index];
  if (!compare(z, stored)) return false;
  if constexpr (kDepth == DepthMode::kTestWrite) {
    stored = z;
    mark_hiz_dirty(tc, block);
  }
  return true;
}

// Writes a pixel's RGBA8 colour to its samples in `samples` (bit s: sample s), the pixel's
// value at `index` in sample plane 0.
HWY_INLINE void write_packed(const TileContext& tc, size_t index, uint32_t samples,
                             uint32_t packed) {
  uint32_t* colour = reinterpret_cast<uint32_t*>(tc.rgba8) + index;
  for (uint32_t rest = samples; rest != 0; rest &= rest - 1)
    colour[std::countr_zero(rest) * kSamplePlane] = packed;
}

// The same for a colour as channels, in the target's format.
template <ColorMode kColor>
HWY_INLINE void write_pixel(const TileContext& tc, size_t index, uint32_t samples,
                            const float (&channel)[4]) {
  if (tc.blend != nullptr) {
    const blend::Rgba src = {channel[0], channel[1], channel[2], channel[3]};
    for (uint32_t rest = samples; rest != 0; rest &= rest - 1) {
      const size_t at = std::countr_zero(rest) * kSamplePlane + index;
      blend::write_sample(*tc.blend, tc.blend_constant, src,
                          kColor == ColorMode::kRGBA8 ? tc.rgba8 + at * 4 : nullptr,
                          kColor == ColorMode::kRGBA8 ? nullptr : tc.rgba32f + at * 4);
    }
    return;
  }
  if constexpr (kColor == ColorMode::kRGBA8) {
    write_packed(tc, index, samples, pack_rgba8(channel));
  } else {
    for (uint32_t rest = samples; rest != 0; rest &= rest - 1)
      std::copy(channel, channel + 4,
                tc.rgba32f + (std::countr_zero(rest) * kSamplePlane + index) * 4);
  }
}

// The counters of a triangle drawn pixel by pixel. The blocks of its box (x0, y0)-(x1, y1)
// in this tile: those
// with a covered pixel (`blocks`, bit (by - by0) * 2 + (bx - bx0)) partial, the others rejected
// (as the small path counts blocks its edges miss).
HWY_INLINE void count_pixels(const TileContext& tc, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                             uint32_t blocks, uint32_t covered, uint32_t passed, uint32_t shaded,
                             Counters& counters) {
  const int32_t bx0 = std::max(x0, tc.x0) >> 3, bx1 = std::min(x1, tc.x1) >> 3;
  const int32_t by0 = std::max(y0, tc.y0) >> 3, by1 = std::min(y1, tc.y1) >> 3;
  const uint32_t partial = static_cast<uint32_t>(std::popcount(blocks));
  counters.blocks_partial += partial;
  counters.blocks_rejected +=
      static_cast<uint32_t>(std::max(bx1 - bx0 + 1, 0) * std::max(by1 - by0 + 1, 0)) - partial;
  counters.samples_covered += covered;
  counters.samples_passed += passed;
  counters.pixels_shaded += shaded;
}

// One sample per pixel, and a triangle whose box is at most 3x3 pixels: its covered pixels
// (`centres`, bit (y - y0) * 4 + (x - x0)) in this tile are drawn one by one, with no lanes to
// fill. Each value is the float sum raster_block forms for that pixel's lane (plane bases at
// the block's first pixel, then the offset to the pixel, in the same order), clamped, rounded
// and compared as its lanes are, so the bytes are the same.
template <DepthMode kDepth, ColorMode kColor, bool kCount>
HWY_INLINE void raster_centres(const TileContext& tc, const TriangleSetup& t, uint32_t centres,
                               Counters& counters) {
  uint32_t covered = 0, passed = 0, blocks = 0;  // as count_pixels takes them
  for (uint32_t bits = centres; bits != 0; bits &= bits - 1) {
    const uint32_t bit = static_cast<uint32_t>(std::countr_zero(bits));
    const int32_t x = t.x0 + static_cast<int32_t>(bit & 3),
                  y = t.y0 + static_cast<int32_t>(bit >> 2);
    if (x < tc.x0 || x > tc.x1 || y < tc.y0 || y > tc.y1) continue;  // another tile's
    const PixelSite site(tc, t.x0, t.y0, x, y);
    const PixelOffsets offsets(t, x, y);
    if constexpr (kCount) {
      ++covered;
      blocks |= site.block_bit;
    }
    if constexpr (kDepth != DepthMode::kOff) {
      if (!pixel_depth_passes<kDepth>(tc, site.block, site.index, centre_depth(t, offsets),
                                      AnyCompare{tc.compare})) {
        continue;
      }
    }
    if constexpr (kCount) ++passed;
    if constexpr (kColor != ColorMode::kOff) {
      float channel[4];
      pixel_colour(t, offsets, 0.0f, 0.0f, channel);
      write_pixel<kColor>(tc, site.index, 1u, channel);
    }
  }
  if constexpr (kCount) {
    count_pixels(tc, t.x0, t.y0, t.x1, t.y1, blocks, covered, passed,
                 kColor != ColorMode::kOff ? passed : 0, counters);
  }
}

// A pixel record (pixel_record.hpp): its pixels in this tile, depth-tested and written with
// the values the setup computed for them, which are raster_centres' for the same pixels.
template <DepthMode kDepth, ColorMode kColor, bool kCount, class Compare>
HWY_INLINE void raster_pixel_record(const TileContext& tc, const PixelRecord& r, Counters& counters,
                                    [[maybe_unused]] Compare compare) {
  static_assert(kColor != ColorMode::kRGBA32F, "pixel records hold RGBA8 colour");
  const int32_t x0 = r.x0, y0 = r.y0;
  const uint32_t n = r.pixels();
  uint32_t covered = 0, passed = 0, blocks = 0;  // as count_pixels takes them
  for (uint32_t i = 0; i < n; ++i) {
    const int32_t x = x0 + (r.offset[i] & 3), y = y0 + (r.offset[i] >> 2);
    if (x < tc.x0 || x > tc.x1 || y < tc.y0 || y > tc.y1) continue;  // another tile's
    const PixelSite site(tc, x0, y0, x, y);
    if constexpr (kCount) {
      ++covered;
      blocks |= site.block_bit;
    }
    if constexpr (kDepth != DepthMode::kOff) {
      if (!pixel_depth_passes<kDepth>(tc, site.block, site.index, r.z[i], compare)) continue;
    }
    if constexpr (kCount) ++passed;
    if constexpr (kColor == ColorMode::kRGBA8) {
      reinterpret_cast<uint32_t*>(tc.rgba8)[site.index] = r.rgba8[i];
    }
  }
  if constexpr (kCount) {
    count_pixels(tc, x0, y0, x0 + r.last_x(), y0 + r.last_y(), blocks, covered, passed,
                 kColor != ColorMode::kOff ? passed : 0, counters);
  }
}

// The samples in `cov` (bit s: sample s) of the pixel at `index` of `block` that pass the depth
// test, and with kTestWrite their depth written (the block's Hi-Z bounds then out of date).
// Each sample's depth is raster_block's sum for its lane: the plane's base at the block's
// first pixel (z_base), plus the sample's offset (set_up_state's), plus the pixel's offset in
// the block, clamped and rounded as the lanes are.
template <DepthMode kDepth, class Compare>
HWY_INLINE uint32_t samples_depth_pass(const TileContext& tc, size_t block, size_t index,
                                       uint32_t cov, float z_base, float z_dx, float z_dy,
                                       Compare compare) {
  const float fx = static_cast<float>(index & 7), fy = static_cast<float>((index >> 3) & 7);
  const float z_rel = fx * z_dx + fy * z_dy;
  uint32_t pass = 0;
  for (uint32_t rest = cov; rest != 0; rest &= rest - 1) {
    const uint32_t s = static_cast<uint32_t>(std::countr_zero(rest));
    const float z_offset = z_dx * tc.sample_fx[s] + z_dy * tc.sample_fy[s];
    float z = (z_base + z_offset) + z_rel;
    z = z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f;  // hn::Min(hn::Max(z, 0), 1)
    if (tc.depth_scale > 0.0f) z = std::nearbyint(z * tc.depth_scale);
    float& stored = tc.depth[s * kSamplePlane + index];
    const bool passes = compare(z, stored);
    pass |= passes ? 1u << s : 0u;
    if constexpr (kDepth == DepthMode::kTestWrite) stored = passes ? z : stored;
  }
  if (kDepth == DepthMode::kTestWrite && pass != 0) mark_hiz_dirty(tc, block);
  return pass;
}

// Two or four samples per pixel, and a triangle whose box is at most 3x3 pixels: its covered
// samples (`sample_bits`, bit ((y - y0) * 3 + (x - x0)) * samples + s) in this tile are
// depth-tested one by one and each pixel with a passing sample shaded once, with no lanes to
// fill. Each value is the float sum raster_block forms for that sample or pixel (plane bases
// at the block's first pixel, then the offsets, in the same order), clamped, rounded and
// compared as its lanes are, so the bytes are the same.
template <DepthMode kDepth, ColorMode kColor, bool kCount>
HWY_INLINE void raster_samples(const TileContext& tc, const TriangleSetup& t, Counters& counters) {
  const uint32_t samples = tc.samples;
  const uint32_t pixel_samples = (1u << samples) - 1;
  uint32_t pixels = 0;  // bit p: pixel p has a covered sample
  for (uint32_t p = 0; p < 32 / samples && p < 9; ++p)
    pixels |= ((t.sample_bits >> (p * samples)) & pixel_samples) != 0 ? 1u << p : 0u;
  uint32_t covered = 0, passed = 0, shaded = 0, blocks = 0;  // as count_pixels takes them
  for (; pixels != 0; pixels &= pixels - 1) {
    const uint32_t p = static_cast<uint32_t>(std::countr_zero(pixels));
    const int32_t x = t.x0 + static_cast<int32_t>(p % 3), y = t.y0 + static_cast<int32_t>(p / 3);
    if (x < tc.x0 || x > tc.x1 || y < tc.y0 || y > tc.y1) continue;  // another tile's
    const uint32_t cov = (t.sample_bits >> (p * samples)) & pixel_samples;
    const PixelSite site(tc, t.x0, t.y0, x, y);
    const size_t block = site.block, index = site.index;
    const PixelOffsets offsets(t, x, y);
    if constexpr (kCount) {
      covered += static_cast<uint32_t>(std::popcount(cov));
      blocks |= site.block_bit;
    }
    uint32_t pass = cov;
    if constexpr (kDepth != DepthMode::kOff) {
      const float z_base = static_cast<float>(t.z0 + t.z_dx * offsets.dx + t.z_dy * offsets.dy);
      pass = samples_depth_pass<kDepth>(tc, block, index, cov, z_base, t.z_dx, t.z_dy,
                                        AnyCompare{tc.compare});
      if (pass == 0) continue;
    }
    if constexpr (kCount) passed += static_cast<uint32_t>(std::popcount(pass));
    if constexpr (kColor != ColorMode::kOff) {
      if constexpr (kCount) ++shaded;
      const uint32_t first = static_cast<uint32_t>(std::countr_zero(pass));
      float channel[4];
      pixel_colour(t, offsets, tc.sample_fx[first], tc.sample_fy[first], channel);
      write_pixel<kColor>(tc, index, pass, channel);
    }
  }
  if constexpr (kCount) {
    count_pixels(tc, t.x0, t.y0, t.x1, t.y1, blocks, covered, passed, shaded, counters);
  }
}

// A sample record (pixel_record.hpp): its pixels in this tile, each covered sample's depth
// tested with the value raster_samples forms for it from the same floats, and the colour the
// setup computed written to the passing samples.
template <DepthMode kDepth, ColorMode kColor, bool kCount, class Compare>
HWY_INLINE void raster_sample_record(const TileContext& tc, const SampleRecord& r,
                                     Counters& counters, [[maybe_unused]] Compare compare) {
  static_assert(kColor != ColorMode::kRGBA32F, "sample records hold RGBA8 colour");
  const int32_t x0 = r.x0, y0 = r.y0;
  const uint32_t n = r.pixels();
  uint32_t covered = 0, passed = 0, shaded = 0, blocks = 0;  // as count_pixels takes them
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t place = r.place(i);
    const int32_t x = x0 + static_cast<int32_t>(place & 3),
                  y = y0 + static_cast<int32_t>(place >> 2);
    if (x < tc.x0 || x > tc.x1 || y < tc.y0 || y > tc.y1) continue;  // another tile's
    const uint32_t cov = r.samples(i);
    const PixelSite site(tc, x0, y0, x, y);
    if constexpr (kCount) {
      covered += static_cast<uint32_t>(std::popcount(cov));
      blocks |= site.block_bit;
    }
    uint32_t pass = cov;
    if constexpr (kDepth != DepthMode::kOff) {
      pass = samples_depth_pass<kDepth>(tc, site.block, site.index, cov, r.z_base[i], r.z_dx,
                                        r.z_dy, compare);
      if (pass == 0) continue;
    }
    if constexpr (kCount) {
      passed += static_cast<uint32_t>(std::popcount(pass));
      shaded += kColor != ColorMode::kOff ? 1 : 0;
    }
    if constexpr (kColor == ColorMode::kRGBA8) write_packed(tc, site.index, pass, r.rgba8[i]);
  }
  if constexpr (kCount) {
    count_pixels(tc, x0, y0, x0 + r.last_x(), y0 + r.last_y(), blocks, covered, passed, shaded,
                 counters);
  }
}

template <DepthMode kDepth, ColorMode kColor, bool kCount>
void RasterPixels(const TileContext& tc, const PixelRecord& r, Counters& counters) {
  with_compare<kDepth>(tc, [&](auto compare) {
    raster_pixel_record<kDepth, kColor, kCount>(tc, r, counters, compare);
  });
}

template <DepthMode kDepth, ColorMode kColor, bool kCount>
void RasterSamples(const TileContext& tc, const SampleRecord& r, Counters& counters) {
  with_compare<kDepth>(tc, [&](auto compare) {
    raster_sample_record<kDepth, kColor, kCount>(tc, r, counters, compare);
  });
}

// One triangle over its blocks in this tile. kCount compiles the block, Hi-Z and sample
// counters in; without it the kernel carries no counting code at all. Small triangles whose
// bounding box is more than kSmallHizBox pixels wide or tall test Hi-Z per block (below that,
// recomputing the bounds of blocks written since their last test costs more than the blocks it
// rejects: `tiny` 1.14x, `small` 1.12x, benchmarks/RESULTS.md decisions 18 and 135).
template <DepthMode kDepth, ColorMode kColor, shade::Shader kShader, bool kMulti, bool kCount>
void RasterTriangle(const TileContext& tc, const TriangleSetup& t,
                    [[maybe_unused]] const float* planes, Counters& counters) {
  if constexpr (kShader != shade::Shader::kGouraud) {
    // A shaded draw: the block paths, which shade lane groups (pixel-by-pixel and window paths
    // write a Gouraud colour).
    if (!t.small) {
      raster_general<kDepth, kColor, kShader, kMulti, kCount>(tc, t, planes, counters);
    } else if (tc.hiz && (t.x1 - t.x0 >= kSmallHizBox || t.y1 - t.y0 >= kSmallHizBox)) {
      raster_small_hiz<kDepth, kColor, kShader, kMulti, kCount>(tc, t, planes, counters);
    } else {
      raster_small<kDepth, kColor, kShader, kMulti, kCount, false>(tc, t, planes, counters);
    }
    return;
  }
  if (!kMulti && t.centres != 0) {
    raster_centres<kDepth, kColor, kCount>(tc, t, t.centres, counters);
  } else if (kMulti && t.sample_bits != 0) {
    raster_samples<kDepth, kColor, kCount>(tc, t, counters);
  } else if (!kMulti && t.small && t.x1 - t.x0 < kCentresBox && t.y1 - t.y0 < kCentresBox) {
    raster_centres<kDepth, kColor, kCount>(tc, t, centres_inside(tc, t), counters);
  } else if (!t.small) {
    raster_general<kDepth, kColor, kShader, kMulti, kCount>(tc, t, nullptr, counters);
  } else if (tc.hiz && (t.x1 - t.x0 >= kSmallHizBox || t.y1 - t.y0 >= kSmallHizBox)) {
    raster_small_hiz<kDepth, kColor, kShader, kMulti, kCount>(tc, t, nullptr, counters);
  } else {
    if constexpr (kColor != ColorMode::kRGBA32F) {
      const size_t lanes = hn::Lanes(hn::ScalableTag<int32_t>());
      if ((lanes == 8 || lanes == 16) && t.x1 - t.x0 < kWindowBox) {
        const bool two = window_spans_two_blocks(tc, t);
        with_compare<kDepth>(tc, [&](auto compare) {
          const bool simple =
              (kMulti ? tc.samples == 4 : kColor == ColorMode::kOff || packs_without_clamp(t)) &&
              t.flat_q && tc.depth_scale == 0.0f && !window_depth_may_clamp(t);
          if (two && simple) {
            raster_window<kDepth, kColor, kMulti, kCount, true, true>(tc, t, counters, compare);
          } else if (two) {
            raster_window<kDepth, kColor, kMulti, kCount, true, false>(tc, t, counters, compare);
          } else if (simple) {
            raster_window<kDepth, kColor, kMulti, kCount, false, true>(tc, t, counters, compare);
          } else {
            raster_window<kDepth, kColor, kMulti, kCount, false, false>(tc, t, counters, compare);
          }
        });
        return;
      }
    }
    raster_small<kDepth, kColor, kShader, kMulti, kCount, false>(tc, t, nullptr, counters);
  }
}

template <DepthMode kDepth, ColorMode kColor, bool kMulti>
void fill_count(KernelTable& t) {
  t.kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][kMulti][0] =
      &RasterTriangle<kDepth, kColor, shade::Shader::kGouraud, kMulti, false>;
  t.kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][kMulti][1] =
      &RasterTriangle<kDepth, kColor, shade::Shader::kGouraud, kMulti, true>;
}

template <DepthMode kDepth, ColorMode kColor>
void fill_multi(KernelTable& t) {
  fill_count<kDepth, kColor, false>(t);
  fill_count<kDepth, kColor, true>(t);
  if constexpr (kColor != ColorMode::kRGBA32F) {
    t.pixel_kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][0] =
        &RasterPixels<kDepth, kColor, false>;
    t.pixel_kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][1] =
        &RasterPixels<kDepth, kColor, true>;
    t.sample_kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][0] =
        &RasterSamples<kDepth, kColor, false>;
    t.sample_kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][1] =
        &RasterSamples<kDepth, kColor, true>;
  }
}

template <shade::Shader kShader, DepthMode kDepth, ColorMode kColor>
void fill_shaded(KernelTable& t) {
  auto& row = t.shaded_kernels[static_cast<int>(kShader)][static_cast<int>(kDepth)]
                              [static_cast<int>(kColor)];
  row[0][0] = &RasterTriangle<kDepth, kColor, kShader, false, false>;
  row[0][1] = &RasterTriangle<kDepth, kColor, kShader, false, true>;
  row[1][0] = &RasterTriangle<kDepth, kColor, kShader, true, false>;
  row[1][1] = &RasterTriangle<kDepth, kColor, kShader, true, true>;
}

}  // namespace

// The twelve triangle kernels of depth mode kDepth (every colour mode, single or multisample,
// counting or not) into table.kernels[kDepth], and its four pixel-record and four
// sample-record kernels into table.pixel_kernels[kDepth] and table.sample_kernels[kDepth]. Each
// block_kernel_depth_*.cpp instantiates it for its mode; block_kernel.cpp calls the three.
template <DepthMode kDepth>
void FillDepthKernels(KernelTable& table) {
  fill_multi<kDepth, ColorMode::kOff>(table);
  fill_multi<kDepth, ColorMode::kRGBA8>(table);
  fill_multi<kDepth, ColorMode::kRGBA32F>(table);
}

// The 24 triangle kernels of shader kShader (every depth mode, RGBA8 or RGBA32F colour, single
// or multisample, counting or not) into table.shaded_kernels[kShader]. Each
// block_kernel_shader_*.cpp instantiates it for its shader; block_kernel.cpp calls them.
template <shade::Shader kShader>
void FillShaderKernels(KernelTable& table) {
  if constexpr (kShader == shade::Shader::kUser) {
    // A user shader's colour is written by its back end, for either format: one instance of
    // each other state serves both.
    constexpr int kRGBA8 = static_cast<int>(ColorMode::kRGBA8);
    constexpr int kRGBA32F = static_cast<int>(ColorMode::kRGBA32F);
    auto& rows = table.shaded_kernels[static_cast<int>(kShader)];
    fill_shaded<kShader, DepthMode::kOff, ColorMode::kRGBA8>(table);
    fill_shaded<kShader, DepthMode::kTest, ColorMode::kRGBA8>(table);
    fill_shaded<kShader, DepthMode::kTestWrite, ColorMode::kRGBA8>(table);
    for (auto& depth : rows)
      std::copy(&depth[kRGBA8][0][0], &depth[kRGBA8][0][0] + 4, &depth[kRGBA32F][0][0]);
    return;
  }
  fill_shaded<kShader, DepthMode::kOff, ColorMode::kRGBA8>(table);
  fill_shaded<kShader, DepthMode::kOff, ColorMode::kRGBA32F>(table);
  fill_shaded<kShader, DepthMode::kTest, ColorMode::kRGBA8>(table);
  fill_shaded<kShader, DepthMode::kTest, ColorMode::kRGBA32F>(table);
  fill_shaded<kShader, DepthMode::kTestWrite, ColorMode::kRGBA8>(table);
  fill_shaded<kShader, DepthMode::kTestWrite, ColorMode::kRGBA32F>(table);
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // TESSERA_ENGINE_SRC_FAST_BLOCK_KERNEL_INL_H_
