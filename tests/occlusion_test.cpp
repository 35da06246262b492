// Occlusion queries (tessera/occlusion.hpp): rectangles, boxes and triangle lists behind
// occluders, exact answers against the depth buffer's samples by hand, conservative answers
// never hidden where the exact one is visible, on every SIMD target, sample count, depth
// format and with reversed Z; concurrent queries; bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"
#include "tests/expect_error.hpp"
#include "tests/simd_targets.hpp"

namespace tessera {
namespace {

// A clip-space quad over window pixels [x0, x1) x [y0, y1) of a w x h buffer at depth z.
std::vector<Float4> quad(float x0, float y0, float x1, float y1, float z, float w, float h) {
  const auto cx = [&](float x) { return x / w * 2 - 1; };
  const auto cy = [&](float y) { return 1 - y / h * 2; };
  return {{cx(x0), cy(y0), z, 1}, {cx(x1), cy(y0), z, 1}, {cx(x1), cy(y1), z, 1},
          {cx(x0), cy(y0), z, 1}, {cx(x1), cy(y1), z, 1}, {cx(x0), cy(y1), z, 1}};
}

DrawInput input_of(const std::vector<Float4>& positions) {
  DrawInput in;
  in.positions = positions;
  return in;
}

std::vector<SimdTarget> targets() {
  return test::runnable_simd_targets();
}

constexpr OcclusionMode kModes[] = {OcclusionMode::kConservative, OcclusionMode::kExact};

TEST(Occlusion, AnEmptyBufferSeesWhatIsOnItAndNothingElse) {
  const OcclusionBuffer occlusion({64, 48});
  for (OcclusionMode mode : kModes) {
    EXPECT_TRUE(occlusion.rect_visible(10, 10, 20, 20, 0.99f, mode));
    EXPECT_TRUE(occlusion.rect_visible(-5, -5, 1, 1, 1.0f, mode));     // a corner pixel
    EXPECT_FALSE(occlusion.rect_visible(64, 0, 80, 48, 0.5f, mode));   // right of the buffer
    EXPECT_FALSE(occlusion.rect_visible(10, 10, 10, 20, 0.5f, mode));  // empty
    const glm::mat4 identity(1.0f);
    EXPECT_TRUE(occlusion.box_visible({-0.5f, -0.5f, 0.2f}, {0.5f, 0.5f, 0.4f}, identity, mode));
    EXPECT_FALSE(
        occlusion.box_visible({2, 2, 0.2f}, {3, 3, 0.4f}, identity, mode));  // off to the side
    EXPECT_TRUE(occlusion.box_visible({-0.5f, -0.5f, -0.2f}, {0.5f, 0.5f, 0.4f}, identity,
                                      mode));  // through the near plane
  }
}

// A wall at depth 0.5 over the left half (x < 32) of a 64 x 48 buffer: behind it hidden, in
// front or beside it visible, at its depth visible (LESS_EQUAL), in every configuration.
TEST(Occlusion, AWallHidesWhatIsBehindItInEveryConfiguration) {
  for (SimdTarget simd : targets()) {
    for (uint32_t samples : {1u, 4u}) {
      for (DepthFormat format :
           {DepthFormat::kFloat32, DepthFormat::kUnorm24, DepthFormat::kUnorm16}) {
        for (bool reversed : {false, true}) {
          OcclusionDesc desc{64, 48, samples, format, reversed, 2, simd};
          OcclusionBuffer occlusion(desc);
          // Reversed Z: depth d is stored as 1 - d, nearer larger.
          const auto z = [&](float d) { return reversed ? 1 - d : d; };
          const std::vector<Float4> wall = quad(0, 0, 32, 48, z(0.5f), 64, 48);
          occlusion.draw_occluders(input_of(wall));
          const std::string where = "target " + std::to_string(int(simd)) + ", " +
                                    std::to_string(samples) + " samples, format " +
                                    std::to_string(int(format)) + (reversed ? ", reversed" : "");
          for (OcclusionMode mode : kModes) {
            const std::string at = where + (mode == OcclusionMode::kExact ? ", exact" : "");
            EXPECT_FALSE(occlusion.rect_visible(0, 0, 32, 48, z(0.6f), mode)) << at;
            EXPECT_FALSE(occlusion.rect_visible(5, 7, 29, 40, z(0.9f), mode)) << at;
            EXPECT_TRUE(occlusion.rect_visible(5, 7, 29, 40, z(0.4f), mode)) << at;
            EXPECT_TRUE(occlusion.rect_visible(5, 7, 29, 40, z(0.5f), mode)) << at;
            EXPECT_TRUE(occlusion.rect_visible(24, 7, 40, 40, z(0.9f), mode)) << at;
            const std::vector<Float4> behind = quad(4, 4, 28, 44, z(0.7f), 64, 48);
            EXPECT_FALSE(occlusion.triangles_visible(input_of(behind), mode)) << at;
            const std::vector<Float4> beside = quad(30, 4, 50, 44, z(0.7f), 64, 48);
            EXPECT_TRUE(occlusion.triangles_visible(input_of(beside), mode)) << at;
          }
          // The exact answer looks at samples: a rectangle whose pixels the conservative one
          // sees only in part of a block (x 32 to 34 is behind nothing) differs from a
          // rectangle that stops at the wall's edge.
          EXPECT_TRUE(occlusion.rect_visible(28, 8, 34, 16, z(0.9f), OcclusionMode::kExact))
              << where;
          EXPECT_FALSE(occlusion.rect_visible(28, 8, 32, 16, z(0.9f), OcclusionMode::kExact))
              << where;
          occlusion.clear();
          EXPECT_TRUE(occlusion.rect_visible(0, 0, 32, 48, z(0.6f))) << where;
        }
      }
    }
  }
}

// A camera before a wall: boxes behind it hidden, in front of it or beside it visible.
TEST(Occlusion, BoxesBehindAWallThroughACamera) {
  OcclusionBuffer occlusion({128, 96});
  Camera camera;
  camera.eye = {0, 0, 5};
  camera.target = {0, 0, 0};
  camera.fov_y_degrees = 60.0f;
  camera.near_plane = 0.5f;
  camera.far_plane = 100.0f;
  const glm::mat4 vp = camera.projection(128.0f / 96.0f) * camera.view();
  // The wall: x, y in [-2, 2] at z = 0.
  std::vector<Float4> wall;
  for (const glm::vec3& p : {glm::vec3(-2, -2, 0), glm::vec3(2, -2, 0), glm::vec3(2, 2, 0),
                             glm::vec3(-2, -2, 0), glm::vec3(2, 2, 0), glm::vec3(-2, 2, 0)}) {
    const glm::vec4 c = vp * glm::vec4(p, 1.0f);
    wall.push_back({c.x, c.y, c.z, c.w});
  }
  occlusion.draw_occluders(input_of(wall));
  for (OcclusionMode mode : kModes) {
    EXPECT_FALSE(occlusion.box_visible({-0.5f, -0.5f, -3}, {0.5f, 0.5f, -1}, vp, mode));
    EXPECT_TRUE(occlusion.box_visible({-0.5f, -0.5f, 1}, {0.5f, 0.5f, 2}, vp, mode));
    EXPECT_TRUE(occlusion.box_visible({-0.5f, -0.5f, -1}, {0.5f, 0.5f, 1}, vp, mode));  // through
    EXPECT_TRUE(occlusion.box_visible({8, -0.5f, -10}, {10, 0.5f, -5}, vp, mode));      // beside
    EXPECT_FALSE(
        occlusion.box_visible({2.5f, -0.5f, -30}, {3.5f, 0.5f, -20}, vp, mode));  // far behind
    EXPECT_TRUE(occlusion.box_visible({-1, -1, 3}, {1, 1, 6}, vp, mode));         // around the eye
  }
}

// Random occluders and random rectangles with corners on whole pixels (so a pixel's samples
// are inside exactly when the pixel is): the exact answer is whether any covered pixel's
// stored depth is at or behind the rectangle's (one sample: read_depth), and the conservative
// answer is visible wherever the exact one is.
TEST(Occlusion, ExactAnswersMatchTheDepthBufferAndConservativeOnesNeverHideMore) {
  constexpr uint32_t kW = 96, kH = 80;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> pos(-1.2f, 1.2f), depth(0.1f, 0.9f);
  std::uniform_int_distribution<int> px(-4, kW + 4), py(-4, kH + 4);
  int hidden = 0, conservative_hidden = 0, queries = 0;
  for (int scene = 0; scene < 8; ++scene) {
    OcclusionBuffer occlusion({kW, kH});
    std::vector<Float4> occluders;
    for (int t = 0; t < 60; ++t) {
      for (int k = 0; k < 3; ++k)
        occluders.push_back({pos(rng), pos(rng), depth(rng) * 0.5f, 1.0f});
    }
    occlusion.draw_occluders(input_of(occluders));
    const std::vector<float> stored = occlusion.framebuffer().read_depth();
    for (int q = 0; q < 300; ++q) {
      int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
      if (x0 > x1) std::swap(x0, x1);
      if (y0 > y1) std::swap(y0, y1);
      const float z = depth(rng) * 0.6f;
      bool want = false;
      for (int y = std::max(y0, 0); y < std::min<int>(y1, kH); ++y) {
        for (int x = std::max(x0, 0); x < std::min<int>(x1, kW); ++x)
          want |= z <= stored[size_t(y) * kW + x];
      }
      const bool exact = occlusion.rect_visible(float(x0), float(y0), float(x1), float(y1), z,
                                                OcclusionMode::kExact);
      ASSERT_EQ(exact, want) << "scene " << scene << ", query " << q << ": [" << x0 << ", " << x1
                             << ") x [" << y0 << ", " << y1 << ") at " << z;
      const bool conservative =
          occlusion.rect_visible(float(x0), float(y0), float(x1), float(y1), z);
      if (exact) {
        ASSERT_TRUE(conservative) << "scene " << scene << ", query " << q;
      }
      ++queries;
      hidden += !exact;
      conservative_hidden += !conservative;
    }
  }
  // Both answers occur, and the conservative one finds most hidden rectangles.
  EXPECT_GT(hidden, queries / 10);
  EXPECT_LT(hidden, queries * 9 / 10);
  EXPECT_GT(conservative_hidden, hidden / 2);
  std::printf("%d queries: %d hidden, %d of them found by Hi-Z alone\n", queries, hidden,
              conservative_hidden);
}

// Random rectangles with corners anywhere (whole, half and quarter pixels, and between): the
// exact answer, which may come from the Hi-Z blocks alone, is the answer of drawing the
// rectangle's two triangles, at 1, 4 and 16 samples, float and 16-bit depth, and reversed Z.
TEST(Occlusion, ExactRectanglesAnswerAsTheirTwoTrianglesDo) {
  constexpr uint32_t kW = 80, kH = 72;
  // The rectangle as rect_visible draws it: corners through clip space in double.
  const auto corners = [](double x0, double y0, double x1, double y1, float z) {
    const auto cx = [](double x) { return static_cast<float>(x / kW * 2 - 1); };
    const auto cy = [](double y) { return static_cast<float>(1 - y / kH * 2); };
    return std::vector<Float4>{{cx(x0), cy(y0), z, 1}, {cx(x1), cy(y0), z, 1},
                               {cx(x1), cy(y1), z, 1}, {cx(x0), cy(y0), z, 1},
                               {cx(x1), cy(y1), z, 1}, {cx(x0), cy(y1), z, 1}};
  };
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> pos(-1.2f, 1.2f), depth(0.1f, 0.9f);
  std::uniform_int_distribution<int> px(0, int(kW) * 4), py(0, int(kH) * 4), frac(0, 3);
  for (uint32_t samples : {1u, 4u, 16u}) {
    for (DepthFormat format : {DepthFormat::kFloat32, DepthFormat::kUnorm16}) {
      for (bool reversed : {false, true}) {
        OcclusionBuffer occlusion({kW, kH, samples, format, reversed});
        const auto z = [&](float d) { return reversed ? 1 - d : d; };
        std::vector<Float4> occluders;
        for (int t = 0; t < 40; ++t) {
          for (int k = 0; k < 3; ++k)
            occluders.push_back({pos(rng), pos(rng), z(depth(rng) * 0.5f), 1.0f});
        }
        occlusion.draw_occluders(input_of(occluders));
        int visible = 0;
        for (int q = 0; q < 150; ++q) {
          // A quarter-pixel grid, and off it a third of the time.
          const auto corner = [&](int quarter) {
            return quarter / 4.0 - 4 + (frac(rng) == 0 ? 0.3 : 0.0);
          };
          double x0 = corner(px(rng)), x1 = corner(px(rng)), y0 = corner(py(rng)),
                 y1 = corner(py(rng));
          if (x0 > x1) std::swap(x0, x1);
          if (y0 > y1) std::swap(y0, y1);
          const float d = z(depth(rng) * 0.6f);
          const bool rect = occlusion.rect_visible(float(x0), float(y0), float(x1), float(y1), d,
                                                   OcclusionMode::kExact);
          const bool drawn = occlusion.triangles_visible(
              input_of(corners(float(x0), float(y0), float(x1), float(y1), d)),
              OcclusionMode::kExact);
          ASSERT_EQ(rect, drawn) << samples << " samples, format " << int(format)
                                 << (reversed ? ", reversed" : "") << ", query " << q << ": [" << x0
                                 << ", " << x1 << ") x [" << y0 << ", " << y1 << ") at " << d;
          visible += rect;
        }
        // Both answers occur.
        EXPECT_GT(visible, 15) << samples << " samples";
        EXPECT_LT(visible, 135) << samples << " samples";
      }
    }
  }
}

// Random triangle queries: the conservative answer is visible wherever the exact one is, at
// one and four samples; and queries from four threads at once give the serial answers.
TEST(Occlusion, TriangleQueriesAreConservativeAndSafeFromSeveralThreads) {
  for (uint32_t samples : {1u, 4u}) {
    std::mt19937 rng(9 + samples);
    std::uniform_real_distribution<float> pos(-1.1f, 1.1f), depth(0.1f, 0.9f), size(0.02f, 0.4f);
    OcclusionBuffer occlusion({128, 128, samples});
    std::vector<Float4> occluders;
    for (int t = 0; t < 200; ++t) {
      for (int k = 0; k < 3; ++k)
        occluders.push_back({pos(rng), pos(rng), depth(rng) * 0.5f, 1.0f});
    }
    occlusion.draw_occluders(input_of(occluders));
    std::vector<std::vector<Float4>> queries(400);
    for (std::vector<Float4>& q : queries) {
      const float cx = pos(rng), cy = pos(rng), s = size(rng);
      for (int t = 0; t < 2; ++t) {
        for (int k = 0; k < 3; ++k) {
          q.push_back({cx + s * pos(rng), cy + s * pos(rng), depth(rng) * 0.7f + 0.1f, 1.0f});
        }
      }
    }
    std::vector<char> exact(queries.size()), conservative(queries.size());
    int hidden = 0;
    for (size_t i = 0; i < queries.size(); ++i) {
      exact[i] = occlusion.triangles_visible(input_of(queries[i]), OcclusionMode::kExact);
      conservative[i] = occlusion.triangles_visible(input_of(queries[i]));
      if (exact[i]) {
        ASSERT_TRUE(conservative[i]) << samples << " samples, query " << i;
      }
      hidden += !exact[i];
    }
    EXPECT_GT(hidden, 20) << samples << " samples";
    std::vector<std::thread> threads;
    std::vector<char> mismatch(4, 0);
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&, t] {
        for (size_t i = size_t(t); i < queries.size(); i += 2) {
          const OcclusionMode mode =
              i % 4 < 2 ? OcclusionMode::kExact : OcclusionMode::kConservative;
          const bool got = occlusion.triangles_visible(input_of(queries[i]), mode);
          const bool want = mode == OcclusionMode::kExact ? exact[i] : conservative[i];
          if (got != want) mismatch[size_t(t)] = 1;
        }
      });
    }
    for (std::thread& t : threads)
      t.join();
    EXPECT_EQ(mismatch, std::vector<char>(4, 0)) << samples << " samples";
  }
}

TEST(Occlusion, BadInputIsAnErrorNamingIt) {
  OcclusionBuffer occlusion({32, 32});
  using test::expect_error;
  expect_error([] { OcclusionBuffer({0, 32}); }, ErrorCode::kInvalidArgument, "width");
  expect_error([&] { (void)occlusion.rect_visible(NAN, 0, 4, 4, 0.5f); },
               ErrorCode::kInvalidArgument, "NaN");
  expect_error(
      [&] {
        (void)occlusion.box_visible({1, 0, 0}, {0, 1, 1}, glm::mat4(1.0f));
      },
      ErrorCode::kInvalidArgument, "lo <= hi");
  const std::vector<Float4> tri = {{0, 0, 0.5f, 1}, {1, 0, 0.5f, 1}, {0, 1, 0.5f, 1}};
  const std::vector<uint32_t> bad_indices = {0, 1, 7};
  DrawInput in = input_of(tri);
  in.indices = bad_indices;
  for (OcclusionMode mode : kModes) {
    expect_error([&] { (void)occlusion.triangles_visible(in, mode); }, ErrorCode::kInvalidInput,
                 "7");
  }
  expect_error([&] { occlusion.draw_occluders(in); }, ErrorCode::kInvalidInput, "7");
  std::vector<Float4> nan_tri = tri;
  nan_tri[1].y = NAN;
  for (OcclusionMode mode : kModes) {
    expect_error([&] { (void)occlusion.triangles_visible(input_of(nan_tri), mode); },
                 ErrorCode::kInvalidInput, "1");
  }
  // Nothing was drawn by the failed draw.
  EXPECT_EQ(occlusion.framebuffer().read_depth(), std::vector<float>(32 * 32, 1.0f));
}

}  // namespace
}  // namespace tessera
