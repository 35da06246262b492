// The block kernel, written once against Highway and compiled for every SIMD target through
// hwy/foreach_target.h (the Embree / Masked Occlusion Culling per-ISA pattern). Lanes are
// pixels of the 8x8 block in row-major order; each sample is a pass over the lanes with its own
// edge and depth offsets. Edge functions step exactly in int32 (bound in block_kernel.hpp).
#include <cstring>
#include <limits>

#include "engine/src/fast/block_kernel.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "binning/tile_grid.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

constexpr size_t kSamplePlane = binning::kTilePixels;  // values between two samples' planes

template <class D>
HWY_INLINE auto all_lanes(D d) {
  return hn::FirstN(d, hn::Lanes(d));
}

template <class D, class V>
HWY_INLINE auto depth_passes(D d, CompareOp op, V incoming, V stored) {
  switch (op) {
    case CompareOp::kNever: return hn::FirstN(d, 0);
    case CompareOp::kLess: return hn::Lt(incoming, stored);
    case CompareOp::kEqual: return hn::Eq(incoming, stored);
    case CompareOp::kLessEqual: return hn::Le(incoming, stored);
    case CompareOp::kGreater: return hn::Gt(incoming, stored);
    case CompareOp::kNotEqual: return hn::Ne(incoming, stored);
    case CompareOp::kGreaterEqual: return hn::Ge(incoming, stored);
    case CompareOp::kAlways: break;
  }
  return all_lanes(d);
}

// A plane's value at the lanes' pixel centres: at0 + gx * x + gy * y.
template <class DF, class VF>
HWY_INLINE VF plane_at(DF df, VF fx, VF fy, float at0, float gx, float gy) {
  return hn::Add(hn::Set(df, at0), hn::Add(hn::Mul(fx, hn::Set(df, gx)), hn::Mul(fy, hn::Set(df, gy))));
}

// Float colour to unorm8 exactly as to_unorm8 does: NaN and <= 0 give 0, >= 1 gives 255,
// otherwise truncate(c * 255 + 0.5) (multiply, then add: never fused, the build forbids
// contraction).
template <class DF, class VF>
HWY_INLINE auto to_unorm8(DF df, VF c) {
  const hn::RebindToUnsigned<DF> du;
  const auto scaled = hn::Add(hn::Mul(c, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
  auto u = hn::BitCast(du, hn::ConvertTo(hn::RebindToSigned<DF>(), scaled));
  u = hn::IfThenElseZero(hn::RebindMask(du, hn::Gt(c, hn::Zero(df))), u);
  return hn::IfThenElse(hn::RebindMask(du, hn::Ge(c, hn::Set(df, 1.0f))), hn::Set(du, 255u), u);
}

template <DepthMode kDepth, ColorMode kColor, bool kMulti>
void RasterBlock(const KernelConstants& k, const BlockJob& job, BlockStats& stats) {
  const hn::ScalableTag<int32_t> di;
  const hn::ScalableTag<uint32_t> du;
  const hn::ScalableTag<float> df;
  const size_t lanes = hn::Lanes(di);
  const uint32_t samples = kMulti ? k.samples : 1;
  constexpr bool kTestsDepth = kDepth == DepthMode::kTest || kDepth == DepthMode::kTestWrite;
  constexpr bool kWritesDepth = kDepth == DepthMode::kTestWrite || kDepth == DepthMode::kWrite;

  // Per-sample offsets of the edge functions and of depth.
  int32_t edge_offset[16][3];
  float z_offset[16];
  for (uint32_t s = 0; s < samples; ++s) {
    for (int e = 0; e < 3; ++e) {
      edge_offset[s][e] = kMulti ? job.a[e] * k.sample_x[s] + job.b[e] * k.sample_y[s] : 0;
    }
    z_offset[s] = kMulti ? job.z + job.z_dx * k.sample_fx[s] + job.z_dy * k.sample_fy[s] : job.z;
  }
  const bool clipped_block = job.cols < 8 || job.rows < 8;

  uint32_t covered = 0, passed = 0, shaded = 0;
  bool wrote = false;
  for (size_t i = 0; i < 64; i += lanes) {
    const auto pixel = hn::Iota(di, static_cast<int32_t>(i));
    const auto px = hn::And(pixel, hn::Set(di, 7));
    const auto py = hn::ShiftRight<3>(pixel);
    const auto fx = hn::ConvertTo(df, px);
    const auto fy = hn::ConvertTo(df, py);

    auto inside_fb = all_lanes(di);
    if (clipped_block) {
      inside_fb = hn::And(hn::Lt(px, hn::Set(di, static_cast<int32_t>(job.cols))),
                          hn::Lt(py, hn::Set(di, static_cast<int32_t>(job.rows))));
    }
    const auto e0 = hn::Add(hn::Add(hn::Set(di, job.e[0]), hn::Mul(px, hn::Set(di, job.step_x[0]))),
                            hn::Mul(py, hn::Set(di, job.step_y[0])));
    const auto e1 = hn::Add(hn::Add(hn::Set(di, job.e[1]), hn::Mul(px, hn::Set(di, job.step_x[1]))),
                            hn::Mul(py, hn::Set(di, job.step_y[1])));
    const auto e2 = hn::Add(hn::Add(hn::Set(di, job.e[2]), hn::Mul(px, hn::Set(di, job.step_x[2]))),
                            hn::Mul(py, hn::Set(di, job.step_y[2])));
    const auto coverage_bits =
        job.coverage ? hn::LoadU(du, job.coverage + i) : hn::Zero(du);

    auto pass_bits = hn::Zero(du);  // bit s: sample s passed
    for (uint32_t s = 0; s < samples; ++s) {
      auto cov = inside_fb;
      if (job.coverage) {
        cov = hn::And(cov, hn::RebindMask(di, hn::TestBit(coverage_bits, hn::Set(du, 1u << s))));
      } else {
        // Inside when E >= 0, i.e. E > -1 (integer lanes have no >= here).
        const auto minus_one = hn::Set(di, -1);
        if (job.edge_mask & 1) cov = hn::And(cov, hn::Gt(hn::Add(e0, hn::Set(di, edge_offset[s][0])), minus_one));
        if (job.edge_mask & 2) cov = hn::And(cov, hn::Gt(hn::Add(e1, hn::Set(di, edge_offset[s][1])), minus_one));
        if (job.edge_mask & 4) cov = hn::And(cov, hn::Gt(hn::Add(e2, hn::Set(di, edge_offset[s][2])), minus_one));
      }
      if (hn::AllFalse(di, cov)) continue;
      covered += static_cast<uint32_t>(hn::CountTrue(di, cov));
      auto pass = hn::RebindMask(df, cov);
      if constexpr (kDepth != DepthMode::kOff) {
        auto z = hn::Add(hn::Set(df, z_offset[s]),
                         hn::Add(hn::Mul(fx, hn::Set(df, job.z_dx)), hn::Mul(fy, hn::Set(df, job.z_dy))));
        z = hn::Min(hn::Max(z, hn::Zero(df)), hn::Set(df, 1.0f));
        float* plane = job.depth + s * kSamplePlane + i;
        if constexpr (kTestsDepth) {
          pass = hn::And(pass, depth_passes(df, k.compare, z, hn::LoadU(df, plane)));
        }
        if constexpr (kWritesDepth) {
          if (!hn::AllFalse(df, pass)) {
            hn::BlendedStore(z, pass, df, plane);
            wrote = true;
          }
        }
      }
      passed += static_cast<uint32_t>(hn::CountTrue(df, pass));
      pass_bits = hn::Or(pass_bits, hn::IfThenElseZero(hn::RebindMask(du, pass), hn::Set(du, 1u << s)));
    }

    if constexpr (kColor != ColorMode::kOff) {
      const auto any = hn::Ne(pass_bits, hn::Zero(du));
      if (hn::AllFalse(du, any)) continue;
      shaded += static_cast<uint32_t>(hn::CountTrue(du, any));
      auto r = plane_at(df, fx, fy, job.qa[0], job.qa_dx[0], job.qa_dy[0]);
      auto g = plane_at(df, fx, fy, job.qa[1], job.qa_dx[1], job.qa_dy[1]);
      auto b = plane_at(df, fx, fy, job.qa[2], job.qa_dx[2], job.qa_dy[2]);
      auto a = plane_at(df, fx, fy, job.qa[3], job.qa_dx[3], job.qa_dy[3]);
      if (k.perspective) {
        const auto q = plane_at(df, fx, fy, job.q, job.q_dx, job.q_dy);
        const auto inv_q = hn::Div(hn::Set(df, 1.0f), q);
        r = hn::Mul(r, inv_q);
        g = hn::Mul(g, inv_q);
        b = hn::Mul(b, inv_q);
        a = hn::Mul(a, inv_q);
        const auto bad = hn::AndNot(hn::Gt(q, hn::Zero(df)), hn::RebindMask(df, any));
        if (!hn::AllFalse(df, bad)) {
          // The pixel centre lies beyond the triangle's horizon (1/w <= 0 there): evaluate at
          // the pixel's first passing sample instead, which is inside the triangle.
          alignas(64) float rr[64], gg[64], bb[64], aa[64];
          alignas(64) uint32_t bits[64];
          hn::Store(r, df, rr);
          hn::Store(g, df, gg);
          hn::Store(b, df, bb);
          hn::Store(a, df, aa);
          hn::Store(pass_bits, du, bits);
          for (size_t l = 0; l < lanes; ++l) {
            const float lx = static_cast<float>((i + l) & 7), ly = static_cast<float>((i + l) >> 3);
            const float qc = job.q + job.q_dx * lx + job.q_dy * ly;
            if (bits[l] == 0 || qc > 0.0f) continue;
            uint32_t s = 0;
            while (!(bits[l] & (1u << s))) ++s;
            const float sx = lx + k.sample_fx[s], sy = ly + k.sample_fy[s];
            const float qs = job.q + job.q_dx * sx + job.q_dy * sy;
            float* out[4] = {&rr[l], &gg[l], &bb[l], &aa[l]};
            for (int c = 0; c < 4; ++c) *out[c] = (job.qa[c] + job.qa_dx[c] * sx + job.qa_dy[c] * sy) / qs;
          }
          r = hn::Load(df, rr);
          g = hn::Load(df, gg);
          b = hn::Load(df, bb);
          a = hn::Load(df, aa);
        }
      }
      if constexpr (kColor == ColorMode::kRGBA8) {
        const auto packed = hn::Or(
            hn::Or(to_unorm8(df, r), hn::ShiftLeft<8>(to_unorm8(df, g))),
            hn::Or(hn::ShiftLeft<16>(to_unorm8(df, b)), hn::ShiftLeft<24>(to_unorm8(df, a))));
        for (uint32_t s = 0; s < samples; ++s) {
          const auto m = hn::TestBit(pass_bits, hn::Set(du, 1u << s));
          uint32_t* dst = reinterpret_cast<uint32_t*>(job.rgba8) + s * kSamplePlane + i;
          hn::BlendedStore(packed, m, du, dst);
        }
      } else {
        for (uint32_t s = 0; s < samples; ++s) {
          const auto m = hn::RebindMask(df, hn::TestBit(pass_bits, hn::Set(du, 1u << s)));
          float* dst = job.rgba32f + (s * kSamplePlane + i) * 4;
          hn::Vec<decltype(df)> r0, g0, b0, a0;
          hn::LoadInterleaved4(df, dst, r0, g0, b0, a0);
          hn::StoreInterleaved4(hn::IfThenElse(m, r, r0), hn::IfThenElse(m, g, g0),
                                hn::IfThenElse(m, b, b0), hn::IfThenElse(m, a, a0), df, dst);
        }
      }
    }
  }

  stats.covered = covered;
  stats.passed = passed;
  stats.shaded = shaded;
  stats.depth_written = wrote;
  if (wrote) {
    // Hi-Z: the block's nearest and farthest depth over every sample after the writes.
    auto lo = hn::Set(df, std::numeric_limits<float>::infinity());
    auto hi = hn::Set(df, -std::numeric_limits<float>::infinity());
    for (uint32_t s = 0; s < samples; ++s) {
      for (size_t i = 0; i < 64; i += lanes) {
        const auto z = hn::LoadU(df, job.depth + s * kSamplePlane + i);
        lo = hn::Min(lo, z);
        hi = hn::Max(hi, z);
      }
    }
    stats.z_min = hn::GetLane(hn::MinOfLanes(df, lo));
    stats.z_max = hn::GetLane(hn::MaxOfLanes(df, hi));
  }
}

template <DepthMode kDepth, ColorMode kColor>
void fill_multi(KernelTable& t) {
  t.kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][0] = &RasterBlock<kDepth, kColor, false>;
  t.kernels[static_cast<int>(kDepth)][static_cast<int>(kColor)][1] = &RasterBlock<kDepth, kColor, true>;
}

template <DepthMode kDepth>
void fill_color(KernelTable& t) {
  fill_multi<kDepth, ColorMode::kOff>(t);
  fill_multi<kDepth, ColorMode::kRGBA8>(t);
  fill_multi<kDepth, ColorMode::kRGBA32F>(t);
}

}  // namespace

const KernelTable* GetKernelTable() {
  static const KernelTable table = [] {
    KernelTable t{};
    fill_color<DepthMode::kOff>(t);
    fill_color<DepthMode::kTest>(t);
    fill_color<DepthMode::kTestWrite>(t);
    fill_color<DepthMode::kWrite>(t);
    return t;
  }();
  return &table;
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "tessera/error.hpp"

namespace tessera::fast {

namespace {
struct TargetEntry {
  int64_t bit;
  const KernelTable* (*table)();
};
constexpr TargetEntry kTargets[] = {
#if HWY_TARGETS & HWY_AVX3_DL
    {HWY_AVX3_DL, &N_AVX3_DL::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_AVX3
    {HWY_AVX3, &N_AVX3::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_AVX2
    {HWY_AVX2, &N_AVX2::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_SSE4
    {HWY_SSE4, &N_SSE4::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_SSSE3
    {HWY_SSSE3, &N_SSSE3::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_SVE2
    {HWY_SVE2, &N_SVE2::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_SVE
    {HWY_SVE, &N_SVE::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_NEON
    {HWY_NEON, &N_NEON::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_EMU128
    {HWY_EMU128, &N_EMU128::GetKernelTable},
#endif
#if HWY_TARGETS & HWY_SCALAR
    {HWY_SCALAR, &N_SCALAR::GetKernelTable},
#endif
};
}  // namespace

const KernelTable& kernel_table(int64_t target) {
  for (const TargetEntry& entry : kTargets) {
    if (entry.bit == target) return *entry.table();
  }
  throw Error(ErrorCode::kInvalidArgument, "no block kernels compiled for SIMD target bit " +
                                               std::to_string(target));
}

}  // namespace tessera::fast
#endif  // HWY_ONCE
