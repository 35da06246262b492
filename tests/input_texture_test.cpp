// Texture files through OpenImageIO (tessera/io.hpp's load_texture): 8-bit files as RGBA8 (sRGB
// when asked) or R8, deeper ones as float, grey and grey-alpha expanded, and errors that name
// the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/io.hpp"
#include "tessera/tessera.hpp"
#include "tests/temp_dir.hpp"

namespace tessera {
namespace {

using test::TempDir;

// Image files through OpenImageIO: 8-bit files as RGBA8 (sRGB when asked) or R8, deeper ones as
// float; grey and grey-alpha expanded; the texels as the file holds them.
TEST(TextureFiles, LoadThroughOpenImageIO) {
  TempDir dir;
  // RGBA8 PNG.
  std::vector<uint8_t> rgba(5 * 3 * 4);
  for (size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = static_cast<uint8_t>(i * 11);
  write_image(dir / "rgba.png", 5, 3, 4, std::span<const uint8_t>(rgba));
  const Texture t = load_texture(dir / "rgba.png", false, true);
  EXPECT_EQ(t.desc().format, TextureFormat::kRGBA8);
  EXPECT_EQ(t.desc().width, 5u);
  EXPECT_EQ(t.desc().height, 3u);
  EXPECT_EQ(t.levels(), 3u);
  const std::span<const std::byte> level0 = t.level_bytes(0);
  ASSERT_EQ(level0.size(), rgba.size());
  EXPECT_TRUE(std::equal(rgba.begin(), rgba.end(), level0.begin(),
                         [](uint8_t a, std::byte b) { return a == std::to_integer<uint8_t>(b); }));
  EXPECT_EQ(load_texture(dir / "rgba.png", true, false).desc().format, TextureFormat::kRGBA8Srgb);
  // RGB: alpha 1. Grey + alpha: (g, g, g, a). Grey: R8.
  const std::vector<uint8_t> rgb = {10, 20, 30, 40, 50, 60};
  write_image(dir / "rgb.png", 2, 1, 3, std::span<const uint8_t>(rgb));
  EXPECT_EQ(load_texture(dir / "rgb.png", false, false).texel(0, 1, 0),
            (std::array<float, 4>{40 / 255.0f, 50 / 255.0f, 60 / 255.0f, 1.0f}));
  const std::vector<uint8_t> ga = {100, 200};
  write_image(dir / "ga.png", 1, 1, 2, std::span<const uint8_t>(ga));
  EXPECT_EQ(load_texture(dir / "ga.png", false, false).texel(0, 0, 0),
            (std::array<float, 4>{100 / 255.0f, 100 / 255.0f, 100 / 255.0f, 200 / 255.0f}));
  write_image(dir / "g.png", 1, 1, 1, std::span<const uint8_t>(ga.data(), 1));
  EXPECT_EQ(load_texture(dir / "g.png", false, false).desc().format, TextureFormat::kR8);
  // Float EXR: RGBA32F, values as stored; with srgb the colour decoded, alpha not.
  const std::vector<float> f = {0.5f, 2.0f, -1.0f, 0.25f};
  write_image(dir / "f.exr", 1, 1, 4, std::span<const float>(f));
  const Texture ft = load_texture(dir / "f.exr", false, false);
  EXPECT_EQ(ft.desc().format, TextureFormat::kRGBA32F);
  EXPECT_EQ(ft.texel(0, 0, 0), (std::array<float, 4>{0.5f, 2.0f, -1.0f, 0.25f}));
  const std::array<float, 4> decoded = load_texture(dir / "f.exr", true, false).texel(0, 0, 0);
  EXPECT_NEAR(decoded[0], 0.2140411f, 1e-6f);  // ((0.5 + 0.055) / 1.055)^2.4
  EXPECT_EQ(decoded[3], 0.25f);
  const std::vector<float> one = {0.75f};
  write_image(dir / "r.exr", 1, 1, 1, std::span<const float>(one));
  EXPECT_EQ(load_texture(dir / "r.exr", false, false).desc().format, TextureFormat::kR32F);
  // Errors name the file.
  try {
    load_texture(dir / "missing.png", false, false);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kIo);
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
  }
  const std::vector<uint8_t> wide(16385, 7);
  write_image(dir / "wide.png", 16385, 1, 1, std::span<const uint8_t>(wide));
  try {
    load_texture(dir / "wide.png", false, false);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("wide.png: 16385x1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
