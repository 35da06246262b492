// The engine's sampler: tessera/texture.hpp's rules (sampling.hpp) in float.
#include "engine/src/texture/sampling.hpp"

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

void sample(const Texture& texture, const Sampler& sampler, const FragmentBatch& batch,
            uint32_t u_varying, uint32_t v_varying, float* rgba) {
  constexpr uint32_t kStride = kFragmentBatchStride;
  const Texture::Storage& s = detail::TextureAccess::storage(texture);
  const float* u = batch.varyings + size_t{u_varying} * kStride;
  const float* v = batch.varyings + size_t{v_varying} * kStride;
  const float* du_dx = batch.ddx + size_t{u_varying} * kStride;
  const float* dv_dx = batch.ddx + size_t{v_varying} * kStride;
  const float* du_dy = batch.ddy + size_t{u_varying} * kStride;
  const float* dv_dy = batch.ddy + size_t{v_varying} * kStride;
  for (uint32_t i = 0; i < batch.count; ++i) {
    const float lambda = texture::lod<float>(s, sampler, du_dx[i], dv_dx[i], du_dy[i], dv_dy[i]);
    const std::array<float, 4> c = texture::sample<float>(s, sampler, u[i], v[i], lambda);
    for (uint32_t k = 0; k < 4; ++k)
      rgba[k * kStride + i] = c[k];
  }
}

}  // namespace tessera
