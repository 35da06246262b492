// A user fragment shader (docs/WRITING_A_SHADER.md): a procedural checkerboard on a ground plane
// seen in perspective, box-filtered over each pixel's footprint, which the screen derivatives
// of its texture coordinates give, so that it fades to grey towards the horizon instead of
// breaking into noise. Draws it with the fast engine and the reference, checks that they agree
// and that the near checks are crisp and the far ones grey, and writes the fast engine's image.
// Usage: tessera-shader-checkerboard [OUTPUT.png]   (default checkerboard.png). Exits 1 on a
// failed check.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "tessera/image_io.hpp"
#include "tessera/tessera.hpp"

namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;

// The integral of the square wave that is +1 on [0, 1) and -1 on [1, 2), period 2: a triangle
// wave. (S(x + w/2) - S(x - w/2)) / w is the wave's mean over [x - w/2, x + w/2].
float square_integral(float x) {
  const float m = x - 2.0f * std::floor(x / 2.0f);  // x mod 2, in [0, 2)
  return 1.0f - std::abs(m - 1.0f);
}

// The square wave's mean over a footprint of width w centred on x.
float filtered_square(float x, float w) {
  if (w < 1e-6f) return std::floor(x) - 2.0f * std::floor(x / 2.0f) < 0.5f ? 1.0f : -1.0f;
  return (square_integral(x + 0.5f * w) - square_integral(x - 0.5f * w)) / w;
}

// The shader: varyings 0 and 1 are the texture coordinates u and v (one check per unit).
// Everything is per fragment and reads only the fragment's own inputs, so the function may run
// on any thread, for any batch.
void checkerboard(const tessera::FragmentBatch& batch, const tessera::FragmentOutput& out) {
  constexpr uint32_t kStride = tessera::kFragmentBatchStride;
  const float* u = batch.varyings;
  const float* v = batch.varyings + kStride;
  const float* du_dx = batch.ddx;
  const float* du_dy = batch.ddy;
  const float* dv_dx = batch.ddx + kStride;
  const float* dv_dy = batch.ddy + kStride;
  for (uint32_t i = 0; i < batch.count; ++i) {
    // The pixel's footprint in texture space, per axis (GLSL's fwidth).
    const float wu = std::abs(du_dx[i]) + std::abs(du_dy[i]);
    const float wv = std::abs(dv_dx[i]) + std::abs(dv_dy[i]);
    const float c = filtered_square(u[i], wu) * filtered_square(v[i], wv);  // -1 .. 1
    const float t = 0.5f + 0.5f * c;                                        // 0 dark, 1 light
    out.color[0 * kStride + i] = 0.10f + 0.80f * t;
    out.color[1 * kStride + i] = 0.15f + 0.70f * t;
    out.color[2 * kStride + i] = 0.30f + 0.55f * t;
    out.color[3 * kStride + i] = 1.0f;
  }
}

// A ground plane y = -1 from z = -1 to z = -200 in front of a camera at the origin, in clip
// space (perspective, 60 degrees vertically), with u, v = x, z in world units.
tessera::Float4 project(float x, float y, float z) {
  const float f = 1.0f / std::tan(3.14159265f / 6.0f), aspect = float(kWidth) / kHeight;
  const float near = 0.5f, far = 500.0f;
  return {f / aspect * x, f * y, (far + near) / (near - far) * z + 2 * far * near / (near - far),
          -z};
}

std::vector<uint8_t> render(tessera::Backend backend, const tessera::DrawInput& input) {
  tessera::RendererOptions options;
  options.backend = backend;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({kWidth, kHeight, 1, tessera::ColorFormat::kRGBA8});
  fb.clear_color({0.55f, 0.70f, 0.90f, 1.0f});  // sky
  tessera::PipelineState pipeline;
  pipeline.shader = tessera::FragmentShader::kUser;
  pipeline.fragment_function = checkerboard;
  renderer.draw(fb, pipeline, input);
  return fb.read_rgba8();
}

}  // namespace

int main(int argc, char** argv) try {
  const char* output = argc > 1 ? argv[1] : "checkerboard.png";
  const float corners[4][2] = {{-40, -1}, {40, -1}, {40, -200}, {-40, -200}};  // (x, z)
  std::vector<tessera::Float4> positions;
  std::vector<float> uv;
  for (int k : {0, 1, 2, 0, 2, 3}) {
    positions.push_back(project(corners[k][0], -1.0f, corners[k][1]));
    uv.push_back(corners[k][0]);
    uv.push_back(corners[k][1]);
  }
  const tessera::DrawInput input{positions, uv, 2, {}};
  const std::vector<uint8_t> fast = render(tessera::Backend::kFast, input);
  const std::vector<uint8_t> reference = render(tessera::Backend::kReference, input);

  int failures = 0;
  const auto check = [&](bool ok, const char* what) {
    std::printf("%s: %s\n", ok ? "ok" : "FAILED", what);
    failures += ok ? 0 : 1;
  };
  int worst = 0;
  for (size_t i = 0; i < fast.size(); ++i)
    worst = std::max(worst, std::abs(int{fast[i]} - reference[i]));
  std::printf("largest difference from the reference: %d/255\n", worst);
  check(worst <= 2, "the fast engine and the reference agree within 2/255");
  // Near the bottom edge the checks are many pixels wide: mostly pure dark or light red.
  // Just below the horizon they are far below a pixel: the filter leaves the mean, grey.
  const auto red = [&](uint32_t x, uint32_t y) {
    return fast[(size_t{y} * kWidth + x) * 4] / 255.0f;
  };
  int crisp = 0;
  for (uint32_t x = 0; x < kWidth; ++x) {
    const float r = red(x, kHeight - 3);
    crisp += std::abs(r - 0.10f) < 0.02f || std::abs(r - 0.90f) < 0.02f;
  }
  std::printf("bottom row: %d of %u pixels pure dark or light\n", crisp, kWidth);
  check(crisp > int(kWidth) * 3 / 4, "near checks are crisp");
  float far_low = 1, far_high = 0;
  for (uint32_t x = kWidth / 4; x < kWidth * 3 / 4; ++x) {
    far_low = std::min(far_low, red(x, kHeight / 2 + 2));
    far_high = std::max(far_high, red(x, kHeight / 2 + 2));
  }
  std::printf("red just below the horizon: %.3f to %.3f (mean 0.5)\n", far_low, far_high);
  check(far_low > 0.4f && far_high < 0.6f, "far checks are filtered to grey");
  tessera::write_image(output, kWidth, kHeight, 4, fast);
  std::printf("wrote %s\n", output);
  return failures == 0 ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "tessera-shader-checkerboard: %s\n", e.what());
  return 1;
}
