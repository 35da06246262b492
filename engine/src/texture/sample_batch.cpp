// The SIMD sampler (sample_batch.hpp), compiled for every SIMD target. Each fragment's level of
// detail and level choice come from the scalar rules (lod(), choose_levels(): once per quad, as
// a quad's fragments share their derivatives); the texel positions, wrapping, gathers,
// decoding and filtering run in lanes with the scalar sampler's operations in its order
// (multiplies and adds, no contraction), so every target gives the scalar sampler's bits.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/texture/sample_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cstring>

#include "engine/src/texture/sample_batch.hpp"
#include "engine/src/texture/sampling.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::texture::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

constexpr uint32_t kStride = kFragmentBatchStride;
constexpr uint32_t kMaxLevels = 16;  // a 16384-texel side has 15
constexpr float kLimit = float(1 << 30);
// Per-fragment arrays hold whole lane groups past a batch's last fragment (SVE's vectors may
// hold any multiple of four floats, up to 64).
constexpr uint32_t kPadded = 2 * kStride;

// What the lanes read: the texture's texels as 32-bit words, each level's size and first
// texel, the sRGB table, the wrap modes and the border colour.
struct Source {
  const int32_t* texels;
  alignas(64) int32_t width[kMaxLevels];
  alignas(64) int32_t height[kMaxLevels];
  alignas(64) int32_t offset[kMaxLevels];
  const float* srgb;  // null for linear RGBA8
  Wrap wrap_u, wrap_v;
  float border[4];
};

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
HWY_INLINE void fetch(DF df, const Source& src, VI offset, VI w, VI x, VI y, hn::Mask<DI> inside,
                      VF& r, VF& g, VF& b, VF& a) {
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
  if (src.wrap_u == Wrap::kClampToBorder || src.wrap_v == Wrap::kClampToBorder) {
    const auto in = hn::RebindMask(df, inside);
    r = hn::IfThenElse(in, r, hn::Set(df, src.border[0]));
    g = hn::IfThenElse(in, g, hn::Set(df, src.border[1]));
    b = hn::IfThenElse(in, b, hn::Set(df, src.border[2]));
    a = hn::IfThenElse(in, a, hn::Set(df, src.border[3]));
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

// sample_level (sampling.hpp) in lanes: level `level` of each lane, nearest or linear.
template <class DF, class VF = hn::Vec<DF>, class DI = hn::RebindToSigned<DF>,
          class VI = hn::Vec<DI>>
HWY_INLINE void sample_level(DF df, const Source& src, VI level, bool linear, VF u, VF v, VF& r,
                             VF& g, VF& b, VF& a) {
  const DI di;
  const VI w = hn::GatherIndex(di, src.width, level), h = hn::GatherIndex(di, src.height, level);
  const VI offset = hn::GatherIndex(di, src.offset, level);
  const VF x = hn::Mul(u, hn::ConvertTo(df, w)), y = hn::Mul(v, hn::ConvertTo(df, h));
  const VF lo = hn::Set(df, -kLimit), hi = hn::Set(df, kLimit);
  hn::Mask<DI> in_x0, in_y0;
  if (!linear) {
    const VI i = hn::ConvertTo(di, hn::Floor(hn::Min(hn::Max(x, lo), hi)));
    const VI j = hn::ConvertTo(di, hn::Floor(hn::Min(hn::Max(y, lo), hi)));
    const VI xi = wrap_lanes(di, i, w, src.wrap_u, in_x0);
    const VI yi = wrap_lanes(di, j, h, src.wrap_v, in_y0);
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
  const VI x0 = wrap_lanes(di, i0, w, src.wrap_u, in_x0);
  const VI x1 = wrap_lanes(di, hn::Add(i0, one), w, src.wrap_u, in_x1);
  const VI y0 = wrap_lanes(di, j0, h, src.wrap_v, in_y0);
  const VI y1 = wrap_lanes(di, hn::Add(j0, one), h, src.wrap_v, in_y1);
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
HWY_INLINE void sample_level_mixed(DF df, const Source& src, VI level, hn::Mask<DI> linear_lanes,
                                   VF u, VF v, VF& r, VF& g, VF& b, VF& a) {
  const DI di;
  if (hn::AllTrue(di, linear_lanes)) return sample_level(df, src, level, true, u, v, r, g, b, a);
  if (hn::AllFalse(di, linear_lanes)) {
    return sample_level(df, src, level, false, u, v, r, g, b, a);
  }
  VF r1, g1, b1, a1;
  sample_level(df, src, level, false, u, v, r, g, b, a);
  sample_level(df, src, level, true, u, v, r1, g1, b1, a1);
  const auto m = hn::RebindMask(df, linear_lanes);
  r = hn::IfThenElse(m, r1, r);
  g = hn::IfThenElse(m, g1, g);
  b = hn::IfThenElse(m, b1, b);
  a = hn::IfThenElse(m, a1, a);
}

bool power_of_two(uint32_t n) {
  return std::has_single_bit(n);
}

// Whether the lanes take this texture and sampler (sample_batch.hpp).
bool lanes_apply(const Texture::Storage& s, const Sampler& sampler) {
  if (s.desc.format != TextureFormat::kRGBA8 && s.desc.format != TextureFormat::kRGBA8Srgb) {
    return false;
  }
  const auto side_ok = [](Wrap wrap, uint32_t n) {
    return (wrap != Wrap::kRepeat && wrap != Wrap::kMirroredRepeat) || power_of_two(n);
  };
  return s.levels.size() <= kMaxLevels && side_ok(sampler.wrap_u, s.desc.width) &&
         side_ok(sampler.wrap_v, s.desc.height);
}

}  // namespace

void SampleBatch(const Texture::Storage& s, const Sampler& sampler, const BatchCoordinates& in,
                 float* rgba) {
  const uint32_t count = std::min(in.count, kStride);
  if (!lanes_apply(s, sampler)) {
    for (uint32_t i = 0; i < count; ++i) {
      const float lambda =
          lod<float>(s, sampler, in.du_dx[i], in.dv_dx[i], in.du_dy[i], in.dv_dy[i]);
      const std::array<float, 4> c = sample<float>(s, sampler, in.u[i], in.v[i], lambda);
      for (uint32_t k = 0; k < 4; ++k)
        rgba[k * kStride + i] = c[k];
    }
    return;
  }

  Source src;
  src.texels = reinterpret_cast<const int32_t*>(s.bytes.data());
  for (uint32_t l = 0; l < kMaxLevels; ++l) {
    const auto& level = s.levels[std::min<size_t>(l, s.levels.size() - 1)];
    src.width[l] = static_cast<int32_t>(level.width);
    src.height[l] = static_cast<int32_t>(level.height);
    src.offset[l] = static_cast<int32_t>(level.offset / 4);
  }
  src.srgb = s.desc.format == TextureFormat::kRGBA8Srgb ? srgb_table<float>().data() : nullptr;
  src.wrap_u = sampler.wrap_u;
  src.wrap_v = sampler.wrap_v;
  std::copy_n(sampler.border_color.begin(), 4, src.border);

  // Per fragment: its coordinates (NaN read as 0, as sample_level does) and its level choice,
  // computed once per run of equal derivatives (a quad's). The lanes past `count` sample level 0
  // at (0, 0) and are not stored.
  alignas(64) float u[kPadded] = {}, v[kPadded] = {}, weight[kPadded] = {};
  alignas(64) int32_t first[kPadded] = {}, second[kPadded] = {}, linear[kPadded] = {},
                      blend[kPadded] = {};
  float previous[4] = {};
  LevelChoice<float> choice;
  for (uint32_t i = 0; i < count; ++i) {
    u[i] = in.u[i] == in.u[i] ? in.u[i] : 0.0f;
    v[i] = in.v[i] == in.v[i] ? in.v[i] : 0.0f;
    const float d[4] = {in.du_dx[i], in.dv_dx[i], in.du_dy[i], in.dv_dy[i]};
    if (i == 0 || std::memcmp(d, previous, sizeof d) != 0) {
      std::memcpy(previous, d, sizeof d);
      choice = choose_levels<float>(s, sampler, lod<float>(s, sampler, d[0], d[1], d[2], d[3]));
    }
    first[i] = static_cast<int32_t>(choice.first);
    second[i] = static_cast<int32_t>(choice.second);
    weight[i] = choice.weight;
    linear[i] = choice.filter == Filter::kLinear ? -1 : 0;
    blend[i] = choice.blend ? -1 : 0;
  }

  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const size_t lanes = hn::Lanes(df);
  alignas(64) float out[4][kPadded];
  for (uint32_t i = 0; i < count; i += static_cast<uint32_t>(lanes)) {
    const auto fu = hn::Load(df, u + i), fv = hn::Load(df, v + i);
    const auto linear_lanes = hn::Ne(hn::Load(di, linear + i), hn::Zero(di));
    auto r = hn::Zero(df), g = r, b = r, a = r;
    sample_level_mixed(df, src, hn::Load(di, first + i), linear_lanes, fu, fv, r, g, b, a);
    const auto blend_lanes = hn::Ne(hn::Load(di, blend + i), hn::Zero(di));
    if (!hn::AllFalse(di, blend_lanes)) {
      auto r1 = r, g1 = g, b1 = b, a1 = a;
      sample_level_mixed(df, src, hn::Load(di, second + i), linear_lanes, fu, fv, r1, g1, b1, a1);
      auto rb = r, gb = g, bb = b, ab = a;
      lerp(rb, gb, bb, ab, r1, g1, b1, a1, hn::Load(df, weight + i));
      const auto m = hn::RebindMask(df, blend_lanes);
      r = hn::IfThenElse(m, rb, r);
      g = hn::IfThenElse(m, gb, g);
      b = hn::IfThenElse(m, bb, b);
      a = hn::IfThenElse(m, ab, a);
    }
    hn::Store(r, df, out[0] + i);
    hn::Store(g, df, out[1] + i);
    hn::Store(b, df, out[2] + i);
    hn::Store(a, df, out[3] + i);
  }
  for (uint32_t k = 0; k < 4; ++k)
    std::copy_n(out[k], count, rgba + k * kStride);
}

}  // namespace tessera::texture::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/target_list.hpp"

namespace tessera::texture {

namespace {
using SampleFn = void (*)(const Texture::Storage&, const Sampler&, const BatchCoordinates&, float*);
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<SampleFn>{bit, &ns::SampleBatch},
constexpr simd::TargetEntry<SampleFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

void sample_batch(int64_t target, const Texture::Storage& storage, const Sampler& sampler,
                  const BatchCoordinates& in, float* rgba) {
  simd::find_target(kTargets, target)(storage, sampler, in, rgba);
}

}  // namespace tessera::texture
#endif  // HWY_ONCE
