// Depth bias (PipelineState::depth_bias_*), the formula of Direct3D and Vulkan: a triangle's
// window depth is offset by constant * r + slope * max(|dz/dx|, |dz/dy|) (dz/dx, dz/dy per
// pixel), clamped by depth_bias_clamp when it is not 0 (to at most it if positive, at least it
// if negative). r is the depth format's smallest step: 2^-16 for kUnorm16, 2^-24 for kUnorm24,
// and for kFloat32 2^(e - 23), e the exponent of the largest |z| of the triangle's vertices
// (2^e <= |z| < 2^(e + 1); 0 when every z is 0). Both backends add the bias to each vertex's z
// before depth is interpolated; the fast engine's vectorized setup forms r from the bits of
// that largest |z| (setup_kernel.cpp), which gives the same value.
#pragma once

#include <algorithm>
#include <cmath>

#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"

namespace tessera {

inline bool has_depth_bias(const PipelineState& p) {
  return p.depth_bias_constant != 0.0f || p.depth_bias_slope != 0.0f;
}

// r for a triangle whose largest vertex |z| is z_abs_max.
inline double depth_bias_unit(DepthFormat format, double z_abs_max) {
  switch (format) {
    case DepthFormat::kUnorm16:
      return std::ldexp(1.0, -16);
    case DepthFormat::kUnorm24:
      return std::ldexp(1.0, -24);
    case DepthFormat::kFloat32:
      break;
  }
  if (!(z_abs_max > 0.0)) return 0.0;
  return std::ldexp(1.0, std::ilogb(z_abs_max) - 23);
}

// The bias of a triangle given r (depth_bias_unit) and its depth gradients per pixel.
inline double depth_bias(const PipelineState& p, double unit, double dz_dx, double dz_dy) {
  double bias = double{p.depth_bias_constant} * unit +
                double{p.depth_bias_slope} * std::max(std::abs(dz_dx), std::abs(dz_dy));
  const double clamp = p.depth_bias_clamp;
  if (clamp > 0.0) bias = std::min(bias, clamp);
  if (clamp < 0.0) bias = std::max(bias, clamp);
  return bias;
}

}  // namespace tessera
