// The engine's sampler: tessera/texture.hpp's rules (sampling.hpp) in float.
#include "engine/src/texture/sample_batch.hpp"
#include "engine/src/texture/sampling.hpp"
#include "simd/dispatch.hpp"
#include "tessera/error.hpp"

namespace tessera {

float texture_lod(const Texture& texture, const Sampler& sampler, float du_dx, float dv_dx,
                  float du_dy, float dv_dy) {
  return texture::lod<float>(detail::TextureAccess::storage(texture), sampler, du_dx, dv_dx, du_dy,
                             dv_dy);
}

std::array<float, 4> sample(const Texture& texture, const Sampler& sampler, float u, float v,
                            float lod) {
  return texture::sample<float>(detail::TextureAccess::storage(texture), sampler, u, v, lod);
}

std::array<float, 4> sample(const Texture& texture, const Sampler& sampler, float u, float v,
                            float du_dx, float dv_dx, float du_dy, float dv_dy) {
  return texture::sample_footprint<float>(detail::TextureAccess::storage(texture), sampler, u, v,
                                          du_dx, dv_dx, du_dy, dv_dy);
}

void sample(const Texture& texture, const Sampler& sampler, const FragmentBatch& batch,
            uint32_t u_varying, uint32_t v_varying, float* rgba) {
  // The automatic SIMD target (TESSERA_SIMD's when set): every target gives the same bits, so
  // an unusable TESSERA_SIMD, which a renderer reports, falls back to the portable baseline.
  static const int64_t target = [] {
    try {
      return simd::resolve_target(SimdTarget::kAuto);
    } catch (const Error&) {
      return int64_t{0};
    }
  }();
  const Texture::Storage& storage = detail::TextureAccess::storage(texture);
  texture::LaneTexture lanes;
  const bool in_lanes = texture::lanes_apply(storage, sampler, lanes);
  texture::sample_batch(target, storage, sampler, in_lanes ? &lanes : nullptr,
                        texture::coordinates_of(batch, u_varying, v_varying), rgba);
}

}  // namespace tessera
