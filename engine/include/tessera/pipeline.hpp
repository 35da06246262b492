// Pipeline state: everything about a draw that is not its vertex data.
// Conventions (ARCHITECTURE.md section 2): clip space visible in -w <= x, y <= w and
// 0 <= z <= w; window origin top-left, y down; top-left fill rule; counter-clockwise in NDC
// (y up) is front-facing by default.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "tessera/shading.hpp"
#include "tessera/texture.hpp"

namespace tessera {

enum class CompareOp {
  kNever,
  kLess,
  kEqual,
  kLessEqual,
  kGreater,
  kNotEqual,
  kGreaterEqual,
  kAlways
};
enum class CullMode { kNone, kFront, kBack };
enum class FrontFace { kCounterClockwise, kClockwise };  // as seen in NDC, y up

// Which clip-space depth range the vertex data uses. kNegativeOneToOne (OpenGL,
// -w <= z <= w, like glClipControl) is mapped to 0..1 at the viewport transform.
enum class ClipDepth { kZeroToOne, kNegativeOneToOne };

// Attribute interpolation: perspective-correct (a/w and 1/w interpolated, divided per pixel)
// or affine (linear in screen space). The default of every varying; VaryingMode overrides it
// per varying.
enum class Interpolation { kPerspective, kAffine };

// Blending (OpenGL 4.6 section 17.3.6, Vulkan's VkBlendFactor and VkBlendOp): a colour target's
// stored value becomes op(src * src_factor, dst * dst_factor), per channel, with separate
// factors and op for alpha. kMin and kMax ignore the factors. kSrcAlphaSaturate is
// min(src alpha, 1 - dst alpha) for R, G and B and 1 for alpha.
enum class BlendFactor {
  kZero,
  kOne,
  kSrcColor,
  kOneMinusSrcColor,
  kDstColor,
  kOneMinusDstColor,
  kSrcAlpha,
  kOneMinusSrcAlpha,
  kDstAlpha,
  kOneMinusDstAlpha,
  kConstantColor,
  kOneMinusConstantColor,
  kConstantAlpha,
  kOneMinusConstantAlpha,
  kSrcAlphaSaturate
};
enum class BlendOp { kAdd, kSubtract, kReverseSubtract, kMin, kMax };

// Bits of BlendState::write_mask.
inline constexpr uint8_t kWriteRed = 1, kWriteGreen = 2, kWriteBlue = 4, kWriteAlpha = 8;
inline constexpr uint8_t kWriteAll = 0xF;

// One colour target's blend state. RGBA8 targets blend as a unorm8 GPU does: source, constant
// and destination (byte / 255) as floats in [0, 1] (source and constant clamped), the
// equation in float, the result clamped to [0, 1] and rounded to nearest (to_unorm8). Float
// targets blend in float with nothing clamped. Channels outside write_mask keep their stored
// value, blending or not.
struct BlendState {
  bool enable = false;
  BlendFactor src_color = BlendFactor::kOne;
  BlendFactor dst_color = BlendFactor::kZero;
  BlendOp color_op = BlendOp::kAdd;
  BlendFactor src_alpha = BlendFactor::kOne;
  BlendFactor dst_alpha = BlendFactor::kZero;
  BlendOp alpha_op = BlendOp::kAdd;
  uint8_t write_mask = kWriteAll;

  // Whether a draw with this state stores its colour as it is (no blend, every channel).
  constexpr bool replaces() const { return !enable && write_mask == kWriteAll; }
  friend constexpr bool operator==(const BlendState&, const BlendState&) = default;

  // The usual states: OpenGL's (SRC_ALPHA, ONE_MINUS_SRC_ALPHA) for colour and (ONE,
  // ONE_MINUS_SRC_ALPHA) for alpha; (ONE, ONE); (DST_COLOR, ZERO); (ONE,
  // ONE_MINUS_SRC_ALPHA) for both.
  static constexpr BlendState over();
  static constexpr BlendState additive();
  static constexpr BlendState multiply();
  static constexpr BlendState premultiplied_over();
};

constexpr BlendState BlendState::over() {
  BlendState b;
  b.enable = true;
  b.src_color = BlendFactor::kSrcAlpha;
  b.dst_color = BlendFactor::kOneMinusSrcAlpha;
  b.src_alpha = BlendFactor::kOne;
  b.dst_alpha = BlendFactor::kOneMinusSrcAlpha;
  return b;
}
constexpr BlendState BlendState::additive() {
  BlendState b;
  b.enable = true;
  b.src_color = b.dst_color = b.src_alpha = b.dst_alpha = BlendFactor::kOne;
  return b;
}
constexpr BlendState BlendState::multiply() {
  BlendState b;
  b.enable = true;
  b.src_color = b.src_alpha = BlendFactor::kDstColor;
  b.dst_color = b.dst_alpha = BlendFactor::kZero;
  return b;
}
constexpr BlendState BlendState::premultiplied_over() {
  BlendState b;
  b.enable = true;
  b.src_color = b.src_alpha = BlendFactor::kOne;
  b.dst_color = b.dst_alpha = BlendFactor::kOneMinusSrcAlpha;
  return b;
}

// A rectangle of window pixels: its first pixel (x, y), counted from the top-left pixel with
// y down, and its size.
struct Rect {
  int32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
};

inline constexpr uint32_t kMinSubpixelBits = 4;
inline constexpr uint32_t kMaxSubpixelBits = 8;

struct PipelineState {
  // Depth. With depth_test off, depth is neither tested nor written (OpenGL semantics).
  bool depth_test = true;
  bool depth_write = true;
  CompareOp depth_compare = CompareOp::kLess;

  // Depth bias (Direct3D's and Vulkan's formula, engine/src/depth_bias.hpp): each triangle's
  // depth is offset by depth_bias_constant * r + depth_bias_slope * max(|dz/dx|, |dz/dy|), r
  // the depth format's smallest step at the triangle's depth, clamped by depth_bias_clamp when
  // it is not 0. It applies to triangles, the triangles wide lines, square points and polygons
  // are drawn as included; not to one-pixel or antialiased lines or round points.
  float depth_bias_constant = 0.0f;
  float depth_bias_slope = 0.0f;
  float depth_bias_clamp = 0.0f;

  bool color_write = true;
  // The scissor test: with scissor_test, a draw writes only the pixels inside `scissor`
  // (clipped to the framebuffer; an empty rectangle draws nothing). Samples outside it are
  // neither covered nor tested.
  bool scissor_test = false;
  Rect scissor;

  // Blending and write masks per colour target (target 0, then the extra targets). Blending
  // applies to target 0; an extra target takes only BlendState{} (Error otherwise).
  std::array<BlendState, kMaxColorTargets> blend{};
  std::array<float, 4> blend_constant{0.0f, 0.0f, 0.0f, 0.0f};  // kConstantColor, kConstantAlpha

  CullMode cull = CullMode::kNone;
  FrontFace front_face = FrontFace::kCounterClockwise;
  ClipDepth clip_depth = ClipDepth::kZeroToOne;
  Interpolation interpolation = Interpolation::kPerspective;

  // Samples per pixel; 0 means "whatever the framebuffer has". Otherwise it must equal the
  // framebuffer's sample count.
  uint32_t samples = 0;

  // Fractional bits of the fixed-point window coordinates vertices are snapped to (4..8).
  uint32_t subpixel_bits = 8;

  // Shading (tessera/shading.hpp). Triangles only: points, lines and polygons take their
  // colour from the colour varyings 0..3 as before.
  std::array<VaryingMode, kMaxVaryings> varying_modes{};  // per varying; kDefault: interpolation
  FragmentShader shader = FragmentShader::kGouraud;
  TargetOutput output = TargetOutput::kColor;  // what colour target 0 receives
  // What extra target t + 1 of a framebuffer with several (FramebufferDesc::extra_targets)
  // receives. An R32UI target takes kPrimitiveId, kObjectId (exact) or a user shader's
  // kColor (FragmentOutput::extra_uint); a float target stores R of RGBA.
  std::array<TargetOutput, kMaxColorTargets - 1> extra_outputs{};
  VaryingRoles roles;
  PhongState phong;                    // FragmentShader::kPhong
  FragmentFunction fragment_function;  // FragmentShader::kUser
  // FragmentShader::kTextured: the texture (shared, never modified by a draw) and how it is
  // sampled.
  std::shared_ptr<const Texture> texture;
  Sampler sampler;
  uint32_t object_id = 0;  // TargetOutput::kObjectId
};

}  // namespace tessera
