// Frame-time statistics shared by the benchmark programs: each times a few frames and reports
// the median, the figure least moved by a shared machine's disturbances.
#pragma once

#include <algorithm>
#include <vector>

namespace tessera::bench {

// The median of `v` (the mean of the two middle values for an even count), 0 for none.
inline double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace tessera::bench
