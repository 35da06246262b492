// Fixed-point triangle setup; the conventions (window mapping, snapping, fill rule, culling)
// follow ARCHITECTURE.md section 2 to the bit, as the reference rasterizer does. Triangles
// inside every clip plane (nearly all) go straight from the caller's floats to the setup; only
// the others take the general clipper shared with the reference.
#include "engine/src/fast/triangle_setup.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/src/depth_bias.hpp"
#include "engine/src/fast/block_kernel.hpp"

namespace tessera::fast {

namespace {

struct Snapped {
  int64_t x, y;  // fixed point, y down
  double z;      // z / w
  double inv_w;
  // The colour (a Gouraud draw), or a shaded draw's interpolants.
  std::array<double, shade::kMaxInterpolants> value;
};
static_assert(shade::kMaxInterpolants >= 4);

// What setup_snapped needs for a shaded draw's planes: the layout, the first vertex's values
// (the flat interpolants'), and where the planes go.
struct ShadedPlanes {
  const shade::Layout& layout;
  const std::array<double, shade::kMaxInterpolants>& flat;
  PlaneList& planes;
};

// Round to nearest, ties to even, for |v| < 2^51: adding and subtracting 1.5 * 2^52 leaves
// the integer part, rounded by the FPU's default mode. Same result as std::nearbyint, without
// a library call.
inline int64_t round_to_int(double v) {
  constexpr double kMagic = 6755399441055744.0;
  return static_cast<int64_t>((v + kMagic) - kMagic);
}

// window x = (x / w + 1) * width / 2, window y = (1 - y / w) * height / 2, in double, then
// round to nearest (ties to even) at 2^subpixel_bits: the convention both rasterizers share.
// Multiplying by 2^bits is exact, as ldexp is.
Snapped snap(double x, double y, double z, double w, const SetupContext& ctx) {
  const double scale = static_cast<double>(1u << ctx.subpixel_bits);
  const double wx = (x / w + 1.0) * (0.5 * ctx.width);
  const double wy = (1.0 - y / w) * (0.5 * ctx.height);
  Snapped s;
  s.x = round_to_int(wx * scale);
  s.y = round_to_int(wy * scale);
  s.z = z / w;
  s.inv_w = 1.0 / w;
  return s;
}

// Sets up a snapped triangle: with `shaded`, a shaded draw's (its planes appended beside the
// setup), else a Gouraud draw's, whose setup holds the colour planes.
void setup_snapped(const SetupContext& ctx, const std::array<Snapped, 3>& in, SetupList& out,
                   Counters& counters, const ShadedPlanes* shaded = nullptr) {
  // The vertices by reference (each carries up to kMaxInterpolants values: copies would cost
  // more than the setup of a small triangle), in the order the setup takes them.
  std::array<const Snapped*, 3> v = {&in[0], &in[1], &in[2]};
  int64_t area =
      (v[1]->x - v[0]->x) * (v[2]->y - v[0]->y) - (v[1]->y - v[0]->y) * (v[2]->x - v[0]->x);
  if (area == 0) {
    ++counters.triangles_culled;
    return;
  }
  const PipelineState& p = *ctx.pipeline;
  // y points down in window space: counter-clockwise in NDC (y up) means negative area here.
  const bool front = (area < 0) == (p.front_face == FrontFace::kCounterClockwise);
  if ((p.cull == CullMode::kBack && !front) || (p.cull == CullMode::kFront && front)) {
    ++counters.triangles_culled;
    return;
  }
  if (area < 0) {
    std::swap(v[1], v[2]);
    area = -area;
  }

  const int bits = static_cast<int>(ctx.subpixel_bits);
  const int shift = bits - 4;
  TriangleSetup t;
  const int64_t lo_x = std::min({v[0]->x, v[1]->x, v[2]->x}),
                hi_x = std::max({v[0]->x, v[1]->x, v[2]->x});
  const int64_t lo_y = std::min({v[0]->y, v[1]->y, v[2]->y}),
                hi_y = std::max({v[0]->y, v[1]->y, v[2]->y});
  if (hi_x < 0 || hi_y < 0 || lo_x >= int64_t{ctx.width} << bits ||
      lo_y >= int64_t{ctx.height} << bits) {  // inside the guard band but off screen
    ++counters.triangles_culled;
    return;
  }
  ++counters.triangles_rasterized;
  // The pixels with a sample between the vertices' smallest and largest coordinates: pixel i's
  // samples lie at (16 i + 8 + d) << shift for the pattern's offsets d (>> floors; ceil(n / 2^b)
  // is -floor(-n / 2^b)). None: the triangle covers no sample.
  t.x0 = static_cast<int32_t>(
      std::max<int64_t>(-(((int64_t{8 + ctx.sample_dx_hi} << shift) - lo_x) >> bits), 0));
  t.y0 = static_cast<int32_t>(
      std::max<int64_t>(-(((int64_t{8 + ctx.sample_dy_hi} << shift) - lo_y) >> bits), 0));
  t.x1 = static_cast<int32_t>(
      std::min<int64_t>((hi_x - (int64_t{8 + ctx.sample_dx_lo} << shift)) >> bits, ctx.width - 1));
  t.y1 = static_cast<int32_t>(
      std::min<int64_t>((hi_y - (int64_t{8 + ctx.sample_dy_lo} << shift)) >> bits, ctx.height - 1));
  if (t.x0 > t.x1 || t.y0 > t.y1) return;  // not drawn, but not culled either

  // Edge k runs from vertex k+1 to vertex k+2: E(p) = (bx - ax)(py - ay) - (by - ay)(px - ax).
  // Planes: a vertex value v_k spreads as E_k / area (the barycentric of vertex k), so the
  // gradient per fixed-point unit is sum v_k * a_k / area. Values are taken at the centre of
  // pixel (x0, y0) from the exact (unbiased) edge functions.
  const int64_t cx = (int64_t{t.x0} * 16 + 8) << shift;
  const int64_t cy = (int64_t{t.y0} * 16 + 8) << shift;
  const double inv_area = 1.0 / static_cast<double>(area);
  const double per_pixel = static_cast<double>(1u << bits) * inv_area;
  double weight0[3], wdx[3], wdy[3];  // barycentrics at the origin and per pixel
  int64_t max_step = 0, max_delta = 0;
  for (int k = 0; k < 3; ++k) {
    const Snapped& from = *v[(k + 1) % 3];
    const Snapped& to = *v[(k + 2) % 3];
    const int64_t dx = to.x - from.x, dy = to.y - from.y;
    // Top-left rule (clockwise on screen, y down): a top edge is horizontal running to +x, a
    // left edge runs upwards. Samples exactly on other edges are outside: bias c by -1.
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    t.a[k] = static_cast<int32_t>(-dy);
    t.b[k] = static_cast<int32_t>(dx);
    t.c[k] = dy * from.x - dx * from.y - (top_left ? 0 : 1);
    max_step = std::max(max_step, std::abs(dy) + std::abs(dx));
    max_delta = std::max({max_delta, std::abs(dy), std::abs(dx)});
    weight0[k] = static_cast<double>(dx * (cy - from.y) - dy * (cx - from.x)) * inv_area;
    wdx[k] = static_cast<double>(-dy) * per_pixel;
    wdy[k] = static_cast<double>(dx) * per_pixel;
  }
  t.centres = 0;
  if (ctx.centre_sample_only() && t.x1 - t.x0 <= 1 && t.y1 - t.y0 <= 1) {
    // One sample per pixel and at most 2x2 pixels: drawn only if a pixel centre is inside,
    // and the kernel is told which.
    for (int32_t py = t.y0; py <= t.y1; ++py) {
      for (int32_t px = t.x0; px <= t.x1; ++px) {
        const int64_t sx = (int64_t{px} * 16 + 8) << shift, sy = (int64_t{py} * 16 + 8) << shift;
        bool inside = true;
        for (int k = 0; k < 3; ++k)
          inside &= t.a[k] * sx + t.b[k] * sy + t.c[k] >= 0;
        if (inside) t.centres |= static_cast<uint8_t>(1u << ((py - t.y0) * 4 + (px - t.x0)));
      }
    }
    if (t.centres == 0) return;
  }
  t.sample_bits = 0;
  t.small = max_delta < (int64_t{32} << bits);
  if (ctx.small_sample_bits() && t.small && t.x1 - t.x0 <= 2 && t.y1 - t.y0 <= 2 &&
      static_cast<uint32_t>((t.y1 - t.y0) * 3 + (t.x1 - t.x0) + 1) * ctx.samples <= 32) {
    // Two or four samples, a small triangle and at most 3x3 pixels whose samples fit 32 bits
    // (as the vectorized setup): drawn only if a sample is inside, and the kernel is told which.
    for (int32_t py = t.y0; py <= t.y1; ++py) {
      for (int32_t px = t.x0; px <= t.x1; ++px) {
        const uint32_t pixel = static_cast<uint32_t>((py - t.y0) * 3 + (px - t.x0));
        for (uint32_t s = 0; s < ctx.samples; ++s) {
          const int64_t sx = (int64_t{px} * 16 + 8 + ctx.sample_dx[s]) << shift;
          const int64_t sy = (int64_t{py} * 16 + 8 + ctx.sample_dy[s]) << shift;
          bool inside = true;
          for (int k = 0; k < 3; ++k)
            inside &= t.a[k] * sx + t.b[k] * sy + t.c[k] >= 0;
          if (inside) t.sample_bits |= 1u << (pixel * ctx.samples + s);
        }
      }
    }
    if (t.sample_bits == 0) return;
  }
  t.narrow = max_step < narrow_edge_limit(ctx.subpixel_bits);

  auto plane = [&](double v0, double v1, double v2, double& at0, float& gx, float& gy) {
    at0 = weight0[0] * v0 + weight0[1] * v1 + weight0[2] * v2;
    gx = static_cast<float>(wdx[0] * v0 + wdx[1] * v1 + wdx[2] * v2);
    gy = static_cast<float>(wdy[0] * v0 + wdy[1] * v1 + wdy[2] * v2);
  };
  double z[3] = {v[0]->z, v[1]->z, v[2]->z};
  if (has_depth_bias(p)) {  // depth_bias.hpp, added to each vertex's z
    const double gx = wdx[0] * z[0] + wdx[1] * z[1] + wdx[2] * z[2];
    const double gy = wdy[0] * z[0] + wdy[1] * z[1] + wdy[2] * z[2];
    const double z_abs_max = std::max({std::abs(z[0]), std::abs(z[1]), std::abs(z[2])});
    const double bias = depth_bias(p, depth_bias_unit(ctx.depth_format, z_abs_max), gx, gy);
    for (double& value : z)
      value += bias;
  }
  plane(z[0], z[1], z[2], t.z0, t.z_dx, t.z_dy);
  t.z_min = static_cast<float>(std::clamp(std::min({z[0], z[1], z[2]}), 0.0, 1.0));
  t.z_max = static_cast<float>(std::clamp(std::max({z[0], z[1], z[2]}), 0.0, 1.0));

  double q[3] = {1.0, 1.0, 1.0};
  const bool needs_q = shaded ? shaded->layout.needs_q : p.interpolation != Interpolation::kAffine;
  t.flat_q = !needs_q || (v[0]->inv_w == v[1]->inv_w && v[1]->inv_w == v[2]->inv_w);
  if (!t.flat_q) {
    const double q_max = std::max({v[0]->inv_w, v[1]->inv_w, v[2]->inv_w});
    for (int k = 0; k < 3; ++k)
      q[k] = v[k]->inv_w / q_max;
  }
  double at0;
  plane(q[0], q[1], q[2], at0, t.q_dx, t.q_dy);
  t.q0 = static_cast<float>(at0);
  if (shaded) {
    // The interpolants' planes; the colour planes are not read.
    const shade::Layout& layout = shaded->layout;
    for (int c = 0; c < 4; ++c)
      t.qa0[c] = t.qa_dx[c] = t.qa_dy[c] = 0.0f;
    t.unit_colour = 0;
    const size_t at = shaded->planes.size();
    shaded->planes.resize(at + 3 * size_t{layout.count});
    float* plane_out = shaded->planes.data() + at;
    for (uint32_t j = 0; j < layout.count; ++j, plane_out += 3) {
      const VaryingMode mode = layout.values[j].mode;
      if (layout.values[j].source == shade::Source::kPrimitiveBits) {
        plane_out[0] = std::bit_cast<float>(static_cast<uint32_t>(shaded->flat[j]));
        plane_out[1] = plane_out[2] = 0.0f;
        continue;
      }
      if (mode == VaryingMode::kFlat) {
        plane_out[0] = static_cast<float>(shaded->flat[j]);
        plane_out[1] = plane_out[2] = 0.0f;
        continue;
      }
      const double* w = mode == VaryingMode::kPerspective ? q : nullptr;
      const auto scaled = [&](int k) { return (w ? w[k] : 1.0) * v[k]->value[j]; };
      plane(scaled(0), scaled(1), scaled(2), at0, plane_out[1], plane_out[2]);
      plane_out[0] = static_cast<float>(at0);
    }
    out.push_back(t);
    return;
  }
  for (int c = 0; c < 4; ++c) {
    plane(q[0] * v[0]->value[c], q[1] * v[1]->value[c], q[2] * v[2]->value[c], at0, t.qa_dx[c],
          t.qa_dy[c]);
    t.qa0[c] = static_cast<float>(at0);
  }
  bool unit = ctx.samples == 1 && t.flat_q;
  float gradient = 0.0f;
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k < 3; ++k)
      unit = unit && v[k]->value[c] >= 0.0 && v[k]->value[c] <= 1.0;
    gradient = std::max({gradient, std::abs(t.qa_dx[c]), std::abs(t.qa_dy[c])});
  }
  const float reach = static_cast<float>((t.x1 - t.x0) + (t.y1 - t.y0) + 15);
  t.unit_colour = unit && gradient * reach <= kUnitColourReach ? 1 : 0;
  out.push_back(t);
}

// Clips triangle `tri`, whose first `count` values the clipper carries (those for which
// affine(j) holds as a * w: see setup_triangle), and sets up each piece of the fan it leaves
// with its values divided back by w where affine; `shaded` as setup_snapped's.
template <class Affine>
void clip_and_set_up(const SetupContext& ctx, const std::array<ClipVertex, 3>& tri, uint32_t count,
                     const Affine& affine, SetupList& out, Counters& counters,
                     const ShadedPlanes* shaded) {
  ClipPolygon polygon;
  const ClipResult clip = clip_triangle(tri, count, ctx.guard_band, polygon);
  if (clip.clipped) ++counters.triangles_clipped;
  if (!clip.visible) {
    ++counters.triangles_culled;
    return;
  }
  std::array<Snapped, kMaxClipVertices> s;
  for (int i = 0; i < polygon.count; ++i) {
    const ClipVertex& v = polygon.vertices[i];
    s[i] = snap(v.x, v.y, v.z, v.w, ctx);
    for (uint32_t j = 0; j < count; ++j)
      s[i].value[j] = affine(j) ? v.attributes[j] / v.w : v.attributes[j];
  }
  for (int i = 1; i + 1 < polygon.count; ++i)
    setup_snapped(ctx, {s[0], s[i], s[i + 1]}, out, counters, shaded);
}

// The colour attributes of a vertex: the first four, missing ones (0, 0, 0, 1).
std::array<double, 4> color_of(const float* attributes, uint32_t count) {
  std::array<double, 4> c{0.0, 0.0, 0.0, 1.0};
  for (uint32_t i = 0; i < std::min(count, 4u); ++i)
    c[i] = attributes[i];
  return c;
}

}  // namespace

void SetupContext::set_sample_pattern(std::span<const SampleOffset> pattern) {
  samples = static_cast<uint32_t>(pattern.size());
  sample_dx_lo = sample_dx_hi = pattern[0].dx;
  sample_dy_lo = sample_dy_hi = pattern[0].dy;
  for (size_t s = 0; s < pattern.size(); ++s) {
    sample_dx[s] = pattern[s].dx;
    sample_dy[s] = pattern[s].dy;
    sample_dx_lo = std::min<int32_t>(sample_dx_lo, pattern[s].dx);
    sample_dx_hi = std::max<int32_t>(sample_dx_hi, pattern[s].dx);
    sample_dy_lo = std::min<int32_t>(sample_dy_lo, pattern[s].dy);
    sample_dy_hi = std::max<int32_t>(sample_dy_hi, pattern[s].dy);
  }
}

void setup_triangle(const SetupContext& ctx, const std::array<const Float4*, 3>& positions,
                    const std::array<const float*, 3>& attributes, SetupList& out,
                    Counters& counters) {
  ++counters.triangles_submitted;
  const bool gl_depth = ctx.pipeline->clip_depth == ClipDepth::kNegativeOneToOne;
  const uint32_t count = ctx.color_count();
  // Clipping interpolates attributes linearly in clip space, right for perspective-correct
  // ones; affine ones are linear in screen space, so they are clipped as a * w and divided by
  // the new w (as the reference does; OpenGL 4.6 section 13.7).
  const bool affine = ctx.pipeline->interpolation == Interpolation::kAffine;
  std::array<ClipVertex, 3> tri;
  for (int k = 0; k < 3; ++k) {
    const Float4& p = *positions[k];
    tri[k].x = p.x;
    tri[k].y = p.y;
    tri[k].w = p.w;
    // OpenGL's -w <= z <= w becomes 0 <= z <= w: z' = (z + w) / 2, linear, so clipping and
    // interpolation commute with it.
    tri[k].z = gl_depth ? 0.5 * (double{p.z} + p.w) : p.z;
    const std::array<double, 4> c = count ? color_of(attributes[k], count) : color_of(nullptr, 0);
    for (int i = 0; i < 4; ++i)
      tri[k].attributes[i] = affine ? c[i] * tri[k].w : c[i];
  }
  clip_and_set_up(
      ctx, tri, 4, [&](uint32_t) { return affine; }, out, counters, nullptr);
}

void setup_shaded_triangle(const SetupContext& ctx, const shade::Layout& layout,
                           const std::array<const Float4*, 3>& positions,
                           const std::array<const float*, 3>& varyings, uint32_t primitive,
                           SetupList& out, PlaneList& planes, Counters& counters) {
  ++counters.triangles_submitted;
  const bool gl_depth = ctx.pipeline->clip_depth == ClipDepth::kNegativeOneToOne;
  // Each vertex's position (OpenGL's z as setup_triangle maps it) and interpolant values.
  std::array<std::array<double, 4>, 3> clip;
  std::array<std::array<double, shade::kMaxInterpolants>, 3> value;
  for (int k = 0; k < 3; ++k) {
    const Float4& p = *positions[k];
    clip[k] = {p.x, p.y, gl_depth ? 0.5 * (double{p.z} + p.w) : p.z, p.w};
    for (uint32_t j = 0; j < layout.count; ++j) {
      const shade::Interpolant& in = layout.values[j];
      switch (in.source) {
        case shade::Source::kVarying:
          value[k][j] = varyings[k][in.index];
          break;
        case shade::Source::kClipW:
          value[k][j] = p.w;
          break;
        case shade::Source::kBarycentric:
          value[k][j] = in.index == static_cast<uint32_t>(k) ? 1.0 : 0.0;
          break;
        case shade::Source::kPrimitive:
        case shade::Source::kPrimitiveBits:
          value[k][j] = primitive;
          break;
      }
    }
  }
  // The flat interpolants take the provoking vertex's values, clipped or not.
  const ShadedPlanes shaded{layout, value[0], planes};
  if (inside_clip_planes(clip, ctx.guard_band)) {
    // No plane cuts it (nearly every triangle): the clipper would return it as it is.
    std::array<Snapped, 3> s;
    for (int k = 0; k < 3; ++k) {
      s[k] = snap(clip[k][0], clip[k][1], clip[k][2], clip[k][3], ctx);
      std::copy_n(value[k].begin(), layout.count, s[k].value.begin());
    }
    setup_snapped(ctx, s, out, counters, &shaded);
    return;
  }
  // Affine values are clipped as a * w and divided by the new w (see setup_triangle).
  const auto affine = [&](uint32_t j) { return layout.values[j].mode == VaryingMode::kAffine; };
  std::array<ClipVertex, 3> tri;
  for (int k = 0; k < 3; ++k) {
    tri[k].x = clip[k][0];
    tri[k].y = clip[k][1];
    tri[k].z = clip[k][2];
    tri[k].w = clip[k][3];
    for (uint32_t j = 0; j < layout.count; ++j)
      tri[k].attributes[j] = affine(j) ? value[k][j] * tri[k].w : value[k][j];
  }
  clip_and_set_up(ctx, tri, layout.count, affine, out, counters, &shaded);
}

void setup_shaded_range(const SetupContext& ctx, const shade::Layout& layout,
                        const DrawInput& input, std::span<const uint32_t> primitive_ids,
                        size_t begin, size_t end, SetupList& out, PlaneList& planes,
                        binning::Bins& bins, Counters& counters) {
  const bool indexed = !input.indices.empty();
  const uint32_t count = input.attribute_count;
  for (size_t t = begin; t < end; ++t) {
    std::array<const Float4*, 3> position;
    std::array<const float*, 3> varying{};
    for (int k = 0; k < 3; ++k) {
      const size_t vertex = indexed ? input.indices[t * 3 + k] : t * 3 + k;
      position[k] = &input.positions[vertex];
      if (count) varying[k] = &input.attributes[vertex * count];
    }
    const size_t first = out.size();
    const uint32_t primitive = primitive_ids.empty() ? static_cast<uint32_t>(t) : primitive_ids[t];
    setup_shaded_triangle(ctx, layout, position, varying, primitive, out, planes, counters);
    for (size_t i = first; i < out.size(); ++i) {
      const TriangleSetup& setup = out[i];
      bins.record(
          binning::tile_rect(static_cast<uint32_t>(setup.x0), static_cast<uint32_t>(setup.y0),
                             static_cast<uint32_t>(setup.x1), static_cast<uint32_t>(setup.y1),
                             ctx.bin_tile_log2),
          static_cast<uint32_t>(i));
    }
  }
}

}  // namespace tessera::fast
