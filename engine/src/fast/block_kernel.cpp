// The raster kernel table: for every SIMD target, the 36 Gouraud triangle kernels in
// block_kernel-inl.h (depth mode x colour mode x single or multisample x counting or not), the
// 12 pixel-record and 12 sample-record kernels (depth mode x no colour or RGBA8 x counting or
// not), and 24 triangle kernels for each other shader (depth mode x RGBA8 or RGBA32F x single
// or multisample x counting or not; a user shader's 12 serve both colour formats). Each depth
// mode's Gouraud instances compile in their own source (block_kernel_depth_*.cpp), and each
// shader's (block_kernel_shader_*.cpp), for the same targets as this file, so the kernels build in
// parallel; this file only gathers them, per target, into one table and picks the table for the
// target a renderer runs on.
#include "engine/src/fast/block_kernel.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/fast/block_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/hiz-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {

// Defined in block_kernel-inl.h, instantiated by one block_kernel_depth_*.cpp each.
template <DepthMode kDepth>
void FillDepthKernels(KernelTable& table);
extern template void FillDepthKernels<DepthMode::kOff>(KernelTable& table);
extern template void FillDepthKernels<DepthMode::kTest>(KernelTable& table);
extern template void FillDepthKernels<DepthMode::kTestWrite>(KernelTable& table);
// Likewise, instantiated by one block_kernel_shader_*.cpp each.
template <shade::Shader kShader>
void FillShaderKernels(KernelTable& table);
extern template void FillShaderKernels<shade::Shader::kInterpolated>(KernelTable& table);
extern template void FillShaderKernels<shade::Shader::kNormalized>(KernelTable& table);
extern template void FillShaderKernels<shade::Shader::kPhong>(KernelTable& table);
extern template void FillShaderKernels<shade::Shader::kTextured>(KernelTable& table);
extern template void FillShaderKernels<shade::Shader::kUser>(KernelTable& table);

const KernelTable* GetKernelTable() {
  static const KernelTable table = [] {
    KernelTable t{};
    FillDepthKernels<DepthMode::kOff>(t);
    FillDepthKernels<DepthMode::kTest>(t);
    FillDepthKernels<DepthMode::kTestWrite>(t);
    FillShaderKernels<shade::Shader::kInterpolated>(t);
    FillShaderKernels<shade::Shader::kNormalized>(t);
    FillShaderKernels<shade::Shader::kPhong>(t);
    FillShaderKernels<shade::Shader::kTextured>(t);
    FillShaderKernels<shade::Shader::kUser>(t);
    t.refresh_hiz_block = &RefreshHizBlock;
    return t;
  }();
  return &table;
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "simd/target_list.hpp"

namespace tessera::fast {

namespace {
using TableFn = const KernelTable* (*)();
#define TESSERA_TARGET_ENTRY(bit, ns) simd::TargetEntry<TableFn>{bit, &ns::GetKernelTable},
constexpr simd::TargetEntry<TableFn> kTargets[] = {
    TESSERA_FOR_EACH_SIMD_TARGET(TESSERA_TARGET_ENTRY)};
#undef TESSERA_TARGET_ENTRY
}  // namespace

const KernelTable& kernel_table(int64_t target) {
  return *simd::find_target(kTargets, target)();
}

}  // namespace tessera::fast
#endif  // HWY_ONCE
