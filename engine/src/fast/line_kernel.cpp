// The line shading kernel (line_kernel.hpp), compiled for every SIMD target through
// hwy/foreach_target.h. Lanes are pixels of one run, in double precision: each lane computes
// exactly what the reference's scalar code computes for its pixel (same operations in the same
// order, contraction off), then converts to float and to unorm8 as to_unorm8 does.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/src/fast/line_kernel.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/line_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "binning/tile_grid.hpp"
#include "engine/src/fast/unorm8-inl.h"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

// Pixel (px, py)'s place in a one-sample framebuffer's storage (sample_index).
HWY_INLINE uint32_t pixel_offset(uint32_t px, uint32_t py, uint32_t tiles_x) {
  return ((py >> binning::kTileSizeLog2) * tiles_x + (px >> binning::kTileSizeLog2)) *
             binning::kTilePixels +
         detail::in_tile(px, py);
}

#if !HWY_HAVE_FLOAT64 || HWY_TARGET == HWY_SCALAR
void shade_scalar(const LineShading& sh, const int32_t* x, const int32_t* y, size_t n,
                  const LineRunOut& out) {
  for (size_t i = 0; i < n; ++i) {
    double t = ((static_cast<double>(x[i]) + 0.5 - sh.ax) * sh.ex +
                (static_cast<double>(y[i]) + 0.5 - sh.ay) * sh.ey) *
               sh.inv_len2;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    out.depth[i] = static_cast<float>(sh.z + t * sh.dz);
    const uint32_t offset =
        pixel_offset(static_cast<uint32_t>(x[i]), static_cast<uint32_t>(y[i]), out.tiles_x);
    out.offset[i] = offset;
    float coverage = 0.0f;
    if (sh.smooth) {
      const double qx = static_cast<double>(x[i]) + 0.5 - sh.ax;
      const double qy = static_cast<double>(y[i]) + 0.5 - sh.ay;
      const double along = qx * sh.ux + qy * sh.uy;
      const double across = std::abs(qx * sh.uy - qy * sh.ux);
      const double c_across = std::clamp(sh.cover_reach - across, 0.0, 1.0);
      const double c_along = std::clamp(std::min(along, sh.length - along) + 0.5, 0.0, 1.0);
      coverage = static_cast<float>(c_across * c_along);
      out.coverage[i] = coverage;
    }
    // No colour written (dst null): rgba[i] is not formed. A smooth line's pixel that is not
    // drawn reads no dst either.
    if (out.dst == nullptr || (sh.smooth && !(coverage > 0.0f))) continue;
    double tc = t;  // the colour parameter (color_t)
    if (sh.perspective) {
      const double qa = (1.0 - t) * sh.inv_wa, qb = t * sh.inv_wb;
      tc = qa + qb > 0.0 ? qb / (qa + qb) : t;
    }
    float color[4];
    for (int c = 0; c < 4; ++c)
      color[c] = static_cast<float>(sh.color[c] + tc * sh.dcolor[c]);
    if (sh.smooth) {
      const float a = std::clamp(color[3], 0.0f, 1.0f) * std::min(coverage, 1.0f);
      float dst[4];
      for (int c = 0; c < 4; ++c)
        dst[c] = static_cast<float>((out.dst[offset] >> (8 * c)) & 0xFFu) / 255.0f;
      for (int c = 0; c < 3; ++c)
        color[c] = color[c] * a + dst[c] * (1.0f - a);
      color[3] = a + dst[3] * (1.0f - a);
    }
    uint32_t packed = 0;
    for (int c = 0; c < 4; ++c)
      packed |= uint32_t{to_unorm8(color[c])} << (8 * c);
    out.rgba[i] = packed;
  }
}
#endif

#if HWY_HAVE_FLOAT64 && HWY_TARGET != HWY_SCALAR
// t of the pixels at x[0..], y[0..] (one double vector): the reference's projection, clamped.
template <class DD>
HWY_INLINE hn::Vec<DD> line_t(DD dd, const LineShading& sh, const int32_t* x, const int32_t* y) {
  const hn::Rebind<int32_t, DD> di;
  const auto px = hn::PromoteTo(dd, hn::LoadU(di, x));
  const auto py = hn::PromoteTo(dd, hn::LoadU(di, y));
  const auto half = hn::Set(dd, 0.5);
  const auto along =
      hn::Add(hn::Mul(hn::Sub(hn::Add(px, half), hn::Set(dd, sh.ax)), hn::Set(dd, sh.ex)),
              hn::Mul(hn::Sub(hn::Add(py, half), hn::Set(dd, sh.ay)), hn::Set(dd, sh.ey)));
  return hn::Min(hn::Max(hn::Mul(along, hn::Set(dd, sh.inv_len2)), hn::Zero(dd)), hn::Set(dd, 1.0));
}

// An antialiased line's coverage of the pixels at x[0..], y[0..] (one double vector), as
// reference_lines.cpp computes it: across the line times along it.
template <class DD>
HWY_INLINE hn::Vec<DD> smooth_coverage(DD dd, const LineShading& sh, const int32_t* x,
                                       const int32_t* y) {
  const hn::Rebind<int32_t, DD> di;
  const auto half = hn::Set(dd, 0.5), zero = hn::Zero(dd), one = hn::Set(dd, 1.0);
  const auto qx = hn::Sub(hn::Add(hn::PromoteTo(dd, hn::LoadU(di, x)), half), hn::Set(dd, sh.ax));
  const auto qy = hn::Sub(hn::Add(hn::PromoteTo(dd, hn::LoadU(di, y)), half), hn::Set(dd, sh.ay));
  const auto ux = hn::Set(dd, sh.ux), uy = hn::Set(dd, sh.uy);
  const auto along = hn::Add(hn::Mul(qx, ux), hn::Mul(qy, uy));
  const auto across = hn::Abs(hn::Sub(hn::Mul(qx, uy), hn::Mul(qy, ux)));
  const auto c_across = hn::Min(hn::Max(hn::Sub(hn::Set(dd, sh.cover_reach), across), zero), one);
  const auto c_along = hn::Min(
      hn::Max(hn::Add(hn::Min(along, hn::Sub(hn::Set(dd, sh.length), along)), half), zero), one);
  return hn::Mul(c_across, c_along);
}

// The colour parameter: t, or with perspective t wb / ((1 - t) wa + t wb) where that is > 0.
template <class DD>
HWY_INLINE hn::Vec<DD> color_t(DD dd, const LineShading& sh, hn::Vec<DD> t) {
  if (!sh.perspective) return t;
  const auto qa = hn::Mul(hn::Sub(hn::Set(dd, 1.0), t), hn::Set(dd, sh.inv_wa));
  const auto qb = hn::Mul(t, hn::Set(dd, sh.inv_wb));
  const auto q = hn::Add(qa, qb);
  return hn::IfThenElse(hn::Gt(q, hn::Zero(dd)), hn::Div(qb, q), t);
}

// base + t d in double for both halves, rounded to float, as one float vector.
template <class DF, class DD>
HWY_INLINE hn::Vec<DF> lerp_to_float(DF df, DD dd, double base, double d, hn::Vec<DD> t_lo,
                                     hn::Vec<DD> t_hi) {
  const hn::Half<DF> dfh;
  const auto b = hn::Set(dd, base), dv = hn::Set(dd, d);
  return hn::Combine(df, hn::DemoteTo(dfh, hn::Add(b, hn::Mul(t_hi, dv))),
                     hn::DemoteTo(dfh, hn::Add(b, hn::Mul(t_lo, dv))));
}
#endif

void ShadeLinePixels(const LineShading& sh, const int32_t* x, const int32_t* y, size_t n,
                     const LineRunOut& out) {
#if HWY_HAVE_FLOAT64 && HWY_TARGET != HWY_SCALAR
  // A step covers one float vector of pixels: two double vectors, each rounded to half of it.
  const hn::ScalableTag<float> df;
  const hn::Repartition<double, decltype(df)> dd;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::Half<decltype(df)> dfh;
  const size_t lanes = hn::Lanes(df), half_lanes = hn::Lanes(dd);
  const auto tile_mask = hn::Set(di, static_cast<int32_t>(binning::kTileSize - 1));
  const auto block_mask = hn::Set(di, static_cast<int32_t>(detail::kBlockSize - 1));
  const auto block_pixels = hn::Set(di, static_cast<int32_t>(detail::kBlockPixels));
  const auto tiles_x = hn::Set(di, static_cast<int32_t>(out.tiles_x));
  if (n == 0) return;
  // Where lanes that draw nothing read the framebuffer for the blend: the run's first pixel,
  // which lies in the tile this task draws (other lanes' offsets may lie in another task's
  // tile, or off the framebuffer).
  const auto first_pixel = hn::Set(
      du, pixel_offset(static_cast<uint32_t>(x[0]), static_cast<uint32_t>(y[0]), out.tiles_x));
  for (size_t i = 0; i < n; i += lanes) {
    // sample_index: the storage tile's pixels, then detail::in_tile: block (ty / 8) * 8 + tx / 8
    // of 64 pixels, then row-major in the block.
    const auto ix = hn::LoadU(di, x + i), iy = hn::LoadU(di, y + i);
    const auto tile = hn::Add(hn::Mul(hn::ShiftRight<binning::kTileSizeLog2>(iy), tiles_x),
                              hn::ShiftRight<binning::kTileSizeLog2>(ix));
    const auto tx = hn::And(ix, tile_mask), ty = hn::And(iy, tile_mask);
    const auto block =
        hn::Add(hn::ShiftLeft<detail::kBlockSizeLog2>(hn::ShiftRight<detail::kBlockSizeLog2>(ty)),
                hn::ShiftRight<detail::kBlockSizeLog2>(tx));
    const auto offset = hn::Add(
        hn::Add(hn::ShiftLeft<2 * binning::kTileSizeLog2>(tile), hn::Mul(block, block_pixels)),
        hn::Add(hn::ShiftLeft<detail::kBlockSizeLog2>(hn::And(ty, block_mask)),
                hn::And(tx, block_mask)));
    hn::StoreU(hn::BitCast(du, offset), du, out.offset + i);

    const auto t_lo = line_t(dd, sh, x + i, y + i);
    const auto t_hi = line_t(dd, sh, x + i + half_lanes, y + i + half_lanes);
    const auto coverage =
        sh.smooth ? hn::Combine(df,
                                hn::DemoteTo(dfh, smooth_coverage(dd, sh, x + i + half_lanes,
                                                                  y + i + half_lanes)),
                                hn::DemoteTo(dfh, smooth_coverage(dd, sh, x + i, y + i)))
                  : hn::Zero(df);
    if (sh.smooth) hn::StoreU(coverage, df, out.coverage + i);
    // Without colour writes (dst null) the colour is neither formed nor blended.
    if (out.dst != nullptr) {
      const auto tc_lo = color_t(dd, sh, t_lo), tc_hi = color_t(dd, sh, t_hi);
      auto r = lerp_to_float(df, dd, sh.color[0], sh.dcolor[0], tc_lo, tc_hi);
      auto g = lerp_to_float(df, dd, sh.color[1], sh.dcolor[1], tc_lo, tc_hi);
      auto b = lerp_to_float(df, dd, sh.color[2], sh.dcolor[2], tc_lo, tc_hi);
      auto a = lerp_to_float(df, dd, sh.color[3], sh.dcolor[3], tc_lo, tc_hi);
      if (sh.smooth) {
        // Source over the framebuffer's colour, read where the pixel is drawn.
        const auto drawn =
            hn::And(hn::Gt(coverage, hn::Zero(df)), hn::RebindMask(df, hn::FirstN(di, n - i)));
        const auto dst =
            hn::GatherIndex(du, out.dst,
                            hn::BitCast(di, hn::IfThenElse(hn::RebindMask(du, drawn),
                                                           hn::BitCast(du, offset), first_pixel)));
        const auto alpha = hn::Mul(hn::Min(hn::Max(a, hn::Zero(df)), hn::Set(df, 1.0f)),
                                   hn::Min(coverage, hn::Set(df, 1.0f)));
        const auto keep = hn::Sub(hn::Set(df, 1.0f), alpha);
        const auto channel = [&](int shift) {
          const auto byte = hn::And(hn::ShiftRightSame(dst, shift), hn::Set(du, 0xFFu));
          return hn::Div(hn::ConvertTo(df, hn::BitCast(di, byte)), hn::Set(df, 255.0f));
        };
        r = hn::Add(hn::Mul(r, alpha), hn::Mul(channel(0), keep));
        g = hn::Add(hn::Mul(g, alpha), hn::Mul(channel(8), keep));
        b = hn::Add(hn::Mul(b, alpha), hn::Mul(channel(16), keep));
        a = hn::Add(alpha, hn::Mul(channel(24), keep));
      }
      hn::StoreU(pack_unorm8(df, r, g, b, a), du, out.rgba + i);
    }
    hn::StoreU(lerp_to_float(df, dd, sh.z, sh.dz, t_lo, t_hi), df, out.depth + i);
  }
#else
  shade_scalar(sh, x, y, n, out);
#endif
}

}  // namespace

LineShadeFn GetLineShadeKernel() {
  return &ShadeLinePixels;
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/target_list.hpp"

namespace tessera::fast {

namespace {
using KernelFn = LineShadeFn (*)();
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<KernelFn>{bit, &ns::GetLineShadeKernel},
constexpr simd::TargetEntry<KernelFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

LineShadeFn line_shade_kernel(int64_t target) {
  return simd::find_target(kTargets, target)();
}

}  // namespace tessera::fast
#endif  // HWY_ONCE
