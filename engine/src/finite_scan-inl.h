// The finiteness test of float vectors, written once against Highway for every target: the
// dispatched scan of a draw's arrays (finite_scan.cpp) and the vectorized setup's check of its
// lanes (fast/setup_kernel.cpp) call it, so both take the same two operations a vector.

// Per-target include guard (as fast/block_kernel-inl.h's).
#if defined(TESSERA_ENGINE_SRC_FINITE_SCAN_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_FINITE_SCAN_INL_H_
#undef TESSERA_ENGINE_SRC_FINITE_SCAN_INL_H_
#else
#define TESSERA_ENGINE_SRC_FINITE_SCAN_INL_H_
#endif

#include <cstddef>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Whether the floats of [from, from + count) are all finite; count is a multiple of
// Lanes(df). A float is not finite when its exponent bits are all set: the largest exponent
// field over the range says, two operations a vector (IsFinite takes four).
template <class DF>
HWY_INLINE bool vectors_finite(DF df, const float* from, size_t count) {
  const hn::RebindToUnsigned<DF> du;
  const auto exponent = hn::Set(du, 0x7F800000u);
  auto largest = hn::Zero(du);
  for (size_t i = 0; i < count; i += hn::Lanes(df))
    largest = hn::Max(largest, hn::And(hn::BitCast(du, hn::LoadU(df, from + i)), exponent));
  return hn::AllTrue(du, hn::Lt(largest, exponent));
}

}  // namespace tessera::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // include guard
