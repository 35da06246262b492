// Writing and reading images (PNG, EXR, and whatever else OpenImageIO knows by the file
// extension). Part of Tessera::io (the tessera_io library), which links OpenImageIO and
// Assimp; the core library (Tessera::tessera) needs neither.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "tessera/export.hpp"
#include "tessera/texture.hpp"

namespace tessera {

// Pixels top row first, `channels` values per pixel, stored as given (colour is not divided by
// alpha: images with alpha hold straight, not premultiplied, colour). Throws Error(kIo) naming the
// file when it cannot be written, Error(kInvalidArgument) when the pixel count does not match.
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const uint8_t> pixels);
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const float> pixels);
// Unsigned 32-bit integers (IDs): for formats that keep them, such as EXR and TIFF.
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const uint32_t> pixels);

// An image read back from a file: float values, 8-bit files scaled to 0..1, top row first, as
// the file stores them (colour not multiplied by alpha).
struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t channels = 0;
  std::vector<float> pixels;  // channels values per pixel

  const float* at(uint32_t x, uint32_t y) const {
    return &pixels[(static_cast<size_t>(y) * width + x) * channels];
  }
};

// Throws Error(kIo) naming the file when it cannot be opened or decoded.
TESSERA_API Image read_image(const std::filesystem::path& path);

// A texture from an image file, its top row first (texel (0, 0) is the image's top-left).
// Files of 8 bits per channel become kRGBA8 (kRGBA8Srgb with `srgb`), or kR8 for one channel;
// deeper ones (16-bit, half, float) kRGBA32F or kR32F, their values scaled to 0..1 for integer
// files and, with `srgb`, decoded from sRGB to linear (alpha stays linear). Grey and alpha
// become (g, g, g, a), RGB gets alpha 1, channels past the fourth are dropped. With `mipmaps`
// the chain is generated (Texture's 2x2 box rule). Throws Error(kIo) naming the file when it
// cannot be read, Error(kInvalidArgument) naming it when a side is above kMaxTextureSize.
TESSERA_API Texture load_texture(const std::filesystem::path& path, bool srgb, bool mipmaps);

}  // namespace tessera
