// The raster kernel instances of the shaded draws whose shader is shade::Shader::kTextured (the
// textured shader in lanes), compiled for every SIMD target from block_kernel-inl.h. Each shader
// has its own source, so that its kernels compile in parallel with the others; block_kernel.cpp
// gathers them into the kernel table.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel_shader_textured.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/block_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
template void FillShaderKernels<shade::Shader::kTextured>(KernelTable& table);
}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();
