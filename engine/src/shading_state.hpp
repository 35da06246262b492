// Reading the shading state (tessera/shading.hpp) the same way in every backend.
#pragma once

#include <cstdint>

#include "tessera/pipeline.hpp"

namespace tessera {

// The varying mode a pipeline's interpolation gives a varying declared kDefault.
inline VaryingMode default_mode(Interpolation interpolation) {
  return interpolation == Interpolation::kAffine ? VaryingMode::kAffine : VaryingMode::kPerspective;
}

// How varying `i` is interpolated: its own mode, or for kDefault the pipeline's interpolation
// (never kDefault).
inline VaryingMode resolved_mode(const PipelineState& pipeline, uint32_t i) {
  const VaryingMode m = pipeline.varying_modes[i];
  return m != VaryingMode::kDefault ? m : default_mode(pipeline.interpolation);
}

// What colour target t receives: `output` for target 0, extra_outputs[t - 1] for the others.
inline TargetOutput output_of(const PipelineState& pipeline, uint32_t t) {
  return t == 0 ? pipeline.output : pipeline.extra_outputs[t - 1];
}

}  // namespace tessera
