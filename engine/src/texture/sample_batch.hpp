// The SIMD sampler: tessera/texture.hpp's sampling rules in lanes (sample_lanes-inl.h), for the
// batch form of tessera::sample (sample_batch.cpp), the quad back end's textured targets and
// the fast engine's textured shader (shade-inl.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/src/texture/texture_storage.hpp"

namespace tessera::texture {

// A texture and sampler as the lanes read them: the texels as 32-bit words, each level's size
// and first texel, the sRGB table, the wrap modes and the border colour.
struct LaneTexture {
  static constexpr uint32_t kMaxLevels = 16;  // a 16384-texel side has 15
  const Texture::Storage* storage = nullptr;
  Sampler sampler;
  const int32_t* texels = nullptr;
  alignas(64) int32_t width[kMaxLevels] = {};
  alignas(64) int32_t height[kMaxLevels] = {};
  alignas(64) int32_t offset[kMaxLevels] = {};
  const float* srgb = nullptr;  // null for linear RGBA8
};

// Whether the lanes sample `storage` with `sampler`: RGBA8 and sRGB textures, except with
// repeat or mirrored wrapping on a side that is not a power of two. When
// they do, fills `out` (which refers to `storage` from then on).
bool lanes_apply(const Texture::Storage& storage, const Sampler& sampler, LaneTexture& out);

// A batch's texture coordinates and their derivatives per pixel step, `count` (at most
// kFragmentBatchStride) values each.
struct BatchCoordinates {
  const float* u;
  const float* v;
  const float* du_dx;
  const float* dv_dx;
  const float* du_dy;
  const float* dv_dy;
  uint32_t count;
};

// A user shader's batch's varyings `u_varying` and `v_varying` and their derivatives.
inline BatchCoordinates coordinates_of(const FragmentBatch& batch, uint32_t u_varying,
                                       uint32_t v_varying) {
  const auto row = [](const float* values, uint32_t varying) {
    return values + size_t{varying} * kFragmentBatchStride;
  };
  return {row(batch.varyings, u_varying),
          row(batch.varyings, v_varying),
          row(batch.ddx, u_varying),
          row(batch.ddx, v_varying),
          row(batch.ddy, u_varying),
          row(batch.ddy, v_varying),
          batch.count};
}

// sample_footprint() (sampling.hpp, in float) at every fragment of the batch, into rgba[c *
// kFragmentBatchStride + i] for channel c of fragment i < count: the same bits as the scalar
// sampler, on the SIMD target `target` (a Highway target bit, as simd::resolve_target gives; one
// this build lacks runs the portable baseline): in lanes with `lanes` (what lanes_apply filled for
// this texture and sampler), fragment by fragment without (null).
void sample_batch(int64_t target, const Texture::Storage& storage, const Sampler& sampler,
                  const LaneTexture* lanes, const BatchCoordinates& in, float* rgba);

}  // namespace tessera::texture
