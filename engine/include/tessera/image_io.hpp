// Writing and reading images (PNG, EXR, and whatever else OpenImageIO knows by the file
// extension). Part of Tessera::io (the tessera_io library), which links OpenImageIO and
// Assimp; the core library (Tessera::tessera) needs neither.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "tessera/export.hpp"

namespace tessera {

// Pixels top row first, `channels` values per pixel. Throws Error(kIo) naming the file when
// it cannot be written, Error(kInvalidArgument) when the pixel count does not match.
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const uint8_t> pixels);
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const float> pixels);
// Unsigned 32-bit integers (IDs): for formats that keep them, such as EXR and TIFF.
TESSERA_API void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                             uint32_t channels, std::span<const uint32_t> pixels);

// An image read back from a file: float values, 8-bit files scaled to 0..1, top row first.
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

}  // namespace tessera
