// The SIMD sampler (sample_batch.cpp): tessera/texture.hpp's sampling rules over a batch of
// fragments, for the batch form of tessera::sample and the engine's textured shader.
#pragma once

#include <cstdint>

#include "engine/src/texture/texture_storage.hpp"

namespace tessera::texture {

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

// sample() (sampling.hpp, in float) at every fragment of the batch, with the level of detail
// from its derivatives (lod()), into rgba[c * kFragmentBatchStride + i] for channel c of
// fragment i < count: the same bits as the scalar sampler, on the SIMD target `target` (a
// Highway target bit, as simd::resolve_target gives; one this build lacks runs the portable
// baseline). RGBA8 and sRGB textures are sampled in SIMD lanes, except with repeat or mirrored
// wrapping on a side that is not a power of two; the rest fragment by fragment.
void sample_batch(int64_t target, const Texture::Storage& storage, const Sampler& sampler,
                  const BatchCoordinates& in, float* rgba);

}  // namespace tessera::texture
