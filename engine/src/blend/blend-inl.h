// Blending in SIMD lanes, written once against Highway for every target: blend.hpp's
// operations, in the same order, on a vector of samples at once, so the fast engine's lanes
// store the bytes the reference stores. The state is read per vector (a switch over each
// factor), not compiled in: one copy serves every blend state.

// Per-target include guard (as block_kernel-inl.h's).
#if defined(TESSERA_ENGINE_SRC_BLEND_BLEND_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_BLEND_BLEND_INL_H_
#undef TESSERA_ENGINE_SRC_BLEND_BLEND_INL_H_
#else
#define TESSERA_ENGINE_SRC_BLEND_BLEND_INL_H_
#endif

#include <hwy/highway.h>

#include "engine/src/blend/blend.hpp"
#include "tessera/pipeline.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::blend::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// blend.hpp's saturate: [0, 1], NaN 0.
template <class DF, class VF>
HWY_INLINE VF saturate(DF df, VF v) {
  return hn::Min(hn::IfThenElseZero(hn::Gt(v, hn::Zero(df)), v), hn::Set(df, 1.0f));
}

// blend.hpp's factor for a channel whose source, destination and constant values are sc, dc
// and kc (alpha: sa, da, ka); `alpha` for the alpha channel.
template <class DF, class VF>
HWY_INLINE VF factor(DF df, BlendFactor f, bool alpha, VF sc, VF sa, VF dc, VF da, float kc,
                     float ka) {
  const VF one = hn::Set(df, 1.0f);
  switch (f) {
    case BlendFactor::kZero:
      return hn::Zero(df);
    case BlendFactor::kOne:
      return one;
    case BlendFactor::kSrcColor:
      return sc;
    case BlendFactor::kOneMinusSrcColor:
      return hn::Sub(one, sc);
    case BlendFactor::kDstColor:
      return dc;
    case BlendFactor::kOneMinusDstColor:
      return hn::Sub(one, dc);
    case BlendFactor::kSrcAlpha:
      return sa;
    case BlendFactor::kOneMinusSrcAlpha:
      return hn::Sub(one, sa);
    case BlendFactor::kDstAlpha:
      return da;
    case BlendFactor::kOneMinusDstAlpha:
      return hn::Sub(one, da);
    case BlendFactor::kConstantColor:
      return hn::Set(df, kc);
    case BlendFactor::kOneMinusConstantColor:
      return hn::Set(df, 1.0f - kc);
    case BlendFactor::kConstantAlpha:
      return hn::Set(df, ka);
    case BlendFactor::kOneMinusConstantAlpha:
      return hn::Set(df, 1.0f - ka);
    case BlendFactor::kSrcAlphaSaturate: {
      if (alpha) return one;
      const VF rest = hn::Sub(one, da);
      return hn::IfThenElse(hn::Lt(rest, sa), rest, sa);
    }
  }
  return hn::Zero(df);
}

// blend.hpp's combine.
template <class DF, class VF>
HWY_INLINE VF combine(DF /*df*/, BlendOp op, VF s, VF fs, VF d, VF fd) {
  switch (op) {
    case BlendOp::kAdd:
      return hn::Add(hn::Mul(s, fs), hn::Mul(d, fd));
    case BlendOp::kSubtract:
      return hn::Sub(hn::Mul(s, fs), hn::Mul(d, fd));
    case BlendOp::kReverseSubtract:
      return hn::Sub(hn::Mul(d, fd), hn::Mul(s, fs));
    case BlendOp::kMin:
      return hn::IfThenElse(hn::Lt(s, d), s, d);
    case BlendOp::kMax:
      return hn::IfThenElse(hn::Gt(s, d), s, d);
  }
  return s;
}

// One channel of blend.hpp's blend.
template <class DF, class VF>
HWY_INLINE VF channel(DF df, const BlendState& b, bool alpha, VF sc, VF sa, VF dc, VF da, float kc,
                      float ka) {
  const VF fs = factor(df, alpha ? b.src_alpha : b.src_color, alpha, sc, sa, dc, da, kc, ka);
  const VF fd = factor(df, alpha ? b.dst_alpha : b.dst_color, alpha, sc, sa, dc, da, kc, ka);
  return combine(df, alpha ? b.alpha_op : b.color_op, sc, fs, dc, fd);
}

// blend.hpp's blend of source (r, g, b, a) over destination (dr, dg, db, da) with constant k,
// in place of the source; `unorm` clamps source and constant first. Nothing changes without
// b.enable.
template <class DF, class VF>
HWY_INLINE void blend(DF df, const BlendState& b, const float* k_in, bool unorm, VF& r, VF& g,
                      VF& bl, VF& a, VF dr, VF dg, VF db, VF da) {
  if (!b.enable) return;
  float k[4] = {k_in[0], k_in[1], k_in[2], k_in[3]};
  if (unorm) {
    r = saturate(df, r);
    g = saturate(df, g);
    bl = saturate(df, bl);
    a = saturate(df, a);
    for (float& v : k)
      v = tessera::blend::saturate(v);
  }
  const VF r2 = channel(df, b, false, r, a, dr, da, k[0], k[3]);
  const VF g2 = channel(df, b, false, g, a, dg, da, k[1], k[3]);
  const VF b2 = channel(df, b, false, bl, a, db, da, k[2], k[3]);
  a = channel(df, b, true, a, a, da, da, k[3], k[3]);
  r = r2;
  g = g2;
  bl = b2;
}

}  // namespace tessera::blend::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
