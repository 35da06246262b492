// The line shading kernel (line_kernel.hpp), compiled for every SIMD target through
// hwy/foreach_target.h. Lanes are pixels of one run, in double precision: each lane computes
// exactly what the reference's scalar code computes for its pixel (same operations in the same
// order, contraction off), then converts to float and to unorm8 as to_unorm8 does.
#include <cstring>

#include "engine/src/fast/line_kernel.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/line_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "binning/tile_grid.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

#if !HWY_HAVE_FLOAT64
void shade_scalar(const LineShading& sh, const int32_t* x, const int32_t* y, size_t n,
                  const LineRunOut& out) {
  for (size_t i = 0; i < n; ++i) {
    double t = ((static_cast<double>(x[i]) + 0.5 - sh.ax) * sh.ex +
                (static_cast<double>(y[i]) + 0.5 - sh.ay) * sh.ey) *
               sh.inv_len2;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    double tc = t;
    if (sh.perspective) {
      const double qa = (1.0 - t) * sh.inv_wa, qb = t * sh.inv_wb;
      tc = qa + qb > 0.0 ? qb / (qa + qb) : t;
    }
    uint32_t packed = 0;
    for (int c = 0; c < 4; ++c) {
      packed |= uint32_t{to_unorm8(static_cast<float>(sh.color[c] + tc * sh.dcolor[c]))} << (8 * c);
    }
    out.rgba[i] = packed;
    out.depth[i] = static_cast<float>(sh.z + t * sh.dz);
    out.offset[i] = detail::in_tile(static_cast<uint32_t>(x[i]), static_cast<uint32_t>(y[i]));
  }
}
#else
template <class DF, class VF>
HWY_INLINE auto unorm8(DF df, VF c) {
  const hn::RebindToSigned<DF> di;
  const auto clamped = hn::Min(hn::Max(c, hn::Zero(df)), hn::Set(df, 1.0f));
  const auto scaled = hn::Add(hn::Mul(clamped, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
  return hn::BitCast(hn::RebindToUnsigned<DF>(), hn::ConvertTo(di, scaled));
}
#endif

void ShadeLinePixels(const LineShading& sh, const int32_t* x, const int32_t* y, size_t n,
                     const LineRunOut& out) {
#if HWY_HAVE_FLOAT64
  const hn::ScalableTag<double> dd;
  const hn::Rebind<int32_t, decltype(dd)> di;
  const hn::Rebind<float, decltype(dd)> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  const size_t lanes = hn::Lanes(dd);
  const auto half = hn::Set(dd, 0.5), zero = hn::Zero(dd), one = hn::Set(dd, 1.0);
  const auto ax = hn::Set(dd, sh.ax), ay = hn::Set(dd, sh.ay);
  const auto ex = hn::Set(dd, sh.ex), ey = hn::Set(dd, sh.ey), inv = hn::Set(dd, sh.inv_len2);
  const auto tile_mask = hn::Set(di, static_cast<int32_t>(binning::kTileSize - 1));
  const auto block_mask = hn::Set(di, static_cast<int32_t>(detail::kBlockSize - 1));
  for (size_t i = 0; i < n; i += lanes) {
    const auto ix = hn::LoadU(di, x + i), iy = hn::LoadU(di, y + i);
    const auto px = hn::PromoteTo(dd, ix);
    const auto py = hn::PromoteTo(dd, iy);
    // detail::in_tile: block (ty / 8) * 8 + tx / 8 of 64 pixels, then row-major in the block.
    const auto tx = hn::And(ix, tile_mask), ty = hn::And(iy, tile_mask);
    const auto block =
        hn::Add(hn::ShiftLeft<detail::kBlockSizeLog2>(hn::ShiftRight<detail::kBlockSizeLog2>(ty)),
                hn::ShiftRight<detail::kBlockSizeLog2>(tx));
    const auto offset =
        hn::Add(hn::Mul(block, hn::Set(di, static_cast<int32_t>(detail::kBlockPixels))),
                hn::Add(hn::ShiftLeft<detail::kBlockSizeLog2>(hn::And(ty, block_mask)),
                        hn::And(tx, block_mask)));
    hn::StoreU(hn::BitCast(du, offset), du, out.offset + i);
    const auto along = hn::Add(hn::Mul(hn::Sub(hn::Add(px, half), ax), ex),
                               hn::Mul(hn::Sub(hn::Add(py, half), ay), ey));
    const auto t = hn::Min(hn::Max(hn::Mul(along, inv), zero), one);
    auto tc = t;
    if (sh.perspective) {
      const auto qa = hn::Mul(hn::Sub(one, t), hn::Set(dd, sh.inv_wa));
      const auto qb = hn::Mul(t, hn::Set(dd, sh.inv_wb));
      const auto q = hn::Add(qa, qb);
      tc = hn::IfThenElse(hn::Gt(q, zero), hn::Div(qb, q), t);
    }
    auto packed = hn::Zero(du);
    for (int c = 0; c < 4; ++c) {
      const auto value = hn::Add(hn::Set(dd, sh.color[c]), hn::Mul(tc, hn::Set(dd, sh.dcolor[c])));
      packed = hn::Or(packed, hn::ShiftLeftSame(unorm8(df, hn::DemoteTo(df, value)), 8 * c));
    }
    hn::StoreU(packed, du, out.rgba + i);
    hn::StoreU(hn::DemoteTo(df, hn::Add(hn::Set(dd, sh.z), hn::Mul(t, hn::Set(dd, sh.dz)))), df,
               out.depth + i);
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
