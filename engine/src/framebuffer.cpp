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
    throw Error(ErrorCode::kInvalidArgument,
                "framebuffer colour format (target 0) is not kRGBA8 or kRGBA32F");
  }
  if (d.extra_targets > kMaxColorTargets - 1) {
    throw Error(ErrorCode::kInvalidArgument,
                "framebuffer extra_targets " + std::to_string(d.extra_targets) +
                    " is out of range (0.." + std::to_string(kMaxColorTargets - 1) + ")");
  }
  for (uint32_t t = 0; t < d.extra_targets; ++t) {
    const auto f = static_cast<uint32_t>(d.extra_formats[t]);
    if (f > static_cast<uint32_t>(ColorFormat::kR32UI)) {
      throw Error(ErrorCode::kInvalidArgument,
                  "framebuffer extra_formats[" + std::to_string(t) + "] is not a ColorFormat");
    }
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
  uint64_t sample_bytes = (desc.color_format == ColorFormat::kRGBA8 ? 4 : 16) + 4;
  for (uint32_t t = 0; t < desc.extra_targets; ++t)
    sample_bytes += 4 * detail::words_per_sample(desc.extra_formats[t]);
  const uint64_t bytes = samples * sample_bytes;
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
    for (uint32_t t = 0; t < desc.extra_targets; ++t) {
      detail::ExtraTarget& target = s->extra[t];
      target.format = desc.extra_formats[t];
      target.words = detail::words_per_sample(target.format);
      target.data.assign(samples * target.words, 0u);
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

namespace {

// The extra target `target` (1..3) of `s`, or an error naming what was wrong.
const detail::ExtraTarget& extra_target(const detail::FramebufferStorage& s, uint32_t target) {
  if (target == 0 || target > s.desc.extra_targets) {
    throw Error(ErrorCode::kInvalidArgument, "colour target " + std::to_string(target) +
                                                 " does not exist (the framebuffer has " +
                                                 std::to_string(1 + s.desc.extra_targets) + ")");
  }
  return s.extra[target - 1];
}

const char* format_name(ColorFormat f) {
  switch (f) {
    case ColorFormat::kRGBA8:
      return "RGBA8";
    case ColorFormat::kRGBA32F:
      return "RGBA32F";
    case ColorFormat::kR32F:
      return "R32F";
    case ColorFormat::kR32UI:
      return "R32UI";
  }
  return "?";
}

}  // namespace

ColorFormat Framebuffer::target_format(uint32_t target) const {
  if (target == 0) return storage_->desc.color_format;
  return extra_target(*storage_, target).format;
}

void Framebuffer::clear_target(uint32_t target, std::array<float, 4> rgba) {
  if (target == 0) {
    clear_color(rgba);
    return;
  }
  if (extra_target(*storage_, target).format == ColorFormat::kR32UI) {
    throw Error(ErrorCode::kInvalidArgument, "colour target " + std::to_string(target) +
                                                 " is R32UI: clear it with clear_target_uint");
  }
  detail::ExtraTarget& t = storage_->extra[target - 1];
  uint32_t value[4];
  detail::store_target_value(t.format, value, rgba.data(), 0);
  for (size_t i = 0; i < t.data.size(); i += t.words)
    std::copy_n(value, t.words, t.data.data() + i);
}

void Framebuffer::clear_target_uint(uint32_t target, uint32_t value) {
  if (target == 0 || extra_target(*storage_, target).format != ColorFormat::kR32UI) {
    throw Error(ErrorCode::kInvalidArgument, "colour target " + std::to_string(target) + " is " +
                                                 format_name(target_format(target)) +
                                                 ", not R32UI: clear it with clear_target");
  }
  detail::ExtraTarget& t = storage_->extra[target - 1];
  std::fill(t.data.begin(), t.data.end(), value);
}

std::vector<float> Framebuffer::read_target(uint32_t target) const {
  if (target == 0) return read_rgba32f();
  const detail::ExtraTarget& t = extra_target(*storage_, target);
  if (t.format == ColorFormat::kR32UI) {
    throw Error(ErrorCode::kInvalidArgument, "colour target " + std::to_string(target) +
                                                 " is R32UI: read it with read_target_uint");
  }
  const detail::FramebufferStorage& s = *storage_;
  const uint32_t n = s.desc.samples;
  const uint32_t channels = t.format == ColorFormat::kR32F ? 1 : 4;
  std::vector<float> out(size_t{s.desc.width} * s.desc.height * channels);
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x) {
      const size_t o = (size_t{y} * s.desc.width + x) * channels;
      for (uint32_t c = 0; c < channels; ++c) {
        // The box resolve: RGBA8 like read_rgba8 (the bytes' rounded mean), floats averaged.
        uint32_t bytes = 0;
        float sum = 0.0f;
        for (uint32_t k = 0; k < n; ++k) {
          const uint32_t* at = t.data.data() + s.sample_index(x, y, k) * t.words;
          if (t.format == ColorFormat::kRGBA8) {
            uint8_t b[4];
            std::memcpy(b, at, 4);
            bytes += b[c];
          } else {
            float f;
            std::memcpy(&f, at + c, 4);
            sum += f;
          }
        }
        out[o + c] = t.format == ColorFormat::kRGBA8
                         ? static_cast<float>((bytes + n / 2) / n) / 255.0f
                         : sum / static_cast<float>(n);
      }
    }
  }
  return out;
}

std::vector<uint32_t> Framebuffer::read_target_uint(uint32_t target) const {
  if (target == 0 || extra_target(*storage_, target).format != ColorFormat::kR32UI) {
    throw Error(ErrorCode::kInvalidArgument, "colour target " + std::to_string(target) + " is " +
                                                 format_name(target_format(target)) +
                                                 ", not R32UI: read it with read_target");
  }
  const detail::FramebufferStorage& s = *storage_;
  const detail::ExtraTarget& t = s.extra[target - 1];
  std::vector<uint32_t> out(size_t{s.desc.width} * s.desc.height);
  for (uint32_t y = 0; y < s.desc.height; ++y) {
    for (uint32_t x = 0; x < s.desc.width; ++x)
      out[size_t{y} * s.desc.width + x] = t.data[s.sample_index(x, y, 0)];
  }
  return out;
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
