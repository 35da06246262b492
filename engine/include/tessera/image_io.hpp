// Writing images (PNG, EXR, and whatever else OpenImageIO knows by the file extension).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace tessera {

// Pixels top row first, `channels` values per pixel. Throws Error(kIo) naming the file when
// it cannot be written, Error(kInvalidArgument) when the pixel count does not match.
void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const uint8_t> pixels);
void write_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                 uint32_t channels, std::span<const float> pixels);

}  // namespace tessera
