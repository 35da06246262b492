// Textures and samplers: 2D images with mip chains, sampled with OpenGL 4.6's rules (section
// 8.14, level of detail; 8.14.2, the filters; table 8.20, the wrap modes) from user fragment
// shaders (FragmentBatch's varyings and derivatives give the coordinates and the LOD).
//
// Texel (0, 0) is the image's top-left texel; u grows right and v grows down, so u = v = 0 is
// the top-left corner of the image and (1, 1) its bottom-right corner.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tessera/export.hpp"
#include "tessera/shading.hpp"

namespace tessera {

namespace detail {
struct TextureAccess;
}  // namespace detail

enum class TextureFormat : uint8_t {
  kRGBA8,      // 8-bit unorm RGBA, linear
  kRGBA8Srgb,  // 8-bit RGBA, RGB sRGB-encoded (decoded to linear when sampled), alpha linear
  kRGBA32F,    // float RGBA
  kR8,         // 8-bit unorm red; sampled as (r, 0, 0, 1)
  kR32F,       // float red; sampled as (r, 0, 0, 1)
};

inline constexpr uint32_t kMaxTextureSize = 16384;
inline constexpr uint32_t kMaxAnisotropy = 16;  // Sampler::max_anisotropy's largest value

// Bytes of one texel of `format`.
TESSERA_API uint32_t texel_bytes(TextureFormat format);

struct TextureDesc {
  uint32_t width = 0;   // 1..kMaxTextureSize
  uint32_t height = 0;  // 1..kMaxTextureSize
  TextureFormat format = TextureFormat::kRGBA8;
};

// A texture: level 0 and, when asked for, the whole mip chain down to 1x1. Level n is
// max(1, floor(width / 2^n)) by max(1, floor(height / 2^n)) texels (OpenGL's sizes). A generated
// level's texel (x, y) is the mean of the 2x2 texels (2x, 2y) to (2x + 1, 2y + 1) of the level
// above, a side of 1 counting its one texel twice; so an odd side's last column or row does not
// reach the next level. Means are taken on linear values: sRGB texels are decoded, averaged
// and encoded again; 8-bit means are rounded to nearest (halves up).
class TESSERA_API Texture {
 public:
  // Copies `pixels`, level 0's texels top row first, tightly packed (texel_bytes each). Throws
  // Error(kInvalidArgument) for a zero or oversized side or a pixel span of the wrong size,
  // Error(kOutOfMemory) when the storage cannot be allocated. Nothing the caller passed is kept.
  Texture(const TextureDesc& desc, std::span<const std::byte> pixels, bool mipmaps);
  ~Texture();
  Texture(Texture&&) noexcept;
  Texture& operator=(Texture&&) noexcept;
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  const TextureDesc& desc() const noexcept;
  uint32_t levels() const noexcept;  // 1 without mipmaps
  uint32_t width(uint32_t level) const;
  uint32_t height(uint32_t level) const;
  // Replaces level `level` with the caller's texels (a mip chain supplied level by level).
  // Throws Error(kInvalidArgument) for a level past levels() or a span of the wrong size.
  void set_level(uint32_t level, std::span<const std::byte> pixels);
  // Level `level`'s stored bytes, top row first.
  std::span<const std::byte> level_bytes(uint32_t level) const;
  // Texel (x, y) of `level` as linear float RGBA (sRGB decoded; red formats (r, 0, 0, 1)).
  std::array<float, 4> texel(uint32_t level, uint32_t x, uint32_t y) const;

  struct Storage;  // internal

 private:
  friend struct detail::TextureAccess;
  std::unique_ptr<Storage> storage_;
};

enum class Filter : uint8_t { kNearest, kLinear };
enum class MipFilter : uint8_t {
  kNone,     // level 0 only
  kNearest,  // the nearest level
  kLinear,   // linear between the two nearest levels (with Filter::kLinear: trilinear)
};
enum class Wrap : uint8_t { kRepeat, kClampToEdge, kMirroredRepeat, kClampToBorder };

struct Sampler {
  Filter mag_filter = Filter::kLinear;
  Filter min_filter = Filter::kLinear;
  MipFilter mip_filter = MipFilter::kLinear;
  Wrap wrap_u = Wrap::kRepeat;
  Wrap wrap_v = Wrap::kRepeat;
  std::array<float, 4> border_color{0, 0, 0, 0};  // Wrap::kClampToBorder
  float lod_bias = 0;                             // added to log2 of the scale factor
  float min_lod = -1000, max_lod = 1000;          // the LOD is clamped to [min_lod, max_lod]
  // Anisotropic filtering: up to floor(max_anisotropy) samples along a stretched footprint
  // (sample_footprint); 1 (the default) turns it off. 1 to kMaxAnisotropy.
  float max_anisotropy = 1;
};

// The level of detail at a fragment from the derivatives of (u, v) per pixel step (OpenGL 4.6
// equations 8.4 to 8.6 with the larger of the two axes' lengths): rho = max(|(du/dx w,
// dv/dx h)|, |(du/dy w, dv/dy h)|) in level-0 texels, lambda = log2(rho) + lod_bias, clamped to
// [min_lod, max_lod]. -infinity when rho is 0, and the clamp applies to it.
TESSERA_API float texture_lod(const Texture& texture, const Sampler& sampler, float du_dx,
                              float dv_dx, float du_dy, float dv_dy);

// The filtered, linear RGBA at (u, v) with level of detail `lod` (texture_lod's): magnified
// (lod <= 0) with mag_filter from level 0, else minified with min_filter from the level(s)
// mip_filter picks (nearest: level ceil(lod + 1/2) - 1; linear: floor(lod) and the next, by
// lod's fraction; clamped to the chain). Within a level, nearest takes the texel containing
// (u w, v h) and linear the four around (u w - 1/2, v h - 1/2), each wrapped as the sampler
// says. A NaN coordinate or LOD samples as 0 does; coordinates beyond 2^30 texels are clamped
// there. Computed in float: the texel position u w is rounded to float (an error of 2^-24 of
// it: 1/16 texel at a million texels).
TESSERA_API std::array<float, 4> sample(const Texture& texture, const Sampler& sampler, float u,
                                        float v, float lod);

// The filtered, linear RGBA at (u, v) over the footprint that the derivatives of (u, v) per
// pixel step give, as the built-in textured shader and the batch form below sample: with
// max_anisotropy 1, sample() at texture_lod(); above 1, anisotropic (EXT_texture_filter_
// anisotropic's formulation, core in OpenGL 4.6): with px and py the two axes' lengths in
// level-0 texels (texture_lod's), N = min(ceil(max(px, py) / min(px, py)),
// floor(max_anisotropy)) samples (1 for an empty or NaN footprint), each sample() at lambda =
// log2(max(px, py) / N) + lod_bias (clamped), at (u, v) plus i / (N + 1) - 1/2 steps along the
// longer axis for i = 1..N, averaged.
TESSERA_API std::array<float, 4> sample(const Texture& texture, const Sampler& sampler, float u,
                                        float v, float du_dx, float dv_dx, float du_dy,
                                        float dv_dy);

// sample() at every fragment of a user shader's batch, with (u, v) = varyings `u_varying` and
// `v_varying` over the footprint their derivatives give (the derivatives' sample()), into rgba[c *
// kFragmentBatchStride + i] for channel c of fragment i.
TESSERA_API void sample(const Texture& texture, const Sampler& sampler, const FragmentBatch& batch,
                        uint32_t u_varying, uint32_t v_varying, float* rgba);

}  // namespace tessera
