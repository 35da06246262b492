// The reference's texture sampling: tessera/texture.hpp's rules (texture/sampling.hpp) in
// double, the oracle the engine's float sampler is tested against.
#pragma once

#include <array>

#include "tessera/texture.hpp"

namespace tessera::reference {

double texture_lod(const Texture& texture, const Sampler& sampler, double du_dx, double dv_dx,
                   double du_dy, double dv_dy);
std::array<double, 4> sample(const Texture& texture, const Sampler& sampler, double u, double v,
                             double lod);
// The sample over the footprint of the derivatives (tessera::sample's derivative form).
std::array<double, 4> sample(const Texture& texture, const Sampler& sampler, double u, double v,
                             double du_dx, double dv_dx, double du_dy, double dv_dy);

}  // namespace tessera::reference
