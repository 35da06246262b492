// Pixel records: the setup of a tiny triangle reduced to the values of the pixels it covers.
//
// At one sample per pixel, a triangle whose bounding box is at most 3x3 pixels and which covers
// at most three pixel centres needs nothing from the raster phase but those pixels' depth
// and colour: the setup computes them and stores a 32-byte PixelRecord instead of a
// 160-byte TriangleSetup, and the raster phase only tests and writes them. The records are
// read at scattered places long after they are written, so one fifth of the bytes is one fifth
// of the cache lines fetched from memory.
//
// The values are the ones the kernels form for that pixel from the TriangleSetup (the same
// float operations in the same order, contraction off), so the images are the same bytes
// whichever record a triangle gets: the kernels' per-pixel paths use the functions below, and
// the vectorized setup (setup_kernel.cpp, PixelValues) does the same operations in its lanes.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "engine/src/aligned_allocator.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/sample_positions.hpp"

namespace tessera::fast {

struct PixelRecord {
  uint16_t x0, y0;  // the bounding box's first pixel
  // Bits 0-1: the covered pixels (1 to 3); bits 2-3 and 4-5: the box's width and height in
  // pixels, less one (0 to 2).
  uint8_t shape;
  // Each covered pixel's place in the box: (y - y0) * 4 + (x - x0), in row-major order.
  uint8_t offset[3];
  float z[3];         // z / w, clamped to [0, 1] (not yet rounded to a fixed-point format)
  uint32_t rgba8[3];  // colour, packed as the RGBA8 target stores it

  // The fields of shape.
  uint32_t pixels() const { return shape & 3u; }
  int32_t last_x() const { return (shape >> 2) & 3; }  // width - 1
  int32_t last_y() const { return (shape >> 4) & 3; }  // height - 1
};
static_assert(sizeof(PixelRecord) == 32 && std::is_trivially_default_constructible_v<PixelRecord>);

// The most pixels a pixel record holds.
inline constexpr uint32_t kPixelRecordPixels = 3;

// For each set of covered pixels of a box of kPixels / 3 rows of 3 (bit (y - y0) * 3 + (x - x0)):
// the places (y - y0) * 4 + (x - x0) of its first `slots` pixels in row-major order, `bits` bits
// each (0 for slots past the last), and in the top byte how many pixels the set holds. The
// vectorized setup looks its lanes' coverage up here instead of tracking the first pixels
// while testing them.
template <uint32_t kPixels>
constexpr std::array<uint32_t, (1u << kPixels)> first_pixels_table(uint32_t slots, uint32_t bits) {
  std::array<uint32_t, (1u << kPixels)> table{};
  for (uint32_t mask = 0; mask < table.size(); ++mask) {
    uint32_t entry = 0, count = 0;
    for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
      if ((mask & (1u << pixel)) == 0) continue;
      if (count < slots) entry |= ((pixel / 3) * 4 + pixel % 3) << (bits * count);
      ++count;
    }
    table[mask] = entry | count << 24;
  }
  return table;
}

// The pixel records' entries: PixelRecord::offset's bytes.
inline constexpr std::array<uint32_t, 512> kFirstPixels =
    first_pixels_table<9>(kPixelRecordPixels, 8);

// A bin reference with this bit set names a pixel record (one sample) or a sample record (two
// or four); without it, a TriangleSetup.
inline constexpr uint32_t kPixelRecordBit = 0x80000000u;

using PixelList = detail::UninitializedVector<PixelRecord>;

// Sample records, the multisample counterpart: at two or four samples per pixel, a small
// triangle whose box is at most 3 pixels wide and 4 high and which has covered samples in at most
// kSampleRecordPixels pixels, none beyond its horizon at the pixel centre, is stored as its pixels'
// sample masks, depth planes and colours in one 64-byte line instead of a 160-byte TriangleSetup.
// The raster phase tests each covered sample's depth, formed as the kernels form it from the same
// float values, and writes the colour shaded once per pixel.
struct SampleRecord {
  uint16_t x0, y0;  // the bounding box's first pixel
  // Bits 0-7, the shape: bits 0-2 the pixels with a covered sample (1 to 5), bits 3-4 and 5-6
  // the box's width and height in pixels, less one (0 to 2 and 0 to 3). From bit 8, pixel i's
  // place in the box, (y - y0) * 4 + (x - x0), in bits 8 + 4i to 11 + 4i, in row-major order.
  uint32_t shape_places;
  uint32_t coverage;  // pixel i's covered samples (bit s: sample s) in bits 4i to 4i + 3
  float z_dx, z_dy;   // the depth plane's gradients per pixel (TriangleSetup's)
  // Pixel i's depth plane at the first pixel of its 8x8 block (the kernels' block base), and
  // its colour at its centre, packed as the RGBA8 target stores it.
  float z_base[5];
  uint32_t rgba8[5];
  uint32_t unused;  // to 64 bytes: one cache line

  // The fields of shape_places.
  uint32_t pixels() const { return shape_places & 7u; }
  int32_t last_x() const { return static_cast<int32_t>((shape_places >> 3) & 3u); }  // width - 1
  int32_t last_y() const { return static_cast<int32_t>((shape_places >> 5) & 3u); }  // height - 1
  uint32_t place(uint32_t i) const { return (shape_places >> (8 + 4 * i)) & 15u; }
  // Pixel i's covered samples.
  uint32_t samples(uint32_t i) const { return (coverage >> (4 * i)) & 15u; }
};
static_assert(sizeof(SampleRecord) == 64 &&
              std::is_trivially_default_constructible_v<SampleRecord>);

// The most pixels a sample record holds.
inline constexpr uint32_t kSampleRecordPixels = 5;

// The boxes a sample record may have: at most 3 pixels wide and 4 high, 12 pixels.
inline constexpr uint32_t kSampleRecordBoxPixels = 12;

// The sample records' entries: SampleRecord::shape_places' places.
inline constexpr std::array<uint32_t, (1u << kSampleRecordBoxPixels)> kFirstSamplePixels =
    first_pixels_table<kSampleRecordBoxPixels>(kSampleRecordPixels, 4);

using SampleList = detail::UninitializedVector<SampleRecord>;

// A pixel's offsets for plane evaluation, as the kernels form them for its lane: from its 8x8
// block's first pixel (fx, fy), and from that pixel to the plane origin (dx, dy).
struct PixelOffsets {
  PixelOffsets(const TriangleSetup& t, int32_t x, int32_t y)
      : fx(static_cast<float>(x & 7)),
        fy(static_cast<float>(y & 7)),
        dx((x >> 3) * 8.0 - t.x0),
        dy((y >> 3) * 8.0 - t.y0) {}
  float fx, fy;
  double dx, dy;
};

// z at the pixel's centre, clamped to [0, 1]: the block's base in double, then the offset in
// float (raster_block's sum).
inline float centre_depth(const TriangleSetup& t, const PixelOffsets& o) {
  const float z_base = static_cast<float>(t.z0 + t.z_dx * o.dx + t.z_dy * o.dy);
  const float z = z_base + (o.fx * t.z_dx + o.fy * t.z_dy);
  return z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f;  // hn::Min(hn::Max(z, 0), 1)
}

// The colour of a pixel drawn one by one: the plane sums raster_block forms for its lane
// (bases at the block's first pixel, then the offset to the pixel), divided by q. Beyond the
// triangle's horizon at the pixel centre (q <= 0), raster_block evaluates at the pixel's first
// passing sample, (sample_fx, sample_fy) pixels from the centre, which is inside the triangle.
inline void pixel_colour(const TriangleSetup& t, const PixelOffsets& o, float sample_fx,
                         float sample_fy, float (&channel)[4]) {
  const float fdx = static_cast<float>(o.dx), fdy = static_cast<float>(o.dy);
  float qa_base[4];
  for (int c = 0; c < 4; ++c) {
    qa_base[c] = t.qa0[c] + (t.qa_dx[c] * fdx + t.qa_dy[c] * fdy);
    channel[c] = qa_base[c] + (o.fx * t.qa_dx[c] + o.fy * t.qa_dy[c]);
  }
  if (t.flat_q) return;
  const float q_base = t.q0 + (t.q_dx * fdx + t.q_dy * fdy);
  const float q = q_base + (o.fx * t.q_dx + o.fy * t.q_dy);
  if (q > 0.0f) {
    const float inv_q = 1.0f / q;
    for (float& v : channel)
      v *= inv_q;
    return;
  }
  const float sx = o.fx + sample_fx, sy = o.fy + sample_fy;
  const float qs = q_base + (t.q_dx * sx + t.q_dy * sy);
  for (int c = 0; c < 4; ++c)
    channel[c] = (qa_base[c] + (t.qa_dx[c] * sx + t.qa_dy[c] * sy)) / qs;
}

// A colour as the RGBA8 target stores it.
inline uint32_t pack_rgba8(const float (&channel)[4]) {
  return uint32_t{to_unorm8(channel[0])} | uint32_t{to_unorm8(channel[1])} << 8 |
         uint32_t{to_unorm8(channel[2])} << 16 | uint32_t{to_unorm8(channel[3])} << 24;
}

}  // namespace tessera::fast
