// The raster kernel instances that test depth without writing it (DepthMode::kTest), compiled
// for every SIMD target from block_kernel-inl.h. Each depth mode has its own source so that the
// three sets of kernels compile in parallel; block_kernel.cpp gathers them into the kernel table.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel_depth_test.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/block_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
template void FillDepthKernels<DepthMode::kTest>(KernelTable& table);
}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
