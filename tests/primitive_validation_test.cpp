// draw_points, draw_lines and draw_polygon reject bad input before drawing anything, like
// draw(): a tessera::Error with the right code and a one-line message naming what is wrong,
// the framebuffer byte-identical and the counters unchanged. Every backend.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

class PrimitiveValidation : public ::testing::TestWithParam<Backend> {
 protected:
  PrimitiveValidation() : renderer_(RendererOptions{1, GetParam()}) {
    fb_.clear_color({0.2f, 0.4f, 0.6f, 1.0f});
    fb_.clear_depth(0.75f);
  }

  std::vector<Float4> positions_ = {{-0.5f, -0.5f, 0.5f, 1},
                                    {0.5f, -0.5f, 0.5f, 1},
                                    {0.5f, 0.5f, 0.5f, 1},
                                    {-0.5f, 0.5f, 0.5f, 1}};
  std::vector<float> colors_ = std::vector<float>(16, 1.0f);
  DrawInput input() const { return {positions_, colors_, 4, {}}; }

  void expect_rejected(ErrorCode code, const std::string& part, const std::function<void()>& draw) {
    const std::vector<uint8_t> color_before = fb_.read_rgba8();
    const std::vector<float> depth_before = fb_.read_sample_depth();
    try {
      draw();
      ADD_FAILURE() << "expected tessera::Error containing '" << part << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), code) << e.what();
      const std::string message = e.what();
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(fb_.read_rgba8(), color_before);
    const std::vector<float> depth_after = fb_.read_sample_depth();
    EXPECT_EQ(
        std::memcmp(depth_after.data(), depth_before.data(), depth_before.size() * sizeof(float)),
        0);
    EXPECT_EQ(renderer_.counters().samples_covered, 0u);
    EXPECT_EQ(renderer_.counters().points_submitted, 0u);
    EXPECT_EQ(renderer_.counters().lines_submitted, 0u);
    EXPECT_EQ(renderer_.counters().polygons_submitted, 0u);
  }

  Renderer renderer_;
  Framebuffer fb_{{32, 32, 1, ColorFormat::kRGBA8}};
};

TEST_P(PrimitiveValidation, NanPositionsAreAnErrorForEveryPrimitive) {
  positions_[2].y = kNaN;
  expect_rejected(ErrorCode::kInvalidInput, "position of vertex 2 is not finite",
                  [&] { renderer_.draw_points(fb_, {}, {}, input()); });
  expect_rejected(ErrorCode::kInvalidInput, "position of vertex 2 is not finite",
                  [&] { renderer_.draw_lines(fb_, {}, {}, input()); });
  expect_rejected(ErrorCode::kInvalidInput, "position of vertex 2 is not finite",
                  [&] { renderer_.draw_polygon(fb_, {}, {}, input()); });
}

TEST_P(PrimitiveValidation, BadPointStateIsAnError) {
  for (float size : {0.5f, kNaN, 2000.0f}) {
    expect_rejected(ErrorCode::kInvalidArgument, "point size", [&] {
      renderer_.draw_points(fb_, {}, {size, PointShape::kSquare}, input());
    });
  }
  expect_rejected(ErrorCode::kInvalidArgument, "point shape", [&] {
    renderer_.draw_points(fb_, {}, {1.0f, static_cast<PointShape>(7)}, input());
  });
}

TEST_P(PrimitiveValidation, BadLineStateIsAnError) {
  LineState s;
  s.width = kNaN;
  expect_rejected(ErrorCode::kInvalidArgument, "line width",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
  s = {};
  s.stipple.factor = 0;
  expect_rejected(ErrorCode::kInvalidArgument, "line stipple factor 0",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
  s.stipple.factor = 257;
  expect_rejected(ErrorCode::kInvalidArgument, "line stipple factor 257",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
  s = {};
  s.algorithm = static_cast<LineAlgorithm>(9);
  expect_rejected(ErrorCode::kInvalidArgument, "line algorithm",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
  s = {};
  s.join = static_cast<LineJoin>(9);
  expect_rejected(ErrorCode::kInvalidArgument, "line join",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
  s = {};
  s.miter_limit = 0.5f;
  expect_rejected(ErrorCode::kInvalidArgument, "miter limit",
                  [&] { renderer_.draw_lines(fb_, {}, s, input()); });
}

TEST_P(PrimitiveValidation, LineListNeedsPairsAndPolygonContoursMustAddUp) {
  positions_.pop_back();
  colors_.resize(12);
  expect_rejected(ErrorCode::kInvalidInput, "even number of vertices, got 3",
                  [&] { renderer_.draw_lines(fb_, {}, {}, input()); });
  const std::vector<uint32_t> sizes = {2, 2};
  expect_rejected(ErrorCode::kInvalidInput, "add up to 4 vertices, but the draw has 3",
                  [&] { renderer_.draw_polygon(fb_, {}, {}, input(), sizes); });
  PolygonState p;
  p.fill_rule = static_cast<FillRule>(3);
  expect_rejected(ErrorCode::kInvalidArgument, "polygon fill rule",
                  [&] { renderer_.draw_polygon(fb_, {}, p, input()); });
}

TEST_P(PrimitiveValidation, TessellationHasAVertexLimit) {
  positions_.assign(kMaxTessellationVertices + 1, {0.1f, 0.2f, 0.5f, 1});
  colors_.assign(positions_.size() * 4, 1.0f);
  expect_rejected(ErrorCode::kInvalidInput, "too large to tessellate", [&] {
    renderer_.draw_polygon(fb_, {}, {FillRule::kEvenOdd, PolygonMethod::kTessellation}, input());
  });
}

TEST_P(PrimitiveValidation, DegenerateInputDrawsNothingWithoutError) {
  const std::vector<Float4> same = {
      {0.1f, 0.1f, 0.5f, 1}, {0.1f, 0.1f, 0.5f, 1}, {0.1f, 0.1f, 0.5f, 1}};
  const std::vector<float> colors(12, 1.0f);
  const std::vector<uint8_t> before = fb_.read_rgba8();
  renderer_.draw_lines(fb_, {}, {}, {std::span(same).first(2), std::span(colors).first(8), 4, {}});
  LineState wide;
  wide.width = 5;
  renderer_.draw_lines(fb_, {}, wide,
                       {std::span(same).first(2), std::span(colors).first(8), 4, {}});
  renderer_.draw_polygon(fb_, {}, {}, {same, colors, 4, {}});
  renderer_.draw_polygon(fb_, {}, {FillRule::kNonZero, PolygonMethod::kTessellation},
                         {same, colors, 4, {}});
  renderer_.draw_lines(fb_, {}, {}, {});  // no vertices at all
  renderer_.draw_points(fb_, {}, {}, {});
  EXPECT_EQ(fb_.read_rgba8(), before);
}

INSTANTIATE_TEST_SUITE_P(Backends, PrimitiveValidation,
                         ::testing::Values(Backend::kReference, Backend::kFast),
                         [](const ::testing::TestParamInfo<Backend>& param_info) {
                           return std::string(param_info.param == Backend::kReference ? "Reference"
                                                                                      : "Fast");
                         });

}  // namespace
}  // namespace tessera
