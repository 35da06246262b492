// The camera's projections (scene.hpp): where the near and far planes land in window depth for
// both clip-depth conventions, with and without reversed Z, in perspective and orthographic.
#include <gtest/gtest.h>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "tessera/tessera.hpp"

namespace tessera {
namespace {

// Window depth (0..1) of the point on the view axis at distance d in front of the eye.
double window_depth(const Camera& camera, ClipDepth convention, float d) {
  const glm::vec4 clip = camera.projection(1.5f, convention) * glm::vec4(0.0f, 0.0f, -d, 1.0f);
  const double ndc = double{clip.z} / clip.w;
  return convention == ClipDepth::kNegativeOneToOne ? 0.5 * (ndc + 1.0) : ndc;
}

TEST(SceneCamera, NearAndFarPlanesMapToTheEndsOfTheDepthRange) {
  for (bool orthographic : {false, true}) {
    for (ClipDepth convention : {ClipDepth::kZeroToOne, ClipDepth::kNegativeOneToOne}) {
      for (bool reversed : {false, true}) {
        Camera camera;
        camera.orthographic = orthographic;
        camera.near_plane = 0.5f;
        camera.far_plane = 200.0f;
        camera.reversed_z = reversed;
        const double near_depth = window_depth(camera, convention, 0.5f);
        const double far_depth = window_depth(camera, convention, 200.0f);
        const double middle = window_depth(camera, convention, 20.0f);
        SCOPED_TRACE(testing::Message()
                     << "orthographic " << orthographic << " convention "
                     << static_cast<int>(convention) << " reversed " << reversed);
        EXPECT_NEAR(near_depth, reversed ? 1.0 : 0.0, 1e-6);
        EXPECT_NEAR(far_depth, reversed ? 0.0 : 1.0, 1e-6);
        // Depth is monotonic in distance: increasing, or decreasing when reversed.
        EXPECT_TRUE(reversed ? (near_depth > middle && middle > far_depth)
                             : (near_depth < middle && middle < far_depth));
      }
    }
  }
}

TEST(SceneCamera, ReversedZDrawsTheNearerSurfaceWithCompareGreater) {
  // Two screen-filling quads at distances 10 (green) and 11 (red), red drawn last: with
  // reversed Z, compare kGreater and a depth buffer cleared to 0, green stays in front.
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.near_plane = 0.1f;
  camera.far_plane = 1000.0f;
  camera.reversed_z = true;
  const glm::mat4 vp = camera.projection(1.0f) * camera.view();
  std::vector<Float4> positions;
  std::vector<float> colors;
  const auto quad = [&](float d, std::array<float, 4> c) {
    const float s = 2.0f * d;  // wider than the view at distance d (45 degree field)
    const glm::vec4 corners[6] = {{-s, -s, -d, 1}, {s, -s, -d, 1}, {s, s, -d, 1},
                                  {-s, -s, -d, 1}, {s, s, -d, 1},  {-s, s, -d, 1}};
    for (const glm::vec4& p : corners) {
      const glm::vec4 clip = vp * p;
      positions.push_back({clip.x, clip.y, clip.z, clip.w});
      colors.insert(colors.end(), c.begin(), c.end());
    }
  };
  quad(10.0f, {0, 1, 0, 1});
  quad(11.0f, {1, 0, 0, 1});
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer fb({16, 16, 1, ColorFormat::kRGBA8});
    fb.clear_depth(0.0f);
    PipelineState pipeline;
    pipeline.depth_compare = CompareOp::kGreater;
    DrawInput input;
    input.positions = positions;
    input.attributes = colors;
    input.attribute_count = 4;
    renderer.draw(fb, pipeline, input);
    const std::vector<uint8_t> rgba = fb.read_rgba8();
    for (size_t i = 0; i < rgba.size(); i += 4) {
      ASSERT_EQ(rgba[i], 0) << "pixel " << i / 4;
      ASSERT_EQ(rgba[i + 1], 255) << "pixel " << i / 4;
    }
  }
}

}  // namespace
}  // namespace tessera
