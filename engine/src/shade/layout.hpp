// What a shaded draw's fragments are made of in the fast engine: the values its triangle setups
// carry as planes (interpolants), how each is interpolated, and which built-in shader turns
// them into the colour target's RGBA. Built once per draw from the pipeline's shading state
// (tessera/shading.hpp); the setup (triangle_setup.cpp) writes the planes, and the shader
// policies (shade-inl.h) read them. Draws of the plain Gouraud colour (every colour varying
// interpolated as the pipeline's interpolation says) keep the setup's own colour planes and
// need none of this.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "engine/src/texture/sample_batch.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"

namespace tessera::shade {

// The fragment shader a kernel instance is compiled for.
enum class Shader : uint8_t {
  kGouraud,       // the setup's four colour planes (TriangleSetup::qa0...): the common case
  kInterpolated,  // each RGBA channel an interpolant or a constant
  kNormalized,    // interpolants 0..2 normalized, as RGB (A = 1): TargetOutput::kNormal
  kPhong,         // per-pixel Phong (PhongState) of the normal and position interpolants
  kTextured,      // Layout::texture sampled in lanes at interpolants 0 and 1 (u, v), times the
                  // colour interpolants 2..5 with has_color
  kUser,          // the quad back end (user_batch.hpp), for a user FragmentFunction, textured
                  // draws and framebuffers with several colour targets (Layout::targets)
};
inline constexpr int kShaders = 6;

// What a vertex carries for one interpolant.
enum class Source : uint8_t {
  kVarying,        // varying `index` of the draw
  kClipW,          // its clip-space w: the eye depth, perspective-correct
  kBarycentric,    // 1 for vertex `index` of the draw's triangle, 0 for the others
  kPrimitive,      // the triangle's index in the draw (flat)
  kPrimitiveBits,  // the same index, its 32 bits stored as the plane's float (flat): exact
                   // beyond 2^24
};

struct Interpolant {
  Source source = Source::kVarying;
  uint32_t index = 0;
  VaryingMode mode = VaryingMode::kPerspective;  // never kDefault
};

// A user shader reads every varying and the primitive index; a built-in shader at most 10, a
// vision output at most 3; several colour targets each their own (kUser: Layout::targets).
inline constexpr uint32_t kMaxInterpolants = kMaxVaryings + 1 + 3 * kMaxColorTargets;

struct Targets;

// A light as the Phong policy reads it: directions normalized and negated where the model
// needs them, in double and then rounded to float, as the reference normalizes them.
struct PreparedLight {
  LightKind kind = LightKind::kPoint;
  std::array<float, 3> position{};  // point and spot
  std::array<float, 3> to_light{};  // directional: the unit vector toward the light
  std::array<float, 3> axis{};      // spot: the unit direction the light travels
  std::array<float, 3> diffuse{}, specular{};
  float c0 = 1, c1 = 0, c2 = 0;
  // c1 = c2 = 0: the attenuation 1 / c0 is the same everywhere (the same float the per-pixel
  // division gives, as 0 d and 0 d^2 are 0).
  bool constant_attenuation = true;
  float attenuation = 1;
  float spot_cos_cutoff = 0, spot_exponent = 0;
};

struct Layout {
  Shader shader = Shader::kGouraud;
  uint32_t count = 0;  // interpolants per triangle: 3 floats of planes each
  std::array<Interpolant, kMaxInterpolants> values{};
  bool needs_q = false;  // a perspective-correct interpolant: the setup's 1/w plane is read
  // kInterpolated: channel c is interpolant channel[c], or constant[c] where that is kConstant.
  static constexpr uint8_t kConstant = 0xFF;
  std::array<uint8_t, 4> channel{kConstant, kConstant, kConstant, kConstant};
  std::array<float, 4> constant{0, 0, 0, 1};
  // kPhong: the normal is interpolants 0..2, the position 3..5, and with has_color the colour
  // varyings 6..9, which scale the base colour.
  bool has_color = false;
  PhongState phong{};  // the draw's material (phong.lights unused: see lights)
  std::array<PreparedLight, kMaxLights> lights{};
  // kTextured: the pipeline's texture and sampler as the lanes read them (alive for the draw).
  std::shared_ptr<const texture::LaneTexture> texture;
  // kUser: the pipeline's function (valid for the draw) where a target takes its values; the
  // draw's varyings as interpolants 0..function_varyings - 1 when the function or a texture
  // reads them; each colour target's shading; and the last interpolant, the primitive index's
  // bits.
  const FragmentFunction* function = nullptr;
  uint32_t function_varyings = 0;
  std::shared_ptr<const Targets> targets;
};

// How the quad back end fills one colour target.
struct TargetShading {
  ColorFormat format = ColorFormat::kRGBA8;
  TargetOutput output = TargetOutput::kColor;
  bool from_function = false;  // the user function's values
  // FragmentShader::kTextured: Targets::texture sampled at the fragment's texture coordinates
  // (the batch's varyings and derivatives), times the colour `layout` gives.
  bool textured = false;
  // Otherwise kPrimitiveId and kObjectId come from the fragment's IDs, and the other outputs
  // from `layout` (kInterpolated, kNormalized or kPhong), whose interpolants are the draw's
  // from `first` on.
  uint32_t first = 0;
  Layout layout;
};

struct Targets {
  uint32_t count = 1;
  std::array<TargetShading, kMaxColorTargets> target{};
  uint32_t object_id = 0;
  // A textured target's texture (the pipeline's, alive for the draw), sampler, and the first of
  // its two texture coordinate varyings.
  const Texture* texture = nullptr;
  Sampler sampler;
  std::shared_ptr<const texture::LaneTexture> lanes;  // how the lanes read them; null: they do not
  uint32_t texcoord = 0;
};

// The layout of a draw with `attribute_count` varyings under `pipeline`'s shading state into a
// framebuffer of `desc`: Shader::kGouraud (and nothing else set) for the plain Gouraud colour,
// and for draws that write no colour, whose fragments have no values.
Layout layout_for(const PipelineState& pipeline, uint32_t attribute_count,
                  const FramebufferDesc& desc);

}  // namespace tessera::shade
