// The SIMD sampler's lanes (sample_batch.hpp), written once against Highway for every target:
// tessera/texture.hpp's rules with the scalar sampler's operations (sampling.hpp) in its order
// (multiplies and adds, no contraction), so every target gives the scalar sampler's bits. Each
// lane's level of detail and level choice come from the scalar rules (lod_of_rho(),
// choose_levels()) once per distinct footprint in the lane group (a quad's fragments share
// theirs); the texel positions, wrapping, gathers, decoding and filtering run in lanes.

// Per-target include guard (see engine/src/fast/block_kernel-inl.h).
#if defined(TESSERA_ENGINE_SRC_TEXTURE_SAMPLE_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_TEXTURE_SAMPLE_LANES_INL_H_
#undef TESSERA_ENGINE_SRC_TEXTURE_SAMPLE_LANES_INL_H_
#else
#define TESSERA_ENGINE_SRC_TEXTURE_SAMPLE_LANES_INL_H_
#endif

#include <algorithm>
#include <bit>
#include <cstdint>

#include <hwy/highway.h>

#include "engine/src/texture/sample_batch.hpp"
#include "engine/src/texture/sampling.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::texture::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Where `mask` is set, (r1, g1, b1, a1) replace (r, g, b, a).
template <class VF, class M>
HWY_INLINE void select(M mask, VF& r, VF& g, VF& b, VF& a, VF r1, VF g1, VF b1, VF a1) {
  r = hn::IfThenElse(mask, r1, r);
  g = hn::IfThenElse(mask, g1, g);
  b = hn::IfThenElse(mask, b1, b);
  a = hn::IfThenElse(mask, a1, a);
}

// Index i on an axis of n texels under `wrap` (n a power of two for repeat and mirrored
// repeat), clamped into the axis; `inside` is false where the border replaces the texel.
template <class DI, class VI = hn::Vec<DI>>
HWY_INLINE VI wrap_lanes(DI di, VI i, VI n, Wrap wrap, hn::Mask<DI>& inside) {
  const VI one = hn::Set(di, 1);
  inside = hn::FirstN(di, hn::Lanes(di));
  switch (wrap) {
    case Wrap::kRepeat:
      return hn::And(i, hn::Sub(n, one));
    case Wrap::kMirroredRepeat: {
      const VI last = hn::Sub(hn::Add(n, n), one);  // 2n - 1
      const VI m = hn::And(i, last);
      return hn::IfThenElse(hn::Lt(m, n), m, hn::Sub(last, m));
    }
    case Wrap::kClampToEdge:
      break;
    case Wrap::kClampToBorder:
      inside = hn::And(hn::Gt(i, hn::Set(di, -1)), hn::Lt(i, n));  // no Ge for integers
      break;
  }
  return hn::Min(hn::Max(i, hn::Zero(di)), hn::Sub(n, one));
}

// The texels at (x, y) of the level starting at `offset` with rows of `w` texels, decoded
// (texture_storage.hpp's unorm8 and sRGB table), the border where `inside` is false.
template <class DF, class VF = hn::Vec<DF>, class DI = hn::RebindToSigned<DF>,
          class VI = hn::Vec<DI>>
HWY_INLINE void fetch(DF df, const LaneTexture& src, VI offset, VI w, VI x, VI y,
                      hn::Mask<DI> inside, VF& r, VF& g, VF& b, VF& a) {
  const DI di;
  const VI t = hn::GatherIndex(di, src.texels, hn::Add(offset, hn::Add(hn::Mul(y, w), x)));
  const VI byte = hn::Set(di, 0xFF);
  const VI c0 = hn::And(t, byte), c1 = hn::And(hn::ShiftRight<8>(t), byte);
  const VI c2 = hn::And(hn::ShiftRight<16>(t), byte), c3 = hn::And(hn::ShiftRight<24>(t), byte);
  const VF scale = hn::Set(df, 255.0f);
  if (src.srgb != nullptr) {
    r = hn::GatherIndex(df, src.srgb, c0);
    g = hn::GatherIndex(df, src.srgb, c1);
    b = hn::GatherIndex(df, src.srgb, c2);
  } else {
    r = hn::Div(hn::ConvertTo(df, c0), scale);
    g = hn::Div(hn::ConvertTo(df, c1), scale);
    b = hn::Div(hn::ConvertTo(df, c2), scale);
  }
  a = hn::Div(hn::ConvertTo(df, c3), scale);
  const Sampler& s = src.sampler;
  if (s.wrap_u == Wrap::kClampToBorder || s.wrap_v == Wrap::kClampToBorder) {
    select(hn::Not(hn::RebindMask(df, inside)), r, g, b, a, hn::Set(df, s.border_color[0]),
           hn::Set(df, s.border_color[1]), hn::Set(df, s.border_color[2]),
           hn::Set(df, s.border_color[3]));
  }
}

// `top` + weight (`bottom` - `top`), per channel, into the first four.
template <class VF>
HWY_INLINE void lerp(VF& r, VF& g, VF& b, VF& a, VF r1, VF g1, VF b1, VF a1, VF weight) {
  r = hn::Add(r, hn::Mul(weight, hn::Sub(r1, r)));
  g = hn::Add(g, hn::Mul(weight, hn::Sub(g1, g)));
  b = hn::Add(b, hn::Mul(weight, hn::Sub(b1, b)));
  a = hn::Add(a, hn::Mul(weight, hn::Sub(a1, a)));
}

// sample_level (sampling.hpp) in lanes: level `level` of each lane (`same` when every lane has
// that one, else -1), nearest or linear.
template <class DF, class VF = hn::Vec<DF>, class DI = hn::RebindToSigned<DF>,
          class VI = hn::Vec<DI>>
HWY_INLINE void sample_level(DF df, const LaneTexture& src, VI level, int32_t same, bool linear,
                             VF u, VF v, VF& r, VF& g, VF& b, VF& a) {
  const DI di;
  VI w, h, offset;
  if (same >= 0) {
    w = hn::Set(di, src.width[same]);
    h = hn::Set(di, src.height[same]);
    offset = hn::Set(di, src.offset[same]);
  } else {
    w = hn::GatherIndex(di, src.width, level);
    h = hn::GatherIndex(di, src.height, level);
    offset = hn::GatherIndex(di, src.offset, level);
  }
  const VF x = hn::Mul(u, hn::ConvertTo(df, w)), y = hn::Mul(v, hn::ConvertTo(df, h));
  const VF lo = hn::Set(df, -static_cast<float>(kPositionLimit)),
           hi = hn::Set(df, static_cast<float>(kPositionLimit));
  hn::Mask<DI> in_x0, in_y0;
  if (!linear) {
    const VI i = hn::ConvertTo(di, hn::Floor(hn::Min(hn::Max(x, lo), hi)));
    const VI j = hn::ConvertTo(di, hn::Floor(hn::Min(hn::Max(y, lo), hi)));
    const VI xi = wrap_lanes(di, i, w, src.sampler.wrap_u, in_x0);
    const VI yi = wrap_lanes(di, j, h, src.sampler.wrap_v, in_y0);
    fetch(df, src, offset, w, xi, yi, hn::And(in_x0, in_y0), r, g, b, a);
    return;
  }
  const VF half = hn::Set(df, 0.5f);
  const VF xc = hn::Min(hn::Max(hn::Sub(x, half), lo), hi);
  const VF yc = hn::Min(hn::Max(hn::Sub(y, half), lo), hi);
  const VI i0 = hn::ConvertTo(di, hn::Floor(xc)), j0 = hn::ConvertTo(di, hn::Floor(yc));
  const VF fa = hn::Sub(xc, hn::ConvertTo(df, i0)), fb = hn::Sub(yc, hn::ConvertTo(df, j0));
  const VI one = hn::Set(di, 1);
  hn::Mask<DI> in_x1, in_y1;
  const VI x0 = wrap_lanes(di, i0, w, src.sampler.wrap_u, in_x0);
  const VI x1 = wrap_lanes(di, hn::Add(i0, one), w, src.sampler.wrap_u, in_x1);
  const VI y0 = wrap_lanes(di, j0, h, src.sampler.wrap_v, in_y0);
  const VI y1 = wrap_lanes(di, hn::Add(j0, one), h, src.sampler.wrap_v, in_y1);
  VF r10, g10, b10, a10, r01, g01, b01, a01, r11, g11, b11, a11;
  fetch(df, src, offset, w, x0, y0, hn::And(in_x0, in_y0), r, g, b, a);
  fetch(df, src, offset, w, x1, y0, hn::And(in_x1, in_y0), r10, g10, b10, a10);
  fetch(df, src, offset, w, x0, y1, hn::And(in_x0, in_y1), r01, g01, b01, a01);
  fetch(df, src, offset, w, x1, y1, hn::And(in_x1, in_y1), r11, g11, b11, a11);
  lerp(r, g, b, a, r10, g10, b10, a10, fa);          // top
  lerp(r01, g01, b01, a01, r11, g11, b11, a11, fa);  // bottom
  lerp(r, g, b, a, r01, g01, b01, a01, fb);
}

// The level filter per lane: nearest, linear, or each lane's own (`linear_lanes`).
template <class DF, class VF = hn::Vec<DF>, class DI = hn::RebindToSigned<DF>,
          class VI = hn::Vec<DI>>
HWY_INLINE void sample_level_mixed(DF df, const LaneTexture& src, VI level, int32_t same,
                                   hn::Mask<DI> linear_lanes, VF u, VF v, VF& r, VF& g, VF& b,
                                   VF& a) {
  const DI di;
  if (hn::AllTrue(di, linear_lanes)) {
    return sample_level(df, src, level, same, true, u, v, r, g, b, a);
  }
  if (hn::AllFalse(di, linear_lanes)) {
    return sample_level(df, src, level, same, false, u, v, r, g, b, a);
  }
  VF r1, g1, b1, a1;
  sample_level(df, src, level, same, false, u, v, r, g, b, a);
  sample_level(df, src, level, same, true, u, v, r1, g1, b1, a1);
  select(hn::RebindMask(df, linear_lanes), r, g, b, a, r1, g1, b1, a1);
}

// The filtered, linear RGBA of each lane over the footprint of its derivatives:
// sample_footprint() of sampling.hpp in lanes.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE void sample_lanes(DF df, const LaneTexture& src, VF u, VF v, VF du_dx, VF dv_dx,
                             VF du_dy, VF dv_dy, VF& r, VF& g, VF& b, VF& a) {
  const hn::RebindToSigned<DF> di;
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  const Texture::Storage& s = *src.storage;
  const Sampler& sampler = src.sampler;
  const uint32_t limit = anisotropy_limit(sampler);
  const auto not_nan = [](VF x) { return hn::IfThenElseZero(hn::Eq(x, x), x); };
  if (limit == 1 && sampler.mip_filter == MipFilter::kNone &&
      sampler.mag_filter == sampler.min_filter) {
    // Level 0 with the one filter whatever the level of detail (choose_levels): no footprint.
    const bool linear = sampler.min_filter == Filter::kLinear;
    const auto lanes_linear = linear ? hn::FirstN(di, hn::Lanes(di)) : hn::FirstN(di, 0);
    return sample_level_mixed(df, src, hn::Zero(di), 0, lanes_linear, not_nan(u), not_nan(v), r, g,
                              b, a);
  }
  // The footprint in level-0 texels, as lod() computes it.
  const VF w = hn::Set(df, static_cast<float>(s.desc.width));
  const VF h = hn::Set(df, static_cast<float>(s.desc.height));
  const auto length = [&](VF du, VF dv) {
    const VF a0 = hn::Mul(du, w), b0 = hn::Mul(dv, h);
    return hn::Sqrt(hn::Add(hn::Mul(a0, a0), hn::Mul(b0, b0)));
  };
  const VF x = length(du_dx, dv_dx), y = length(du_dy, dv_dy);
  alignas(64) float xs[kMaxLanes], ys[kMaxLanes], weight[kMaxLanes];
  alignas(64) int32_t first[kMaxLanes], second[kMaxLanes], linear[kMaxLanes], blend[kMaxLanes],
      count[kMaxLanes];
  hn::Store(x, df, xs);
  hn::Store(y, df, ys);
  const size_t lanes = hn::Lanes(df);
  // The choices of the last few distinct footprints: a lane group holds parts of a few quads
  // (a row of four on 16 lanes, then the row below), each with one footprint.
  constexpr uint32_t kMemo = 4;
  uint64_t memo_key[kMemo];
  Anisotropy<float> memo_aniso[kMemo];
  LevelChoice<float> memo[kMemo];
  uint32_t memo_count = 0, memo_next = 0, most = 1;
  int32_t same_first = -2, same_second = -2;  // -2: no lane yet; -1: lanes differ
  for (size_t i = 0; i < lanes; ++i) {
    const uint64_t key =
        uint64_t{std::bit_cast<uint32_t>(xs[i])} << 32 | std::bit_cast<uint32_t>(ys[i]);
    uint32_t k = 0;
    while (k < memo_count && memo_key[k] != key)
      ++k;
    if (k == memo_count) {
      k = memo_next;
      memo_next = (memo_next + 1) % kMemo;
      memo_count = std::min(memo_count + 1, kMemo);
      memo_key[k] = key;
      memo_aniso[k] = anisotropy<float>(limit, xs[i], ys[i]);
      memo[k] =
          choose_levels<float>(s, src.sampler, lod_of_rho<float>(src.sampler, memo_aniso[k].rho));
    }
    const LevelChoice<float>& choice = memo[k];
    count[i] = static_cast<int32_t>(memo_aniso[k].count);
    most = std::max(most, memo_aniso[k].count);
    first[i] = static_cast<int32_t>(choice.first);
    second[i] = static_cast<int32_t>(choice.second);
    weight[i] = choice.weight;
    linear[i] = choice.filter == Filter::kLinear ? -1 : 0;
    blend[i] = choice.blend ? -1 : 0;
    same_first = same_first == -2 || same_first == first[i] ? first[i] : -1;
    same_second = same_second == -2 || same_second == second[i] ? second[i] : -1;
  }
  const auto linear_lanes = hn::Ne(hn::Load(di, linear), hn::Zero(di));
  const auto blend_lanes = hn::Ne(hn::Load(di, blend), hn::Zero(di));
  // sample() at (su, sv) (not NaN) with each lane's level choice.
  const auto sample_at = [&](VF su, VF sv, VF& r0, VF& g0, VF& b0, VF& a0) {
    sample_level_mixed(df, src, hn::Load(di, first), same_first, linear_lanes, su, sv, r0, g0, b0,
                       a0);
    if (hn::AllFalse(di, blend_lanes)) return;
    VF r1, g1, b1, a1;
    sample_level_mixed(df, src, hn::Load(di, second), same_second, linear_lanes, su, sv, r1, g1, b1,
                       a1);
    VF rb = r0, gb = g0, bb = b0, ab = a0;
    lerp(rb, gb, bb, ab, r1, g1, b1, a1, hn::Load(df, weight));
    select(hn::RebindMask(df, blend_lanes), r0, g0, b0, a0, rb, gb, bb, ab);
  };
  if (most == 1) return sample_at(not_nan(u), not_nan(v), r, g, b, a);
  // Anisotropic: sample i of each lane's n at offset i / (n + 1) - 1/2 along the longer axis
  // (none where n is 1), summed in order where i <= n, then divided by n.
  const auto n = hn::Load(di, count);
  const auto one = hn::Set(di, 1);
  const auto single = hn::RebindMask(df, hn::Eq(n, one));
  const VF n_plus_1 = hn::ConvertTo(df, hn::Add(n, one));
  const auto along_x = hn::Gt(x, y);
  const VF step_u = hn::IfThenElse(along_x, du_dx, du_dy);
  const VF step_v = hn::IfThenElse(along_x, dv_dx, dv_dy);
  for (uint32_t i = 1; i <= most; ++i) {
    const VF t = hn::Sub(hn::Div(hn::Set(df, static_cast<float>(i)), n_plus_1), hn::Set(df, 0.5f));
    const VF su = hn::IfThenElse(single, u, hn::Add(u, hn::Mul(t, step_u)));
    const VF sv = hn::IfThenElse(single, v, hn::Add(v, hn::Mul(t, step_v)));
    if (i == 1) {
      sample_at(not_nan(su), not_nan(sv), r, g, b, a);
      continue;
    }
    VF ri, gi, bi, ai;
    sample_at(not_nan(su), not_nan(sv), ri, gi, bi, ai);
    const auto active = hn::RebindMask(df, hn::Lt(hn::Set(di, static_cast<int32_t>(i) - 1), n));
    select(active, r, g, b, a, hn::Add(r, ri), hn::Add(g, gi), hn::Add(b, bi), hn::Add(a, ai));
  }
  const VF nf = hn::ConvertTo(df, n);
  r = hn::Div(r, nf);
  g = hn::Div(g, nf);
  b = hn::Div(b, nf);
  a = hn::Div(a, nf);
}

}  // namespace tessera::texture::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
