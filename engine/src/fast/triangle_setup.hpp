// Triangle setup for the fast engine, done once per triangle: clip when needed, snap to fixed
// point, cull, and turn the triangle into edge equations and attribute planes that the tile
// kernels evaluate incrementally (Pineda 1988; Olano and Greer 1997 for the planes).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "binning/bins.hpp"
#include "engine/src/aligned_allocator.hpp"
#include "engine/src/clip.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/shade/layout.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// One triangle ready to rasterize, oriented so that its area is positive in y-down window
// space (clockwise on screen).
//
// Edge k (opposite vertex k) is E_k(X, Y) = a[k] * X + b[k] * Y + c[k] over fixed-point sample
// positions, with the top-left rule folded into c: a sample is inside when E_k >= 0 for all k.
// Ranges (window coordinates below 2^16 px after guard-band clipping, 8 subpixel bits):
// |X|, |Y| < 2^24, so |a|, |b| < 2^25, |c| < 2^50 and |E| < 2^51 at any sample: exact in
// int64. `narrow` says 32-bit lanes can step the triangle exactly inside one 8x8 block: see
// block_kernel.hpp for the bound.
struct TriangleSetup {
  // The 8-byte fields first and the 4-byte ones after them, in the order the vectorized setup
  // writes them (setup_kernel.cpp: two 16-byte pieces of 8-byte fields, then eight of 4-byte).
  std::array<int64_t, 3> c;
  // Planes over pixel coordinates, as value at the centre of pixel (x0, y0) plus gradients per
  // pixel (z0 below, the gradients further down). z is z/w in [0, 1]. q is 1/w scaled so its
  // largest vertex value is 1 (1 everywhere for affine interpolation); qa[c] is q times colour
  // channel c, so colour = qa / q.
  double z0;
  std::array<int32_t, 3> a;
  std::array<int32_t, 3> b;
  // The pixels with a sample inside the triangle's bounding box (inclusive), on screen: none
  // outside may be covered.
  int32_t x0, y0, x1, y1;
  bool narrow;
  bool small;   // every edge spans under 32 px in x and in y (see block_kernel-inl.h)
  bool flat_q;  // q is 1 everywhere (affine, or every vertex has the same w): no division
  // One sample per pixel and a bounding box of at most 2x2 pixels: which of its pixel centres
  // are inside, bit (y - y0) * 4 + (x - x0), from exact edge functions. 0 when not known (any
  // other triangle, and draws that take pixel records, whose setup tests boxes up to 3x3 for
  // the records instead): the kernel then tests the edges itself, pixel centre by pixel centre
  // for boxes up to kCentresBox (3) pixels across and down (block_kernel-inl.h).
  uint8_t centres;
  float z_dx, z_dy;
  float z_min, z_max;  // over the vertices
  float q0;
  float q_dx, q_dy;
  std::array<float, 4> qa0;
  std::array<float, 4> qa_dx, qa_dy;
  // Two or four samples per pixel, a small triangle and a bounding box of at most 3x3 pixels
  // whose samples fit 32 bits (any at two samples; at four, all but 3x3): which samples are
  // inside, bit ((y - y0) * 3 + (x - x0)) * samples + s, from exact edge functions. 0 when not
  // known (any other triangle): the kernel then tests the edges itself.
  uint32_t sample_bits;
  // 1 when q is flat (q = 1), every vertex's four colour channels lie in [0, 1] (so the exact
  // colour planes lie in [0, 1] over the triangle) and the largest colour gradient G (per pixel,
  // in x or y) times the box's reach (x1 - x0) + (y1 - y0) + 15 is at most kUnitColourReach; 0
  // otherwise, or when not known (set at one sample per pixel only). The kernels then pack
  // RGBA8 at one sample without a clamp (block_kernel-inl.h, packs_without_clamp).
  uint32_t unit_colour;  // (the last 4 bytes: 160 in all, ten 16-byte pieces)
};

// TriangleSetup::unit_colour's bound on a triangle's colour gradients times its box's reach.
inline constexpr float kUnitColourReach = 512.0f;

// Setups of one worker's range of a draw (large: see aligned_allocator.hpp). The vectorized
// setup appends uninitialized records and fills them with streaming stores.
static_assert(std::is_trivially_default_constructible_v<TriangleSetup>);
static_assert(sizeof(TriangleSetup) == 160 && offsetof(TriangleSetup, a) == 32 &&
              offsetof(TriangleSetup, x0) == 56 && offsetof(TriangleSetup, narrow) == 72 &&
              offsetof(TriangleSetup, z_dx) == 76 && offsetof(TriangleSetup, qa0) == 104 &&
              offsetof(TriangleSetup, sample_bits) == 152);
using SetupList = detail::UninitializedVector<TriangleSetup>;

// A shaded draw's planes (shade/layout.hpp), beside its setups: setup i's interpolant j is the
// plane value + gx * x + gy * y over pixel offsets from the centre of pixel (x0, y0), with its
// value, gx and gy at floats 3 * (i * layout.count + j) + 0, 1, 2. A perspective-correct
// interpolant's plane is of q times the value (divided by the q plane per pixel), an affine
// one's of the value, and a flat one's is the first vertex's value with zero gradients.
using PlaneList = detail::UninitializedVector<float>;

struct SetupContext {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t subpixel_bits = 8;
  uint32_t attribute_count = 0;
  // The colour's first varying (PipelineState::roles.color) and how many of its four channels
  // the draw has (missing ones read as 0, 0, 0, 1).
  uint32_t color_first = 0;
  uint32_t color_count() const {
    return attribute_count > color_first ? std::min(attribute_count - color_first, 4u) : 0;
  }
  const PipelineState* pipeline = nullptr;
  DepthFormat depth_format = DepthFormat::kFloat32;  // r of the depth bias (depth_bias.hpp)
  GuardBand guard_band;
  // The samples' offsets from the pixel centre, smallest and largest over the pattern, in 1/16
  // pixel (sample_positions.hpp): the bounding box keeps only pixels with a sample inside the
  // triangle's. The defaults hold every pattern.
  int32_t sample_dx_lo = -8, sample_dx_hi = 8;
  int32_t sample_dy_lo = -8, sample_dy_hi = 8;
  // The samples per pixel and their offsets in 1/16 pixel, for TriangleSetup::sample_bits.
  uint32_t samples = 1;
  std::array<int32_t, 16> sample_dx{}, sample_dy{};
  // The draw's positions and colours were not checked for NaN and infinity: the vectorized
  // setup checks each batch it reads (setup_kernel.hpp).
  bool check_finite = false;
  // log2 of the bin tiles' side in pixels: the vectorized setup records each setup's tiles.
  uint32_t bin_tile_log2 = 6;

  // One sample per pixel, at its centre.
  bool centre_sample_only() const {
    return sample_dx_lo == 0 && sample_dx_hi == 0 && sample_dy_lo == 0 && sample_dy_hi == 0;
  }
  // One sample per pixel and a colour target that is RGBA8 or not written: the vectorized
  // setup turns triangles that cover at most three pixels of a box of at most 3x3 into pixel
  // records (pixel_record.hpp).
  bool pixel_records = false;
  // Two or four samples per pixel and a colour target that is RGBA8 or not written: the
  // vectorized setup turns small triangles whose covered samples lie in at most five pixels of
  // a box of at most 3 pixels across and 4 down into sample records (pixel_record.hpp).
  bool sample_records = false;

  // Sets samples, sample_dx / sample_dy and their extremes from a sample pattern
  // (sample_pattern(n)).
  void set_sample_pattern(std::span<const SampleOffset> pattern);

  // Whether small triangles' setups carry TriangleSetup::sample_bits.
  bool small_sample_bits() const { return samples == 2 || samples == 4; }
};

// Sets up one input triangle through the clipper shared with the reference: clip-space
// positions as given to the draw (the pipeline's depth convention) and each vertex's
// attributes (attribute_count floats; null when there are none). Appends one setup per piece
// that survives clipping and culling. The vectorized setup (setup_kernel.hpp) sends here the
// triangles a clip plane cuts.
void setup_triangle(const SetupContext& context, const std::array<const Float4*, 3>& positions,
                    const std::array<const float*, 3>& attributes, SetupList& out,
                    Counters& counters);

// Sets up one triangle of a shaded draw (layout.shader is not kGouraud) the same way, with the
// layout's planes appended to `planes` for each setup appended to `out`: `varyings` are each
// vertex's attribute_count varyings, `primitive` the triangle's index in the draw. Its flat
// interpolants take the first vertex's values, clipped or not, and its setups carry no colour
// planes.
void setup_shaded_triangle(const SetupContext& context, const shade::Layout& layout,
                           const std::array<const Float4*, 3>& positions,
                           const std::array<const float*, 3>& varyings, uint32_t primitive,
                           SetupList& out, PlaneList& planes, Counters& counters);

// Sets up triangles [begin, end) of a shaded draw in order with setup_shaded_triangle,
// recording each setup's bin tiles (context.bin_tile_log2) and index in `bins`. The triangles'
// primitive indices are `primitive_ids[t]`, or t where that is empty.
void setup_shaded_range(const SetupContext& context, const shade::Layout& layout,
                        const DrawInput& input, std::span<const uint32_t> primitive_ids,
                        size_t begin, size_t end, SetupList& out, PlaneList& planes,
                        binning::Bins& bins, Counters& counters);

}  // namespace tessera::fast
