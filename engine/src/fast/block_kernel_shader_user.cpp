// The raster kernel instances of the shaded draws whose shader is shade::Shader::kUser (a
// user fragment function, or several colour targets: user_fragments-inl.h is their back end),
// compiled for every SIMD target from block_kernel-inl.h. Each shader has its own source, so
// that its kernels compile in parallel with the others; block_kernel.cpp gathers them into the
// kernel table.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel_shader_user.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/block_kernel-inl.h"
#include "engine/src/fast/user_fragments-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
template void FillShaderKernels<shade::Shader::kUser>(KernelTable& table);
}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
