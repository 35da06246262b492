// Renderer::draw rejects bad input before drawing anything (renderer.hpp, error.hpp): every
// bad call throws tessera::Error with the right code and a one-line message that says what is
// wrong, and leaves the framebuffer byte-identical, the caller's arrays untouched and the
// renderer's counters unchanged. Run on every backend, since validation is shared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Byte equality: NaN (the very input some tests pass) is not equal to itself as a float.
template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

class DrawValidation : public ::testing::TestWithParam<Backend> {
 protected:
  DrawValidation() : renderer_(RendererOptions{1, GetParam()}) {
    // A framebuffer that is not uniform (a clear, then a triangle over part of it), so that a
    // stray write anywhere would show.
    fb_.clear_color({0.2f, 0.4f, 0.6f, 1.0f});
    fb_.clear_depth(0.75f);
    const std::vector<Float4> tri = {{-1, -1, 0.25f, 1}, {1, -1, 0.25f, 1}, {-1, 1, 0.25f, 1}};
    const std::vector<float> red = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    renderer_.draw(fb_, {}, {tri, red, 4, {}});
    renderer_.reset_counters();
  }

  // A valid indexed draw: two triangles over four vertices, RGBA colour per vertex.
  std::vector<Float4> positions_ = {{-0.5f, -0.5f, 0.5f, 1},
                                    {0.5f, -0.5f, 0.5f, 1},
                                    {0.5f, 0.5f, 0.5f, 1},
                                    {-0.5f, 0.5f, 0.5f, 1}};
  std::vector<float> attributes_ = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  uint32_t attribute_count_ = 4;
  std::vector<uint32_t> indices_ = {0, 1, 2, 0, 2, 3};
  PipelineState pipeline_;

  DrawInput input() const { return {positions_, attributes_, attribute_count_, indices_}; }

  // Draws and expects Error(code) whose message holds every one of `parts` and no line break,
  // with the framebuffer, the caller's arrays and the counters exactly as they were.
  void expect_rejected(ErrorCode code, std::initializer_list<std::string> parts) {
    const std::vector<uint8_t> color_before = fb_.read_rgba8();
    const std::vector<float> depth_before = fb_.read_sample_depth();
    const std::vector<Float4> positions_before = positions_;
    const std::vector<float> attributes_before = attributes_;
    const std::vector<uint32_t> indices_before = indices_;
    try {
      renderer_.draw(fb_, pipeline_, input());
      ADD_FAILURE() << "expected tessera::Error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), code) << e.what();
      const std::string message = e.what();
      for (const std::string& part : parts) {
        EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
      }
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(fb_.read_rgba8(), color_before);
    EXPECT_TRUE(same_bytes(fb_.read_sample_depth(), depth_before));
    EXPECT_TRUE(same_bytes(positions_, positions_before));
    EXPECT_TRUE(same_bytes(attributes_, attributes_before));
    EXPECT_EQ(indices_, indices_before);
    EXPECT_EQ(renderer_.counters().triangles_submitted, 0u);
    EXPECT_EQ(renderer_.counters().samples_passed, 0u);
  }

  // The same draw is accepted and draws something.
  void expect_drawn() {
    const std::vector<uint8_t> before = fb_.read_rgba8();
    renderer_.draw(fb_, pipeline_, input());
    EXPECT_NE(fb_.read_rgba8(), before);
  }

  Framebuffer fb_{{24, 16, 4, ColorFormat::kRGBA8}};
  Renderer renderer_;
};

TEST_P(DrawValidation, TheValidDrawOfTheseTestsIsAccepted) {
  expect_drawn();
}

TEST_P(DrawValidation, IndexOutOfRangeIsRejectedNamingTheIndexAndItsPosition) {
  indices_ = {0, 1, 2, 0, 2, 7};
  expect_rejected(ErrorCode::kInvalidInput, {"index 7", "position 5", "4 vertices"});
}

TEST_P(DrawValidation, IndexEqualToTheVertexCountIsOutOfRange) {
  indices_ = {0, 1, 2, 4, 2, 3};
  expect_rejected(ErrorCode::kInvalidInput, {"index 4", "position 3", "out of range"});
}

TEST_P(DrawValidation, LargestIndexIsOutOfRange) {
  indices_ = {0, 1, 0xFFFFFFFFu};
  expect_rejected(ErrorCode::kInvalidInput, {"index 4294967295", "position 2"});
}

TEST_P(DrawValidation, IndexCountNotAMultipleOfThreeIsRejected) {
  indices_ = {0, 1, 2, 3};
  expect_rejected(ErrorCode::kInvalidInput, {"multiple of 3 indices", "got 4"});
}

TEST_P(DrawValidation, NonIndexedPositionCountNotAMultipleOfThreeIsRejected) {
  indices_.clear();
  expect_rejected(ErrorCode::kInvalidInput, {"multiple of 3 positions", "got 4"});
}

TEST_P(DrawValidation, AttributeArrayShorterThanVerticesTimesCountIsRejected) {
  attributes_.pop_back();
  expect_rejected(ErrorCode::kInvalidInput, {"15 floats", "4 vertices", "need 16"});
}

TEST_P(DrawValidation, AttributeArrayLongerThanVerticesTimesCountIsRejected) {
  attributes_.push_back(0.5f);
  expect_rejected(ErrorCode::kInvalidInput, {"17 floats", "need 16"});
}

TEST_P(DrawValidation, AttributesWithoutAnAttributeCountAreRejected) {
  attribute_count_ = 0;
  expect_rejected(ErrorCode::kInvalidInput, {"16 floats", "need 0"});
}

TEST_P(DrawValidation, AttributeCountAboveThirtyTwoIsRejected) {
  attribute_count_ = kMaxVaryings + 1;
  attributes_.assign(positions_.size() * attribute_count_, 0.5f);
  expect_rejected(ErrorCode::kInvalidArgument, {"attribute_count 33", "maximum of 32"});
}

TEST_P(DrawValidation, AttributeCountOfThirtyTwoIsAccepted) {
  attribute_count_ = kMaxVaryings;
  attributes_.assign(positions_.size() * attribute_count_, 0.5f);
  expect_drawn();
}

TEST_P(DrawValidation, NaNPositionIsRejectedNamingTheVertex) {
  positions_[2].y = kNaN;
  expect_rejected(ErrorCode::kInvalidInput, {"vertex 2", "not finite", "nan"});
}

TEST_P(DrawValidation, InfinitePositionIsRejectedNamingTheVertex) {
  positions_[1].x = kInf;
  expect_rejected(ErrorCode::kInvalidInput, {"vertex 1", "not finite", "inf"});
}

TEST_P(DrawValidation, InfiniteWIsRejected) {
  positions_[3].w = -kInf;
  expect_rejected(ErrorCode::kInvalidInput, {"vertex 3", "not finite"});
}

TEST_P(DrawValidation, NaNPositionOfAVertexNoIndexUsesIsStillRejected) {
  positions_.push_back({kNaN, 0, 0, 1});
  attributes_.insert(attributes_.end(), {0, 0, 0, 1});
  expect_rejected(ErrorCode::kInvalidInput, {"vertex 4", "not finite"});
}

TEST_P(DrawValidation, NaNAttributeIsRejectedNamingAttributeAndVertex) {
  attributes_[3 * 4 + 2] = kNaN;
  expect_rejected(ErrorCode::kInvalidInput, {"attribute 2", "vertex 3", "not finite"});
}

TEST_P(DrawValidation, InfiniteAttributeIsRejectedNamingAttributeAndVertex) {
  attributes_[1 * 4 + 0] = -kInf;
  expect_rejected(ErrorCode::kInvalidInput, {"attribute 0", "vertex 1", "not finite"});
}

TEST_P(DrawValidation, PipelineSampleCountOtherThanTheFramebuffersIsRejected) {
  pipeline_.samples = 1;
  expect_rejected(ErrorCode::kInvalidArgument, {"sample count 1", "framebuffer's 4"});
}

TEST_P(DrawValidation, PipelineSampleCountOfZeroOrTheFramebuffersIsAccepted) {
  pipeline_.samples = 0;
  expect_drawn();
  fb_.clear_color({0, 0, 0, 0});
  fb_.clear_depth(1.0f);
  pipeline_.samples = 4;
  expect_drawn();
}

TEST_P(DrawValidation, SubpixelBitsBelowFourAreRejected) {
  pipeline_.subpixel_bits = kMinSubpixelBits - 1;
  expect_rejected(ErrorCode::kInvalidArgument, {"subpixel_bits 3", "4..8"});
}

TEST_P(DrawValidation, SubpixelBitsAboveEightAreRejected) {
  pipeline_.subpixel_bits = kMaxSubpixelBits + 1;
  expect_rejected(ErrorCode::kInvalidArgument, {"subpixel_bits 9", "4..8"});
}

TEST_P(DrawValidation, SubpixelBitsOfFourAndEightAreAccepted) {
  pipeline_.subpixel_bits = kMinSubpixelBits;
  expect_drawn();
  fb_.clear_color({0, 0, 0, 0});
  fb_.clear_depth(1.0f);
  pipeline_.subpixel_bits = kMaxSubpixelBits;
  expect_drawn();
}

TEST_P(DrawValidation, EnumValueOutsideItsTypeIsRejected) {
  pipeline_.cull = static_cast<CullMode>(7);
  expect_rejected(ErrorCode::kInvalidArgument, {"cull", "7"});
}

TEST_P(DrawValidation, EmptyDrawIsAcceptedAndDrawsNothing) {
  const std::vector<uint8_t> before = fb_.read_rgba8();
  renderer_.draw(fb_, pipeline_, {});
  EXPECT_EQ(fb_.read_rgba8(), before);
  EXPECT_EQ(renderer_.counters().samples_covered, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, DrawValidation,
                         ::testing::Values(Backend::kReference, Backend::kFast),
                         [](const ::testing::TestParamInfo<Backend>& p) {
                           return p.param == Backend::kReference ? std::string("Reference")
                                                                 : std::string("Fast");
                         });

// A soup of `count` vertices: thin triangles `size` across in clip space, in rows over x.
std::vector<Float4> soup_positions(uint32_t count, float size) {
  std::vector<Float4> positions(count);
  for (uint32_t v = 0; v < count; ++v) {
    const float x = static_cast<float>(v % 1000) / 500.0f - 1.0f;
    positions[v] = {x + (v % 3 == 1 ? size : 0.0f), (v % 3 == 2 ? size : 0.0f), 0.5f, 1.0f};
  }
  return positions;
}

TEST(DrawValidationOfLargeDraws, ScansInPiecesOnTheRenderersThreadsAndStillNamesTheCulprit) {
  // 300,000 vertices: the finiteness and index scans run in pieces on the renderer's threads.
  // Each bad value, far into its array, is still found and named, nothing is drawn, and the
  // same draw without it is accepted.
  constexpr uint32_t kVertices = 300000;
  const std::vector<Float4> positions = soup_positions(kVertices, 0.002f);
  std::vector<float> attributes(size_t{kVertices} * 4, 0.5f);
  std::vector<uint32_t> indices(kVertices);
  for (uint32_t i = 0; i < kVertices; ++i)
    indices[i] = kVertices - 1 - i;
  for (uint32_t threads : {1u, 2u}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    Renderer renderer(RendererOptions{threads, Backend::kFast});
    Framebuffer fb({64, 64, 1, ColorFormat::kRGBA8});
    fb.clear_color({0.2f, 0.4f, 0.6f, 1.0f});
    const std::vector<uint8_t> before = fb.read_rgba8();
    const auto expect_rejected = [&](const DrawInput& input,
                                     std::initializer_list<std::string> parts) {
      try {
        renderer.draw(fb, {}, input);
        ADD_FAILURE() << "expected tessera::Error";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidInput);
        for (const std::string& part : parts) {
          EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
              << "'" << part << "' not in: " << e.what();
        }
      }
      EXPECT_EQ(fb.read_rgba8(), before);
      EXPECT_EQ(renderer.counters().triangles_submitted, 0u);
    };
    std::vector<Float4> bad_positions = positions;
    bad_positions[250001].w = kNaN;
    expect_rejected({bad_positions, attributes, 4, {}}, {"vertex 250001", "not finite"});
    std::vector<float> bad_attributes = attributes;
    bad_attributes[size_t{299999} * 4 + 3] = kInf;
    expect_rejected({positions, bad_attributes, 4, {}}, {"attribute 3", "vertex 299999"});
    std::vector<uint32_t> bad_indices = indices;
    bad_indices[280000] = kVertices;
    expect_rejected({positions, attributes, 4, bad_indices},
                    {"index 300000", "position 280000", "300000 vertices"});
    renderer.draw(fb, {}, {positions, attributes, 4, indices});
    EXPECT_EQ(renderer.counters().triangles_submitted, kVertices / 3);
  }
}

// The fast engine checks a triangle soup's positions and colours as its setup reads them, not
// in a scan of their own first. A NaN or infinity anywhere, in any chunk of the draw, in a pass
// after the first (a small bin budget), or in an attribute setup does not read (more than four
// attributes: checked before drawing), gives the reference backend's error word for word, and
// nothing is drawn or counted.
TEST(DrawValidationOfLargeDraws, SoupsCheckedDuringSetupFailAsTheReferenceDoesBeforeDrawing) {
  constexpr uint32_t kVertices = 300000;
  const std::vector<Float4> positions = soup_positions(kVertices, 0.02f);
  struct Case {
    const char* name;
    uint32_t attribute_count;
    uint32_t bad_position;  // kVertices: none
    size_t bad_attribute;   // index into the attributes; SIZE_MAX: none
  };
  constexpr size_t kNone = SIZE_MAX;
  const Case cases[] = {
      {"first position", 4, 0, kNone},
      {"position in a middle chunk", 4, 150001, kNone},
      {"last position", 4, kVertices - 1, kNone},
      {"last colour", 4, kVertices, size_t{kVertices - 2} * 4 + 1},
      {"position after a colour", 4, 200000, size_t{100000} * 4},
      {"three attributes", 3, kVertices, size_t{250000} * 3 + 2},
      {"sixth attribute", 6, kVertices, size_t{123456} * 6 + 5},
  };
  // The reference backend's message for each case, which validates everything before drawing.
  const auto message = [&](Backend backend, uint32_t threads, uint64_t budget, const Case& k,
                           Framebuffer& fb) {
    RendererOptions options{threads, backend};
    options.bin_memory_budget = budget;
    Renderer renderer(options);
    std::vector<Float4> p = positions;
    std::vector<float> a(size_t{kVertices} * k.attribute_count, 0.5f);
    if (k.bad_position < kVertices) p[k.bad_position].y = kNaN;
    if (k.bad_attribute != kNone) a[k.bad_attribute] = -kInf;
    std::string what;
    try {
      renderer.draw(fb, {}, {p, a, k.attribute_count, {}});
      ADD_FAILURE() << "expected tessera::Error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidInput);
      what = e.what();
    }
    EXPECT_EQ(renderer.counters().triangles_submitted, 0u);
    EXPECT_EQ(renderer.counters().bin_references, 0u);
    return what;
  };
  for (const Case& k : cases) {
    Framebuffer reference_fb({64, 64, 1, ColorFormat::kRGBA8});
    const std::string expected =
        message(Backend::kReference, 1, kDefaultBinMemoryBudget, k, reference_fb);
    EXPECT_NE(expected.find("not finite"), std::string::npos) << expected;
    for (uint32_t threads : {1u, 2u, 3u}) {
      for (uint64_t budget : {kDefaultBinMemoryBudget, uint64_t{1} << 20}) {
        SCOPED_TRACE(std::string(k.name) + ", " + std::to_string(threads) + " threads, budget " +
                     std::to_string(budget));
        Framebuffer fb({64, 64, 1, ColorFormat::kRGBA8});
        fb.clear_color({0.2f, 0.4f, 0.6f, 1.0f});
        const std::vector<uint8_t> before = fb.read_rgba8();
        EXPECT_EQ(message(Backend::kFast, threads, budget, k, fb), expected);
        EXPECT_EQ(fb.read_rgba8(), before);
      }
    }
  }
  // The same soup without a bad value is drawn, under the small budget in several passes.
  RendererOptions options{2, Backend::kFast};
  options.bin_memory_budget = uint64_t{1} << 20;
  Renderer renderer(options);
  Framebuffer fb({64, 64, 1, ColorFormat::kRGBA8});
  const std::vector<float> attributes(size_t{kVertices} * 4, 0.5f);
  renderer.draw(fb, {}, {positions, attributes, 4, {}});
  EXPECT_EQ(renderer.counters().triangles_submitted, kVertices / 3);
  EXPECT_GT(renderer.counters().bin_passes, 1u);
}

// Validation rejects only what cannot be drawn: any finite clip-space position is valid input,
// clipped like any other whatever its magnitude or the sign of w, drawn without an error and
// without undefined behaviour (the sanitizer build checks that), and never leaves a depth
// outside [0, 1].
struct ExtremeTriangle {
  const char* name;
  std::vector<Float4> positions;
};

constexpr float kMax = std::numeric_limits<float>::max();
constexpr float kTiny = std::numeric_limits<float>::denorm_min();

const ExtremeTriangle kExtremeTriangles[] = {
    {"HugeXY", {{1e30f, 1e30f, 0.5f, 1}, {-1e30f, 1e30f, 0.5f, 1}, {0, -1e30f, 0.5f, 1}}},
    {"LargestFloatEverywhere",
     {{kMax, kMax, kMax, kMax}, {-kMax, kMax, 0, kMax}, {0, -kMax, -kMax, kMax}}},
    {"LargestXYOverTinyW",
     {{kMax, kMax, 0.5f, 1e-38f}, {-kMax, kMax, 0.5f, 1e-38f}, {0, -kMax, 0.5f, 1e-38f}}},
    {"ZeroW", {{1, 1, 0.5f, 0}, {-1, 1, 0.5f, 0}, {0, -1, 0.5f, 0}}},
    {"NegativeW", {{1, 1, 0.5f, -1}, {-1, 1, 0.5f, -1}, {0, -1, 0.5f, -1}}},
    {"TinyPositiveAndNegativeW",
     {{0.5f, 0.5f, 0.5f, 1}, {-0.5f, 0.5f, 0.5f, 1e-38f}, {0, -0.5f, 0.5f, -1e-38f}}},
    {"LargestZ", {{0.5f, 0.5f, -kMax, 1}, {-0.5f, 0.5f, kMax, 1}, {0, -0.5f, 0.5f, 1}}},
    {"Denormals", {{kTiny, kTiny, kTiny, kTiny}, {-kTiny, kTiny, 0, kTiny}, {0, -kTiny, 0, kTiny}}},
    {"LargestAndTinyWTogether",
     {{0.5f, 0.5f, 0.5f, kMax}, {-0.5f, 0.5f, 0.5f, 1}, {0, -0.5f, 0.5f, 1e-30f}}},
};

class ExtremeCoordinates
    : public ::testing::TestWithParam<std::tuple<Backend, const ExtremeTriangle*>> {};

TEST_P(ExtremeCoordinates, FiniteTriangleIsDrawnWithoutErrorOrDepthOutsideZeroToOne) {
  const auto [backend, triangle] = GetParam();
  Renderer renderer(RendererOptions{1, backend});
  Framebuffer fb({24, 16, 4, ColorFormat::kRGBA8});
  const std::vector<float> grey(12, 0.5f);
  for (const ClipDepth depth : {ClipDepth::kZeroToOne, ClipDepth::kNegativeOneToOne}) {
    PipelineState pipeline;
    pipeline.clip_depth = depth;
    EXPECT_NO_THROW(renderer.draw(fb, pipeline, {triangle->positions, grey, 4, {}}));
  }
  for (float d : fb.read_sample_depth()) {
    ASSERT_GE(d, 0.0f);
    ASSERT_LE(d, 1.0f);
  }
}

std::vector<const ExtremeTriangle*> extreme_triangles() {
  std::vector<const ExtremeTriangle*> all;
  for (const ExtremeTriangle& t : kExtremeTriangles)
    all.push_back(&t);
  return all;
}

INSTANTIATE_TEST_SUITE_P(
    Backends, ExtremeCoordinates,
    ::testing::Combine(::testing::Values(Backend::kReference, Backend::kFast),
                       ::testing::ValuesIn(extreme_triangles())),
    [](const ::testing::TestParamInfo<std::tuple<Backend, const ExtremeTriangle*>>& p) {
      return std::string(std::get<1>(p.param)->name) +
             (std::get<0>(p.param) == Backend::kReference ? "_Reference" : "_Fast");
    });

}  // namespace
}  // namespace tessera
