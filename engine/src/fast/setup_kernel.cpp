// Triangle setup vectorized across triangles (one triangle per double lane; the Masked
// Occlusion Culling approach), written once against Highway and compiled for every target.
// Every step is the scalar setup's (triangle_setup.cpp) in double precision and in the same
// order of operations: window coordinates are integers below 2^25 and products of two of them
// stay below 2^51, so snapping, areas and edge coefficients are exact in double lanes, and the
// planes round exactly as the scalar code does. The setups are therefore the same bits on
// every target. Triangles that a clip plane cuts leave the vector path for the scalar clipper.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "engine/src/fast/setup_kernel.hpp"

#include "engine/src/depth_bias.hpp"

// Arrays of vectors need sized vector types: targets with sizeless vectors are not compiled
// here and use the portable (EMU128/scalar) instance instead. The build's own exclusions
// (cmake/TesseraDependencies.cmake) still apply.
#ifndef TESSERA_HWY_DISABLED_TARGETS_EXPR
#define TESSERA_HWY_DISABLED_TARGETS_EXPR 0
#endif
#undef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS \
  (TESSERA_HWY_DISABLED_TARGETS_EXPR | HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/setup_kernel.cpp"
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/unorm8-inl.h"
#include "engine/src/finite_scan-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);

// One batch's vertices as given (positions, and colours with missing channels filled in),
// [vertex][lane]: copied whole from the draw, deinterleaved and widened by the vector code.
struct Batch {
  alignas(64) Float4 position[3][kMaxLanes];
  alignas(64) float color[3][kMaxLanes][4];  // r, g, b, a
};

// Results per lane, written by the vector code, and the records' bytes made from them.
struct Out {
  // Lane masks, bit l for lane l: a clip plane cuts the triangle (the scalar clipper sets it
  // up), it is kept (not culled), it is binned (kept and covering a sample), its record is a
  // pixel or sample record (SetupContext::pixel_records, sample_records; read for binned lanes
  // only).
  uint32_t clipped, kept, binned, pixel;
  alignas(64) double x0[kMaxLanes], y0[kMaxLanes], x1[kMaxLanes], y1[kMaxLanes];
  // The box's bin tiles (kept lanes; 0 in the others): x0, y0, x1, y1 in bits 0, 16, 32, 48.
  alignas(64) uint64_t tiles[kMaxLanes];
  alignas(64) double a[3][kMaxLanes], b[3][kMaxLanes], c[3][kMaxLanes];
  alignas(64) double narrow[kMaxLanes], small[kMaxLanes], flat_q[kMaxLanes], centres[kMaxLanes],
      sample_bits[kMaxLanes], unit_colour[kMaxLanes];
  // The pixel records' bytes, lane l's two 16-byte pieces at pixel_words[k][4 l]; the sample
  // records', its four at sample_words[k][4 l].
  alignas(64) uint32_t pixel_words[2][kMaxLanes * 4];
  alignas(64) uint32_t sample_words[4][kMaxLanes * 4];
  alignas(64) double z0[kMaxLanes], z_dx[kMaxLanes], z_dy[kMaxLanes], z_min[kMaxLanes],
      z_max[kMaxLanes];
  alignas(64) double q0[kMaxLanes], q_dx[kMaxLanes], q_dy[kMaxLanes];
  alignas(64) double qa0[4][kMaxLanes], qa_dx[4][kMaxLanes], qa_dy[4][kMaxLanes];
  // The records' bytes, converted and interleaved by PackLanes: lane l's 16-byte pieces at
  // wide[k][2 l] (TriangleSetup's first 32 bytes) and words[k][4 l] (the other 128).
  alignas(64) uint64_t wide[2][kMaxLanes * 2];
  alignas(64) uint32_t words[8][kMaxLanes * 4];
};

template <class D, class V>
HWY_INLINE V round_to_int(D d, V v) {
  // Ties to even for |v| < 2^51, as triangle_setup.cpp's round_to_int.
  const auto magic = hn::Set(d, 6755399441055744.0);
  return hn::Sub(hn::Add(v, magic), magic);
}

// An integer-valued double lane that fits int32, as int64 (exact). AVX-512 converts doubles to
// int64 in one instruction; x86 targets below it have no such instruction (Highway emulates it
// in about thirty), so they convert through int32 instead.
template <class D64, class V>
HWY_INLINE hn::Vec<D64> small_to_int64(D64 d64, V v) {
#if HWY_ARCH_X86 && HWY_TARGET > HWY_AVX3
  return hn::PromoteTo(d64, hn::DemoteTo(hn::Rebind<int32_t, D64>(), v));
#else
  return hn::ConvertTo(d64, v);
#endif
}

// a / b, correctly rounded (the bits of Div(a, b)), from r = 1 / b correctly rounded: with a
// fused multiply-add the quotient's residual a - q b is exact, and one correction step from a
// faithful q gives the rounded quotient (Markstein's theorem). A division takes far longer than
// the three operations (Intel: a 512-bit double division issues every 16 cycles), so the setup
// divides once per vertex (1 / w) instead of four times. Targets without a fused multiply-add
// divide.
template <class V>
HWY_INLINE V quotient(V a, V b, V r) {
#if HWY_NATIVE_FMA
  const V q = hn::Mul(a, r);
  return hn::MulAdd(hn::NegMulAdd(q, b, a), r, q);
#else
  (void)r;
  return hn::Div(a, b);
#endif
}

// A mask's lanes as bits (at most 32 lanes: kMaxLanes).
template <class D, class M>
HWY_INLINE uint32_t mask_bits(D d, M m) {
  uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, m, bytes);
  uint32_t bits;
  std::memcpy(&bits, bytes, sizeof(bits));
  return bits;
}

// A mask as 1.0 / 0.0 per lane, to store.
template <class D, class M>
HWY_INLINE hn::Vec<D> as_double_mask(D d, M m) {
  return hn::IfThenElseZero(m, hn::Set(d, 1.0));
}

// TriangleSetup's bytes for the lanes from l0, from the fields Out holds for them (stored just
// before, in cache): each value converted as the scalar packing did (static_cast to int32,
// int64, float or bool: the same bits) and interleaved lane by lane into 16-byte pieces in
// the record's order (triangle_setup.hpp), so a record is ten 16-byte copies.
template <class D>
HWY_INLINE void PackLanes(D d, size_t l0, Out& out) {
  const hn::RebindToSigned<D> d64;
  const hn::RebindToUnsigned<D> du64;
  const hn::Rebind<int32_t, D> di;
  const hn::Rebind<uint32_t, D> du;
  const hn::Rebind<float, D> df;
  const auto load = [&](const double* p) { return hn::Load(d, p + l0); };
  const auto i64 = [&](const double* p) { return hn::BitCast(du64, hn::ConvertTo(d64, load(p))); };
  const auto i32 = [&](const double* p) { return hn::BitCast(du, hn::DemoteTo(di, load(p))); };
  const auto f32 = [&](const double* p) { return hn::BitCast(du, hn::DemoteTo(df, load(p))); };
  hn::StoreInterleaved2(i64(out.c[0]), i64(out.c[1]), du64, out.wide[0] + 2 * l0);
  hn::StoreInterleaved2(i64(out.c[2]), hn::BitCast(du64, load(out.z0)), du64, out.wide[1] + 2 * l0);
  // narrow, small and flat_q as bools (1 where non-zero) and centres, one byte each.
  const auto flag = [&](const double* p, int shift) {
    return hn::IfThenElseZero(hn::RebindMask(du, hn::Ne(hn::DemoteTo(df, load(p)), hn::Zero(df))),
                              hn::Set(du, 1u << shift));
  };
  const auto flags = hn::Or(hn::Or(flag(out.narrow, 0), flag(out.small, 8)),
                            hn::Or(flag(out.flat_q, 16), hn::ShiftLeft<24>(i32(out.centres))));
  const auto put = [&](int k, auto v0, auto v1, auto v2, auto v3) {
    hn::StoreInterleaved4(v0, v1, v2, v3, du, out.words[k] + 4 * l0);
  };
  put(0, i32(out.a[0]), i32(out.a[1]), i32(out.a[2]), i32(out.b[0]));
  put(1, i32(out.b[1]), i32(out.b[2]), i32(out.x0), i32(out.y0));
  put(2, i32(out.x1), i32(out.y1), flags, f32(out.z_dx));
  put(3, f32(out.z_dy), f32(out.z_min), f32(out.z_max), f32(out.q0));
  put(4, f32(out.q_dx), f32(out.q_dy), f32(out.qa0[0]), f32(out.qa0[1]));
  // The colour gradients as float bits, and the largest magnitude's (as int32, the magnitudes'
  // bits order as the values: finite floats), G: unit_colour holds only where G times the box's
  // reach is at most kUnitColourReach (TriangleSetup::unit_colour).
  hn::Vec<decltype(du)> qa_dx[4], qa_dy[4];
  auto gradient = hn::Zero(di);
  const auto magnitude = [&](hn::Vec<decltype(du)> v) {
    return hn::BitCast(di, hn::And(v, hn::Set(du, 0x7FFFFFFFu)));
  };
  for (int c = 0; c < 4; ++c) {
    qa_dx[c] = f32(out.qa_dx[c]);
    qa_dy[c] = f32(out.qa_dy[c]);
    gradient = hn::Max(gradient, hn::Max(magnitude(qa_dx[c]), magnitude(qa_dy[c])));
  }
  const auto reach = hn::DemoteTo(
      df, hn::Add(hn::Add(hn::Sub(load(out.x1), load(out.x0)), hn::Sub(load(out.y1), load(out.y0))),
                  hn::Set(d, 15.0)));
  const auto within =
      hn::Le(hn::Mul(hn::BitCast(df, gradient), reach), hn::Set(df, kUnitColourReach));
  const auto unit = hn::IfThenElseZero(hn::RebindMask(du, within), flag(out.unit_colour, 0));
  put(5, f32(out.qa0[2]), f32(out.qa0[3]), qa_dx[0], qa_dx[1]);
  put(6, qa_dx[2], qa_dx[3], qa_dy[0], qa_dy[1]);
  put(7, qa_dy[2], qa_dy[3], i32(out.sample_bits), unit);
}

// The first word of a record for the lanes from l0 (`origin`: the box's first pixel, x0 | y0 << 16)
// and its shape byte: the count of pixels `first` holds (a first_pixels_table entry), then
// the box's width and height less one, two bits each from bit kCountBits.
template <int kCountBits, class D, class VI, class VU>
HWY_INLINE VU RecordShape(D d, size_t l0, VI first, const Out& out, VU& origin) {
  const hn::Rebind<int32_t, D> di;
  const hn::Rebind<uint32_t, D> du;
  const auto load = [&](const double* p) { return hn::Load(d, p + l0); };
  const auto i32 = [&](hn::Vec<D> v) { return hn::BitCast(du, hn::DemoteTo(di, v)); };
  const auto x0 = load(out.x0), y0 = load(out.y0);
  origin = hn::Or(i32(x0), hn::ShiftLeft<16>(i32(y0)));
  const auto count = hn::BitCast(du, hn::ShiftRight<24>(first));
  return hn::Or(count, hn::Or(hn::ShiftLeft<kCountBits>(i32(hn::Sub(load(out.x1), x0))),
                              hn::ShiftLeft<kCountBits + 2>(i32(hn::Sub(load(out.y1), y0)))));
}

// The values of the record pixels of the lanes from l0, whose pixels `first` holds as a
// first_pixels_table entry (pixel_record.hpp: the places of the first kSlots ones, kBits bits
// each, and their count): each pixel's depth and colour from the planes Out holds, as the
// kernels' per-pixel path forms them (centre_depth and pixel_colour in pixel_record.hpp) with
// the same operations in the same order in float lanes, so the same bits, and converted to
// unorm8 as the kernels' lanes do (unorm8-inl.h: for finite values the same bytes as
// pack_rgba8). For each slot some lane uses, slot(i, place, z_base, z, rgba8) gets the
// pixels' places in the box, the depth plane at their block's first pixel, the depth at their
// centre (clamped) and the packed colour. Returns the lanes with a used pixel whose centre is
// beyond the horizon (q <= 0), where the colour is v / q at the centre.
template <uint32_t kSlots, int kBits, class D, class VI, class Slot>
HWY_INLINE auto RecordValues(D d, size_t l0, VI first, const Out& out, const Slot& slot) {
  using V = hn::Vec<D>;
  const hn::Rebind<float, D> df;
  const hn::Rebind<int32_t, D> di;
  const auto count = hn::ShiftRight<24>(first);
  const auto load = [&](const double* p) { return hn::Load(d, p + l0); };
  const auto f32 = [&](const double* p) { return hn::DemoteTo(df, load(p)); };
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const auto flat_f = hn::Ne(f32(out.flat_q), zero);
  const bool all_flat = hn::AllTrue(df, flat_f);
  const auto z_dx = f32(out.z_dx), z_dy = f32(out.z_dy);
  const V z0 = load(out.z0), z_dx_d = hn::PromoteTo(d, z_dx), z_dy_d = hn::PromoteTo(d, z_dy);
  const auto q0 = f32(out.q0), q_dx = f32(out.q_dx), q_dy = f32(out.q_dy);
  hn::Vec<decltype(df)> qa0[4], qa_dx[4], qa_dy[4];
  for (int c = 0; c < 4; ++c) {
    qa0[c] = f32(out.qa0[c]);
    qa_dx[c] = f32(out.qa_dx[c]);
    qa_dy[c] = f32(out.qa_dy[c]);
  }
  const V x0 = load(out.x0), y0 = load(out.y0);
  const auto x0i = hn::DemoteTo(di, x0), y0i = hn::DemoteTo(di, y0);
  auto any_beyond_lanes = hn::FirstN(df, 0);
  for (uint32_t i = 0; i < kSlots; ++i) {
    // Most tiny triangles cover one or two pixels: the slots no lane uses are skipped.
    const auto used = hn::Gt(count, hn::Set(di, static_cast<int32_t>(i)));
    if (hn::AllFalse(di, used)) break;
    // PixelOffsets: fx, fy from the pixel's block; dx, dy from the block to the box's first pixel.
    const auto place =
        hn::And(hn::ShiftRightSame(first, static_cast<int>(kBits * i)), hn::Set(di, 15));
    const auto bxi = hn::And(place, hn::Set(di, 3)), byi = hn::ShiftRight<2>(place);
    const auto xi = hn::Add(x0i, bxi), yi = hn::Add(y0i, byi);
    const auto fxi = hn::And(xi, hn::Set(di, 7)), fyi = hn::And(yi, hn::Set(di, 7));
    const V dx = hn::Sub(hn::PromoteTo(d, hn::Sub(xi, fxi)), x0);
    const V dy = hn::Sub(hn::PromoteTo(d, hn::Sub(yi, fyi)), y0);
    const auto fx = hn::ConvertTo(df, fxi), fy = hn::ConvertTo(df, fyi);
    // centre_depth.
    const auto z_base =
        hn::DemoteTo(df, hn::Add(hn::Add(z0, hn::Mul(z_dx_d, dx)), hn::Mul(z_dy_d, dy)));
    const auto z = hn::Add(z_base, hn::Add(hn::Mul(fx, z_dx), hn::Mul(fy, z_dy)));
    const auto z_clamped =
        hn::IfThenElse(hn::Gt(z, zero), hn::IfThenElse(hn::Lt(z, one), z, one), zero);
    // pixel_colour at the centre (no sample offset).
    const auto fdx = hn::DemoteTo(df, dx), fdy = hn::DemoteTo(df, dy);
    // Where q is not flat, colour = v / q: v * (1 / q) where q > 0. Beyond the horizon
    // (q <= 0) the first sample is the centre: v / q. That is rare (only float rounding puts a
    // covered centre there), so divided only when some used lane needs it. Draws with w = 1
    // everywhere have no q to evaluate.
    auto q = one, inv_q = one;
    auto beyond = hn::FirstN(df, 0);
    bool any_beyond = false;
    if (!all_flat) {
      const auto q_base = hn::Add(q0, hn::Add(hn::Mul(q_dx, fdx), hn::Mul(q_dy, fdy)));
      q = hn::Add(q_base, hn::Add(hn::Mul(fx, q_dx), hn::Mul(fy, q_dy)));
      inv_q = hn::Div(one, q);
      beyond = hn::AndNot(hn::Or(flat_f, hn::Gt(q, zero)), hn::RebindMask(df, used));
      any_beyond = !hn::AllFalse(df, beyond);
      any_beyond_lanes = hn::Or(any_beyond_lanes, beyond);
    }
    hn::Vec<decltype(df)> channel[4];
    for (int c = 0; c < 4; ++c) {
      const auto qa_base = hn::Add(qa0[c], hn::Add(hn::Mul(qa_dx[c], fdx), hn::Mul(qa_dy[c], fdy)));
      const auto v = hn::Add(qa_base, hn::Add(hn::Mul(fx, qa_dx[c]), hn::Mul(fy, qa_dy[c])));
      channel[c] = all_flat ? v : hn::IfThenElse(flat_f, v, hn::Mul(v, inv_q));
      if (any_beyond) channel[c] = hn::IfThenElse(beyond, hn::Div(v, q), channel[c]);
    }
    slot(i, place, z_base, z_clamped,
         pack_unorm8(df, channel[0], channel[1], channel[2], channel[3]));
  }
  return any_beyond_lanes;
}

// The pixel records of the lanes from l0, whose covered pixels `first` holds as a
// kFirstPixels entry (lanes with 1 to kPixelRecordPixels become records): RecordValues'
// depth and colour, then PixelRecord's bytes in Out::pixel_words. Slots no lane fills are zero.
template <class D, class VI>
HWY_INLINE void PixelValues(D d, size_t l0, VI first, Out& out) {
  const hn::Rebind<int32_t, D> di;
  const hn::Rebind<uint32_t, D> du;
  hn::Vec<decltype(du)> z_bits[kPixelRecordPixels], rgba8[kPixelRecordPixels];
  for (uint32_t i = 0; i < kPixelRecordPixels; ++i) {
    z_bits[i] = hn::Zero(du);
    rgba8[i] = hn::Zero(du);
  }
  RecordValues<kPixelRecordPixels, 8>(d, l0, first, out,
                                      [&](uint32_t i, auto, auto, auto z, auto packed) {
                                        z_bits[i] = hn::BitCast(du, z);
                                        rgba8[i] = packed;
                                      });
  auto origin = hn::Zero(du);
  const auto shape = RecordShape<2>(d, l0, first, out, origin);
  const auto offsets = hn::BitCast(du, hn::And(first, hn::Set(di, 0xFFFFFF)));
  static_assert(kPixelRecordPixels == 3);
  hn::StoreInterleaved4(origin, hn::Or(shape, hn::ShiftLeft<8>(offsets)), z_bits[0], z_bits[1], du,
                        out.pixel_words[0] + 4 * l0);
  hn::StoreInterleaved4(z_bits[2], rgba8[0], rgba8[1], rgba8[2], du, out.pixel_words[1] + 4 * l0);
}

// The sample records of the lanes from l0 (two or four samples), whose pixels with a covered
// sample `first` holds as a kFirstSamplePixels entry and whose covered samples `low` and `high`
// hold as bits 0-31 and 32-63 of bit (py * 3 + px) * samples + s: SampleRecord's bytes in
// Out::sample_words. Returns the lanes
// that cannot be sample records: a pixel's centre beyond the horizon, where the colour depends
// on which sample passes first.
template <class D, class VI, class VU>
HWY_INLINE auto SampleValues(D d, size_t l0, VI first, VU low, VU high, uint32_t samples,
                             Out& out) {
  const hn::Rebind<int32_t, D> di;
  const hn::Rebind<uint32_t, D> du;
  const hn::Rebind<float, D> df;
  hn::Vec<decltype(du)> z_base_bits[kSampleRecordPixels], rgba8[kSampleRecordPixels];
  for (uint32_t i = 0; i < kSampleRecordPixels; ++i) {
    z_base_bits[i] = hn::Zero(du);
    rgba8[i] = hn::Zero(du);
  }
  auto coverage = hn::Zero(du);
  const auto pixel_samples = hn::Set(du, (1u << samples) - 1);
  const auto beyond = RecordValues<kSampleRecordPixels, 4>(
      d, l0, first, out, [&](uint32_t i, auto place, auto z_base, auto, auto packed) {
        // The pixel's samples: bits from (y * 3 + x) * samples of low, or of high past 31.
        const auto pixel = hn::Add(hn::Mul(hn::ShiftRight<2>(place), hn::Set(di, 3)),
                                   hn::And(place, hn::Set(di, 3)));
        const auto bit = hn::Mul(pixel, hn::Set(di, static_cast<int32_t>(samples)));
        const auto past = hn::Gt(bit, hn::Set(di, 31));
        const auto shift =
            hn::BitCast(du, hn::IfThenElse(past, hn::Sub(bit, hn::Set(di, 32)), bit));
        const auto cov =
            hn::And(hn::IfThenElse(hn::RebindMask(du, past), high, low) >> shift, pixel_samples);
        coverage = hn::Or(coverage, hn::ShiftLeftSame(cov, static_cast<int>(4 * i)));
        z_base_bits[i] = hn::BitCast(du, z_base);
        rgba8[i] = packed;
      });
  auto origin = hn::Zero(du);
  const auto shape = RecordShape<3>(d, l0, first, out, origin);
  const auto places = hn::BitCast(du, hn::And(first, hn::Set(di, 0xFFFFF)));
  const auto load = [&](const double* p) { return hn::Load(d, p + l0); };
  const auto z_dx = hn::BitCast(du, hn::DemoteTo(df, load(out.z_dx)));
  const auto z_dy = hn::BitCast(du, hn::DemoteTo(df, load(out.z_dy)));
  static_assert(kSampleRecordPixels == 5);
  hn::StoreInterleaved4(origin, hn::Or(shape, hn::ShiftLeft<8>(places)), coverage, z_dx, du,
                        out.sample_words[0] + 4 * l0);
  hn::StoreInterleaved4(z_dy, z_base_bits[0], z_base_bits[1], z_base_bits[2], du,
                        out.sample_words[1] + 4 * l0);
  hn::StoreInterleaved4(z_base_bits[3], z_base_bits[4], rgba8[0], rgba8[1], du,
                        out.sample_words[2] + 4 * l0);
  hn::StoreInterleaved4(rgba8[2], rgba8[3], rgba8[4], hn::Zero(du), du,
                        out.sample_words[3] + 4 * l0);
  // As lanes of D.
  const auto beyond_i = hn::VecFromMask(di, hn::RebindMask(di, beyond));
  return hn::Lt(hn::PromoteTo(d, beyond_i), hn::Zero(d));
}

// table[mask] for each lane's mask (a double lane holding an index of the table). When every
// mask is 0 (no lane has a record pixel: most vectors of `small`), table[0] in every lane,
// without the gather.
template <class D, class DI, size_t kEntries>
HWY_INLINE hn::Vec<DI> table_entries(D d, DI di, const std::array<uint32_t, kEntries>& table,
                                     hn::Vec<D> mask) {
  if (hn::AllFalse(d, hn::Gt(mask, hn::Zero(d)))) {
    return hn::Set(di, static_cast<int32_t>(table[0]));
  }
  return hn::GatherIndex(di, reinterpret_cast<const int32_t*>(table.data()),
                         hn::DemoteTo(di, mask));
}

// The context's values that the lanes compare with or scale by, as doubles: formed once for a
// range of triangles rather than for each vector (each takes a conversion, a shift or a
// division), so that a vector broadcasts them from memory.
struct LaneConstants {
  explicit LaneConstants(const SetupContext& ctx) {
    const int bits = static_cast<int>(ctx.subpixel_bits), shift = bits - 4;
    const auto reach = [&](int32_t offset) {  // a sample offset (1/16 px) from the pixel corner
      return static_cast<double>(int64_t{8 + offset} << shift);
    };
    scale = static_cast<double>(1u << bits);
    inv_scale = 1.0 / scale;
    half_width = 0.5 * ctx.width;
    half_height = 0.5 * ctx.height;
    width_limit = ctx.width * scale;
    height_limit = ctx.height * scale;
    last_x = ctx.width - 1.0;
    last_y = ctx.height - 1.0;
    reach_x_hi = reach(ctx.sample_dx_hi);
    reach_y_hi = reach(ctx.sample_dy_hi);
    reach_x_lo = reach(ctx.sample_dx_lo);
    reach_y_lo = reach(ctx.sample_dy_lo);
    centre_unit = static_cast<double>(1u << shift);
    narrow_limit = static_cast<double>(narrow_edge_limit(ctx.subpixel_bits));
    small_limit = 32.0 * scale;
  }
  double scale, inv_scale;           // 2^bits and its inverse
  double half_width, half_height;    // the viewport transform's factors
  double width_limit, height_limit;  // the screen's size in subpixels
  double last_x, last_y;             // the last pixel column and row
  double reach_x_hi, reach_y_hi;     // the samples' extremes from the pixel corner,
  double reach_x_lo, reach_y_lo;     // in subpixels
  double centre_unit;                // 1/16 px in subpixels
  double narrow_limit, small_limit;  // TriangleSetup::narrow's and small's bounds
};

// One vector of lanes from l0, whose vertices' positions `pos` holds as x, y, z, w vectors.
// kUnitW: every vertex has w = 1 (orthographic and 2D draws), so the divisions by w are
// skipped: x / 1 is x exactly, and the results are the same bits.
template <bool kUnitW, class VF>
HWY_INLINE void SetupLaneGroup(const SetupContext& ctx, const LaneConstants& lc,
                               const VF (&pos)[3][4], const VF (&color)[3][4], size_t l0,
                               Out& out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const PipelineState& p = *ctx.pipeline;
  const bool gl_depth = p.clip_depth == ClipDepth::kNegativeOneToOne;
  const int bits = static_cast<int>(ctx.subpixel_bits);
  const int shift = bits - 4;
  const double scale = lc.scale;
  const auto zero = hn::Zero(d);
  V X[3], Y[3], Z[3], IW[3];
  V nearest = zero;  // the least clip distance over the vertices
  for (int k = 0; k < 3; ++k) {
    const VF &px = pos[k][0], &py = pos[k][1], &pz = pos[k][2], &pw = pos[k][3];
    const V x = hn::PromoteTo(d, px), y = hn::PromoteTo(d, py), w = hn::PromoteTo(d, pw);
    // OpenGL's -w <= z <= w becomes 0 <= z <= w: z' = (z + w) / 2 (as setup_triangle).
    const V z = gl_depth ? hn::Mul(hn::Set(d, 0.5), hn::Add(hn::PromoteTo(d, pz), w))
                         : hn::PromoteTo(d, pz);
    // The clip distances of clip.cpp, term for term, and their least: inside every plane where
    // it is not negative (the values are finite, so no distance is NaN). gx - |x| is the lesser
    // of x + gx and -x + gx, with the same bits.
    const V gx = hn::Mul(hn::Set(d, ctx.guard_band.x), w);
    const V gy = hn::Mul(hn::Set(d, ctx.guard_band.y), w);
    const V depth = hn::Min(hn::Min(z, hn::Sub(w, z)), hn::Add(w, hn::Set(d, -kMinClipW)));
    const V least = hn::Min(depth, hn::Min(hn::Sub(gx, hn::Abs(x)), hn::Sub(gy, hn::Abs(y))));
    nearest = k == 0 ? least : hn::Min(nearest, least);
    // window x = (x / w + 1) * width / 2, window y = (1 - y / w) * height / 2, snapped.
    IW[k] = kUnitW ? hn::Set(d, 1.0) : hn::Div(hn::Set(d, 1.0), w);
    const V x_w = kUnitW ? x : quotient(x, w, IW[k]), y_w = kUnitW ? y : quotient(y, w, IW[k]);
    const V wx = hn::Mul(hn::Add(x_w, hn::Set(d, 1.0)), hn::Set(d, lc.half_width));
    const V wy = hn::Mul(hn::Sub(hn::Set(d, 1.0), y_w), hn::Set(d, lc.half_height));
    X[k] = round_to_int(d, hn::Mul(wx, hn::Set(d, scale)));
    Y[k] = round_to_int(d, hn::Mul(wy, hn::Set(d, scale)));
    Z[k] = kUnitW ? z : quotient(z, w, IW[k]);
  }
  const auto inside = hn::Ge(nearest, zero);
  // Lanes outside a plane go to the scalar clipper. Their values here may be NaN or infinite (a
  // vertex at w = 0, or one that is not finite where such vertices are culled): they are made
  // zero, so that no conversion to integers below (undefined for NaN on the scalar target)
  // sees them, and the lanes are neither kept nor binned (zero area).
  for (int k = 0; k < 3; ++k) {
    X[k] = hn::IfThenElseZero(inside, X[k]);
    Y[k] = hn::IfThenElseZero(inside, Y[k]);
    Z[k] = hn::IfThenElseZero(inside, Z[k]);
    IW[k] = hn::IfThenElseZero(inside, IW[k]);
  }
  V area = hn::Sub(hn::Mul(hn::Sub(X[1], X[0]), hn::Sub(Y[2], Y[0])),
                   hn::Mul(hn::Sub(Y[1], Y[0]), hn::Sub(X[2], X[0])));
  // y points down in window space: counter-clockwise in NDC means negative area here.
  const auto ccw = hn::Lt(area, zero);
  const bool ccw_front = p.front_face == FrontFace::kCounterClockwise;
  auto keep = hn::And(inside, hn::Ne(area, zero));
  if (p.cull == CullMode::kBack) keep = ccw_front ? hn::And(keep, ccw) : hn::AndNot(ccw, keep);
  if (p.cull == CullMode::kFront) keep = ccw_front ? hn::AndNot(ccw, keep) : hn::And(keep, ccw);
  // Orient clockwise on screen: swap vertices 1 and 2 where the area is negative.
  V C[3][4];
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 4; ++c)
      C[k][c] = hn::PromoteTo(d, color[k][c]);
  }
  {
    const V x1 = X[1], y1 = Y[1], z1 = Z[1], w1 = IW[1];
    X[1] = hn::IfThenElse(ccw, X[2], X[1]);
    X[2] = hn::IfThenElse(ccw, x1, X[2]);
    Y[1] = hn::IfThenElse(ccw, Y[2], Y[1]);
    Y[2] = hn::IfThenElse(ccw, y1, Y[2]);
    Z[1] = hn::IfThenElse(ccw, Z[2], Z[1]);
    Z[2] = hn::IfThenElse(ccw, z1, Z[2]);
    IW[1] = hn::IfThenElse(ccw, IW[2], IW[1]);
    IW[2] = hn::IfThenElse(ccw, w1, IW[2]);
    for (int c = 0; c < 4; ++c) {
      const V c1 = C[1][c];
      C[1][c] = hn::IfThenElse(ccw, C[2][c], C[1][c]);
      C[2][c] = hn::IfThenElse(ccw, c1, C[2][c]);
    }
    area = hn::Abs(area);
  }
  // On screen (culled if not), then the pixels with a sample inside the vertices' bounding
  // box, clamped to the screen (as triangle_setup.cpp; scaling by 2^-bits is exact).
  const V lo_x = hn::Min(hn::Min(X[0], X[1]), X[2]), hi_x = hn::Max(hn::Max(X[0], X[1]), X[2]);
  const V lo_y = hn::Min(hn::Min(Y[0], Y[1]), Y[2]), hi_y = hn::Max(hn::Max(Y[0], Y[1]), Y[2]);
  keep = hn::And(keep, hn::And(hn::And(hn::Ge(hi_x, zero), hn::Ge(hi_y, zero)),
                               hn::And(hn::Lt(lo_x, hn::Set(d, lc.width_limit)),
                                       hn::Lt(lo_y, hn::Set(d, lc.height_limit)))));
  const V inv_scale = hn::Set(d, lc.inv_scale);
  const V bx0 =
      hn::Max(hn::Ceil(hn::Mul(hn::Sub(lo_x, hn::Set(d, lc.reach_x_hi)), inv_scale)), zero);
  const V by0 =
      hn::Max(hn::Ceil(hn::Mul(hn::Sub(lo_y, hn::Set(d, lc.reach_y_hi)), inv_scale)), zero);
  const V bx1 = hn::Min(hn::Floor(hn::Mul(hn::Sub(hi_x, hn::Set(d, lc.reach_x_lo)), inv_scale)),
                        hn::Set(d, lc.last_x));
  const V by1 = hn::Min(hn::Floor(hn::Mul(hn::Sub(hi_y, hn::Set(d, lc.reach_y_lo)), inv_scale)),
                        hn::Set(d, lc.last_y));
  auto any_sample = hn::And(hn::Le(bx0, bx1), hn::Le(by0, by1));
  out.clipped |= mask_bits(d, hn::Not(inside)) << l0;
  out.kept |= mask_bits(d, keep) << l0;
  hn::Store(bx0, d, out.x0 + l0);
  hn::Store(by0, d, out.y0 + l0);
  hn::Store(bx1, d, out.x1 + l0);
  hn::Store(by1, d, out.y1 + l0);
  {
    const hn::RebindToSigned<decltype(d)> dt;
    const int log2 = static_cast<int>(ctx.bin_tile_log2);
    const auto tile_of = [&](V v) {
      return hn::ShiftRightSame(small_to_int64(dt, hn::IfThenElseZero(keep, v)), log2);
    };
    const auto tiles =
        hn::Or(hn::Or(tile_of(bx0), hn::ShiftLeft<16>(tile_of(by0))),
               hn::Or(hn::ShiftLeft<32>(tile_of(bx1)), hn::ShiftLeft<48>(tile_of(by1))));
    hn::Store(hn::BitCast(hn::RebindToUnsigned<decltype(d)>(), tiles),
              hn::RebindToUnsigned<decltype(d)>(), out.tiles + l0);
  }

  // Edges and barycentric planes (see triangle_setup.cpp).
  const V cx =
      hn::Mul(hn::Add(hn::Mul(bx0, hn::Set(d, 16.0)), hn::Set(d, 8.0)), hn::Set(d, lc.centre_unit));
  const V cy =
      hn::Mul(hn::Add(hn::Mul(by0, hn::Set(d, 16.0)), hn::Set(d, 8.0)), hn::Set(d, lc.centre_unit));
  const V inv_area = hn::Div(hn::Set(d, 1.0), area);
  const V per_pixel = hn::Mul(hn::Set(d, scale), inv_area);
  V weight0[3], wdx[3], wdy[3];
  V max_step = zero, max_delta = zero;
  // One sample per pixel and a bounding box of at most 2x2 pixels: whether a pixel centre
  // of the box is inside, from the edge functions there (exact in double: below 2^51).
  // Two or four samples and a box of at most 3x3 pixels (TriangleSetup::sample_bits): which
  // samples are inside, from the same values plus each sample's offset. If none is, the
  // triangle covers nothing and is not binned.
  // (Pixel records take the small boxes' centres from the 3x3 test below; the few setups of
  // such boxes left are tested by the kernel.)
  const bool centre_only = ctx.centre_sample_only() && !ctx.pixel_records;
  // The samples of boxes up to 3x3: sample_bits, or at one sample the centres for pixel records.
  const bool sample_bits = ctx.small_sample_bits() || ctx.pixel_records;
  const V box_dx = hn::Min(hn::Sub(bx1, bx0), hn::Set(d, 1.0));  // 0 or 1 in a small box
  const V box_dy = hn::Min(hn::Sub(by1, by0), hn::Set(d, 1.0));
  auto in00 = hn::Eq(zero, zero), in10 = in00, in01 = in00, in11 = in00;
  V edge_at[3], edge_dx[3], edge_dy[3];  // sample_bits: at the first pixel centre, the deltas
  for (int k = 0; k < 3; ++k) {
    const int from = (k + 1) % 3, to = (k + 2) % 3;
    const V dx = hn::Sub(X[to], X[from]), dy = hn::Sub(Y[to], Y[from]);
    const auto top_left = hn::Or(hn::Lt(dy, zero), hn::And(hn::Eq(dy, zero), hn::Gt(dx, zero)));
    const V bias = hn::IfThenElseZero(hn::Not(top_left), hn::Set(d, 1.0));
    hn::Store(hn::Neg(dy), d, out.a[k] + l0);
    hn::Store(dx, d, out.b[k] + l0);
    const V c = hn::Sub(hn::Sub(hn::Mul(dy, X[from]), hn::Mul(dx, Y[from])), bias);
    hn::Store(c, d, out.c[k] + l0);
    if (centre_only || sample_bits) {
      const V e00 = hn::Add(hn::Sub(c, hn::Mul(dy, cx)), hn::Mul(dx, cy));
      if (centre_only) {
        const V e10 = hn::Sub(e00, hn::Mul(hn::Mul(dy, hn::Set(d, scale)), box_dx));
        const V e01 = hn::Add(e00, hn::Mul(hn::Mul(dx, hn::Set(d, scale)), box_dy));
        const V e11 = hn::Add(e10, hn::Sub(e01, e00));
        in00 = hn::And(in00, hn::Ge(e00, zero));
        in10 = hn::And(in10, hn::Ge(e10, zero));
        in01 = hn::And(in01, hn::Ge(e01, zero));
        in11 = hn::And(in11, hn::Ge(e11, zero));
      }
      edge_at[k] = e00;
      edge_dx[k] = dx;
      edge_dy[k] = dy;
    }
    max_step = hn::Max(max_step, hn::Add(hn::Abs(dy), hn::Abs(dx)));
    max_delta = hn::Max(max_delta, hn::Max(hn::Abs(dy), hn::Abs(dx)));
    weight0[k] = hn::Mul(
        hn::Sub(hn::Mul(dx, hn::Sub(cy, Y[from])), hn::Mul(dy, hn::Sub(cx, X[from]))), inv_area);
    wdx[k] = hn::Mul(hn::Neg(dy), per_pixel);
    wdy[k] = hn::Mul(dx, per_pixel);
  }
  hn::Store(as_double_mask(d, hn::Lt(max_step, hn::Set(d, lc.narrow_limit))), d, out.narrow + l0);
  const auto small = hn::Lt(max_delta, hn::Set(d, lc.small_limit));  // TriangleSetup::small
  hn::Store(as_double_mask(d, small), d, out.small + l0);
  V centres = zero;  // TriangleSetup::centres
  if (centre_only) {
    const auto small_box = hn::And(hn::Le(hn::Sub(bx1, bx0), hn::Set(d, 1.0)),
                                   hn::Le(hn::Sub(by1, by0), hn::Set(d, 1.0)));
    const auto covered = hn::Or(hn::Or(in00, in10), hn::Or(in01, in11));
    any_sample = hn::And(any_sample, hn::Or(hn::Not(small_box), covered));
    // In a box one pixel wide or high, the second column's or row's values repeat the first's.
    const auto two_x = hn::Gt(box_dx, zero), two_y = hn::Gt(box_dy, zero);
    const auto bit = [&](auto m, double value) { return hn::IfThenElseZero(m, hn::Set(d, value)); };
    centres = hn::Add(
        hn::Add(bit(in00, 1.0), bit(hn::And(in10, two_x), 2.0)),
        hn::Add(bit(hn::And(in01, two_y), 16.0), bit(hn::And(in11, hn::And(two_x, two_y)), 32.0)));
    centres = hn::IfThenElseZero(small_box, centres);
  }
  hn::Store(centres, d, out.centres + l0);
  V sample_mask = zero;  // TriangleSetup::sample_bits
  // One sample (pixel records): the kFirstPixels entry of the covered pixels, and their count.
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<uint32_t, decltype(d)> du;
  auto first_pixels = hn::Zero(di);
  // Sample records: the tested pixels' covered samples, bit (py * 3 + px) * samples + s, as
  // bits 0-31 and 32-63.
  auto record_low = hn::Zero(du), record_high = hn::Zero(du);
  auto any_pixel = hn::Lt(zero, zero);  // the lanes that become pixel or sample records
  if (sample_bits) {
    // Sample s of a box pixel is inside edge k when E(centre) + a dx_s + b dy_s >= 0, with
    // a = -dy, b = dx: when E(centre) - (dy dx_s - dx dy_s) is not negative. The setup's pixels
    // (TriangleSetup::sample_bits) are those whose bits fit 32: every 3x3 one at one and two
    // samples, all but the last at four. Sample records take boxes of up to 3 pixels across
    // and 4 down: every pixel of those is tested.
    //
    // Only small triangles (every edge under 32 px: TriangleSetup::small) are tested, in 32-bit
    // lanes, two samples of a triangle side by side in its 64-bit lane (at one sample, two
    // pixels: one row and the next, below). Their edges' |dx|, |dy|
    // are below 2^(bits + 5) and every pixel centre of the loop lies within 4 px of their
    // vertices' bounding box (under 32 px), so |E| < 2 * 2^(bits + 5) * 36 * 2^bits < 2^28 and
    // |dy dx_s - dx dy_s| < 2 * 2^(bits + 5) * 2^(bits - 1) <= 2^21: the difference is exact
    // in int32, and its sign bit says whether the sample is outside. Other boxes of at most 3x3
    // or 3x4 pixels (large triangles cut to a corner of the screen) keep sample_bits 0 and no
    // record: the kernel tests their edges.
    const uint32_t samples = ctx.samples;
    const uint32_t setup_pixels = std::min(9u, 32u / samples);
    const V last_x = hn::Sub(bx1, bx0), last_y = hn::Sub(by1, by0);  // in the box, from 0
    const V two = hn::Set(d, 2.0);
    const auto box = hn::And(hn::And(hn::Le(last_x, two), hn::Le(last_y, two)), small);
    auto fits = box;  // TriangleSetup::sample_bits holds the box's samples
    if (setup_pixels < 9) fits = hn::AndNot(hn::And(hn::Eq(last_x, two), hn::Eq(last_y, two)), box);
    // The boxes whose samples are tested: with sample records, also boxes of four rows (of at
    // most three pixels), which become records when at most kSampleRecordPixels pixels have a
    // covered sample (their pixels lie within 4 px of the vertices' box: the bound above holds).
    const auto tested =
        ctx.sample_records
            ? hn::And(hn::And(hn::Le(last_x, two), hn::Le(last_y, hn::Set(d, 3.0))), small)
            : fits;
    const uint32_t tested_pixels = ctx.sample_records ? kSampleRecordBoxPixels : setup_pixels;
    // Lanes of two samples each: each 64-bit box lane split into two 32-bit lanes, one sample's
    // values in each. Targets with one lane per vector (HWY_SCALAR) test one sample per 64-bit
    // lane.
    constexpr uint32_t kPerLane = HWY_TARGET == HWY_SCALAR ? 1 : 2;
    const hn::RebindToSigned<decltype(d)> d64;
    const std::conditional_t<kPerLane == 2, hn::Repartition<int32_t, decltype(d)>, decltype(d64)>
        ds;
    const hn::RebindToUnsigned<decltype(ds)> dus;
    using VS = hn::Vec<decltype(ds)>;
    // A tested lane's value as an integer (0 in the other lanes, whose values may not fit).
    const auto as_int = [&](V v) { return small_to_int64(d64, hn::IfThenElseZero(tested, v)); };
    // An integer lane's value (which fits int32) in both halves of its 64-bit lane.
    const auto both_halves = [&](hn::Vec<decltype(d64)> v) {
      if constexpr (kPerLane == 1) {
        return v;
      } else {
        return hn::DupEven(hn::BitCast(ds, v));
      }
    };
    // The sign bits of a lane's samples as bits 0 (and 1) of its 64-bit lane.
    const auto sign_bits = [&](VS v) {
      constexpr int kTop = static_cast<int>(sizeof(hn::TFromD<decltype(ds)>) * 8 - 1);
      const auto sign = hn::BitCast(d64, hn::ShiftRight<kTop>(hn::BitCast(dus, v)));
      if constexpr (kPerLane == 1) {
        return sign;
      } else {
        return hn::Or(hn::And(sign, hn::Set(d64, 1)), hn::ShiftRight<31>(sign));
      }
    };
    // Group j: samples kPerLane * j and the next (sample 0 twice at one sample).
    const uint32_t groups = (samples + kPerLane - 1) / kPerLane;
    HWY_DASSERT(groups <= 4 / kPerLane);
    // One sample: rows 2r and 2r + 1 of the box side by side in the two halves, so six steps
    // instead of nine test its pixels (the second pass's row 3 lies in no box: its bits are
    // dropped, and its values are within the bound above). The same bits py * 3 + px as the
    // general loop sets (setup: 3.7% faster on `grid`, 1.5% on `tiny`).
    // The one sample is the pixel centre there, so no sample offsets are formed.
    const bool row_pairs =
        kPerLane == 2 && samples == 1 && ctx.centre_sample_only() && !ctx.sample_records;
    // row: the first row's edge values in both halves, or with row_pairs the first row in the
    // low halves and the second in the high. least: each group's sample offsets, which the
    // general loop subtracts (row_pairs has none to subtract and forms none).
    VS least[3][4 / kPerLane], row[3], step_x[3], step_y[3];
    const uint32_t offset_groups = row_pairs ? 0 : groups;
    // Each group's sample positions (from the pixel centre, in subpixel units), the same for
    // every edge: sample kPerLane * j's in the low halves, the next sample's (or the same
    // sample's, past the last) in the high halves.
    VS group_dx[4 / kPerLane], group_dy[4 / kPerLane];
    for (uint32_t j = 0; j < offset_groups; ++j) {
      const uint32_t s0 = kPerLane * j, s1 = s0 + 1 < samples ? s0 + 1 : s0;
      const auto per_sample = [&](const std::array<int32_t, 16>& offset) {
        const auto low = hn::Set(ds, offset[s0] * (int32_t{1} << shift));
        if constexpr (kPerLane == 1) {
          return low;
        } else {
          return hn::OddEven(hn::Set(ds, offset[s1] * (int32_t{1} << shift)), low);
        }
      };
      group_dx[j] = per_sample(ctx.sample_dx);
      group_dy[j] = per_sample(ctx.sample_dy);
    }
    // The edge's deltas and its value at the first pixel centre are converted once; the steps
    // and sample offsets (dy dx_s - dx dy_s) are formed from them in the integer lanes, where
    // they are exact (the bounds above), so they are the values the double lanes would give.
    for (int k = 0; k < 3; ++k) {
      const VS dx = both_halves(as_int(edge_dx[k])), dy = both_halves(as_int(edge_dy[k]));
      const VS at = both_halves(as_int(edge_at[k]));
      for (uint32_t j = 0; j < offset_groups; ++j)
        least[k][j] = hn::Sub(hn::Mul(dy, group_dx[j]), hn::Mul(dx, group_dy[j]));
      step_x[k] = hn::ShiftLeftSame(dy, bits);
      step_y[k] = hn::ShiftLeftSame(dx, bits);
      row[k] = row_pairs ? hn::OddEven(hn::Add(at, step_y[k]), at) : at;
    }
    const auto pixel_samples = hn::Set(d64, (int64_t{1} << samples) - 1);
    // Every tested pixel's samples, bit pixel * samples + s; sample_mask holds the first
    // setup_pixels pixels' of them.
    auto mask_bits64 = hn::Zero(d64);
    auto any_bits64 = hn::Zero(d64);  // sample records: the pixels with a covered sample
    // With no lane's box fitting, every mask stays 0: the tests are skipped (`small`, most of
    // whose boxes are wider: 0.96x to 0.98x the time at one sample).
    if (row_pairs && !hn::AllFalse(d, fits)) {
      // row advances two rows a pass, in place: GCC makes a copy of it (an array in memory) in
      // 16-byte pieces, which the 32-byte loads after it must wait for.
      VS step_rows[3];
      for (int k = 0; k < 3; ++k)
        step_rows[k] = hn::Add(step_y[k], step_y[k]);
      // Bits 0 and 32 (the two rows): the pixel is in the box.
      const auto low = hn::Set(d64, 1), high = hn::Set(d64, int64_t{1} << 32);
      hn::Vec<decltype(d64)> x_ok[3], y_ok[2];
      for (uint32_t px = 0; px < 3; ++px) {
        x_ok[px] = hn::VecFromMask(
            d64, hn::RebindMask(
                     d64, hn::And(fits, hn::Le(hn::Set(d, static_cast<double>(px)), last_x))));
      }
      for (uint32_t r = 0; r < 2; ++r) {
        y_ok[r] = hn::Or(
            hn::IfThenElseZero(hn::RebindMask(d64, hn::Le(hn::Set(d, 2.0 * r), last_y)), low),
            hn::IfThenElseZero(hn::RebindMask(d64, hn::Le(hn::Set(d, 2.0 * r + 1), last_y)), high));
      }
      for (uint32_t r = 0; r < 2; ++r) {
        VS e[3] = {row[0], row[1], row[2]};
        for (uint32_t px = 0; px < 3; ++px) {
          // Negative where outside an edge: each half's sign bit, at bits 0 (row 2r) and 32
          // (row 2r + 1) after the shift.
          const auto outside = hn::Or(hn::Or(e[0], e[1]), e[2]);
          const auto sign =
              hn::ShiftRight<31>(hn::BitCast(hn::RebindToUnsigned<decltype(d64)>(), outside));
          const auto covered = hn::AndNot(hn::BitCast(d64, sign), hn::And(x_ok[px], y_ok[r]));
          mask_bits64 =
              hn::Or(mask_bits64, hn::ShiftLeftSame(covered, static_cast<int>(6 * r + px)));
          for (int k = 0; k < 3; ++k)
            e[k] = hn::Sub(e[k], step_x[k]);
        }
        for (int k = 0; k < 3; ++k)
          row[k] = hn::Add(row[k], step_rows[k]);
      }
      // Row 2r + 1's bits from 32 + 6 r + px down to 3 + 6 r + px.
      mask_bits64 =
          hn::Or(hn::And(mask_bits64, hn::Set(d64, 0xFFFFFFFF)), hn::ShiftRight<29>(mask_bits64));
    } else if (!row_pairs) {
      // The tests stop at the first row, and in a row at the first column, that lies in no
      // lane's box: neither do the ones after it, and their pixels' masks would all be 0. (At
      // four samples no lane's box has a third row in 64% of `grid`'s vectors, nor a third
      // column in 76%.)
      for (uint32_t py = 0; py * 3 < tested_pixels; ++py) {
        const auto row_in_box =
            hn::And(tested, hn::Le(hn::Set(d, static_cast<double>(py)), last_y));
        if (hn::AllFalse(d, row_in_box)) break;
        VS e[3] = {row[0], row[1], row[2]};
        for (uint32_t px = 0, pixel = py * 3; px < 3 && pixel < tested_pixels; ++px, ++pixel) {
          const auto in_box =
              hn::And(row_in_box, hn::Le(hn::Set(d, static_cast<double>(px)), last_x));
          if (hn::AllFalse(d, in_box)) break;
          auto missed = hn::Zero(d64);  // bit s: sample s outside an edge
          for (uint32_t j = 0; j < groups; ++j) {
            // Negative where the sample is outside an edge.
            const auto outside =
                hn::Or(hn::Or(hn::Sub(e[0], least[0][j]), hn::Sub(e[1], least[1][j])),
                       hn::Sub(e[2], least[2][j]));
            missed = hn::Or(missed,
                            hn::ShiftLeftSame(sign_bits(outside), static_cast<int>(kPerLane * j)));
          }
          const auto pixel_mask =
              hn::IfThenElseZero(hn::RebindMask(d64, in_box), hn::AndNot(missed, pixel_samples));
          mask_bits64 =
              hn::Or(mask_bits64, hn::ShiftLeftSame(pixel_mask, static_cast<int>(pixel * samples)));
          if (ctx.sample_records) {
            any_bits64 = hn::Or(any_bits64, hn::IfThenElseZero(hn::Ne(pixel_mask, hn::Zero(d64)),
                                                               hn::Set(d64, int64_t{1} << pixel)));
          }
          for (int k = 0; k < 3; ++k)
            e[k] = hn::Sub(e[k], step_x[k]);
        }
        for (int k = 0; k < 3; ++k)
          row[k] = hn::Add(row[k], step_y[k]);
      }
    }
    // The setup's pixels' bits (tested_pixels is setup_pixels without sample records): below
    // 2^32, so exact as a double.
    sample_mask = hn::ConvertTo(
        d, tested_pixels == setup_pixels
               ? mask_bits64
               : hn::And(mask_bits64, hn::Set(d64, (int64_t{1} << (setup_pixels * samples)) - 1)));
    const V any_mask = hn::ConvertTo(d, any_bits64);
    // Only boxes that fit keep sample_bits: the others tested (full 3x3 boxes at four samples,
    // boxes of four rows) are binned as without records, with a setup whose sample_bits are 0,
    // unless they become sample records.
    const V fit_mask = ctx.sample_records ? hn::IfThenElseZero(fits, sample_mask) : sample_mask;
    any_sample = hn::And(any_sample, hn::Or(hn::Not(fits), hn::Gt(fit_mask, zero)));
    if (samples == 1) {
      // Pixel records for the lanes with 1 to kPixelRecordPixels covered pixels (the mask
      // holds 9 bits: bit py * 3 + px).
      first_pixels = table_entries(d, di, kFirstPixels, sample_mask);
      const V found = hn::PromoteTo(d, hn::ShiftRight<24>(first_pixels));
      any_pixel = hn::And(hn::Gt(found, zero),
                          hn::Le(found, hn::Set(d, static_cast<double>(kPixelRecordPixels))));
    }
    // As signed 32-bit values, for the conversions below and PackLanes': the same bits.
    const V top = hn::Set(d, 2147483648.0);
    const auto as_signed = [&](V v) {
      return hn::Sub(v, hn::IfThenElseZero(hn::Ge(v, top), hn::Add(top, top)));
    };
    if (ctx.sample_records) {
      // Sample records for the lanes with covered samples in 1 to kSampleRecordPixels pixels,
      // looked up as at one sample.
      // Bits 0-31 and 32-63 of the tested pixels' (pixels do not straddle them).
      const auto tested_bits = hn::BitCast(hn::RebindToUnsigned<decltype(d64)>(), mask_bits64);
      record_low = hn::TruncateTo(du, tested_bits);
      record_high = hn::TruncateTo(du, hn::ShiftRight<32>(tested_bits));
      first_pixels = table_entries(d, di, kFirstSamplePixels, any_mask);
      const V found = hn::PromoteTo(d, hn::ShiftRight<24>(first_pixels));
      any_pixel = hn::And(hn::Gt(found, zero),
                          hn::Le(found, hn::Set(d, static_cast<double>(kSampleRecordPixels))));
    }
    sample_mask = as_signed(fit_mask);
  }
  // At one sample the bits are the pixel records' centres, and the setups carry none.
  hn::Store(ctx.samples == 1 ? zero : sample_mask, d, out.sample_bits + l0);
  const auto binned = hn::And(keep, any_sample);
  out.binned |= mask_bits(d, binned) << l0;
  // Lanes that are not binned need nothing below (their planes, records and setups): a vector
  // of them, common where a dense mesh's triangles cover no pixel centre, stops here.
  if (hn::AllFalse(d, binned)) return;

  auto plane = [&](V v0, V v1, V v2, double* at0, double* gx, double* gy) {
    hn::Store(
        hn::Add(hn::Add(hn::Mul(weight0[0], v0), hn::Mul(weight0[1], v1)), hn::Mul(weight0[2], v2)),
        d, at0 + l0);
    hn::Store(hn::Add(hn::Add(hn::Mul(wdx[0], v0), hn::Mul(wdx[1], v1)), hn::Mul(wdx[2], v2)), d,
              gx + l0);
    hn::Store(hn::Add(hn::Add(hn::Mul(wdy[0], v0), hn::Mul(wdy[1], v1)), hn::Mul(wdy[2], v2)), d,
              gy + l0);
  };
  if (has_depth_bias(p)) {
    // depth_bias.hpp's bias per lane, added to each vertex's z. For float depth, r = 2^(e - 23)
    // from the bits of the largest |z|: its exponent field less 23, shifted back into place (0
    // where that would be below 2^-1000, as for z = 0).
    const hn::RebindToSigned<decltype(d)> di64;
    V unit = hn::Set(d, depth_bias_unit(ctx.depth_format, 1.0));
    if (ctx.depth_format == DepthFormat::kFloat32) {
      const V z_abs = hn::Max(hn::Max(hn::Abs(Z[0]), hn::Abs(Z[1])), hn::Abs(Z[2]));
      const auto exponent = hn::ShiftRight<52>(hn::BitCast(di64, z_abs));
      const auto above = hn::Gt(exponent, hn::Set(di64, 23));
      unit = hn::BitCast(
          d, hn::IfThenElseZero(above, hn::ShiftLeft<52>(hn::Sub(exponent, hn::Set(di64, 23)))));
    }
    const V gx =
        hn::Add(hn::Add(hn::Mul(wdx[0], Z[0]), hn::Mul(wdx[1], Z[1])), hn::Mul(wdx[2], Z[2]));
    const V gy =
        hn::Add(hn::Add(hn::Mul(wdy[0], Z[0]), hn::Mul(wdy[1], Z[1])), hn::Mul(wdy[2], Z[2]));
    V bias =
        hn::Add(hn::Mul(hn::Set(d, double{p.depth_bias_constant}), unit),
                hn::Mul(hn::Set(d, double{p.depth_bias_slope}), hn::Max(hn::Abs(gx), hn::Abs(gy))));
    const double clamp = p.depth_bias_clamp;
    if (clamp > 0.0) bias = hn::Min(bias, hn::Set(d, clamp));
    if (clamp < 0.0) bias = hn::Max(bias, hn::Set(d, clamp));
    for (V& z : Z)
      z = hn::Add(z, bias);
  }
  plane(Z[0], Z[1], Z[2], out.z0, out.z_dx, out.z_dy);
  const V one = hn::Set(d, 1.0);
  hn::Store(hn::Min(hn::Max(hn::Min(hn::Min(Z[0], Z[1]), Z[2]), zero), one), d, out.z_min + l0);
  hn::Store(hn::Min(hn::Max(hn::Max(hn::Max(Z[0], Z[1]), Z[2]), zero), one), d, out.z_max + l0);

  const bool affine = p.interpolation == Interpolation::kAffine;
  const auto flat =
      affine ? hn::Eq(zero, zero) : hn::And(hn::Eq(IW[0], IW[1]), hn::Eq(IW[1], IW[2]));
  hn::Store(as_double_mask(d, flat), d, out.flat_q + l0);
  const V q_max = hn::Max(hn::Max(IW[0], IW[1]), IW[2]);
  V q[3];
  const V inv_q_max = kUnitW ? one : hn::Div(one, q_max);
  for (int k = 0; k < 3; ++k)
    q[k] = kUnitW ? one : hn::IfThenElse(flat, one, quotient(IW[k], q_max, inv_q_max));
  plane(q[0], q[1], q[2], out.q0, out.q_dx, out.q_dy);
  for (int c = 0; c < 4; ++c) {
    plane(hn::Mul(q[0], C[0][c]), hn::Mul(q[1], C[1][c]), hn::Mul(q[2], C[2][c]), out.qa0[c],
          out.qa_dx[c], out.qa_dy[c]);
  }
  if (!hn::AllFalse(d, any_pixel)) {
    if (ctx.samples == 1) {
      PixelValues(d, l0, first_pixels, out);
    } else {
      any_pixel = hn::AndNot(
          SampleValues(d, l0, first_pixels, record_low, record_high, ctx.samples, out), any_pixel);
    }
  }
  out.pixel |= mask_bits(d, any_pixel) << l0;
  // Setup records only for lanes that are binned and not pixel records (the clipper makes its
  // own): often none, with tiny triangles.
  const auto full = hn::AndNot(any_pixel, binned);
  if (!hn::AllFalse(d, full)) {
    if (ctx.samples == 1) {
      // TriangleSetup::unit_colour, from the vertices' smallest and largest channel values
      // (finite: the draw's colours are checked), in float lanes.
      auto lo = color[0][0], hi = color[0][0];
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 4; ++c) {
          lo = hn::Min(lo, color[k][c]);
          hi = hn::Max(hi, color[k][c]);
        }
      }
      const auto unit = hn::And(
          flat, hn::And(hn::Ge(hn::PromoteTo(d, lo), zero), hn::Le(hn::PromoteTo(d, hi), one)));
      hn::Store(as_double_mask(d, unit), d, out.unit_colour + l0);
    } else {
      hn::Store(zero, d, out.unit_colour + l0);
    }
    PackLanes(d, l0, out);
  }
}

// One vector of lanes from l0, from its vertices' positions and colours as x, y, z, w and
// r, g, b, a vectors.
template <class VF>
HWY_INLINE void SetupVertices(const SetupContext& ctx, const LaneConstants& lc,
                              const VF (&pos)[3][4], const VF (&color)[3][4], size_t l0, Out& out) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const auto one = hn::Set(df, 1.0f);
  auto unit_w = hn::Eq(one, one);
  for (int k = 0; k < 3; ++k)
    unit_w = hn::And(unit_w, hn::Eq(pos[k][3], one));
  if (hn::AllTrue(df, unit_w)) {
    SetupLaneGroup<true>(ctx, lc, pos, color, l0, out);
  } else {
    SetupLaneGroup<false>(ctx, lc, pos, color, l0, out);
  }
}

void SetupBatchLanes(const SetupContext& ctx, const LaneConstants& lc, const Batch& in,
                     size_t lanes_used, Out& out) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  for (size_t l0 = 0; l0 < lanes_used; l0 += hn::Lanes(d)) {
    hn::Vec<decltype(df)> pos[3][4], color[3][4];  // x, y, z, w and r, g, b, a of each vertex
    for (int k = 0; k < 3; ++k) {
      hn::LoadInterleaved4(df, &in.position[k][l0].x, pos[k][0], pos[k][1], pos[k][2], pos[k][3]);
      hn::LoadInterleaved4(df, &in.color[k][l0][0], color[k][0], color[k][1], color[k][2],
                           color[k][3]);
    }
    SetupVertices(ctx, lc, pos, color, l0, out);
  }
}

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
// The index tables of LoadTriangleValues' two-source permutes (vpermt2ps: index bit 4 picks
// the second source). pairs(p): lanes 0-7 component 2p, lanes 8-15 component 2p + 1, of the
// 8 vertices in two 512-bit loads (32 floats). merge(k, second): lane t of each half takes
// vertex 3t + k of the 24, which lies in vertex group g = (3t + k) / 8 at lane (3t + k) % 8
// of that group's pair vectors; the first merge takes groups 0 and 1, the second keeps
// those lanes and takes group 2's.
constexpr std::array<int32_t, 16> pair_index(int32_t p) {
  std::array<int32_t, 16> index{};
  for (int32_t i = 0; i < 16; ++i)
    index[i] = i < 8 ? 4 * i + 2 * p : 4 * (i - 8) + 2 * p + 1;
  return index;
}
constexpr std::array<int32_t, 16> merge_index(int32_t k, bool second) {
  std::array<int32_t, 16> index{};
  for (int32_t lane = 0; lane < 16; ++lane) {
    const int32_t v = 3 * (lane % 8) + k, g = v / 8, at = v % 8 + (lane < 8 ? 0 : 8);
    if (second) {
      index[lane] = g == 2 ? 16 + at : lane;
    } else {
      index[lane] = g == 2 ? 0 : g * 16 + at;
    }
  }
  return index;
}
#endif

// One vector's worth of a triangle list's vertex values, four floats per vertex and three
// vertices per triangle in order (Lanes(df) triangles: 12 * Lanes(df) floats from `from`), as
// value[vertex][component] vectors whose lane l is triangle l's: each component is first
// gathered from the four interleaved, then the vertices from the three.
template <class DF>
HWY_INLINE void LoadTriangleValues(DF df, const float* HWY_RESTRICT from,
                                   hn::Vec<DF> (&value)[3][4]) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  if constexpr (hn::MaxLanes(df) == 8) {
    // AVX-512, 8 triangles: their 96 floats in six 512-bit loads, then two rounds of
    // two-source permutes, which put two components of one vertex side by side in a vector
    // (half as many shuffles as the interleaved loads and the store between them).
    alignas(64) static constexpr std::array<int32_t, 16> kPairs[2] = {pair_index(0), pair_index(1)};
    alignas(64) static constexpr std::array<int32_t, 16> kMerge[3][2] = {
        {merge_index(0, false), merge_index(0, true)},
        {merge_index(1, false), merge_index(1, true)},
        {merge_index(2, false), merge_index(2, true)}};
    __m512 pairs[3][2];  // [vertex group][component pair]
    for (int g = 0; g < 3; ++g) {
      const __m512 lo = _mm512_loadu_ps(from + 32 * g), hi = _mm512_loadu_ps(from + 32 * g + 16);
      for (int p = 0; p < 2; ++p) {
        pairs[g][p] = _mm512_permutex2var_ps(lo, _mm512_load_si512(kPairs[p].data()), hi);
      }
    }
    for (int k = 0; k < 3; ++k) {
      const __m512i first = _mm512_load_si512(kMerge[k][0].data());
      const __m512i second = _mm512_load_si512(kMerge[k][1].data());
      for (int p = 0; p < 2; ++p) {
        const __m512 both = _mm512_permutex2var_ps(
            _mm512_permutex2var_ps(pairs[0][p], first, pairs[1][p]), second, pairs[2][p]);
        value[k][2 * p] = hn::Vec<DF>{_mm512_castps512_ps256(both)};
        value[k][2 * p + 1] = hn::Vec<DF>{_mm512_extractf32x8_ps(both, 1)};
      }
    }
    return;
  }
#endif
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(df) == 4) {
    // Four triangles (AVX2): vertex k of triangle l is the four floats at 12 l + 4 k, so each
    // vertex's values are a 4x4 transpose of four loads (8 shuffles), with no stores and loads
    // between (`grid`: 4% fewer instructions in SetupListLanes, callgrind).
    for (int k = 0; k < 3; ++k) {
      const auto r0 = hn::LoadU(df, from + 4 * k), r1 = hn::LoadU(df, from + 12 + 4 * k);
      const auto r2 = hn::LoadU(df, from + 24 + 4 * k), r3 = hn::LoadU(df, from + 36 + 4 * k);
      const auto low01 = hn::InterleaveLower(df, r0, r1), low23 = hn::InterleaveLower(df, r2, r3);
      const auto up01 = hn::InterleaveUpper(df, r0, r1), up23 = hn::InterleaveUpper(df, r2, r3);
      value[k][0] = hn::ConcatLowerLower(df, low23, low01);
      value[k][1] = hn::ConcatUpperUpper(df, low23, low01);
      value[k][2] = hn::ConcatLowerLower(df, up23, up01);
      value[k][3] = hn::ConcatUpperUpper(df, up23, up01);
    }
    return;
  }
#endif
  const size_t n = hn::Lanes(df);
  HWY_ALIGN float component[4][3 * kMaxLanes];
  for (size_t j = 0; j < 3; ++j) {
    hn::Vec<DF> v[4];
    hn::LoadInterleaved4(df, from + 4 * n * j, v[0], v[1], v[2], v[3]);
    for (int c = 0; c < 4; ++c)
      hn::StoreU(v[c], df, component[c] + n * j);
  }
  for (int c = 0; c < 4; ++c)
    hn::LoadInterleaved3(df, component[c], value[0][c], value[1][c], value[2][c]);
}

// SetupBatchLanes for Lanes(d) triangles of a list without indices, whose vertices have four
// colour values each: read from the draw's arrays directly, with no Batch copy.
void SetupListLanes(const SetupContext& ctx, const LaneConstants& lc, const float* positions,
                    const float* colors, Out& out) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  hn::Vec<decltype(df)> pos[3][4], color[3][4];
  LoadTriangleValues(df, positions, pos);
  LoadTriangleValues(df, colors, color);
  SetupVertices(ctx, lc, pos, color, 0, out);
}

}  // namespace

// Whether `count` floats from `from` are all finite (count: a multiple of the float lanes).
HWY_INLINE bool range_finite(const float* from, size_t count) {
  return tessera::HWY_NAMESPACE::vectors_finite(hn::ScalableTag<float>(), from, count);
}

// Whether the batch's first `lanes` lanes of positions and colours are all finite. Each
// vertex's lanes hold 4 * lanes floats, two float vectors (lanes = Lanes(double)).
HWY_INLINE bool batch_finite(const Batch& batch, size_t lanes) {
  bool finite = true;
  for (int k = 0; k < 3; ++k) {
    finite = finite && range_finite(&batch.position[k][0].x, 4 * lanes) &&
             range_finite(&batch.color[k][0][0], 4 * lanes);
  }
  return finite;
}

// Copies triangles [t, t + used) of the draw into the batch's first lanes (of `lanes`); spare
// lanes repeat the last triangle.
HWY_INLINE void fill_batch(const SetupContext& ctx, const DrawInput& input, size_t t, size_t used,
                           size_t lanes, Batch& batch) {
  const bool indexed = !input.indices.empty();
  const uint32_t stride = input.attribute_count, count = ctx.color_count();
  for (size_t l = 0; l < lanes; ++l) {
    const size_t tri = t + std::min(l, used - 1);
    for (int k = 0; k < 3; ++k) {
      const size_t vertex = indexed ? input.indices[tri * 3 + k] : tri * 3 + k;
      batch.position[k][l] = input.positions[vertex];
      const float* a = count ? &input.attributes[vertex * stride + ctx.color_first] : nullptr;
      if (count >= 4) {  // every channel given, no per-channel choice
        std::memcpy(batch.color[k][l], a, sizeof(batch.color[k][l]));
      } else {
        float* c = batch.color[k][l];
        for (uint32_t i = 0; i < 4; ++i)
          c[i] = i < count ? a[i] : (i == 3 ? 1.0f : 0.0f);
      }
    }
  }
}

// Streams 16 bytes (a record's piece) from `from` to `to`, 16-byte aligned: the records are
// read long after, by the raster phase, so writing them through the cache would first read
// each line from memory for nothing.
HWY_INLINE void stream_piece(const void* from, void* to) {
  const hn::CappedTag<uint32_t, 4> d;
  const uint32_t* f = static_cast<const uint32_t*>(from);
  uint32_t* t = static_cast<uint32_t*>(to);
  for (size_t i = 0; i < 4; i += hn::Lanes(d))
    hn::Stream(hn::LoadU(d, f + i), d, t + i);
}

bool SetupRange(const SetupContext& ctx, const DrawInput& input, size_t begin, size_t end,
                SetupList& setups, PixelList& pixels, SampleList& samples, binning::Bins& bins,
                Counters& counters) {
  const hn::ScalableTag<double> d;
  const size_t lanes = std::min(hn::Lanes(d), kMaxLanes);
  const bool indexed = !input.indices.empty();
  const uint32_t count = input.attribute_count;
  Batch batch;
  Out out;
  const LaneConstants lc(ctx);
  bool ok = true;
  // A list without indices and with the four colour values per vertex (captures, most meshes
  // drawn as lists) is read in place a full vector of triangles at a time.
  const bool in_place = !indexed && count == 4 && ctx.color_first == 0;
  // Room for every triangle's record (uninitialized: SetupList's allocator), once for the
  // range; `next` is the first not written, and the lists are cut to it at the end.
  size_t next = setups.size(), next_pixel = pixels.size(), next_sample = samples.size();
  setups.resize(next + (end - begin));
  if (ctx.pixel_records) pixels.resize(next_pixel + (end - begin));
  if (ctx.sample_records) samples.resize(next_sample + (end - begin));
  for (size_t t = begin; t < end; t += lanes) {
    const size_t used = std::min(lanes, end - t);
    out.clipped = out.kept = out.binned = out.pixel = 0;  // the lane groups OR their bits in
    if (in_place && used == lanes) {
      const float* positions = &input.positions[t * 3].x;
      const float* colors = &input.attributes[t * 12];
      if (ctx.check_finite &&
          !(range_finite(positions, 12 * lanes) && range_finite(colors, 12 * lanes))) {
        ok = false;
        break;
      }
      SetupListLanes(ctx, lc, positions, colors, out);
    } else {
      fill_batch(ctx, input, t, used, lanes, batch);
      if (ctx.check_finite && !batch_finite(batch, lanes)) {
        ok = false;
        break;
      }
      SetupBatchLanes(ctx, lc, batch, lanes, out);
    }

    // The lanes' outcomes counted at once; then only the lanes with records are visited, in
    // order (submission order in the bins). With half of a dense mesh's tiny triangles
    // covering no pixel centre, a branch per lane on it mispredicts often.
    const uint32_t lane_bits = used >= 32 ? ~0u : (1u << used) - 1;
    const uint32_t clipped = out.clipped & lane_bits, kept = out.kept & lane_bits;
    const auto unclipped = static_cast<uint64_t>(std::popcount(lane_bits & ~clipped));
    counters.triangles_submitted += unclipped;
    counters.triangles_rasterized += static_cast<uint64_t>(std::popcount(kept));
    counters.triangles_culled += unclipped - static_cast<uint64_t>(std::popcount(kept));
    for (uint32_t visit = (out.binned & lane_bits) | clipped; visit != 0; visit &= visit - 1) {
      const size_t l = static_cast<size_t>(std::countr_zero(visit));
      if ((clipped >> l) & 1) {
        // A clip plane cuts this triangle: the scalar path clips it (and counts it), after the
        // records before it.
        setups.resize(next);
        std::array<const Float4*, 3> position;
        std::array<const float*, 3> attribute{};
        for (int k = 0; k < 3; ++k) {
          const size_t vertex = indexed ? input.indices[(t + l) * 3 + k] : (t + l) * 3 + k;
          position[k] = &input.positions[vertex];
          if (ctx.color_count()) attribute[k] = &input.attributes[vertex * count + ctx.color_first];
        }
        setup_triangle(ctx, position, attribute, setups, counters);
        for (size_t i = next; i < setups.size(); ++i)
          bins.record(binning::tile_rect(static_cast<uint32_t>(setups[i].x0),
                                         static_cast<uint32_t>(setups[i].y0),
                                         static_cast<uint32_t>(setups[i].x1),
                                         static_cast<uint32_t>(setups[i].y1), ctx.bin_tile_log2),
                      static_cast<uint32_t>(i));
        next = setups.size();
        setups.resize(next + (end - (t + l) - 1));
        continue;
      }
      const uint64_t packed = out.tiles[l];
      const binning::TileRect tiles = {
          static_cast<uint16_t>(packed), static_cast<uint16_t>(packed >> 16),
          static_cast<uint16_t>(packed >> 32), static_cast<uint16_t>(packed >> 48)};
      if ((out.pixel >> l) & 1) {
        if (ctx.sample_records) {
          char* record = reinterpret_cast<char*>(&samples[next_sample]);
          for (int k = 0; k < 4; ++k)
            stream_piece(out.sample_words[k] + 4 * l, record + 16 * k);
          bins.record(tiles, kPixelRecordBit | static_cast<uint32_t>(next_sample++));
          continue;
        }
        char* record = reinterpret_cast<char*>(&pixels[next_pixel]);
        for (int k = 0; k < 2; ++k)
          stream_piece(out.pixel_words[k] + 4 * l, record + 16 * k);
        bins.record(tiles, kPixelRecordBit | static_cast<uint32_t>(next_pixel++));
        continue;
      }
      // The record, in ten 16-byte pieces (a record lies at a multiple of 160 bytes from a
      // 64-byte aligned start: every piece is aligned).
      char* record = reinterpret_cast<char*>(&setups[next]);
      for (int k = 0; k < 2; ++k)
        stream_piece(out.wide[k] + 2 * l, record + 16 * k);
      for (int k = 0; k < 8; ++k)
        stream_piece(out.words[k] + 4 * l, record + 32 + 16 * k);
      bins.record(tiles, static_cast<uint32_t>(next++));
    }
  }
  setups.resize(next);
  pixels.resize(next_pixel);
  samples.resize(next_sample);
  hwy::FlushStream();
  return ok;
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/target_list.hpp"

namespace tessera::fast {

namespace {
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<SetupRangeFn>{bit, &ns::SetupRange},
constexpr simd::TargetEntry<SetupRangeFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

SetupRangeFn setup_kernel(int64_t target) {
  return simd::find_target(kTargets, target);
}

}  // namespace tessera::fast
#endif  // HWY_ONCE
