// Triangle setup vectorized across triangles (setup_kernel.cpp), dispatched per SIMD target.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "binning/bins.hpp"
#include "engine/src/fast/pixel_record.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// Sets up triangles [begin, end) of a validated draw, in order, appending their setups exactly
// as triangle_setup.cpp's scalar setup of the snapped vertices does (same bits) and recording
// each one's bin tiles (context.bin_tile_log2) and reference in `bins`; triangles a clip plane
// cuts go through setup_triangle. With context.pixel_records, a triangle that fits a pixel
// record is appended to `pixels` as one instead (its reference has kPixelRecordBit), and with
// context.sample_records one that fits a sample record to `samples`. The records
// are written with streaming stores where the target has them (they are read long after, by the
// raster phase): visible to other threads once the call returns. With context.check_finite, returns
// false (having stopped somewhere in the range) when a position or colour it reads is NaN or
// infinite; otherwise true.
using SetupRangeFn = bool (*)(const SetupContext& context, const DrawInput& input, size_t begin,
                              size_t end, SetupList& out, PixelList& pixels, SampleList& samples,
                              binning::Bins& bins, Counters& counters);

// The setup kernel compiled for a Highway target bit; targets without one (sizeless-vector
// targets such as SVE) get the best portable one.
SetupRangeFn setup_kernel(int64_t target);

}  // namespace tessera::fast
