// The fragment back end of user fragment shaders (FragmentShader::kUser) in the fast engine:
// the raster kernel (block_kernel-inl.h) finds a block's covered samples that pass the depth
// test and hands them here, and this forms the block's 2x2 quads, evaluates the triangle's
// planes into each fragment's varyings and each quad's derivatives, runs the shader on the
// batch (shade/user_batch.hpp), and writes the depth and colour of the fragments it keeps.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/src/fast/block_kernel.hpp"

namespace tessera::fast {

// Block (bx, by) of the tile (8x8 pixels from pixel (8 bx, 8 by); `block` its index in the
// tile's storage) for triangle `t` with planes `planes`. mask[i]: the samples of the block's
// pixel i (row-major) that are covered and passed the depth test. z: null, or the depth to
// write for sample s of pixel i at z[s * 64 + i] (depth writes on).
void shade_user_block(const TileContext& tc, const TriangleSetup& t, const float* planes,
                      int32_t bx, int32_t by, size_t block, const uint32_t* mask, const float* z);

}  // namespace tessera::fast
