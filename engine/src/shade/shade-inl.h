// The built-in fragment shaders of shaded draws (shade/layout.hpp), written once against
// Highway: from a lane group's pixel positions, the triangle's planes are evaluated into the
// interpolants, and the draw's shader turns them into RGBA lanes. The raster kernel
// (engine/src/fast/block_kernel-inl.h) calls shade_fragments once per lane group with a passing
// sample, after the depth test, and stores what it returns; nothing here touches the
// framebuffer. Every operation is a multiply, add, division, square root or compare in one fixed
// order (no contraction; simd/math-inl.h's powers), so every target gives the same bits.

// Per-target include guard (see engine/src/fast/block_kernel-inl.h).
#if defined(TESSERA_ENGINE_SRC_SHADE_SHADE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_SHADE_SHADE_INL_H_
#undef TESSERA_ENGINE_SRC_SHADE_SHADE_INL_H_
#else
#define TESSERA_ENGINE_SRC_SHADE_SHADE_INL_H_
#endif

#include <hwy/highway.h>

#include "engine/src/shade/layout.hpp"
#include "engine/src/texture/sample_lanes-inl.h"
#include "simd/math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::shade::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace hs = tessera::simd::HWY_NAMESPACE;

// One triangle's planes as the shaders read them: the 1/w plane q (1 everywhere when flat_q)
// and the interpolants' planes (layout.hpp: value, gx, gy each), all over pixel offsets from
// the plane origin.
struct FragmentPlanes {
  float q0, q_dx, q_dy;
  bool flat_q;
  const float* planes;
  int32_t x0, y0;  // the plane origin's pixel: the 2x2 quads' alignment (kTextured)
};

// Vectors of three lanes-wide components travel as three arguments, never as a struct or an
// array: sizeless vector types (SVE, RVV) cannot be members or elements.

template <class VF>
HWY_INLINE VF dot(VF ax, VF ay, VF az, VF bx, VF by, VF bz) {
  return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

// (x, y, z) / |(x, y, z)| in place, and 0 where the length is 0 (as the reference's
// normalized()); returns the length.
template <class DF, class VF>
HWY_INLINE VF normalize(DF df, VF& x, VF& y, VF& z) {
  const auto length = hn::Sqrt(dot(x, y, z, x, y, z));
  const auto positive = hn::Gt(length, hn::Zero(df));
  const auto inverse = hn::IfThenElseZero(positive, hn::Div(hn::Set(df, 1.0f), length));
  x = hn::Mul(x, inverse);
  y = hn::Mul(y, inverse);
  z = hn::Mul(z, inverse);
  return length;
}

// Lecture 004's Phong model (tessera/shading.hpp's PhongState) per lane, of the normal n and
// the point p, into (r, g, b), which hold the base colour's RGB on entry: the reference's
// formula (reference_shade.cpp) term by term, in float.
template <class DF, class VF>
HWY_INLINE void phong(DF df, const Layout& layout, VF nx, VF ny, VF nz, VF px, VF py, VF pz, VF& r,
                      VF& g, VF& b) {
  const PhongState& m = layout.phong;
  normalize(df, nx, ny, nz);
  auto vx = hn::Sub(hn::Set(df, m.eye[0]), px);
  auto vy = hn::Sub(hn::Set(df, m.eye[1]), py);
  auto vz = hn::Sub(hn::Set(df, m.eye[2]), pz);
  normalize(df, vx, vy, vz);
  if (m.two_sided) {
    const auto back = hn::Lt(dot(nx, ny, nz, vx, vy, vz), hn::Zero(df));
    nx = hn::IfThenElse(back, hn::Neg(nx), nx);
    ny = hn::IfThenElse(back, hn::Neg(ny), ny);
    nz = hn::IfThenElse(back, hn::Neg(nz), nz);
  }
  auto ir = hn::Set(df, m.ka * m.ambient[0]);
  auto ig = hn::Set(df, m.ka * m.ambient[1]);
  auto ib = hn::Set(df, m.ka * m.ambient[2]);
  for (uint32_t l = 0; l < m.light_count; ++l) {
    const PreparedLight& light = layout.lights[l];
    auto lx = hn::Set(df, light.to_light[0]);
    auto ly = hn::Set(df, light.to_light[1]);
    auto lz = hn::Set(df, light.to_light[2]);
    auto attenuation = hn::Set(df, 1.0f);
    if (light.kind != LightKind::kDirectional) {
      lx = hn::Sub(hn::Set(df, light.position[0]), px);
      ly = hn::Sub(hn::Set(df, light.position[1]), py);
      lz = hn::Sub(hn::Set(df, light.position[2]), pz);
      const auto distance = normalize(df, lx, ly, lz);
      if (light.constant_attenuation) {
        attenuation = hn::Set(df, light.attenuation);
      } else {
        const auto falloff =
            hn::Add(hn::Add(hn::Set(df, light.c0), hn::Mul(hn::Set(df, light.c1), distance)),
                    hn::Mul(hn::Mul(hn::Set(df, light.c2), distance), distance));
        attenuation = hn::Div(hn::Set(df, 1.0f), falloff);
      }
      if (light.kind == LightKind::kSpot) {
        const auto cosine = hn::Neg(dot(lx, ly, lz, hn::Set(df, light.axis[0]),
                                        hn::Set(df, light.axis[1]), hn::Set(df, light.axis[2])));
        const auto cone = hn::Mul(
            attenuation, hs::pow_unit(df, hn::Max(cosine, hn::Zero(df)), light.spot_exponent));
        // No light outside the cone.
        attenuation = hn::IfThenZeroElse(hn::Lt(cosine, hn::Set(df, light.spot_cos_cutoff)), cone);
      }
    }
    const auto n_dot_l = dot(nx, ny, nz, lx, ly, lz);
    const auto diffuse = hn::Mul(hn::Set(df, m.kd), hn::Max(n_dot_l, hn::Zero(df)));
    // R = 2 (N.L) N - L; the specular term only where N.L > 0.
    const auto twice = hn::Mul(hn::Set(df, 2.0f), n_dot_l);
    const auto r_dot_v = dot(hn::Sub(hn::Mul(twice, nx), lx), hn::Sub(hn::Mul(twice, ny), ly),
                             hn::Sub(hn::Mul(twice, nz), lz), vx, vy, vz);
    const auto clamped = hn::Min(hn::Max(r_dot_v, hn::Zero(df)), hn::Set(df, 1.0f));
    const auto specular =
        hn::IfThenElseZero(hn::Gt(n_dot_l, hn::Zero(df)),
                           hn::Mul(hn::Set(df, m.ks), hs::pow_unit(df, clamped, m.shininess)));
    const auto add = [&](VF& intensity, int c) {
      const auto term = hn::Add(hn::Mul(diffuse, hn::Set(df, light.diffuse[c])),
                                hn::Mul(specular, hn::Set(df, light.specular[c])));
      intensity = hn::Add(intensity, hn::Mul(attenuation, term));
    };
    add(ir, 0);
    add(ig, 1);
    add(ib, 2);
  }
  const auto clamp01 = [&](VF v) { return hn::Min(hn::Max(v, hn::Zero(df)), hn::Set(df, 1.0f)); };
  r = clamp01(hn::Mul(ir, r));
  g = clamp01(hn::Mul(ig, g));
  b = clamp01(hn::Mul(ib, b));
}

// The 1/w plane q at lanes evaluated at (x, y) (not flat_q).
template <class DF, class VF>
HWY_INLINE VF q_plane(DF df, const FragmentPlanes& p, VF x, VF y) {
  return hn::Add(hn::Set(df, p.q0),
                 hn::Add(hn::Mul(hn::Set(df, p.q_dx), x), hn::Mul(hn::Set(df, p.q_dy), y)));
}

// Interpolant j at lanes evaluated at (x, y), where 1/q = inv_q.
template <class DF, class VF>
HWY_INLINE VF interpolant(DF df, const Layout& layout, const FragmentPlanes& p, uint32_t j, VF x,
                          VF y, VF inv_q) {
  const float* plane = p.planes + 3 * j;
  const auto v = hn::Add(hn::Set(df, plane[0]), hn::Add(hn::Mul(hn::Set(df, plane[1]), x),
                                                        hn::Mul(hn::Set(df, plane[2]), y)));
  return layout.values[j].mode == VaryingMode::kPerspective ? hn::Mul(v, inv_q) : v;
}

// The textured shader (Shader::kTextured) at lanes evaluated at (x, y) with 1/q = inv_q, whose
// pixels are at (pixel_x, pixel_y): the texture sampled in lanes at interpolants 0 and 1, times
// interpolants 2..5 with has_color. Not inlined: one call per lane group costs little, and the
// sampler's lanes inlined into every raster path would multiply the kernels' size.
template <class DF, class VF>
HWY_NOINLINE void shade_textured(DF df, const Layout& layout, const FragmentPlanes& p, VF x, VF y,
                                 VF pixel_x, VF pixel_y, VF inv_q, VF& r, VF& g, VF& b, VF& a) {
  const auto value = [&](uint32_t j) { return interpolant(df, layout, p, j, x, y, inv_q); };
  // The derivatives of (u, v) at the centre of the lane's 2x2 quad (quads align to even
  // pixels), or where that lies beyond the horizon at the lane's own point, exactly as the
  // quad back end forms them (engine/src/fast/user_fragments-inl.h): d(a / q)/dx = (a_x -
  // (a / q) q_x) / q for a perspective-correct value, the plane's gradient for an affine one,
  // 0 for a flat one.
  const auto centre = [&](VF offset, int32_t origin) {
    const auto absolute = hn::Add(offset, hn::Set(df, static_cast<float>(origin)));
    const auto odd = hn::Sub(
        absolute, hn::Mul(hn::Set(df, 2.0f), hn::Floor(hn::Mul(absolute, hn::Set(df, 0.5f)))));
    return hn::Add(hn::Sub(offset, odd), hn::Set(df, 0.5f));
  };
  auto cx = centre(pixel_x, p.x0), cy = centre(pixel_y, p.y0);
  auto inv_qc = hn::Set(df, 1.0f);
  const float q_dx = p.flat_q ? 0.0f : p.q_dx, q_dy = p.flat_q ? 0.0f : p.q_dy;
  if (!p.flat_q) {
    auto qc = q_plane(df, p, cx, cy);
    const auto behind = hn::Not(hn::Gt(qc, hn::Zero(df)));
    if (HWY_UNLIKELY(!hn::AllFalse(df, behind))) {
      cx = hn::IfThenElse(behind, x, cx);
      cy = hn::IfThenElse(behind, y, cy);
      qc = hn::IfThenElse(behind, q_plane(df, p, x, y), qc);
    }
    inv_qc = hn::Div(hn::Set(df, 1.0f), qc);
  }
  const auto derivatives = [&](uint32_t j, VF& ddx, VF& ddy) {
    const float* plane = p.planes + 3 * j;
    switch (layout.values[j].mode) {
      case VaryingMode::kPerspective: {
        const auto v = interpolant(df, layout, p, j, cx, cy, inv_qc);
        ddx = hn::Mul(hn::Sub(hn::Set(df, plane[1]), hn::Mul(v, hn::Set(df, q_dx))), inv_qc);
        ddy = hn::Mul(hn::Sub(hn::Set(df, plane[2]), hn::Mul(v, hn::Set(df, q_dy))), inv_qc);
        break;
      }
      case VaryingMode::kAffine:
        ddx = hn::Set(df, plane[1]);
        ddy = hn::Set(df, plane[2]);
        break;
      default:
        ddx = ddy = hn::Zero(df);
        break;
    }
  };
  VF du_dx, du_dy, dv_dx, dv_dy;
  derivatives(0, du_dx, du_dy);
  derivatives(1, dv_dx, dv_dy);
  texture::HWY_NAMESPACE::sample_lanes(df, *layout.texture, value(0), value(1), du_dx, dv_dx, du_dy,
                                       dv_dy, r, g, b, a);
  if (layout.has_color) {
    r = hn::Mul(r, value(2));
    g = hn::Mul(g, value(3));
    b = hn::Mul(b, value(4));
    a = hn::Mul(a, value(5));
  }
}

// The RGBA (r, g, b, a) of a lane group's fragments at pixel offsets (x, y) from the plane
// origin, for the lanes in `covered` (the others' values are not used). Where the 1/w plane is
// not positive at a covered lane's pixel centre (beyond the triangle's horizon), the planes are
// evaluated at that pixel's first passing sample instead, whose offsets first_sample(ox, oy)
// gives, as the reference does.
template <Shader kShader, class DF, class VF, class M, class FirstSample>
HWY_INLINE void shade_fragments(DF df, const Layout& layout, const FragmentPlanes& p, VF x, VF y,
                                M covered, const FirstSample& first_sample, VF& r, VF& g, VF& b,
                                VF& a) {
  const VF pixel_x = x, pixel_y = y;  // before a move to a sample
  auto inv_q = hn::Set(df, 1.0f);
  if (!p.flat_q) {
    const auto q_at = [&] { return q_plane(df, p, x, y); };
    auto q = q_at();
    const auto beyond = hn::AndNot(hn::Gt(q, hn::Zero(df)), covered);
    if (HWY_UNLIKELY(!hn::AllFalse(df, beyond))) {
      VF ox, oy;
      first_sample(ox, oy);
      x = hn::Add(x, hn::IfThenElseZero(beyond, ox));
      y = hn::Add(y, hn::IfThenElseZero(beyond, oy));
      q = q_at();
    }
    inv_q = hn::Div(hn::Set(df, 1.0f), q);
  }
  const auto value = [&](uint32_t j) { return interpolant(df, layout, p, j, x, y, inv_q); };
  a = hn::Set(df, 1.0f);
  if constexpr (kShader == Shader::kInterpolated) {
    const auto channel = [&](int c) {
      const uint8_t j = layout.channel[c];
      return j == Layout::kConstant ? hn::Set(df, layout.constant[c]) : value(j);
    };
    r = channel(0);
    // Outputs that repeat one value in R, G and B evaluate it once.
    if (layout.channel[1] == layout.channel[0] && layout.channel[2] == layout.channel[0]) {
      g = r;
      b = r;
    } else {
      g = channel(1);
      b = channel(2);
    }
    a = channel(3);
  } else if constexpr (kShader == Shader::kNormalized) {
    r = value(0);
    g = value(1);
    b = value(2);
    normalize(df, r, g, b);
  } else if constexpr (kShader == Shader::kTextured) {
    shade_textured(df, layout, p, x, y, pixel_x, pixel_y, inv_q, r, g, b, a);
  } else {
    static_assert(kShader == Shader::kPhong);
    // The base colour: the material's, times the colour varyings when the draw has them.
    const auto base = [&](int c) {
      const auto factor = hn::Set(df, layout.phong.base_color[c]);
      return layout.has_color ? hn::Mul(factor, value(6 + static_cast<uint32_t>(c))) : factor;
    };
    r = base(0);
    g = base(1);
    b = base(2);
    a = base(3);
    phong(df, layout, value(0), value(1), value(2), value(3), value(4), value(5), r, g, b);
  }
}

}  // namespace tessera::shade::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
