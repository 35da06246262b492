// A scan of float arrays for NaN and infinity, written once against Highway and run on the best
// SIMD target this CPU supports (the result is the same on every target). Validation scans a
// draw's whole vertex arrays with it, at memory speed.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera {

// Whether every one of values[0, n) is finite (not NaN, not an infinity).
bool values_finite(const float* values, size_t n);

}  // namespace tessera
