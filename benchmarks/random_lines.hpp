// The lecture 003 line workload shared by tessera_line_bench and tessera_llvmpipe_lines:
// 100,000 random lines in a 500x500 window (endpoints uniform over the window, a random colour
// per vertex, depth 0.5), in clip space with w = 1, from a fixed seed so both programs draw
// the same lines.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "tessera/types.hpp"

namespace tessera::bench {

inline constexpr uint32_t kLineWindow = 500;
inline constexpr uint32_t kLineCount = 100000;

struct LineWorkload {
  std::vector<Float4> positions;  // two per line
  std::vector<float> colors;      // RGBA per vertex
};

inline LineWorkload random_lines(uint32_t count = kLineCount, uint32_t window = kLineWindow,
                                 uint32_t seed = 2003) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  LineWorkload w;
  w.positions.reserve(size_t{count} * 2);
  w.colors.reserve(size_t{count} * 8);
  for (uint32_t i = 0; i < 2 * count; ++i) {
    const float x = u(rng) * static_cast<float>(window), y = u(rng) * static_cast<float>(window);
    w.positions.push_back({2.0f * x / static_cast<float>(window) - 1.0f,
                           1.0f - 2.0f * y / static_cast<float>(window), 0.5f, 1.0f});
    for (int c = 0; c < 3; ++c)
      w.colors.push_back(u(rng));
    w.colors.push_back(1.0f);
  }
  return w;
}

}  // namespace tessera::bench
