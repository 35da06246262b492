// The reference's fragment shading: lecture 004's Phong model in double precision, written as
// plainly as tessera/shading.hpp states it, so that a pixel can be checked by hand.
#pragma once

#include <array>

#include "tessera/shading.hpp"

namespace tessera::reference {

// v / |v|, or 0 for a zero vector.
std::array<double, 3> normalized(const std::array<double, 3>& v);

// PhongState's colour at a surface point: clamp(I x base, 0, 1) in RGB, base alpha in A.
// `normal` need not be of unit length (it is normalized here).
std::array<float, 4> phong(const PhongState& state, const std::array<double, 3>& normal,
                           const std::array<double, 3>& position,
                           const std::array<double, 4>& base);

}  // namespace tessera::reference
