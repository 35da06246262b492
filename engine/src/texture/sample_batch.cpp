// The batch form of the SIMD sampler (sample_batch.hpp), compiled for every SIMD target: a
// batch's fragments in lane groups through sample_lanes-inl.h, or fragment by fragment where
// the lanes do not apply.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/texture/sample_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>

#include "engine/src/texture/sample_batch.hpp"
#include "engine/src/texture/sample_lanes-inl.h"
#include "engine/src/texture/sampling.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::texture::HWY_NAMESPACE {

namespace {

constexpr uint32_t kStride = kFragmentBatchStride;
// Per-fragment arrays hold whole lane groups past a batch's last fragment (SVE's vectors may
// hold any multiple of four floats, up to 64).
constexpr uint32_t kPadded = 2 * kStride;

}  // namespace

void SampleBatch(const Texture::Storage& s, const Sampler& sampler, const LaneTexture* src,
                 const BatchCoordinates& in, float* rgba) {
  const uint32_t count = std::min(in.count, kStride);
  if (src == nullptr) {
    for (uint32_t i = 0; i < count; ++i) {
      const std::array<float, 4> c = sample_footprint<float>(
          s, sampler, in.u[i], in.v[i], in.du_dx[i], in.dv_dx[i], in.du_dy[i], in.dv_dy[i]);
      for (uint32_t k = 0; k < 4; ++k)
        rgba[k * kStride + i] = c[k];
    }
    return;
  }
  // The inputs copied into whole lane groups; the lanes past `count` sample at (0, 0) with
  // zero derivatives and are not stored. (Nothing past the last lane group is read, so the
  // arrays are not cleared: batches of a few fragments are common.)
  const hn::ScalableTag<float> df;
  const size_t lanes = hn::Lanes(df);
  const uint32_t padded = static_cast<uint32_t>((count + lanes - 1) / lanes * lanes);
  alignas(64) float values[6][kPadded];
  const float* const from[6] = {in.u, in.v, in.du_dx, in.dv_dx, in.du_dy, in.dv_dy};
  for (uint32_t k = 0; k < 6; ++k) {
    std::copy_n(from[k], count, values[k]);
    std::fill(values[k] + count, values[k] + padded, 0.0f);
  }
  alignas(64) float out[4][kPadded];
  for (uint32_t i = 0; i < count; i += static_cast<uint32_t>(lanes)) {
    auto r = hn::Zero(df), g = r, b = r, a = r;
    sample_lanes(df, *src, hn::Load(df, values[0] + i), hn::Load(df, values[1] + i),
                 hn::Load(df, values[2] + i), hn::Load(df, values[3] + i),
                 hn::Load(df, values[4] + i), hn::Load(df, values[5] + i), r, g, b, a);
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

bool lanes_apply(const Texture::Storage& s, const Sampler& sampler, LaneTexture& out) {
  if (s.desc.format != TextureFormat::kRGBA8 && s.desc.format != TextureFormat::kRGBA8Srgb) {
    return false;
  }
  const auto side_ok = [](Wrap wrap, uint32_t n) {
    return (wrap != Wrap::kRepeat && wrap != Wrap::kMirroredRepeat) || std::has_single_bit(n);
  };
  if (s.levels.size() > LaneTexture::kMaxLevels || !side_ok(sampler.wrap_u, s.desc.width) ||
      !side_ok(sampler.wrap_v, s.desc.height)) {
    return false;
  }
  out.storage = &s;
  out.sampler = sampler;
  out.texels = reinterpret_cast<const int32_t*>(s.bytes.data());
  for (uint32_t l = 0; l < s.levels.size(); ++l) {  // the lanes read no level past the chain
    out.width[l] = static_cast<int32_t>(s.levels[l].width);
    out.height[l] = static_cast<int32_t>(s.levels[l].height);
    out.offset[l] = static_cast<int32_t>(s.levels[l].offset / 4);
  }
  out.srgb = s.desc.format == TextureFormat::kRGBA8Srgb ? srgb_table<float>().data() : nullptr;
  return true;
}

namespace {
using SampleFn = void (*)(const Texture::Storage&, const Sampler&, const LaneTexture*,
                          const BatchCoordinates&, float*);
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<SampleFn>{bit, &ns::SampleBatch},
constexpr simd::TargetEntry<SampleFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

void sample_batch(int64_t target, const Texture::Storage& storage, const Sampler& sampler,
                  const LaneTexture* lanes, const BatchCoordinates& in, float* rgba) {
  simd::find_target(kTargets, target)(storage, sampler, lanes, in, rgba);
}

}  // namespace tessera::texture
#endif  // HWY_ONCE
