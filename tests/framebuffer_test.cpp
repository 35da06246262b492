// Framebuffer construction limits, clears and read-back.
#include <gtest/gtest.h>

#include "tessera/tessera.hpp"

namespace tessera {
namespace {

TEST(Framebuffer, StartsClearedToBlackAndFarDepth) {
  Framebuffer fb({3, 2, 4, ColorFormat::kRGBA8});
  for (uint8_t v : fb.read_rgba8())
    EXPECT_EQ(v, 0);
  for (float d : fb.read_sample_depth())
    EXPECT_EQ(d, 1.0f);
  EXPECT_EQ(fb.read_rgba8().size(), 3u * 2u * 4u);
  EXPECT_EQ(fb.read_sample_depth().size(), 3u * 2u * 4u);
}

TEST(Framebuffer, ClearColorRoundsToNearestUnorm8) {
  Framebuffer fb({70, 65, 2, ColorFormat::kRGBA8});  // spans several tiles
  fb.clear_color({0.5f, 1.0f, 0.0f, 2.0f});
  const std::vector<uint8_t> px = fb.read_rgba8();
  for (size_t i = 0; i < px.size(); i += 4) {
    ASSERT_EQ(px[i], 128);
    ASSERT_EQ(px[i + 1], 255);
    ASSERT_EQ(px[i + 2], 0);
    ASSERT_EQ(px[i + 3], 255);
  }
}

TEST(Framebuffer, RejectsZeroAndOversizedSides) {
  EXPECT_THROW(Framebuffer({0, 10, 1, ColorFormat::kRGBA8}), Error);
  EXPECT_THROW(Framebuffer({10, 0, 1, ColorFormat::kRGBA8}), Error);
  EXPECT_THROW(Framebuffer({kMaxFramebufferSize + 1, 10, 1, ColorFormat::kRGBA8}), Error);
  EXPECT_THROW(Framebuffer({10, 10, 3, ColorFormat::kRGBA8}), Error);
  EXPECT_THROW(Framebuffer({10, 10, 0, ColorFormat::kRGBA8}), Error);
}

TEST(Framebuffer, RejectsStoragePastTheLimitWithoutAllocating) {
  try {
    Framebuffer fb({kMaxFramebufferSize, kMaxFramebufferSize, 16, ColorFormat::kRGBA32F});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutOfMemory);
    EXPECT_NE(std::string(e.what()).find("16 samples"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
