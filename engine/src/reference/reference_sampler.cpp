// Texture sampling in double for the reference (reference_sampler.hpp).
#include "engine/src/reference/reference_sampler.hpp"

#include "engine/src/texture/sampling.hpp"

namespace tessera::reference {

double texture_lod(const Texture& texture, const Sampler& sampler, double du_dx, double dv_dx,
                   double du_dy, double dv_dy) {
  return texture::lod<double>(detail::TextureAccess::storage(texture), sampler, du_dx, dv_dx, du_dy,
                              dv_dy);
}

std::array<double, 4> sample(const Texture& texture, const Sampler& sampler, double u, double v,
                             double lod) {
  return texture::sample<double>(detail::TextureAccess::storage(texture), sampler, u, v, lod);
}

std::array<double, 4> sample(const Texture& texture, const Sampler& sampler, double u, double v,
                             double du_dx, double dv_dx, double du_dy, double dv_dy) {
  return texture::sample_footprint<double>(detail::TextureAccess::storage(texture), sampler, u, v,
                                           du_dx, dv_dx, du_dy, dv_dy);
}

}  // namespace tessera::reference
