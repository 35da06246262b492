// The scalar reference rasterizer: ARCHITECTURE.md section 2 in its plainest form.
// For each triangle: clip (clip.hpp), map to the window, snap to fixed point, then test every
// sample of the bounding box against three exact 64-bit edge functions (Pineda 1988) with the
// top-left fill rule of D3D11/Vulkan. No tiles, no SIMD, no threads, no hierarchy, no Hi-Z:
// a person checking one pixel by hand can follow every step.
//
// Numeric range: after guard-band clipping a window coordinate lies within 2^15 pixels of the
// viewport centre, and the viewport is at most 2^14 pixels wide, so |coordinate| < 2^16
// pixels, i.e. < 2^24 in fixed point with 8 fractional bits. An edge function is a difference
// of two products of such differences (< 2^25 each), so |E| < 2^51: exact in int64.
#include "engine/src/reference/reference_raster.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "engine/src/blend/blend.hpp"
#include "engine/src/clip.hpp"
#include "engine/src/depth_bias.hpp"
#include "engine/src/reference/reference_sampler.hpp"
#include "engine/src/reference/reference_shade.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/scissor.hpp"
#include "engine/src/shade/user_batch.hpp"
#include "engine/src/shading_state.hpp"

namespace tessera::reference {

namespace {

// A vertex in window space: snapped fixed-point position, depth and 1/w.
struct WindowVertex {
  int64_t x = 0;     // window x * 2^subpixel_bits, rounded to nearest (ties to even)
  int64_t y = 0;     // window y (downwards) * 2^subpixel_bits
  double z = 0;      // z / w, in [0, 1]
  double inv_w = 0;  // 1 / w
  const ClipVertex* clip = nullptr;  // for the attributes
};

// Viewport transform and snapping, the convention both rasterizers follow to the bit:
//   window x = (x / w + 1) * width / 2,  window y = (1 - y / w) * height / 2   (in double)
//   fixed    = nearbyint(window * 2^subpixel_bits)
WindowVertex to_window(const ClipVertex& v, uint32_t width, uint32_t height, uint32_t bits) {
  const double wx = (v.x / v.w + 1.0) * (0.5 * width);
  const double wy = (1.0 - v.y / v.w) * (0.5 * height);
  WindowVertex r;
  r.x = static_cast<int64_t>(std::nearbyint(std::ldexp(wx, static_cast<int>(bits))));
  r.y = static_cast<int64_t>(std::nearbyint(std::ldexp(wy, static_cast<int>(bits))));
  r.z = v.z / v.w;
  r.inv_w = 1.0 / v.w;
  r.clip = &v;
  return r;
}

// The edge function of the directed edge a -> b at point (px, py): twice the signed area of
// the triangle (a, b, p). Positive on the inside of a triangle with positive area.
int64_t edge(const WindowVertex& a, const WindowVertex& b, int64_t px, int64_t py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

// Top-left rule, for triangles with positive area in y-down window space (clockwise on
// screen): a top edge is horizontal and runs towards +x; a left edge runs upwards (towards -y).
bool is_top_left(const WindowVertex& a, const WindowVertex& b) {
  const int64_t dx = b.x - a.x;
  const int64_t dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx > 0);
}

// A sample is inside an edge when the edge function is positive, or zero on a top-left edge.
bool inside_edge(int64_t e, bool top_left) {
  return e > 0 || (e == 0 && top_left);
}

// What a draw's fragments are made of: every value a clipped vertex carries (the varyings,
// then with a TargetOutput::kBarycentrics target the three barycentric carriers), each one's
// interpolation resolved, and the first vertex's values for the flat ones.
struct FragmentInputs {
  uint32_t varyings = 0;                           // the draw's attribute_count
  uint32_t values = 0;                             // varyings plus the carriers
  std::array<VaryingMode, kMaxClipValues> mode{};  // kPerspective, kAffine or kFlat
  bool needs_q = false;                            // a perspective value or the eye depth is read
  bool function = false;  // a user fragment function shades a target (FragmentShader::kUser)
  // Fragments go in 2x2 quads with derivatives: for a user function, or a texture's LOD
  // (FragmentShader::kTextured).
  bool quads = false;
  uint32_t targets = 1;  // colour targets
};

FragmentInputs fragment_inputs(const PipelineState& pipeline, uint32_t attribute_count,
                               const FramebufferDesc& desc) {
  FragmentInputs f;
  f.varyings = attribute_count;
  f.targets = 1 + desc.extra_targets;
  bool barycentrics = false, eye_depth = false;
  for (uint32_t t = 0; t < f.targets; ++t) {
    const TargetOutput output = output_of(pipeline, t);
    barycentrics = barycentrics || output == TargetOutput::kBarycentrics;
    eye_depth = eye_depth || output == TargetOutput::kEyeDepth;
    const bool colour = pipeline.color_write && output == TargetOutput::kColor;
    f.function = f.function || (colour && pipeline.shader == FragmentShader::kUser);
    f.quads = f.quads || f.function || (colour && pipeline.shader == FragmentShader::kTextured);
  }
  f.values = attribute_count + (barycentrics ? 3 : 0);
  for (uint32_t i = 0; i < f.values; ++i) {
    // The barycentric carriers after the varyings are perspective-correct.
    f.mode[i] = i < attribute_count ? resolved_mode(pipeline, i) : VaryingMode::kPerspective;
    f.needs_q = f.needs_q || f.mode[i] == VaryingMode::kPerspective;
  }
  f.needs_q = f.needs_q || eye_depth;
  return f;
}

// The values at the fixed-point point (px, py), from the triangle's screen-space barycentrics:
// perspective-correct ones from a/w and 1/w, affine ones linearly, flat ones the first vertex's
// (`flat`); `w` the clip-space w there (1 / the interpolated 1/w). Returns false when the plane
// of 1/w is not positive there (a point beyond the triangle's horizon) and a value needs it.
bool interpolate(const std::array<WindowVertex, 3>& v, int64_t area, int64_t px, int64_t py,
                 const FragmentInputs& in, const std::array<double, kMaxClipValues>& flat,
                 std::array<double, kMaxClipValues>& out, double& w) {
  const double b[3] = {static_cast<double>(edge(v[1], v[2], px, py)) / static_cast<double>(area),
                       static_cast<double>(edge(v[2], v[0], px, py)) / static_cast<double>(area),
                       static_cast<double>(edge(v[0], v[1], px, py)) / static_cast<double>(area)};
  double perspective[3] = {b[0], b[1], b[2]};
  w = 1.0;
  if (in.needs_q) {
    // Interpolate a/w and 1/w linearly in screen space, then divide.
    const double q[3] = {b[0] * v[0].inv_w, b[1] * v[1].inv_w, b[2] * v[2].inv_w};
    const double sum = q[0] + q[1] + q[2];
    if (!(sum > 0.0)) return false;
    for (int i = 0; i < 3; ++i)
      perspective[i] = q[i] / sum;
    w = 1.0 / sum;
  }
  for (uint32_t c = 0; c < in.values; ++c) {
    if (in.mode[c] == VaryingMode::kFlat) {
      out[c] = flat[c];
      continue;
    }
    const double* weight = in.mode[c] == VaryingMode::kPerspective ? perspective : b;
    double a = 0.0;
    for (int i = 0; i < 3; ++i)
      a += weight[i] * v[i].clip->attributes[c];
    out[c] = a;
  }
  return true;
}

// The derivatives per pixel step in x and y of the values at the fixed-point point (px, py),
// exactly, from the barycentrics' gradients: for a perspective-correct value a/q (a and q
// linear on screen), (a_x - (a/q) q_x) / q; for an affine one its gradient; 0 for a flat one.
// `value` holds the values there (interpolate's). Returns false where 1/w is not positive.
bool derivatives(const std::array<WindowVertex, 3>& v, int64_t area, uint32_t bits, int64_t px,
                 int64_t py, const FragmentInputs& in,
                 const std::array<double, kMaxClipValues>& value,
                 std::array<double, kMaxClipValues>& ddx, std::array<double, kMaxClipValues>& ddy) {
  const double a = static_cast<double>(area);
  const double unit = std::ldexp(1.0, static_cast<int>(bits));  // fixed-point units per pixel
  double b[3], bx[3], by[3];
  for (int i = 0; i < 3; ++i) {
    const WindowVertex& from = v[(i + 1) % 3];
    const WindowVertex& to = v[(i + 2) % 3];
    b[i] = static_cast<double>(edge(from, to, px, py)) / a;
    bx[i] = -static_cast<double>(to.y - from.y) * unit / a;
    by[i] = static_cast<double>(to.x - from.x) * unit / a;
  }
  double q = 1.0, qx = 0.0, qy = 0.0;
  if (in.needs_q) {
    q = qx = qy = 0.0;
    for (int i = 0; i < 3; ++i) {
      q += b[i] * v[i].inv_w;
      qx += bx[i] * v[i].inv_w;
      qy += by[i] * v[i].inv_w;
    }
    if (!(q > 0.0)) return false;
  }
  for (uint32_t c = 0; c < in.values; ++c) {
    ddx[c] = ddy[c] = 0.0;
    if (in.mode[c] == VaryingMode::kFlat) continue;
    const bool perspective = in.mode[c] == VaryingMode::kPerspective;
    for (int i = 0; i < 3; ++i) {
      const double scale = perspective ? v[i].inv_w : 1.0;
      ddx[c] += bx[i] * scale * v[i].clip->attributes[c];
      ddy[c] += by[i] * scale * v[i].clip->attributes[c];
    }
    if (perspective) {
      ddx[c] = (ddx[c] - value[c] * qx) / q;
      ddy[c] = (ddy[c] - value[c] * qy) / q;
    }
  }
  return true;
}

// The derivatives of every value per pixel step in x and y, at a quad's centre.
struct Derivatives {
  std::array<double, kMaxClipValues> ddx{}, ddy{};
};

// The fragment's RGBA for `output`: the shader's colour, or a vision output (shade.hpp's
// rules); a textured colour reads `derivatives`, its quad's.
std::array<float, 4> shade(const PipelineState& pipeline, TargetOutput output,
                           const FragmentInputs& in,
                           const std::array<double, kMaxClipValues>& value, double w,
                           uint32_t primitive, const Derivatives* derivatives) {
  const auto group = [&](uint32_t first) {
    return std::array<double, 3>{value[first], value[first + 1], value[first + 2]};
  };
  const auto replicate = [](double x) {
    return std::array<float, 4>{static_cast<float>(x), static_cast<float>(x), static_cast<float>(x),
                                1.0f};
  };
  const auto rgb = [](const std::array<double, 3>& x) {
    return std::array<float, 4>{static_cast<float>(x[0]), static_cast<float>(x[1]),
                                static_cast<float>(x[2]), 1.0f};
  };
  switch (output) {
    case TargetOutput::kColor:
      break;
    case TargetOutput::kEyeDepth:
      return replicate(w);
    case TargetOutput::kNormal:
      return rgb(normalized(group(pipeline.roles.normal)));
    case TargetOutput::kPosition:
      return rgb(group(pipeline.roles.position));
    case TargetOutput::kBarycentrics:
      return rgb(group(in.varyings));
    case TargetOutput::kPrimitiveId:
      return replicate(primitive);
    case TargetOutput::kObjectId:
      return replicate(pipeline.object_id);
  }
  const uint32_t color = pipeline.roles.color;
  const bool has_color = color <= in.varyings && in.varyings - color >= 4;
  if (pipeline.shader == FragmentShader::kPhong) {
    std::array<double, 4> base;
    for (int c = 0; c < 4; ++c)
      base[c] = double{pipeline.phong.base_color[c]} * (has_color ? value[color + c] : 1.0);
    return phong(pipeline.phong, group(pipeline.roles.normal), group(pipeline.roles.position),
                 base);
  }
  if (pipeline.shader == FragmentShader::kTextured) {
    // The texel (over the footprint of the quad's derivatives) times the colour varyings, or
    // white.
    const uint32_t t = pipeline.roles.texcoord;
    const std::array<double, 4> texel = reference::sample(
        *pipeline.texture, pipeline.sampler, value[t], value[t + 1], derivatives->ddx[t],
        derivatives->ddx[t + 1], derivatives->ddy[t], derivatives->ddy[t + 1]);
    std::array<float, 4> out;
    for (int c = 0; c < 4; ++c)
      out[c] = static_cast<float>(texel[c] * (has_color ? value[color + c] : 1.0));
    return out;
  }
  std::array<float, 4> out = {0.0f, 0.0f, 0.0f, 1.0f};
  for (uint32_t c = 0; c < 4 && color + c < in.varyings; ++c)
    out[c] = static_cast<float>(value[color + c]);
  return out;
}

// What a fragment writes to each colour target: RGBA (R32F: R) and an R32UI target's integer.
struct TargetValues {
  std::array<std::array<float, 4>, kMaxColorTargets> rgba{};
  std::array<uint32_t, kMaxColorTargets> id{};
};

// The targets' values a fragment with `value` (and clip w `w`) of triangle `primitive` takes from
// the built-in shaders and outputs; those a user function feeds are left to it.
TargetValues built_in_values(const PipelineState& pipeline, const FragmentInputs& in,
                             const std::array<double, kMaxClipValues>& value, double w,
                             uint32_t primitive, const Derivatives* derivatives = nullptr) {
  TargetValues out;
  for (uint32_t t = 0; t < in.targets; ++t) {
    const TargetOutput output = output_of(pipeline, t);
    if (output == TargetOutput::kColor && pipeline.shader == FragmentShader::kUser) continue;
    out.rgba[t] = shade(pipeline, output, in, value, w, primitive, derivatives);
    out.id[t] = output == TargetOutput::kObjectId ? pipeline.object_id : primitive;
  }
  return out;
}

// Writes the first `targets` colour targets of sample `index`, target 0 under the pipeline's
// blend state.
void write_targets(detail::FramebufferStorage& fb, const PipelineState& pipeline, size_t index,
                   const TargetValues& v, uint32_t targets) {
  const BlendState& blending = pipeline.blend[0];
  const bool rgba8 = fb.desc.color_format == ColorFormat::kRGBA8;
  if (!blending.replaces()) {
    blend::write_sample(blending, pipeline.blend_constant, v.rgba[0],
                        rgba8 ? fb.rgba8.data() + index * 4 : nullptr,
                        rgba8 ? nullptr : fb.rgba32f.data() + index * 4);
  } else if (fb.desc.color_format == ColorFormat::kRGBA8) {
    for (int c = 0; c < 4; ++c)
      fb.rgba8[index * 4 + c] = to_unorm8(v.rgba[0][c]);
  } else {
    for (int c = 0; c < 4; ++c)
      fb.rgba32f[index * 4 + c] = v.rgba[0][c];
  }
  for (uint32_t e = 0; e + 1 < targets; ++e) {
    detail::ExtraTarget& target = fb.extra[e];
    detail::store_target_value(target.format, target.data.data() + index * target.words,
                               v.rgba[e + 1].data(), v.id[e + 1]);
  }
}

// A pixel a user fragment function shades: its samples that passed the depth test and, with
// depth writes, their depths, written after the function for the fragments it keeps.
struct UserFragment {
  int64_t px = 0, py = 0;
  uint32_t mask = 0;
  std::array<float, 16> depth{};
};

// A drawn fragment of a batch and the values its built-in targets take.
struct UserSlot {
  const UserFragment* fragment = nullptr;
  TargetValues values;
};

// Runs the batch and writes the fragments it keeps.
void flush_user_batch(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                      const FragmentInputs& inputs, shade::UserBatch& batch,
                      const std::vector<UserSlot>& slots) {
  if (batch.empty()) return;
  if (inputs.function) {
    batch.run(pipeline.fragment_function);
  } else {
    batch.keep_all();
  }
  const bool write_depth = pipeline.depth_test && pipeline.depth_write;
  constexpr uint32_t kStride = shade::UserBatch::kStride;
  for (uint32_t f = 0; f < batch.size(); ++f) {
    const UserFragment* fragment = slots[f].fragment;
    if (fragment == nullptr || batch.discarded(f)) continue;
    TargetValues values = slots[f].values;
    for (uint32_t t = 0; t < inputs.targets; ++t) {
      // The function's values for the targets it feeds.
      if (!inputs.function || output_of(pipeline, t) != TargetOutput::kColor) continue;
      for (uint32_t c = 0; c < 4; ++c)
        values.rgba[t][c] = batch.target_color(t)[c * kStride + f];
      values.id[t] = batch.target_id(t)[f];
    }
    for (uint32_t s = 0; s < fb.desc.samples; ++s) {
      if (!(fragment->mask & (1u << s))) continue;
      const size_t index = fb.sample_index(static_cast<uint32_t>(fragment->px),
                                           static_cast<uint32_t>(fragment->py), s);
      if (write_depth) fb.depth[index] = fragment->depth[s];
      write_targets(fb, pipeline, index, values, inputs.targets);
    }
  }
  batch.clear();
}

// A user fragment function over one triangle's fragments (rasterize_triangle's), in 2x2 quads
// of pixels in row-major order of the quads: each fragment's values at its pixel centre (or, as
// for the built-in shaders, at its first passing sample where the centre lies beyond the
// horizon; a helper fragment there copies its quad's first drawn one), each quad's derivatives
// at its centre.
void shade_user_fragments(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                          const std::array<WindowVertex, 3>& v, int64_t area,
                          const FragmentInputs& inputs,
                          const std::array<double, kMaxClipValues>& flat, uint32_t primitive,
                          const std::vector<UserFragment>& fragments, shade::UserBatch& batch) {
  const uint32_t bits = pipeline.subpixel_bits;
  const int shift = static_cast<int>(bits) - 4;
  const auto pattern = sample_pattern(fb.desc.samples);
  std::map<std::pair<int64_t, int64_t>, std::array<const UserFragment*, 4>> quads;
  for (const UserFragment& f : fragments)
    quads[{f.py >> 1, f.px >> 1}][(f.py & 1) * 2 + (f.px & 1)] = &f;
  std::vector<UserSlot> slots;
  for (const auto& [key, quad] : quads) {
    if (batch.full()) {
      flush_user_batch(fb, pipeline, inputs, batch, slots);
      slots.clear();
    }
    const int64_t qx = key.second * 2, qy = key.first * 2;
    uint32_t masks[4];
    int live = -1;
    for (int k = 0; k < 4; ++k) {
      masks[k] = quad[k] ? quad[k]->mask : 0u;
      if (live < 0 && masks[k] != 0) live = k;
    }
    const uint32_t first =
        batch.add_quad(static_cast<uint32_t>(qx), static_cast<uint32_t>(qy), primitive, masks);
    std::array<std::array<double, kMaxClipValues>, 4> values;
    std::array<int64_t, 4> at_x{}, at_y{};  // where each fragment was evaluated
    std::array<bool, 4> evaluated{};
    std::array<double, 4> w{1.0, 1.0, 1.0, 1.0};
    const auto evaluate = [&](int k) {
      const int64_t px = qx + (k & 1), py = qy + (k >> 1);
      at_x[k] = (px * 16 + 8) << shift;
      at_y[k] = (py * 16 + 8) << shift;
      evaluated[k] = interpolate(v, area, at_x[k], at_y[k], inputs, flat, values[k], w[k]);
      if (evaluated[k] || masks[k] == 0) return;
      const auto& o = pattern[std::countr_zero(masks[k])];
      at_x[k] = (px * 16 + 8 + o.dx) << shift;
      at_y[k] = (py * 16 + 8 + o.dy) << shift;
      evaluated[k] = interpolate(v, area, at_x[k], at_y[k], inputs, flat, values[k], w[k]);
    };
    evaluate(live);
    // The quad's derivatives at its centre, or where that lies beyond the horizon at the live
    // fragment's point.
    Derivatives d;
    std::array<double, kMaxClipValues> centre;
    const int64_t cx = (qx * 16 + 16) << shift, cy = (qy * 16 + 16) << shift;
    double centre_w = 1.0;
    if (!interpolate(v, area, cx, cy, inputs, flat, centre, centre_w) ||
        !derivatives(v, area, bits, cx, cy, inputs, centre, d.ddx, d.ddy)) {
      derivatives(v, area, bits, at_x[live], at_y[live], inputs, values[live], d.ddx, d.ddy);
    }
    for (uint32_t j = 0; j < inputs.varyings; ++j) {
      batch.set_derivatives(j, first, static_cast<float>(d.ddx[j]), static_cast<float>(d.ddy[j]));
    }
    for (int k = 0; k < 4; ++k) {
      if (k != live) evaluate(k);
      if (!evaluated[k]) {
        values[k] = values[live];
        w[k] = w[live];
      }
      for (uint32_t j = 0; j < inputs.varyings; ++j)
        batch.set_value(j, first + static_cast<uint32_t>(k), static_cast<float>(values[k][j]));
      UserSlot slot;
      if (quad[k] && masks[k] != 0) {
        slot.fragment = quad[k];
        slot.values = built_in_values(pipeline, inputs, values[k], w[k], primitive, &d);
      }
      slots.push_back(slot);
    }
  }
  flush_user_batch(fb, pipeline, inputs, batch, slots);
}

// One triangle (a piece of draw triangle `primitive`, whose first vertex's values are
// `flat`); `batch` for a user fragment function's draw.
void rasterize_triangle(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                        std::array<WindowVertex, 3> v, const FragmentInputs& inputs,
                        const std::array<double, kMaxClipValues>& flat, uint32_t primitive,
                        Counters& counters, shade::UserBatch* batch) {
  int64_t area = edge(v[0], v[1], v[2].x, v[2].y);
  if (area == 0) {
    ++counters.triangles_culled;
    return;
  }
  // Window y points down, so a triangle counter-clockwise in NDC (y up) has negative area here.
  const bool counter_clockwise = area < 0;
  const bool front = counter_clockwise == (pipeline.front_face == FrontFace::kCounterClockwise);
  if ((pipeline.cull == CullMode::kBack && !front) ||
      (pipeline.cull == CullMode::kFront && front)) {
    ++counters.triangles_culled;
    return;
  }
  if (area < 0) {
    std::swap(v[1], v[2]);
    area = -area;
  }
  ++counters.triangles_rasterized;

  const uint32_t bits = pipeline.subpixel_bits;
  if (has_depth_bias(pipeline)) {
    // The plane of z over the snapped positions, per pixel (area is twice the triangle's area
    // in fixed-point units squared, and positive here).
    const double scale = std::ldexp(1.0, static_cast<int>(bits)) / static_cast<double>(area);
    const double z10 = v[1].z - v[0].z, z20 = v[2].z - v[0].z;
    const double x10 = static_cast<double>(v[1].x - v[0].x),
                 x20 = static_cast<double>(v[2].x - v[0].x);
    const double y10 = static_cast<double>(v[1].y - v[0].y),
                 y20 = static_cast<double>(v[2].y - v[0].y);
    // z = z0 + a (x - x0) + b (y - y0) through the three vertices: area = x10 y20 - x20 y10.
    const double dz_dx = (z10 * y20 - z20 * y10) * scale;
    const double dz_dy = (x10 * z20 - x20 * z10) * scale;
    const double z_abs_max = std::max({std::abs(v[0].z), std::abs(v[1].z), std::abs(v[2].z)});
    const double bias =
        depth_bias(pipeline, depth_bias_unit(fb.desc.depth_format, z_abs_max), dz_dx, dz_dy);
    for (WindowVertex& vertex : v)
      vertex.z += bias;
  }
  const int shift = static_cast<int>(bits) - 4;  // 1/16 pixel -> fixed point
  const uint32_t samples = fb.desc.samples;
  const double depth_scale = detail::depth_scale(fb.desc.depth_format);
  const auto pattern = sample_pattern(samples);
  const bool top_left[3] = {is_top_left(v[1], v[2]), is_top_left(v[2], v[0]),
                            is_top_left(v[0], v[1])};

  // Pixels whose samples can be inside: the snapped bounding box, one pixel wider on each side
  // (a sample may sit on its pixel's left or top border), clamped to the framebuffer.
  auto pixel_of = [bits](int64_t fixed) { return fixed >> bits; };  // floor division
  // The scissor test: pixels outside the draw box are not visited.
  const PixelBox box = draw_box(pipeline, fb.desc.width, fb.desc.height);
  const int64_t x0 = std::max<int64_t>(box.x0, pixel_of(std::min({v[0].x, v[1].x, v[2].x})) - 1);
  const int64_t y0 = std::max<int64_t>(box.y0, pixel_of(std::min({v[0].y, v[1].y, v[2].y})) - 1);
  const int64_t x1 = std::min<int64_t>(box.x1, pixel_of(std::max({v[0].x, v[1].x, v[2].x})) + 1);
  const int64_t y1 = std::min<int64_t>(box.y1, pixel_of(std::max({v[0].y, v[1].y, v[2].y})) + 1);

  std::vector<UserFragment> user_fragments;
  for (int64_t py = y0; py <= y1; ++py) {
    for (int64_t px = x0; px <= x1; ++px) {
      std::array<bool, 16> passed{};
      int first_passed = -1;
      UserFragment user{px, py};
      for (uint32_t s = 0; s < samples; ++s) {
        // Sample position in fixed point: pixel corner + 8/16 (centre) + the sample offset.
        const int64_t sx = (px * 16 + 8 + pattern[s].dx) << shift;
        const int64_t sy = (py * 16 + 8 + pattern[s].dy) << shift;
        const int64_t e0 = edge(v[1], v[2], sx, sy);
        const int64_t e1 = edge(v[2], v[0], sx, sy);
        const int64_t e2 = edge(v[0], v[1], sx, sy);
        if (!(inside_edge(e0, top_left[0]) && inside_edge(e1, top_left[1]) &&
              inside_edge(e2, top_left[2]))) {
          continue;
        }
        ++counters.samples_covered;

        // Depth z/w is a plane in screen space: interpolate it with the screen barycentrics
        // (each edge function over the area is the weight of the opposite vertex).
        const double a = static_cast<double>(area);
        const double z = (static_cast<double>(e0) * v[0].z + static_cast<double>(e1) * v[1].z +
                          static_cast<double>(e2) * v[2].z) /
                         a;
        const float depth = detail::encode_depth(std::clamp(z, 0.0, 1.0), depth_scale);
        const size_t index =
            fb.sample_index(static_cast<uint32_t>(px), static_cast<uint32_t>(py), s);
        if (pipeline.depth_test) {
          if (!detail::depth_passes(pipeline.depth_compare, depth, fb.depth[index])) continue;
          if (pipeline.depth_write) {
            // A user function's fragments are written after it, unless it discards them.
            if (inputs.quads) {
              user.depth[s] = depth;
            } else {
              fb.depth[index] = depth;
            }
          }
        }
        user.mask |= 1u << s;
        ++counters.samples_passed;
        passed[s] = true;
        if (first_passed < 0) first_passed = static_cast<int>(s);
      }
      if (first_passed < 0 || !pipeline.color_write) continue;
      if (inputs.quads) {
        user_fragments.push_back(user);
        continue;
      }

      // Shade once per pixel, at the pixel centre (at the first passing sample when the centre
      // lies beyond the triangle's horizon: inside the triangle 1/w is positive), and store to
      // every sample that passed.
      std::array<double, kMaxClipValues> values;
      double w = 1.0;
      const int64_t cx = (px * 16 + 8) << shift;
      const int64_t cy = (py * 16 + 8) << shift;
      if (!interpolate(v, area, cx, cy, inputs, flat, values, w)) {
        const auto& o = pattern[first_passed];
        interpolate(v, area, (px * 16 + 8 + o.dx) << shift, (py * 16 + 8 + o.dy) << shift, inputs,
                    flat, values, w);
      }
      const TargetValues target_values = built_in_values(pipeline, inputs, values, w, primitive);
      for (uint32_t s = 0; s < samples; ++s) {
        if (passed[s]) {
          write_targets(fb, pipeline,
                        fb.sample_index(static_cast<uint32_t>(px), static_cast<uint32_t>(py), s),
                        target_values, inputs.targets);
        }
      }
    }
  }
  if (!user_fragments.empty()) {
    shade_user_fragments(fb, pipeline, v, area, inputs, flat, primitive, user_fragments, *batch);
  }
}

}  // namespace

void draw(detail::FramebufferStorage& fb, const PipelineState& pipeline, const DrawInput& input,
          Counters& counters, std::span<const uint32_t> primitive_ids, bool all_targets) {
  const bool indexed = !input.indices.empty();
  const size_t triangles = (indexed ? input.indices.size() : input.positions.size()) / 3;
  const uint32_t attribute_count = input.attribute_count;
  FramebufferDesc shaded = fb.desc;  // the targets this draw writes
  if (!all_targets) shaded.extra_targets = 0;
  const FragmentInputs inputs = fragment_inputs(pipeline, attribute_count, shaded);
  const GuardBand guard_band = GuardBand::for_viewport(fb.desc.width, fb.desc.height);
  std::optional<shade::UserBatch> batch;
  if (inputs.quads) {
    batch.emplace(attribute_count,
                  std::span<const ColorFormat>(shaded.extra_formats.data(), shaded.extra_targets));
  }

  for (size_t t = 0; t < triangles; ++t) {
    ++counters.triangles_submitted;
    std::array<ClipVertex, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const size_t vertex = indexed ? input.indices[t * 3 + k] : t * 3 + k;
      const Float4& p = input.positions[vertex];
      ClipVertex& c = tri[k];
      c.x = p.x;
      c.y = p.y;
      c.w = p.w;
      // OpenGL's -w <= z <= w becomes 0 <= z <= w: z' = (z + w) / 2, linear, so clipping and
      // interpolation commute with it.
      c.z = pipeline.clip_depth == ClipDepth::kNegativeOneToOne ? 0.5 * (double{p.z} + p.w) : p.z;
      for (uint32_t a = 0; a < attribute_count; ++a) {
        c.attributes[a] = input.attributes[vertex * attribute_count + a];
      }
      // The barycentric carriers: vertex k's weight of vertex j is 1 where j = k, else 0.
      for (uint32_t j = attribute_count; j < inputs.values; ++j) {
        c.attributes[j] = j - attribute_count == static_cast<uint32_t>(k) ? 1.0 : 0.0;
      }
    }
    const std::array<double, kMaxClipValues> flat = tri[0].attributes;  // the provoking vertex

    // The clipper interpolates values linearly in clip space, which is right for
    // perspective-correct ones. Affine values are linear in screen space instead: along an
    // edge cut at clip-space parameter t they take lerp(a w, t) / lerp(w, t). So clip a * w and
    // divide by the new w (OpenGL 4.6 section 13.7, noperspective outputs); otherwise a cut,
    // e.g. at the guard band, would change the colours inside the viewport. (Flat values are
    // read from `flat`, never from the clipped vertices.)
    const auto affine = [&](uint32_t a) { return inputs.mode[a] == VaryingMode::kAffine; };
    std::array<ClipVertex, 3> to_clip = tri;
    for (ClipVertex& c : to_clip) {
      for (uint32_t a = 0; a < inputs.values; ++a) {
        if (affine(a)) c.attributes[a] *= c.w;
      }
    }
    ClipPolygon polygon;
    const ClipResult clip = clip_triangle(to_clip, inputs.values, guard_band, polygon);
    if (clip.clipped) ++counters.triangles_clipped;
    if (!clip.visible) {
      ++counters.triangles_culled;
      continue;
    }
    if (!clip.clipped) {
      // Uncut: the values exactly as given.
      for (int i = 0; i < 3; ++i) {
        polygon.vertices[i] = tri[i];
      }
    } else {
      // Every vertex left after clipping has w >= kMinClipW > 0.
      for (int i = 0; i < polygon.count; ++i) {
        ClipVertex& c = polygon.vertices[i];
        for (uint32_t a = 0; a < inputs.values; ++a) {
          if (affine(a)) c.attributes[a] /= c.w;
        }
      }
    }
    const uint32_t primitive = primitive_ids.empty() ? static_cast<uint32_t>(t) : primitive_ids[t];
    std::array<WindowVertex, kMaxClipVertices> window;
    for (int i = 0; i < polygon.count; ++i) {
      window[i] =
          to_window(polygon.vertices[i], fb.desc.width, fb.desc.height, pipeline.subpixel_bits);
    }
    // The clipped polygon is convex: draw it as a fan. The fan's inner edges are shared by
    // two pieces, and the fill rule gives each of their samples to exactly one piece.
    for (int i = 1; i + 1 < polygon.count; ++i) {
      rasterize_triangle(fb, pipeline, {window[0], window[i], window[i + 1]}, inputs, flat,
                         primitive, counters, batch ? &*batch : nullptr);
    }
  }
}

}  // namespace tessera::reference
