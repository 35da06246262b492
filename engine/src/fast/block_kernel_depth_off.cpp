// The raster kernel instances without a depth test (DepthMode::kOff), compiled for every SIMD
// target from block_kernel-inl.h. Each depth mode has its own source so that the three sets of
// kernels compile in parallel; block_kernel.cpp gathers them into the kernel table.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel_depth_off.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/block_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
template void FillDepthKernels<DepthMode::kOff>(KernelTable& table);
}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
