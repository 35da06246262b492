// The fragment back end of user fragment shaders (FragmentShader::kUser) and of framebuffers
// with several colour targets in the fast engine, compiled for every SIMD target with the user
// shader's raster kernels (block_kernel_shader_user.cpp, after block_kernel-inl.h, which
// declares shade_user_block): the raster kernel finds a block's covered samples that pass the
// depth test and hands them here, and this forms the block's 2x2 quads, evaluates the
// triangle's planes into each fragment's varyings and each quad's derivatives, runs the shader
// on the batch (shade/user_batch.hpp), shades the built-in targets (shade/shade-inl.h, whose
// values are the same bits on every target), and writes the depth and the targets of the
// fragments it keeps. A varying is its plane at the pixel, base + (gx x + gy y), divided by the
// 1/w plane there when perspective-correct: the operations, in the order, of the built-in
// shaders.

#include <algorithm>
#include <bit>

#include "engine/src/blend/blend.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/shade/user_batch.hpp"
#include "engine/src/texture/sample_batch.hpp"

// Per-target include guard (see block_kernel-inl.h).
#if defined(TESSERA_ENGINE_SRC_FAST_USER_FRAGMENTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_FAST_USER_FRAGMENTS_INL_H_
#undef TESSERA_ENGINE_SRC_FAST_USER_FRAGMENTS_INL_H_
#else
#define TESSERA_ENGINE_SRC_FAST_USER_FRAGMENTS_INL_H_
#endif

#include <hwy/highway.h>

#include "engine/src/shade/shade-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

// A triangle's 1/w plane at pixel offset (x, y) from its plane origin (1 where it is flat).
struct QPlane {
  float q0, q_dx, q_dy;
  bool flat;
  float at(float x, float y) const { return flat ? 1.0f : q0 + (q_dx * x + q_dy * y); }
};

// The built-in output `target` of the batch's `count` fragments, evaluated at offsets (fx, fy)
// from the plane origin (beyond-horizon centres already moved to a sample), into the batch's
// buffers for target `index`.
void shade_target(const shade::TargetShading& target, uint32_t index, const shade::Targets& all,
                  const TriangleSetup& t, const float* planes, const float* fx, const float* fy,
                  uint32_t count, shade::UserBatch& batch) {
  float* rgba = batch.target_color(index);
  uint32_t* id = batch.target_id(index);
  constexpr uint32_t kStride = shade::UserBatch::kStride;
  if (target.output == TargetOutput::kPrimitiveId || target.output == TargetOutput::kObjectId) {
    for (uint32_t i = 0; i < count; ++i) {
      id[i] = target.output == TargetOutput::kObjectId ? all.object_id : batch.primitive(i);
      const float value = static_cast<float>(id[i]);
      rgba[i] = rgba[kStride + i] = rgba[2 * kStride + i] = value;
      rgba[3 * kStride + i] = 1.0f;
    }
    return;
  }
  const hn::ScalableTag<float> df;
  const size_t lanes = hn::Lanes(df);
  const shade::HWY_NAMESPACE::FragmentPlanes p{
      t.q0, t.q_dx, t.q_dy, t.flat_q != 0, planes + 3 * target.first, t.x0, t.y0};
  // The points are final: no lane moves to a sample (covered is empty).
  const auto none = [&](hn::Vec<decltype(df)>& ox, hn::Vec<decltype(df)>& oy) {
    ox = hn::Zero(df);
    oy = hn::Zero(df);
  };
  for (uint32_t i = 0; i < count; i += static_cast<uint32_t>(lanes)) {
    const auto x = hn::LoadU(df, fx + i), y = hn::LoadU(df, fy + i);
    auto r = hn::Zero(df), g = r, b = r, a = r;
    const auto covered = hn::FirstN(df, 0);
    switch (target.layout.shader) {
      case shade::Shader::kNormalized:
        shade::HWY_NAMESPACE::shade_fragments<shade::Shader::kNormalized>(
            df, target.layout, p, x, y, covered, none, r, g, b, a);
        break;
      case shade::Shader::kPhong:
        shade::HWY_NAMESPACE::shade_fragments<shade::Shader::kPhong>(df, target.layout, p, x, y,
                                                                     covered, none, r, g, b, a);
        break;
      default:
        shade::HWY_NAMESPACE::shade_fragments<shade::Shader::kInterpolated>(
            df, target.layout, p, x, y, covered, none, r, g, b, a);
        break;
    }
    hn::StoreU(r, df, rgba + i);
    hn::StoreU(g, df, rgba + kStride + i);
    hn::StoreU(b, df, rgba + 2 * kStride + i);
    hn::StoreU(a, df, rgba + 3 * kStride + i);
  }
  if (!target.textured) return;
  // The texel at the fragment's texture coordinates (the LOD from its quad's derivatives)
  // times the colour.
  alignas(64) float texel[4 * kStride];
  texture::sample_batch(
      HWY_TARGET, detail::TextureAccess::storage(*all.texture), all.sampler, all.lanes.get(),
      texture::coordinates_of(batch.view(), all.texcoord, all.texcoord + 1), texel);
  for (uint32_t c = 0; c < 4; ++c) {
    for (uint32_t i = 0; i < count; ++i)
      rgba[c * kStride + i] = texel[c * kStride + i] * rgba[c * kStride + i];
  }
}

}  // namespace

// Declared in block_kernel-inl.h.
void shade_user_block(const TileContext& tc, const TriangleSetup& t, const float* planes,
                      int32_t bx, int32_t by, size_t block, const uint32_t* mask, const float* z) {
  const shade::Layout& layout = *tc.layout;
  const shade::Targets& targets = *layout.targets;
  shade::UserBatch& batch = *tc.user_batch;
  const uint32_t varyings = layout.function_varyings;
  const uint32_t primitive = std::bit_cast<uint32_t>(planes[3 * (layout.count - 1)]);
  const QPlane qp{t.q0, t.flat_q ? 0.0f : t.q_dx, t.flat_q ? 0.0f : t.q_dy, t.flat_q};
  // Offsets of the block's first pixel centre from the plane origin (pixel (x0, y0)'s centre).
  const float ox = static_cast<float>(bx * 8 - t.x0), oy = static_cast<float>(by * 8 - t.y0);
  const auto value_at = [&](uint32_t j, float x, float y, float inv_q) {
    const float* plane = planes + 3 * j;
    const float v = plane[0] + (plane[1] * x + plane[2] * y);
    return layout.values[j].mode == VaryingMode::kPerspective ? v * inv_q : v;
  };

  // A block holds 16 quads of 4 pixels: one batch (UserBatch::kCapacity fragments).
  static_assert(shade::UserBatch::kCapacity >= 64);
  batch.clear();
  uint8_t pixel[64];  // each fragment's pixel in the block
  // Where each fragment's values are evaluated, for the built-in targets (kCapacity entries, so
  // that whole lane groups load).
  alignas(64) float fx[shade::UserBatch::kCapacity] = {};
  alignas(64) float fy[shade::UserBatch::kCapacity] = {};
  for (uint32_t qy = 0; qy < 4; ++qy) {
    for (uint32_t qx = 0; qx < 4; ++qx) {
      uint32_t masks[4];
      uint32_t index[4];
      int live = -1;  // the quad's first fragment with samples
      for (uint32_t k = 0; k < 4; ++k) {
        index[k] = (2 * qy + (k >> 1)) * 8 + 2 * qx + (k & 1);
        masks[k] = mask[index[k]];
        if (live < 0 && masks[k] != 0) live = static_cast<int>(k);
      }
      if (live < 0) continue;
      const uint32_t first =
          batch.add_quad(static_cast<uint32_t>(bx * 8) + 2 * qx,
                         static_cast<uint32_t>(by * 8) + 2 * qy, primitive, masks);
      // Where each fragment is evaluated: its pixel centre, or beyond the triangle's horizon
      // (1/w not positive) its first drawn sample; a helper there copies the live fragment.
      float px[4], py[4], q[4];
      bool copy[4] = {false, false, false, false};
      for (uint32_t k = 0; k < 4; ++k) {
        pixel[first + k] = static_cast<uint8_t>(index[k]);
        px[k] = static_cast<float>(2 * qx + (k & 1)) + ox;
        py[k] = static_cast<float>(2 * qy + (k >> 1)) + oy;
        q[k] = qp.at(px[k], py[k]);
        if (q[k] > 0.0f) continue;
        if (masks[k] == 0) {
          copy[k] = true;
          continue;
        }
        const uint32_t s = static_cast<uint32_t>(std::countr_zero(masks[k]));
        px[k] += tc.sample_fx[s];
        py[k] += tc.sample_fy[s];
        q[k] = qp.at(px[k], py[k]);
      }
      const uint32_t l = static_cast<uint32_t>(live);
      for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t from = copy[k] ? l : k;
        fx[first + k] = px[from];
        fy[first + k] = py[from];
        if (varyings == 0) continue;
        const float inv_q = 1.0f / q[from];
        for (uint32_t j = 0; j < varyings; ++j)
          batch.set_value(j, first + k, value_at(j, px[from], py[from], inv_q));
      }
      if (varyings == 0) continue;
      // Derivatives at the quad's centre, or where that lies beyond the horizon at the live
      // fragment's point: d(a / q)/dx = (a_x - (a / q) q_x) / q for a perspective-correct
      // value, the plane's gradient for an affine one, 0 for a flat one.
      float cx = static_cast<float>(2 * qx) + ox + 0.5f,
            cy = static_cast<float>(2 * qy) + oy + 0.5f;
      float qc = qp.at(cx, cy);
      if (!(qc > 0.0f)) {
        cx = px[l];
        cy = py[l];
        qc = q[l];
      }
      const float inv_qc = 1.0f / qc;
      for (uint32_t j = 0; j < varyings; ++j) {
        const float* plane = planes + 3 * j;
        switch (layout.values[j].mode) {
          case VaryingMode::kPerspective: {
            const float v = value_at(j, cx, cy, inv_qc);
            batch.set_derivatives(j, first, (plane[1] - v * qp.q_dx) * inv_qc,
                                  (plane[2] - v * qp.q_dy) * inv_qc);
            break;
          }
          case VaryingMode::kAffine:
            batch.set_derivatives(j, first, plane[1], plane[2]);
            break;
          default:
            batch.set_derivatives(j, first, 0.0f, 0.0f);
            break;
        }
      }
    }
  }
  if (batch.empty()) return;
  if (layout.function != nullptr) {
    batch.run(*layout.function);
  } else {
    batch.keep_all();
  }
  for (uint32_t k = 0; k < targets.count; ++k) {
    if (!targets.target[k].from_function) {
      shade_target(targets.target[k], k, targets, t, planes, fx, fy, batch.size(), batch);
    }
  }

  constexpr uint32_t kStride = shade::UserBatch::kStride;
  bool wrote = false;
  for (uint32_t f = 0; f < batch.size(); ++f) {
    const uint32_t m = batch.mask(f);
    if (m == 0 || batch.discarded(f)) continue;
    const size_t i = pixel[f];
    const auto colour_of = [&](uint32_t k, float(&rgba)[4]) {
      const float* c = batch.target_color(k);
      for (uint32_t ch = 0; ch < 4; ++ch)
        rgba[ch] = c[ch * kStride + f];
    };
    float colour[4];
    colour_of(0, colour);
    uint8_t packed[4];
    for (uint32_t c = 0; c < 4; ++c)
      packed[c] = to_unorm8(colour[c]);
    for (uint32_t bits = m; bits != 0; bits &= bits - 1) {
      const uint32_t s = static_cast<uint32_t>(std::countr_zero(bits));
      const size_t at = block * 64 + s * kSamplePlane + i;
      if (z != nullptr) {
        tc.depth[at] = z[s * 64 + i];
        wrote = true;
      }
      if (tc.blend != nullptr) {
        blend::write_sample(*tc.blend, tc.blend_constant,
                            {colour[0], colour[1], colour[2], colour[3]},
                            tc.rgba8 != nullptr ? tc.rgba8 + at * 4 : nullptr,
                            tc.rgba8 != nullptr ? nullptr : tc.rgba32f + at * 4);
      } else if (tc.rgba8 != nullptr) {
        std::copy_n(packed, 4, tc.rgba8 + at * 4);
      } else {
        std::copy_n(colour, 4, tc.rgba32f + at * 4);
      }
    }
    for (uint32_t k = 1; k < targets.count; ++k) {
      const ColorFormat format = targets.target[k].format;
      const uint32_t words = detail::words_per_sample(format);
      float rgba[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      if (format == ColorFormat::kR32F) {
        rgba[0] = batch.target_color(k)[f];
      } else if (format != ColorFormat::kR32UI) {
        colour_of(k, rgba);
      }
      const uint32_t id = format == ColorFormat::kR32UI ? batch.target_id(k)[f] : 0u;
      for (uint32_t bits = m; bits != 0; bits &= bits - 1) {
        const uint32_t s = static_cast<uint32_t>(std::countr_zero(bits));
        const size_t at = block * 64 + s * kSamplePlane + i;
        detail::store_target_value(format, tc.extra[k - 1] + at * words, rgba, id);
      }
    }
  }
  if (wrote) mark_hiz_dirty(tc, block);
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
