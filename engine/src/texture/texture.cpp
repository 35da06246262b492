// Texture objects: storage, validation and mip chain generation (tessera/texture.hpp).
#include <algorithm>
#include <cmath>
#include <new>
#include <string>

#include "engine/src/texture/texture_storage.hpp"
#include "tessera/error.hpp"

namespace tessera {

namespace {

[[noreturn]] void fail(ErrorCode code, const std::string& message) {
  throw Error(code, "Texture: " + message);
}

// Linear value c in [0, 1] to sRGB-encoded 8 bits, rounded to nearest.
uint8_t linear_to_srgb8(double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double s = c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(s * 255.0));
}

// Level `to` from level `to - 1` by the 2x2 box filter (the header's rule).
void downsample(Texture::Storage& s, uint32_t to) {
  const auto& src = s.levels[to - 1];
  const auto& dst = s.levels[to];
  const TextureFormat format = s.desc.format;
  for (uint32_t y = 0; y < dst.height; ++y) {
    for (uint32_t x = 0; x < dst.width; ++x) {
      const uint32_t x0 = std::min(2 * x, src.width - 1), x1 = std::min(2 * x + 1, src.width - 1);
      const uint32_t y0 = std::min(2 * y, src.height - 1), y1 = std::min(2 * y + 1, src.height - 1);
      const std::byte* in[4] = {s.at(to - 1, x0, y0), s.at(to - 1, x1, y0), s.at(to - 1, x0, y1),
                                s.at(to - 1, x1, y1)};
      std::byte* out = s.at(to, x, y);
      const uint32_t channels =
          format == TextureFormat::kR8 || format == TextureFormat::kR32F ? 1 : 4;
      for (uint32_t c = 0; c < channels; ++c) {
        if (format == TextureFormat::kRGBA32F || format == TextureFormat::kR32F) {
          float sum = 0;
          for (const std::byte* p : in) {
            float v;
            std::memcpy(&v, p + 4 * c, sizeof v);
            sum += v;
          }
          const float mean = sum * 0.25f;
          std::memcpy(out + 4 * c, &mean, sizeof mean);
        } else if (format == TextureFormat::kRGBA8Srgb && c < 3) {
          double sum = 0;
          for (const std::byte* p : in)
            sum += texture::srgb_to_linear(std::to_integer<uint8_t>(p[c]) / 255.0);
          out[c] = std::byte{linear_to_srgb8(sum * 0.25)};
        } else {
          uint32_t sum = 2;  // rounds the quotient to nearest, halves up
          for (const std::byte* p : in)
            sum += std::to_integer<uint8_t>(p[c]);
          out[c] = std::byte{static_cast<uint8_t>(sum / 4)};
        }
      }
    }
  }
}

}  // namespace

uint32_t texel_bytes(TextureFormat format) {
  switch (format) {
    case TextureFormat::kRGBA8:
    case TextureFormat::kRGBA8Srgb:
    case TextureFormat::kR32F:
      return 4;
    case TextureFormat::kRGBA32F:
      return 16;
    case TextureFormat::kR8:
      return 1;
  }
  fail(ErrorCode::kInvalidArgument,
       "format has the invalid value " + std::to_string(static_cast<int>(format)));
}

Texture::Texture(const TextureDesc& desc, std::span<const std::byte> pixels, bool mipmaps) {
  if (desc.width == 0 || desc.height == 0 || desc.width > kMaxTextureSize ||
      desc.height > kMaxTextureSize) {
    fail(ErrorCode::kInvalidArgument, "size " + std::to_string(desc.width) + "x" +
                                          std::to_string(desc.height) + " is not within 1.." +
                                          std::to_string(kMaxTextureSize) + " on each side");
  }
  const uint32_t texel = texel_bytes(desc.format);
  try {
    storage_ = std::make_unique<Storage>();
    Storage& s = *storage_;
    s.desc = desc;
    s.texel = texel;
    uint32_t w = desc.width, h = desc.height;
    size_t offset = 0;
    while (true) {
      s.levels.push_back({w, h, offset});
      offset += size_t{w} * h * texel;
      if (!mipmaps || (w == 1 && h == 1)) break;
      w = std::max(1u, w / 2);
      h = std::max(1u, h / 2);
    }
    s.bytes.resize(offset);
  } catch (const std::bad_alloc&) {
    fail(ErrorCode::kOutOfMemory, "cannot allocate the storage of a " + std::to_string(desc.width) +
                                      "x" + std::to_string(desc.height) + " texture");
  }
  set_level(0, pixels);
  for (uint32_t level = 1; level < levels(); ++level)
    downsample(*storage_, level);
}

Texture::~Texture() = default;
Texture::Texture(Texture&&) noexcept = default;
Texture& Texture::operator=(Texture&&) noexcept = default;

const TextureDesc& Texture::desc() const noexcept {
  return storage_->desc;
}

uint32_t Texture::levels() const noexcept {
  return static_cast<uint32_t>(storage_->levels.size());
}

uint32_t Texture::width(uint32_t level) const {
  if (level >= levels()) fail(ErrorCode::kInvalidArgument, "no level " + std::to_string(level));
  return storage_->levels[level].width;
}

uint32_t Texture::height(uint32_t level) const {
  if (level >= levels()) fail(ErrorCode::kInvalidArgument, "no level " + std::to_string(level));
  return storage_->levels[level].height;
}

void Texture::set_level(uint32_t level, std::span<const std::byte> pixels) {
  const Storage& s = *storage_;
  if (level >= levels()) {
    fail(ErrorCode::kInvalidArgument, "set_level: level " + std::to_string(level) +
                                          " is past the last level " +
                                          std::to_string(levels() - 1));
  }
  const auto& l = s.levels[level];
  const size_t want = size_t{l.width} * l.height * s.texel;
  if (pixels.size() != want) {
    fail(ErrorCode::kInvalidArgument, "level " + std::to_string(level) + " (" +
                                          std::to_string(l.width) + "x" + std::to_string(l.height) +
                                          ") needs " + std::to_string(want) + " bytes, got " +
                                          std::to_string(pixels.size()));
  }
  std::copy(pixels.begin(), pixels.end(),
            storage_->bytes.begin() + static_cast<ptrdiff_t>(l.offset));
}

std::span<const std::byte> Texture::level_bytes(uint32_t level) const {
  const auto& l = storage_->levels.at(level);
  return {storage_->bytes.data() + l.offset, size_t{l.width} * l.height * storage_->texel};
}

std::array<float, 4> Texture::texel(uint32_t level, uint32_t x, uint32_t y) const {
  if (level >= levels() || x >= width(level) || y >= height(level)) {
    fail(ErrorCode::kInvalidArgument, "texel (" + std::to_string(x) + ", " + std::to_string(y) +
                                          ") of level " + std::to_string(level) +
                                          " is outside the texture");
  }
  return texture::decode<float>(storage_->desc.format, storage_->at(level, x, y));
}

}  // namespace tessera
