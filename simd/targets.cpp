// Run-time detection of SIMD targets through Highway (hwy::SupportedTargets).
#include "simd/targets.hpp"

#include <hwy/targets.h>

namespace tessera::simd {

std::vector<std::string> supported_targets() {
  std::vector<std::string> names;
  const int64_t supported = hwy::SupportedTargets() & HWY_TARGETS;
  // Highway's target bits are ordered best (lowest bit) to worst.
  for (int64_t bit = 1; bit != 0 && bit <= supported; bit <<= 1) {
    if (supported & bit) names.emplace_back(hwy::TargetName(bit));
  }
  return names;
}

}  // namespace tessera::simd
