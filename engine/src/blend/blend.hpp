// Blending of one sample's colour (tessera/pipeline.hpp's BlendState), the scalar form: what
// the reference writes and what the fast engine's per-pixel writers write. The SIMD form
// (blend-inl.h) performs the same float operations in the same order, so both store the same
// bytes. Contraction is off in the whole build: a * b + c is never fused.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "engine/src/sample_positions.hpp"
#include "tessera/pipeline.hpp"

namespace tessera::blend {

using Rgba = std::array<float, 4>;

// The usual states (BlendState::over() and the others), which the fast engine compiles with
// their factors known (a switch per factor per vector otherwise); kOther: any other state.
enum class Preset : uint8_t { kOther, kOver, kPremultipliedOver, kAdditive, kMultiply };

// Preset P's state (BlendState{} for kOther).
template <Preset P>
inline constexpr BlendState kPresetState = P == Preset::kOver ? BlendState::over()
                                           : P == Preset::kPremultipliedOver
                                               ? BlendState::premultiplied_over()
                                           : P == Preset::kAdditive ? BlendState::additive()
                                           : P == Preset::kMultiply ? BlendState::multiply()
                                                                    : BlendState{};

inline Preset preset_of(const BlendState& b) {
  if (b == kPresetState<Preset::kOver>) return Preset::kOver;
  if (b == kPresetState<Preset::kPremultipliedOver>) return Preset::kPremultipliedOver;
  if (b == kPresetState<Preset::kAdditive>) return Preset::kAdditive;
  if (b == kPresetState<Preset::kMultiply>) return Preset::kMultiply;
  return Preset::kOther;
}

// Factor f for channel c (0..2 colour, 3 alpha) of source s, destination d and constant k.
inline float factor(BlendFactor f, int c, const Rgba& s, const Rgba& d, const Rgba& k) {
  switch (f) {
    case BlendFactor::kZero:
      return 0.0f;
    case BlendFactor::kOne:
      return 1.0f;
    case BlendFactor::kSrcColor:
      return s[c];
    case BlendFactor::kOneMinusSrcColor:
      return 1.0f - s[c];
    case BlendFactor::kDstColor:
      return d[c];
    case BlendFactor::kOneMinusDstColor:
      return 1.0f - d[c];
    case BlendFactor::kSrcAlpha:
      return s[3];
    case BlendFactor::kOneMinusSrcAlpha:
      return 1.0f - s[3];
    case BlendFactor::kDstAlpha:
      return d[3];
    case BlendFactor::kOneMinusDstAlpha:
      return 1.0f - d[3];
    case BlendFactor::kConstantColor:
      return k[c];
    case BlendFactor::kOneMinusConstantColor:
      return 1.0f - k[c];
    case BlendFactor::kConstantAlpha:
      return k[3];
    case BlendFactor::kOneMinusConstantAlpha:
      return 1.0f - k[3];
    case BlendFactor::kSrcAlphaSaturate:
      if (c == 3) return 1.0f;
      {
        const float rest = 1.0f - d[3];  // the smaller of s[3] and rest; s[3] on NaN
        return rest < s[3] ? rest : s[3];
      }
  }
  return 0.0f;
}

// op(s * fs, d * fd). kMin and kMax take s and d themselves, and return d when either is NaN
// (the SIMD form selects by the same comparisons).
inline float combine(BlendOp op, float s, float fs, float d, float fd) {
  switch (op) {
    case BlendOp::kAdd:
      return s * fs + d * fd;
    case BlendOp::kSubtract:
      return s * fs - d * fd;
    case BlendOp::kReverseSubtract:
      return d * fd - s * fs;
    case BlendOp::kMin:
      return s < d ? s : d;
    case BlendOp::kMax:
      return s > d ? s : d;
  }
  return s;
}

// Clamps to [0, 1]: NaN becomes 0 (as to_unorm8 takes it).
inline float saturate(float v) {
  return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
}

// The blended colour of source `src` over destination `dst` (both as floats: an RGBA8
// target's bytes / 255) with constant `k`, before the write mask. `unorm`: an RGBA8 target,
// whose source and constant are clamped to [0, 1] first (its result is clamped when stored).
inline Rgba blend(const BlendState& b, const Rgba& k_in, Rgba src, const Rgba& dst, bool unorm) {
  if (!b.enable) return src;
  Rgba k = k_in;
  if (unorm) {
    for (int c = 0; c < 4; ++c) {
      src[c] = saturate(src[c]);
      k[c] = saturate(k[c]);
    }
  }
  Rgba out;
  for (int c = 0; c < 4; ++c) {
    const bool alpha = c == 3;
    const float fs = factor(alpha ? b.src_alpha : b.src_color, c, src, dst, k);
    const float fd = factor(alpha ? b.dst_alpha : b.dst_color, c, src, dst, k);
    out[c] = combine(alpha ? b.alpha_op : b.color_op, src[c], fs, dst[c], fd);
  }
  return out;
}

// An RGBA8 sample's four bytes after a fragment of colour `src`: blended, masked and stored
// as to_unorm8 rounds.
inline void write_rgba8(const BlendState& b, const Rgba& k, const Rgba& src, uint8_t* bytes) {
  const Rgba dst = {bytes[0] / 255.0f, bytes[1] / 255.0f, bytes[2] / 255.0f, bytes[3] / 255.0f};
  const Rgba out = blend(b, k, src, dst, true);
  for (int c = 0; c < 4; ++c)
    if (b.write_mask & (1u << c)) bytes[c] = to_unorm8(out[c]);
}

// An RGBA32F sample's four floats after a fragment of colour `src`.
inline void write_rgba32f(const BlendState& b, const Rgba& k, const Rgba& src, float* values) {
  const Rgba dst = {values[0], values[1], values[2], values[3]};
  const Rgba out = blend(b, k, src, dst, false);
  for (int c = 0; c < 4; ++c)
    if (b.write_mask & (1u << c)) values[c] = out[c];
}

// One sample of the target's format after a fragment of colour `src`: RGBA8 `bytes` or
// RGBA32F `values` (the other null).
inline void write_sample(const BlendState& b, const Rgba& k, const Rgba& src, uint8_t* bytes,
                         float* values) {
  if (bytes != nullptr) {
    write_rgba8(b, k, src, bytes);
  } else {
    write_rgba32f(b, k, src, values);
  }
}

// The colour an antialiased point or line fragment, or any fragment of a draw whose blend
// state does more than store (BlendState::replaces() false), leaves in one sample: RGBA8
// `bytes` or RGBA32F `values` (the other null). With `antialiased`, the fragment's alpha is
// clamp(alpha, 0, 1) * min(coverage, 1) and, where the pipeline's state only stores, it is
// blended source-over (OpenGL's SRC_ALPHA, ONE_MINUS_SRC_ALPHA for colour, ONE,
// ONE_MINUS_SRC_ALPHA for alpha: what GL does for smooth points and lines under the usual blend
// function), colour channels unclamped before the blend. Returns
// false where neither applies: the colour is then stored as it is.
inline bool write_primitive_sample(const PipelineState& pipeline, Rgba color, float coverage,
                                   bool antialiased, uint8_t* bytes, float* values) {
  const BlendState& state = pipeline.blend[0];
  if (!antialiased && state.replaces()) return false;
  if (antialiased) {
    color[3] = std::clamp(color[3], 0.0f, 1.0f) * std::min(coverage, 1.0f);
  }
  if (!state.replaces()) {
    write_sample(state, pipeline.blend_constant, color, bytes, values);
    return true;
  }
  // Source-over with the colour as it is (the line kernel's runs blend the same way).
  const float a = color[3];
  Rgba dst;
  for (int c = 0; c < 4; ++c)
    dst[c] = bytes != nullptr ? bytes[c] / 255.0f : values[c];
  Rgba out;
  for (int c = 0; c < 3; ++c)
    out[c] = color[c] * a + dst[c] * (1.0f - a);
  out[3] = a + dst[3] * (1.0f - a);
  for (int c = 0; c < 4; ++c) {
    if (bytes != nullptr) {
      bytes[c] = to_unorm8(out[c]);
    } else {
      values[c] = out[c];
    }
  }
  return true;
}

}  // namespace tessera::blend
