// The SIMD targets this CPU runs (simd/dispatch.hpp), in order from the portable one up: the
// suites that compare every target's images iterate over them.
#pragma once

#include <vector>

#include "simd/dispatch.hpp"
#include "tessera/renderer.hpp"

namespace tessera::test {

inline std::vector<SimdTarget> runnable_simd_targets() {
  std::vector<SimdTarget> out;
  for (SimdTarget t : {SimdTarget::kScalar, SimdTarget::kSSE4, SimdTarget::kAVX2,
                       SimdTarget::kAVX512, SimdTarget::kNEON, SimdTarget::kSVE}) {
    if (simd::is_available(t)) out.push_back(t);
  }
  return out;
}

}  // namespace tessera::test
