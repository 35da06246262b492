// The scissor test (PipelineState::scissor_test): a scissored draw equals the unscissored
// draw inside the rectangle, byte for byte, and leaves every pixel outside it as it was, in
// both backends, on every SIMD target and thread count; the fast engine (without Hi-Z, whose
// rejected blocks are not counted) covers exactly the reference's samples. Rectangle edges lie on
// and off tile (64 px) and block (8 px) boundaries; triangles of every size class (every raster
// path), blending, Hi-Z, points and lines.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/simd_targets.hpp"

namespace tessera {
namespace {

constexpr uint32_t kWidth = 200, kHeight = 136;  // four tiles across (the last partial), three down

struct Scene {
  std::vector<Float4> positions;
  std::vector<float> colors;
};

// Triangles of every size class at random depths, a third of them spanning several tiles.
Scene soup(uint32_t seed, int count) {
  Scene s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float sizes[] = {1.5f, 3.0f, 7.0f, 14.0f, 60.0f, 260.0f};
  for (int i = 0; i < count; ++i) {
    const float size = sizes[i % 6];
    const float cx = (u(rng) * 1.2f - 0.1f) * kWidth, cy = (u(rng) * 1.2f - 0.1f) * kHeight;
    const float z = u(rng);
    for (int k = 0; k < 3; ++k) {
      const float x = cx + (u(rng) - 0.5f) * size, y = cy + (u(rng) - 0.5f) * size;
      const float w = 0.5f + u(rng);
      s.positions.push_back({(2.0f * x / kWidth - 1.0f) * w, (1.0f - 2.0f * y / kHeight) * w,
                             (z + 0.1f * (u(rng) - 0.5f)) * w, w});
      for (int c = 0; c < 4; ++c)
        s.colors.push_back(u(rng));
    }
  }
  return s;
}

enum class Draw { kTriangles, kPoints, kLines };

struct Image {
  std::vector<float> color;  // resolved, as floats
  std::vector<float> depth;  // every sample
  Counters counters;
};

Image render(const Scene& scene, const PipelineState& pipeline, uint32_t samples,
             ColorFormat format, Backend backend, SimdTarget simd = SimdTarget::kAuto,
             uint32_t threads = 1, Draw draw = Draw::kTriangles, bool hiz = true) {
  RendererOptions options;
  options.backend = backend;
  options.simd = simd;
  options.threads = threads;
  options.raster_counters = true;
  options.hiz = hiz;  // Hi-Z's rejected blocks count no covered samples
  Renderer renderer(options);
  Framebuffer fb({kWidth, kHeight, samples, format});
  fb.clear_color({0.25f, 0.5f, 0.75f, 1.0f});
  DrawInput input;
  input.positions = scene.positions;
  input.attributes = scene.colors;
  input.attribute_count = 4;
  switch (draw) {
    case Draw::kTriangles:
      renderer.draw(fb, pipeline, input);
      break;
    case Draw::kPoints:
      renderer.draw_points(fb, pipeline, {4.0f, PointShape::kRound}, input);
      break;
    case Draw::kLines: {
      LineState lines;
      lines.width = 2.0f;
      lines.antialiased = true;
      input.positions = input.positions.first(scene.positions.size() / 2 * 2);
      input.attributes = input.attributes.first(input.positions.size() * 4);
      renderer.draw_lines(fb, pipeline, lines, input);
      break;
    }
  }
  return {fb.read_rgba32f(), fb.read_sample_depth(), renderer.counters()};
}

// Rectangles whose edges fall on tile and block boundaries and between them, one reaching past
// the framebuffer, one inside a single block, and an empty one.
std::vector<Rect> rectangles() {
  return {{64, 0, 64, 64},   {8, 16, 120, 56}, {13, 29, 101, 67}, {-20, -7, 90, 300},
          {150, 90, 400, 9}, {70, 75, 5, 3},   {0, 0, 0, 10}};
}

bool inside(const Rect& r, uint32_t x, uint32_t y) {
  return int64_t{x} >= r.x && int64_t{x} < int64_t{r.x} + r.width && int64_t{y} >= r.y &&
         int64_t{y} < int64_t{r.y} + r.height;
}

// The scissored image is the unscissored one inside the rectangle and the cleared framebuffer
// outside it.
void expect_cut_out(const Image& scissored, const Image& full, const Image& cleared, const Rect& r,
                    uint32_t samples, const std::string& what) {
  size_t wrong = 0;
  for (uint32_t y = 0; y < kHeight; ++y) {
    for (uint32_t x = 0; x < kWidth; ++x) {
      const Image& expected = inside(r, x, y) ? full : cleared;
      const size_t p = size_t{y} * kWidth + x;
      if (std::memcmp(&scissored.color[p * 4], &expected.color[p * 4], 4 * sizeof(float)) != 0 ||
          std::memcmp(&scissored.depth[p * samples], &expected.depth[p * samples],
                      samples * sizeof(float)) != 0) {
        if (wrong++ == 0) ADD_FAILURE() << what << ": first wrong pixel " << x << ", " << y;
      }
    }
  }
  EXPECT_EQ(wrong, 0u) << what;
}

void check(Draw draw, const PipelineState& base, const std::vector<uint32_t>& thread_counts,
           int count) {
  const Scene scene = soup(11, count);
  for (uint32_t samples : {1u, 4u}) {
    for (ColorFormat format : {ColorFormat::kRGBA8, ColorFormat::kRGBA32F}) {
      const std::string config = std::to_string(samples) + " samples, " +
                                 (format == ColorFormat::kRGBA8 ? "RGBA8" : "RGBA32F");
      const Image cleared = render(Scene{}, base, samples, format, Backend::kReference);
      // The reference's images and counts, then each fast configuration's against its own
      // unscissored image and the reference's counts.
      const Image full =
          render(scene, base, samples, format, Backend::kReference, SimdTarget::kAuto, 1, draw);
      std::vector<Image> references;
      for (const Rect& r : rectangles()) {
        PipelineState p = base;
        p.scissor_test = true;
        p.scissor = r;
        references.push_back(
            render(scene, p, samples, format, Backend::kReference, SimdTarget::kAuto, 1, draw));
        expect_cut_out(references.back(), full, cleared, r, samples, config + ", reference");
      }
      for (SimdTarget simd : test::runnable_simd_targets()) {
        for (uint32_t threads : thread_counts) {
          const std::string where = config + ", target " + std::to_string(static_cast<int>(simd)) +
                                    ", " + std::to_string(threads) + " threads";
          const Image fast_full =
              render(scene, base, samples, format, Backend::kFast, simd, threads, draw);
          for (size_t i = 0; i < rectangles().size(); ++i) {
            const Rect r = rectangles()[i];
            const std::string what = where + ", scissor " + std::to_string(r.x) + "," +
                                     std::to_string(r.y) + " " + std::to_string(r.width) + "x" +
                                     std::to_string(r.height);
            PipelineState p = base;
            p.scissor_test = true;
            p.scissor = r;
            const Image fast =
                render(scene, p, samples, format, Backend::kFast, simd, threads, draw);
            expect_cut_out(fast, fast_full, cleared, r, samples, what);
            if (threads == thread_counts.front()) {
              const Image counted =
                  render(scene, p, samples, format, Backend::kFast, simd, threads, draw, false);
              EXPECT_EQ(counted.counters.samples_covered, references[i].counters.samples_covered)
                  << what;
            }
          }
        }
      }
    }
  }
}

TEST(Scissor, TrianglesDrawOnlyInsideTheRectangleOnEveryTargetAndThreadCount) {
  check(Draw::kTriangles, PipelineState{}, {1, 2}, 1200);
}

TEST(Scissor, BlendedTrianglesWithoutDepthWritesDrawOnlyInsideTheRectangle) {
  PipelineState p;
  p.depth_write = false;
  p.blend[0] = BlendState::over();
  check(Draw::kTriangles, p, {1, 3}, 600);
}

TEST(Scissor, PointsAndLinesDrawOnlyInsideTheRectangle) {
  PipelineState p;
  p.depth_compare = CompareOp::kLessEqual;
  check(Draw::kPoints, p, {1, 2}, 200);
  check(Draw::kLines, p, {1, 2}, 200);
}

TEST(Scissor, OffByDefaultAndIgnoredWhenOff) {
  // A rectangle set with the test off changes nothing.
  const Scene scene = soup(3, 300);
  PipelineState p;
  p.scissor = {10, 10, 5, 5};
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    const Image with = render(scene, p, 1, ColorFormat::kRGBA8, backend);
    const Image without = render(scene, PipelineState{}, 1, ColorFormat::kRGBA8, backend);
    EXPECT_TRUE(with.color == without.color);
  }
  EXPECT_FALSE(PipelineState{}.scissor_test);
}

}  // namespace
}  // namespace tessera
