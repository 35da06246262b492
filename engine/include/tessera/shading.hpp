// Shading state: how a draw's varyings (the per-vertex floats of DrawInput::attributes) are
// interpolated, which fragment shader turns them into a colour, and what the colour target
// receives. Part of PipelineState.
//
// Varyings are interpolated as OpenGL 4.6 section 14.6.1 and Vulkan define smooth
// (perspective-correct), noperspective (affine) and flat outputs; a flat varying takes the
// value of the triangle's first vertex (the provoking vertex of D3D and Vulkan), clipped or
// not. Per-pixel Phong is lecture 004's model (see PhongState).
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "tessera/types.hpp"

namespace tessera {

// How one varying is interpolated across a triangle.
enum class VaryingMode : uint8_t {
  kDefault,      // as PipelineState::interpolation says (perspective-correct unless affine)
  kPerspective,  // a/w and 1/w interpolated linearly on screen, divided per pixel
  kAffine,       // linear on screen (GLSL noperspective)
  kFlat,         // the first vertex's value, constant over the triangle
};

// The fragment shader: what colour a covered pixel gets (once per pixel, at its centre).
enum class FragmentShader : uint8_t {
  kGouraud,   // the colour varyings (VaryingRoles::color), RGBA; missing ones (0, 0, 0, 1)
  kPhong,     // per-pixel Phong lighting (PhongState) of the interpolated normal and position
  kUser,      // PipelineState::fragment_function, on batches of fragments (FragmentBatch)
  kTextured,  // PipelineState::texture sampled at the texture coordinates (VaryingRoles::
              // texcoord) with PipelineState::sampler, times the colour varyings when the draw
              // has them: unlit, the level of detail from each 2x2 quad's derivatives
};

// What the colour target receives. kColor is the fragment shader's colour; the others are the
// vision outputs that dataset and robotics tools read back, written as floats into R, G, B
// (A = 1) and independent of the fragment shader. kPrimitiveId and kObjectId need an RGBA32F
// target (exact below 2^24).
enum class TargetOutput : uint8_t {
  kColor,
  kEyeDepth,      // clip-space w at the pixel: distance along the view axis for a
                  // perspective projection (w = -z_eye); 1 under an orthographic one
  kNormal,        // the interpolated normal varyings, normalized (0 for a zero normal)
  kPosition,      // the interpolated position varyings
  kBarycentrics,  // the perspective-correct weights of the drawn triangle's three vertices
  kPrimitiveId,   // the triangle's index in the draw (clipped pieces keep their triangle's)
  kObjectId,      // PipelineState::object_id
};

// Where the built-in shaders and outputs find their inputs among the varyings: the index of
// the first of each group.
struct VaryingRoles {
  uint32_t color = 0;      // 4 varyings, RGBA: Gouraud's colour, Phong's base colour factor
  uint32_t normal = 4;     // 3 varyings: Phong's N and TargetOutput::kNormal
  uint32_t position = 7;   // 3 varyings: Phong's surface point and TargetOutput::kPosition
  uint32_t texcoord = 10;  // 2 varyings, (u, v): FragmentShader::kTextured
};

enum class LightKind : uint8_t { kDirectional, kPoint, kSpot };

// A light of the Phong model, in the space of the normal and position varyings.
struct Light {
  LightKind kind = LightKind::kPoint;
  std::array<float, 3> position{0, 0, 0};    // point and spot lights
  std::array<float, 3> direction{0, 0, -1};  // directional and spot: where the light travels
  std::array<float, 3> diffuse{1, 1, 1};     // Id
  std::array<float, 3> specular{1, 1, 1};    // Is
  // Attenuation 1 / (c0 + c1 d + c2 d^2) at distance d (point and spot; 1 for directional).
  float c0 = 1, c1 = 0, c2 = 0;
  // Spot lights: no light where the angle between `direction` and the ray to the point has a
  // cosine below spot_cos_cutoff; inside the cone the light is scaled by that cosine to the
  // power spot_exponent (OpenGL 1.x's spot model).
  float spot_cos_cutoff = 0.9f;
  float spot_exponent = 0;
};

inline constexpr uint32_t kMaxLights = 8;

// Lecture 004's Phong model, evaluated per pixel. With N the interpolated normal, normalized,
// and for each light L the unit vector from the point toward it, V the unit vector toward the
// eye and R = 2 (N.L) N - L:
//   I = ka Ia + sum over lights of att (kd max(0, N.L) Id + ks max(0, R.V)^n Is)
// per channel, and the colour is clamp(I x base, 0, 1) in RGB with
// the base's alpha. base = base_color, times the colour varyings when the draw has all four.
// The specular term is 0 where N.L <= 0. With two_sided (OpenGL's two-sided lighting), N is
// turned toward the eye where N.V < 0, so both faces of a surface are lit alike.
struct PhongState {
  std::array<float, 4> base_color{1, 1, 1, 1};
  float ka = 0.1f, kd = 0.7f, ks = 0.2f;
  float shininess = 32;                   // n
  std::array<float, 3> ambient{1, 1, 1};  // Ia
  std::array<float, 3> eye{0, 0, 0};      // in the lights' space
  bool two_sided = false;
  uint32_t light_count = 0;  // 0..kMaxLights
  std::array<Light, kMaxLights> lights{};
};

// User fragment shaders (FragmentShader::kUser; docs/WRITING_A_SHADER.md).
//
// The engine hands the shader batches of fragments in 2x2 quads of pixels and reads back one
// RGBA colour per fragment. Arrays are structure of arrays with kFragmentBatchStride floats
// between one component's array and the next, so a shader loops over i < count per component.
inline constexpr uint32_t kFragmentBatchStride = 64;

struct FragmentBatch {
  // Fragments in the batch: 4 per quad (a multiple of 4, at most kFragmentBatchStride). Quad
  // k is fragments 4k..4k+3: its top-left, top-right, bottom-left and bottom-right pixels.
  uint32_t count = 0;
  uint32_t varying_count = 0;  // the draw's attribute_count
  // Window coordinates of each fragment's pixel centre (pixel x + 0.5, y + 0.5; y down).
  const float* x = nullptr;
  const float* y = nullptr;
  // The fragment's covered samples that passed the depth test, bit s for sample s. 0 marks a
  // helper fragment: a pixel of the quad the triangle does not draw, shaded only so that its
  // neighbours' values exist; its outputs are not written.
  const uint32_t* sample_mask = nullptr;
  // The index of the fragment's triangle in the draw (clipped pieces keep their triangle's).
  const uint32_t* primitive_id = nullptr;
  // Varying v at the pixel centre: varyings[v * kFragmentBatchStride + i], interpolated as
  // the varying's mode says (where the centre lies beyond the triangle's horizon, at the
  // pixel's first drawn sample; a helper fragment there takes its quad's first drawn
  // fragment's values).
  const float* varyings = nullptr;
  // The screen derivatives of varying v per pixel step in x and in y, the same for the four
  // fragments of a quad: the exact derivative of the interpolated varying at the quad's centre
  // (the point its four pixel centres surround), 0 for a flat varying. Indexed as varyings.
  const float* ddx = nullptr;
  const float* ddy = nullptr;
};

struct FragmentOutput {
  // RGBA of fragment i: color[c * kFragmentBatchStride + i] for channel c = 0..3, written as
  // the built-in shaders' colours are (clamped to [0, 1] and rounded in an RGBA8 target; NaN
  // becomes 0 there). Undefined on entry: the shader writes every live fragment's.
  float* color = nullptr;
  // Set discard[i] to nonzero to drop fragment i: neither its colour nor its depth is written
  // (in any target). All zero on entry.
  uint8_t* discard = nullptr;
  // Multiple render targets (FramebufferDesc::extra_targets): extra target t + 1's values,
  // extra[t][c * kFragmentBatchStride + i] for its channels c (4 for an RGBA8 or RGBA32F
  // target, 1 for R32F), and for an R32UI target extra_uint[t][i] instead (extra[t] is then
  // null). Null for targets the framebuffer does not have. The engine keeps what the shader
  // writes only for targets whose output (PipelineState::output, extra_outputs) is kColor;
  // it computes the vision outputs of the others itself.
  std::array<float*, kMaxColorTargets - 1> extra{};
  std::array<uint32_t*, kMaxColorTargets - 1> extra_uint{};
};

// The engine calls the function from several threads at once, for batches of different
// screen tiles, in no particular order across tiles (within a pixel, in draw order). So it
// must be safe to call concurrently, and each fragment's outputs must depend only on that
// fragment's inputs (its own position, varyings, derivatives, IDs and mask), so that images
// do not depend on the thread count or on how fragments are batched. It must not throw: an
// exception leaves the framebuffer partly drawn and is passed on to the draw's caller.
using FragmentFunction = std::function<void(const FragmentBatch&, const FragmentOutput&)>;

}  // namespace tessera
