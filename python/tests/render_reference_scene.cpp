// Renders the fixed scene of test_equivalence.py through the C++ API and writes the image's
// bytes (RGBA8, then float32 depth, both top row first) to the file named by its argument,
// for the test that the Python module draws the same bytes. The scene is made of dyadic
// rationals from a 32-bit LCG, so both languages build exactly the same floats.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <vector>

#include "tessera/tessera.hpp"

namespace {

// Numerical Recipes' LCG; the top 24 bits.
struct Lcg {
  uint32_t state = 12345;
  uint32_t next() {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT\n", argv[0]);
    return 2;
  }
  try {
    constexpr uint32_t kVertices = 240;
    constexpr uint32_t kTriangles = 160;
    Lcg lcg;
    std::vector<tessera::Float4> positions;
    std::vector<float> colors;
    for (uint32_t v = 0; v < kVertices; ++v) {
      const float w = 1.0f + static_cast<float>(lcg.next() % 8) / 8.0f;
      const float x = (static_cast<float>(lcg.next() % 2561) - 1280.0f) / 1024.0f * w;
      const float y = (static_cast<float>(lcg.next() % 2561) - 1280.0f) / 1024.0f * w;
      const float z = static_cast<float>(lcg.next() % 1025) / 1024.0f * w;
      positions.push_back({x, y, z, w});
      for (int c = 0; c < 4; ++c)
        colors.push_back(static_cast<float>(lcg.next() % 257) / 256.0f);
    }
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < 3 * kTriangles; ++i)
      indices.push_back(lcg.next() % kVertices);

    tessera::RendererOptions options;
    options.threads = 2;
    tessera::Renderer renderer(options);
    tessera::FramebufferDesc desc;
    desc.width = 160;
    desc.height = 120;
    desc.samples = 4;
    tessera::Framebuffer framebuffer(desc);
    framebuffer.clear_color({0.125f, 0.25f, 0.5f, 1.0f});
    tessera::PipelineState pipeline;
    pipeline.cull = tessera::CullMode::kBack;
    renderer.draw(framebuffer, pipeline, {positions, colors, 4, indices});

    const std::vector<uint8_t> rgba = framebuffer.read_rgba8();
    const std::vector<float> depth = framebuffer.read_depth();
    std::ofstream out(argv[1], std::ios::binary);
    out.write(reinterpret_cast<const char*>(rgba.data()),
              static_cast<std::streamsize>(rgba.size()));
    out.write(reinterpret_cast<const char*>(depth.data()),
              static_cast<std::streamsize>(depth.size() * sizeof(float)));
    if (!out) {
      std::fprintf(stderr, "cannot write %s\n", argv[1]);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
