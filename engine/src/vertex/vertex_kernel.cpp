// The built-in transform across vertices (vertex_kernel.hpp), written once against Highway and
// compiled for every target through hwy/foreach_target.h. Lanes are vertices; each output row
// is m[0] x + m[1] y + m[2] z + m[3] w summed left to right, the same on every target.
#include "engine/src/vertex/vertex_kernel.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/vertex/vertex_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::vertex::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

void TransformVertices(const TransformMatrices& m, const float* in, uint32_t normal_stream,
                       uint32_t count, float* out) {
  const hn::ScalableTag<float> d;
  const float* x = in;
  const float* y = in + kVertexBatch;
  const float* z = in + 2 * kVertexBatch;
  const float* w = in + 3 * kVertexBatch;
  const float* n = in + normal_stream * 4 * kVertexBatch;
  for (uint32_t i = 0; i < count; i += static_cast<uint32_t>(hn::Lanes(d))) {
    const auto vx = hn::LoadU(d, x + i), vy = hn::LoadU(d, y + i);
    const auto vz = hn::LoadU(d, z + i), vw = hn::LoadU(d, w + i);
    // Row r of a column-major 4x4 matrix times (x, y, z, w).
    const auto row4 = [&](const std::array<float, 16>& a, int r) {
      auto sum = hn::Mul(hn::Set(d, a[r]), vx);
      sum = hn::Add(sum, hn::Mul(hn::Set(d, a[4 + r]), vy));
      sum = hn::Add(sum, hn::Mul(hn::Set(d, a[8 + r]), vz));
      return hn::Add(sum, hn::Mul(hn::Set(d, a[12 + r]), vw));
    };
    for (int r = 0; r < 4; ++r)
      hn::StoreU(row4(m.clip, r), d, out + r * kVertexBatch + i);
    for (int r = 0; r < 3; ++r)
      hn::StoreU(row4(m.position, r), d, out + (4 + r) * kVertexBatch + i);
    if (m.has_normal) {
      const auto nx = hn::LoadU(d, n + i), ny = hn::LoadU(d, n + kVertexBatch + i);
      const auto nz = hn::LoadU(d, n + 2 * kVertexBatch + i);
      for (int r = 0; r < 3; ++r) {
        auto sum = hn::Mul(hn::Set(d, m.normal[r]), nx);
        sum = hn::Add(sum, hn::Mul(hn::Set(d, m.normal[3 + r]), ny));
        sum = hn::Add(sum, hn::Mul(hn::Set(d, m.normal[6 + r]), nz));
        hn::StoreU(sum, d, out + (7 + r) * kVertexBatch + i);
      }
    }
  }
}

}  // namespace

TransformFn GetTransformKernel() {
  return &TransformVertices;
}

}  // namespace tessera::vertex::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/target_list.hpp"

namespace tessera::vertex {

namespace {
using KernelFn = TransformFn (*)();
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<KernelFn>{bit, &ns::GetTransformKernel},
constexpr simd::TargetEntry<KernelFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

TransformFn transform_kernel(int64_t target) {
  return simd::find_target(kTargets, target)();
}

}  // namespace tessera::vertex
#endif  // HWY_ONCE
