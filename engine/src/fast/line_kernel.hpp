// The SIMD part of one-pixel lines: for a run of a segment's pixels (the tile walk in
// line_raster.cpp finds them), the parameter t, the colour and the depth of each pixel, with the
// reference's formulas in the same double arithmetic (so the bytes are the reference's), packed
// for the writes. Written once against Highway, compiled for every target (line_kernel.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::fast {

// Pixels per run: the walk flushes a run once it holds this many, and may add up to this many
// more before it checks (a chunk of columns); the arrays hold padding for a last partial vector.
inline constexpr size_t kLineRunPixels = 64;
inline constexpr size_t kLineRunCapacity = 2 * kLineRunPixels + 16;

// One segment's interpolation: t is the projection of the pixel centre on a -> b, clamped to
// [0, 1] (zero-length: t = 0); with `perspective`, colour uses tc = t wb / ((1 - t) wa + t wb).
struct LineShading {
  double ax = 0, ay = 0, ex = 0, ey = 0, inv_len2 = 0;
  bool perspective = false;
  double inv_wa = 1, inv_wb = 1;
  double z = 0, dz = 0;  // depth a.z + t (b.z - a.z)
  double color[4] = {0, 0, 0, 0};
  double dcolor[4] = {0, 0, 0, 0};  // float (b.c - a.c), as the reference subtracts
  // Antialiased lines: coverage across (within cover_reach = width / 2 + 1/2 of the line along
  // the unit direction (ux, uy)) times coverage along (within 1/2 beyond the ends, length
  // apart), and the colour blended over the framebuffer's (source over).
  bool smooth = false;
  double ux = 0, uy = 0, cover_reach = 0, length = 0;
};

// Shades pixels (x[i], y[i]), i < n: when dst is not null, rgba[i] holds the unorm8 colour (r in
// the low byte; for a smooth line, only where coverage[i] as written is > 0, blended over
// dst[offset[i]]); depth[i] the interpolated depth before clamping and encoding, offset[i] the
// pixel's place in a one-sample framebuffer's storage (FramebufferStorage::sample_index, with
// tiles_x storage tiles per row). Reads and writes up to n rounded up to the vector width (the
// arrays are kLineRunCapacity long).
struct LineRunOut {
  uint32_t* rgba;
  float* depth;
  uint32_t* offset;
  float* coverage;  // smooth lines
  // The RGBA8 framebuffer, which smooth lines read for blending; null when no colour is
  // written (rgba is then not formed).
  const uint32_t* dst;
  uint32_t tiles_x;
};
using LineShadeFn = void (*)(const LineShading&, const int32_t* x, const int32_t* y, size_t n,
                             const LineRunOut& out);

// The kernel compiled for a Highway target bit (see simd/dispatch.hpp).
LineShadeFn line_shade_kernel(int64_t target);

}  // namespace tessera::fast
