// The blended variant of a standard workload, drawn the same way by Tessera
// (tessera_workload_bench) and by llvmpipe (tessera_llvmpipe_bench --shading blended): the
// capture's colours with alpha 0.5, blended over (OpenGL's SRC_ALPHA, ONE_MINUS_SRC_ALPHA for
// colour, ONE, ONE_MINUS_SRC_ALPHA for alpha) with the depth test on and depth writes off, as
// transparent geometry is drawn.
#pragma once

#include <cstddef>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera::bench {

inline constexpr float kBlendedAlpha = 0.5f;

// The capture's RGBA varyings with every alpha kBlendedAlpha.
inline std::vector<float> blended_varyings(const Capture& capture) {
  std::vector<float> out = capture.varyings;
  for (size_t i = 3; i < out.size(); i += 4)
    out[i] = kBlendedAlpha;
  return out;
}

// The capture's state (capture_pipeline()) blending over, without depth writes.
inline PipelineState blended_pipeline() {
  PipelineState pipeline = capture_pipeline();
  pipeline.blend[0] = BlendState::over();
  pipeline.depth_write = false;
  return pipeline;
}

}  // namespace tessera::bench
