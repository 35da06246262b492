// The per-pixel Phong variant of a standard workload, drawn the same way by Tessera
// (tessera_workload_bench) and by llvmpipe (tessera_llvmpipe_bench --shading phong, in GLSL):
// the TRI2 Phong layout of capture.hpp (varyings 0..2 the normal, 3..5 the eye-space position,
// 6..9 the base colour) made from a TRI1 capture, lit by three point lights with the TRI2
// defaults (c0 = 1, c1 = c2 = 0, Ia = Id = Is = 1, ka = 0.1, kd = 0.7, ks = 0.2, n = 32).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera::bench {

// The point lights, in the positions' space.
inline constexpr std::array<std::array<float, 3>, 3> kPhongLights = {
    {{-2.0f, 2.0f, 0.0f}, {3.0f, 1.0f, -1.0f}, {0.5f, -2.5f, -0.5f}}};

inline constexpr uint32_t kPhongVaryings = 10;

// Ten varyings per vertex of `capture` (a TRI1 capture: RGBA per vertex): the normal
// (2r - 1, 2g - 1, 1), left for the shader to normalize; the position (x, y, -w), an eye space
// stretched by the projection's scale in x and y (w = -z for a perspective projection); and the
// vertex's colour as the base colour.
inline std::vector<float> phong_varyings(const Capture& capture) {
  std::vector<float> out;
  out.reserve(capture.positions.size() * kPhongVaryings);
  for (size_t i = 0; i < capture.positions.size(); ++i) {
    const Float4& p = capture.positions[i];
    const float* c = capture.varyings.data() + 4 * i;
    out.insert(out.end(), {2.0f * c[0] - 1.0f, 2.0f * c[1] - 1.0f, 1.0f, p.x, p.y, -p.w, c[0], c[1],
                           c[2], c[3]});
  }
  return out;
}

// The capture's state (capture_pipeline()) with per-pixel Phong of those varyings.
inline PipelineState phong_pipeline() {
  PipelineState pipeline = capture_pipeline();
  pipeline.shader = FragmentShader::kPhong;
  pipeline.roles = {6, 0, 3};
  pipeline.phong.light_count = static_cast<uint32_t>(kPhongLights.size());
  for (size_t l = 0; l < kPhongLights.size(); ++l)
    pipeline.phong.lights[l].position = kPhongLights[l];
  return pipeline;
}

}  // namespace tessera::bench
