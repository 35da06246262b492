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

inline constexpr uint32_t kMinSubpixelBits = 4;
inline constexpr uint32_t kMaxSubpixelBits = 8;

struct PipelineState {
  // Depth. With depth_test off, depth is neither tested nor written (OpenGL semantics).
  bool depth_test = true;
  bool depth_write = true;
  CompareOp depth_compare = CompareOp::kLess;

  bool color_write = true;

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
