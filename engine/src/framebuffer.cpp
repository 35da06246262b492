// Framebuffer allocation, clears and read-back with the MSAA box resolve.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <string>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"
#include "tessera/error.hpp"
#include "tessera/types.hpp"

namespace tessera {

namespace {

void validate(const FramebufferDesc& d) {
  auto side = [](const char* name, uint32_t v) {
    if (v == 0 || v > kMaxFramebufferSize) {
      throw Error(ErrorCode::kInvalidArgument, std::string("framebuffer ") + name + " " +
                                                   std::to_string(v) + " is out of range (1.." +
                                                   std::to_string(kMaxFramebufferSize) + ")");
    }
  };
  side("width", d.width);
  side("height", d.height);
  if (!is_valid_sample_count(d.samples)) {
    throw Error(
        ErrorCode::kInvalidArgument,
        "framebuffer sample count " + std::to_string(d.samples) + " is not one of 1, 2, 4, 8, 16");
  }
  if (d.color_format != ColorFormat::kRGBA8 && d.color_format != ColorFormat::kRGBA32F) {
    throw Error(ErrorCode::kInvalidArgument, "framebuffer colour format is not a ColorFormat");
  }
  if (d.depth_format != DepthFormat::kFloat32 && d.depth_format != DepthFormat::kUnorm24 &&
      d.depth_format != DepthFormat::kUnorm16) {
    throw Error(ErrorCode::kInvalidArgument, "framebuffer depth format is not a DepthFormat");
  }
}

}  // namespace

Framebuffer::Framebuffer(const FramebufferDesc& desc) {
  validate(desc);
  auto s = std::make_unique<detail::FramebufferStorage>();
  s->desc = desc;
  s->grid = binning::TileGrid::for_size(desc.width, desc.height);
  const uint64_t samples = uint64_t{s->grid.tile_count()} * binning::kTilePixels * desc.samples;
  const uint64_t color_bytes = desc.color_format == ColorFormat::kRGBA8 ? 4 : 16;
  const uint64_t bytes = samples * (color_bytes + 4);
  if (bytes > kMaxFramebufferBytes) {
    throw Error(ErrorCode::kOutOfMemory,
                "framebuffer " + std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                    " with " + std::to_string(desc.samples) + " samples needs " +
                    std::to_string(bytes >> 20) + " MiB, more than the limit of " +
                    std::to_string(kMaxFramebufferBytes >> 20) + " MiB");
  }
  try {
    if (desc.color_format == ColorFormat::kRGBA8) {
      s->rgba8.assign(samples * 4, 0);
    } else {
      s->rgba32f.assign(samples * 4, 0.0f);
    }
    const float far = detail::encode_depth(1.0, detail::depth_scale(desc.depth_format));
    s->depth.assign(samples, far);
    s->hiz_min.assign(size_t{s->grid.tile_count()} * detail::kBlocksPerTile, far);
    s->hiz_max.assign(size_t{s->grid.tile_count()} * detail::kBlocksPerTile, far);
    s->hiz_valid = true;
    s->pending.assign(s->grid.tile_count(), 0);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::kOutOfMemory,
                "framebuffer allocation of " + std::to_string(bytes >> 20) + " MiB failed");
  }
  storage_ = std::move(s);
}

Framebuffer::~Framebuffer() = default;
Framebuffer::Framebuffer(Framebuffer&&) noexcept = default;
Framebuffer& Framebuffer::operator=(Framebuffer&&) noexcept = default;

const FramebufferDesc& Framebuffer::desc() const noexcept {
  return storage_->desc;
}

// A clear is recorded per tile and written when the tile is next drawn or read (see
// FramebufferStorage::pending).
void Framebuffer::clear_color(std::array<float, 4> rgba) {
  detail::FramebufferStorage& s = *storage_;
  for (int c = 0; c < 4; ++c)
    s.clear_rgba8[c] = to_unorm8(rgba[c]);
  s.clear_rgba32f = rgba;
  for (uint8_t& p : s.pending)
    p |= detail::FramebufferStorage::kColorPending;
  s.any_pending.store(true, std::memory_order_release);
}

void Framebuffer::clear_depth(float depth) {
  const double scale = detail::depth_scale(storage_->desc.depth_format);
  // Fixed-point formats hold [0, 1]; a float buffer keeps whatever it is given.
  const float stored =
      scale > 0.0 && !std::isnan(depth)
          ? detail::encode_depth(std::clamp(static_cast<double>(depth), 0.0, 1.0), scale)
          : depth;
  storage_->clear_depth = stored;
  for (uint8_t& p : storage_->pending)
    p |= detail::FramebufferStorage::kDepthPending;
  storage_->any_pending.store(true, std::memory_order_release);
  std::fill(storage_->hiz_min.begin(), storage_->hiz_min.end(), stored);
  std::fill(storage_->hiz_max.begin(), storage_->hiz_max.end(), stored);
  storage_->hiz_valid = !std::isnan(depth);
}

namespace detail {

void FramebufferStorage::write_pending(uint32_t tile) {
  const uint8_t p = pending[tile];
  if (p == 0) return;
  const size_t values = size_t{desc.samples} * binning::kTilePixels;
  const size_t first = size_t{tile} * values;
  if (p & kColorPending) {
    if (!rgba8.empty()) {
      uint32_t v;
      std::memcpy(&v, clear_rgba8.data(), 4);
      uint32_t* c = reinterpret_cast<uint32_t*>(rgba8.data()) + first;
      std::fill(c, c + values, v);
    } else {
      float* c = rgba32f.data() + first * 4;
      for (size_t i = 0; i < values; ++i)
        std::copy(clear_rgba32f.begin(), clear_rgba32f.end(), c + i * 4);
    }
  }
  if (p & kDepthPending)
    std::fill(depth.data() + first, depth.data() + first + values, clear_depth);
  pending[tile] = 0;
}

}  // namespace detail

std::vector<uint8_t> Framebuffer::read_rgba8() const {
  const detail::FramebufferStorage& s = detail::FramebufferAccess::storage(*this);
  const uint32_t n = s.desc.samples;
  std::vector<uint8_t> out(size_t{s.desc.width} * s.desc.height * 4);
  std::vector<float> f;
  if (s.desc.color_format == ColorFormat::kRGBA32F) f = read_rgba32f();
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x) {
      const size_t o = (size_t{y} * s.desc.width + x) * 4;
      for (uint32_t c = 0; c < 4; ++c) {
        if (s.desc.color_format == ColorFormat::kRGBA32F) {
          out[o + c] = to_unorm8(f[o + c]);
          continue;
        }
        uint32_t sum = 0;
        for (uint32_t k = 0; k < n; ++k)
          sum += s.rgba8[s.sample_index(x, y, k) * 4 + c];
        out[o + c] = static_cast<uint8_t>((sum + n / 2) / n);
      }
    }
  }
  return out;
}

std::vector<float> Framebuffer::read_rgba32f() const {
  const detail::FramebufferStorage& s = detail::FramebufferAccess::storage(*this);
  const uint32_t n = s.desc.samples;
  if (s.desc.color_format == ColorFormat::kRGBA8) {
    std::vector<uint8_t> bytes = read_rgba8();
    std::vector<float> out(bytes.size());
    std::transform(bytes.begin(), bytes.end(), out.begin(),
                   [](uint8_t b) { return static_cast<float>(b) / 255.0f; });
    return out;
  }
  std::vector<float> out(size_t{s.desc.width} * s.desc.height * 4);
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x) {
      const size_t o = (size_t{y} * s.desc.width + x) * 4;
      for (uint32_t c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (uint32_t k = 0; k < n; ++k)
          sum += s.rgba32f[s.sample_index(x, y, k) * 4 + c];
        out[o + c] = sum / static_cast<float>(n);
      }
    }
  }
  return out;
}

std::vector<float> Framebuffer::read_depth() const {
  const detail::FramebufferStorage& s = detail::FramebufferAccess::storage(*this);
  const double scale = detail::depth_scale(s.desc.depth_format);
  std::vector<float> out(size_t{s.desc.width} * s.desc.height);
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x) {
      out[size_t{y} * s.desc.width + x] =
          detail::decode_depth(s.depth[s.sample_index(x, y, 0)], scale);
    }
  }
  return out;
}

std::vector<float> Framebuffer::read_sample_depth() const {
  const detail::FramebufferStorage& s = detail::FramebufferAccess::storage(*this);
  const double scale = detail::depth_scale(s.desc.depth_format);
  const uint32_t n = s.desc.samples;
  std::vector<float> out(size_t{s.desc.width} * s.desc.height * n);
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x) {
      for (uint32_t k = 0; k < n; ++k) {
        out[(size_t{y} * s.desc.width + x) * n + k] =
            detail::decode_depth(s.depth[s.sample_index(x, y, k)], scale);
      }
    }
  }
  return out;
}

}  // namespace tessera
