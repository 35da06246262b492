// The SIMD instruction sets this build was compiled for and this CPU can run, as Highway
// reports them. Kernels written against simd/ are dispatched to the best of these.
#pragma once

#include <string>
#include <vector>

namespace tessera::simd {

// Names of the targets compiled into this build that the running CPU supports, best first
// (for example "AVX3", "AVX2", "SSE4", "EMU128").
std::vector<std::string> supported_targets();

}  // namespace tessera::simd
