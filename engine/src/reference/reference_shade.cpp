// Per-pixel Phong for the reference rasterizer (reference_shade.hpp): the formula of
// tessera/shading.hpp term by term, in double.
#include "engine/src/reference/reference_shade.hpp"

#include <algorithm>
#include <cmath>

namespace tessera::reference {

namespace {

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 to_double(const std::array<float, 3>& v) {
  return {v[0], v[1], v[2]};
}

Vec3 minus(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

}  // namespace

Vec3 normalized(const Vec3& v) {
  const double length = std::sqrt(dot(v, v));
  if (!(length > 0.0)) return {0.0, 0.0, 0.0};
  return {v[0] / length, v[1] / length, v[2] / length};
}

std::array<float, 4> phong(const PhongState& state, const Vec3& normal, const Vec3& position,
                           const std::array<double, 4>& base) {
  Vec3 n = normalized(normal);
  const Vec3 view = normalized(minus(to_double(state.eye), position));
  if (state.two_sided && dot(n, view) < 0.0) n = {-n[0], -n[1], -n[2]};
  Vec3 intensity;
  for (int c = 0; c < 3; ++c)
    intensity[c] = double{state.ka} * state.ambient[c];
  for (uint32_t l = 0; l < state.light_count; ++l) {
    const Light& light = state.lights[l];
    Vec3 to_light;
    double attenuation = 1.0;
    if (light.kind == LightKind::kDirectional) {
      const Vec3 d = to_double(light.direction);
      to_light = normalized({-d[0], -d[1], -d[2]});
    } else {
      const Vec3 ray = minus(to_double(light.position), position);
      const double distance = std::sqrt(dot(ray, ray));
      to_light = normalized(ray);
      attenuation = 1.0 / (double{light.c0} + light.c1 * distance + light.c2 * distance * distance);
      if (light.kind == LightKind::kSpot) {
        const Vec3 axis = normalized(to_double(light.direction));
        const double cosine = -dot(to_light, axis);
        if (cosine < light.spot_cos_cutoff) continue;
        attenuation *= std::pow(std::max(cosine, 0.0), double{light.spot_exponent});
      }
    }
    const double n_dot_l = dot(n, to_light);
    const double diffuse = double{state.kd} * std::max(0.0, n_dot_l);
    double specular = 0.0;
    if (n_dot_l > 0.0) {
      const Vec3 reflected = {2.0 * n_dot_l * n[0] - to_light[0],
                              2.0 * n_dot_l * n[1] - to_light[1],
                              2.0 * n_dot_l * n[2] - to_light[2]};
      specular =
          double{state.ks} * std::pow(std::max(0.0, dot(reflected, view)), double{state.shininess});
    }
    for (int c = 0; c < 3; ++c)
      intensity[c] += attenuation * (diffuse * light.diffuse[c] + specular * light.specular[c]);
  }
  std::array<float, 4> out;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<float>(std::clamp(intensity[c] * base[c], 0.0, 1.0));
  out[3] = static_cast<float>(base[3]);
  return out;
}

}  // namespace tessera::reference
