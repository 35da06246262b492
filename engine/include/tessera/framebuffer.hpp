// The render target: colour and depth for every sample of every pixel.
// Stored by tile while rendering (each 64x64 tile contiguous); linear, top-row-first images
// exist only when read back, after the MSAA resolve.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "tessera/export.hpp"
#include "tessera/types.hpp"

namespace tessera {

// Formats of colour targets. Target 0 (the colour every primitive draws) is kRGBA8 or kRGBA32F;
// the extra targets of multiple render targets take any of them: kR32F holds one float,
// kR32UI one unsigned 32-bit integer (exact IDs).
enum class ColorFormat { kRGBA8, kRGBA32F, kR32F, kR32UI };

// How depth is kept (docs/TRADEOFFS.md measures each). kFloat32 stores z as a float: finest
// near 0, which is where reversed Z (Camera::reversed_z, compare kGreater, clear to 0) puts
// distant geometry. kUnorm24 and kUnorm16 store round(z * (2^n - 1)) like a fixed-point depth
// buffer of n bits: evenly spaced steps (held in 32-bit lanes, so they change precision, not
// memory). Depth reads return z in [0, 1] for every format.
enum class DepthFormat { kFloat32, kUnorm24, kUnorm16 };

struct FramebufferDesc {
  uint32_t width = 0;                              // 1..kMaxFramebufferSize
  uint32_t height = 0;                             // 1..kMaxFramebufferSize
  uint32_t samples = 1;                            // 1, 2, 4, 8 or 16
  ColorFormat color_format = ColorFormat::kRGBA8;  // target 0: kRGBA8 or kRGBA32F
  DepthFormat depth_format = DepthFormat::kFloat32;
  // Multiple render targets: targets 1..extra_targets (0..3), of formats extra_formats[0..],
  // with the framebuffer's size and samples and one depth buffer for all. Every triangle draw
  // writes every target (what each receives: PipelineState::extra_outputs); points, lines and
  // polygons write target 0 only.
  uint32_t extra_targets = 0;
  std::array<ColorFormat, kMaxColorTargets - 1> extra_formats{};
};

// Largest total storage of one framebuffer (colour + depth, all samples).
inline constexpr uint64_t kMaxFramebufferBytes = uint64_t{8} << 30;

namespace detail {
struct FramebufferAccess;
struct FramebufferStorage;  // internal
}  // namespace detail

class TESSERA_API Framebuffer {
 public:
  // Throws Error(kInvalidArgument) for a zero or oversized side or an unsupported sample
  // count, Error(kOutOfMemory) past kMaxFramebufferBytes. Cleared to colour 0 and depth 1.
  explicit Framebuffer(const FramebufferDesc& desc);
  ~Framebuffer();
  Framebuffer(Framebuffer&&) noexcept;
  Framebuffer& operator=(Framebuffer&&) noexcept;
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  const FramebufferDesc& desc() const noexcept;
  uint32_t width() const noexcept { return desc().width; }
  uint32_t height() const noexcept { return desc().height; }
  uint32_t samples() const noexcept { return desc().samples; }

  // Clears take effect at once for every use of the framebuffer; the fast engine writes them
  // tile by tile as it next draws there (in parallel, into cache), anything else first.
  void clear_color(std::array<float, 4> rgba);
  // Depth in [0, 1] (stored in the framebuffer's depth format).
  void clear_depth(float depth);

  // Resolved colour (box average of the samples), top row first, 4 values per pixel.
  // RGBA8 framebuffers average the stored 8-bit values and round to nearest; read_rgba32f of
  // an RGBA8 framebuffer returns that result divided by 255.
  std::vector<uint8_t> read_rgba8() const;
  std::vector<float> read_rgba32f() const;
  // Any colour target t (0..target_count() - 1). Values per pixel: 4 for the RGBA formats,
  // 1 for kR32F; read_target of an RGBA8 target divides the resolved bytes by 255, as
  // read_rgba32f does. kR32UI targets are read by read_target_uint only, and resolve to
  // sample 0's value (IDs are not averaged). Throws Error(kInvalidArgument) for a target
  // that does not exist or the wrong read for its format.
  uint32_t target_count() const noexcept { return 1 + desc().extra_targets; }
  ColorFormat target_format(uint32_t target) const;
  std::vector<float> read_target(uint32_t target) const;
  std::vector<uint32_t> read_target_uint(uint32_t target) const;
  // Clears one target (clear_color is clear_target(0, ...)); kR32F keeps rgba[0]. The
  // extra targets start cleared to 0.
  void clear_target(uint32_t target, std::array<float, 4> rgba);
  void clear_target_uint(uint32_t target, uint32_t value);

  // Depth of sample 0 of each pixel, top row first, one float per pixel.
  std::vector<float> read_depth() const;
  // Every sample's depth: (y * width + x) * samples + s.
  std::vector<float> read_sample_depth() const;

 private:
  friend struct detail::FramebufferAccess;
  std::unique_ptr<detail::FramebufferStorage> storage_;
};

}  // namespace tessera
