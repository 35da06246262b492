// The sampling rules of tessera/texture.hpp written once, for a number type T: float for the
// engine's sampler (sampler.cpp), double for the reference's oracle
// (reference/reference_sampler.cpp). Wrap modes act on integer texel indices (OpenGL 4.6 table
// 8.20), so both precisions pick texels by the same rules and differ only in the positions and
// weights they compute.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/src/texture/texture_storage.hpp"

namespace tessera::texture {

// Texel index i on an axis of n texels under `wrap`; -1 for the border.
inline int64_t wrap_index(int64_t i, int64_t n, Wrap wrap) {
  switch (wrap) {
    case Wrap::kRepeat: {
      const int64_t m = i % n;
      return m < 0 ? m + n : m;
    }
    case Wrap::kClampToEdge:
      return std::clamp<int64_t>(i, 0, n - 1);
    case Wrap::kMirroredRepeat: {
      int64_t m = i % (2 * n);
      if (m < 0) m += 2 * n;
      return m < n ? m : 2 * n - 1 - m;
    }
    case Wrap::kClampToBorder:
      return i < 0 || i >= n ? -1 : i;
  }
  return 0;
}

// How far from the origin texel positions are clamped, in texels (both samplers).
inline constexpr int32_t kPositionLimit = 1 << 30;

// floor(x) as an integer, x (not NaN: sample_level replaces NaN coordinates) clamped to
// +-2^30 texels first.
template <class T>
int64_t floor_index(T x) {
  constexpr T kLimit = T(kPositionLimit);
  return static_cast<int64_t>(std::floor(std::clamp(x, -kLimit, kLimit)));
}

template <class T>
std::array<T, 4> fetch(const Texture::Storage& s, const Sampler& sampler, uint32_t level, int64_t i,
                       int64_t j) {
  const auto& l = s.levels[level];
  const int64_t x = wrap_index(i, l.width, sampler.wrap_u);
  const int64_t y = wrap_index(j, l.height, sampler.wrap_v);
  if (x < 0 || y < 0) {
    return {T(sampler.border_color[0]), T(sampler.border_color[1]), T(sampler.border_color[2]),
            T(sampler.border_color[3])};
  }
  return decode<T>(s.desc.format, s.at(level, static_cast<uint32_t>(x), static_cast<uint32_t>(y)));
}

// One level, nearest or linear, at (u, v) in [0, 1] texture space.
template <class T>
std::array<T, 4> sample_level(const Texture::Storage& s, const Sampler& sampler, uint32_t level,
                              Filter filter, T u, T v) {
  const auto& l = s.levels[level];
  const T x = (u == u ? u : T(0)) * T(l.width), y = (v == v ? v : T(0)) * T(l.height);
  if (filter == Filter::kNearest)
    return fetch<T>(s, sampler, level, floor_index(x), floor_index(y));
  const T xs = x - T(0.5), ys = y - T(0.5);
  const int64_t i0 = floor_index(xs), j0 = floor_index(ys);
  // The fractions, from positions clamped as floor_index clamps them.
  constexpr T kLimit = T(kPositionLimit);
  const T a = std::clamp(xs, -kLimit, kLimit) - T(i0), b = std::clamp(ys, -kLimit, kLimit) - T(j0);
  const auto t00 = fetch<T>(s, sampler, level, i0, j0),
             t10 = fetch<T>(s, sampler, level, i0 + 1, j0);
  const auto t01 = fetch<T>(s, sampler, level, i0, j0 + 1);
  const auto t11 = fetch<T>(s, sampler, level, i0 + 1, j0 + 1);
  std::array<T, 4> out;
  for (int c = 0; c < 4; ++c) {
    const T top = t00[c] + a * (t10[c] - t00[c]);
    const T bottom = t01[c] + a * (t11[c] - t01[c]);
    out[c] = top + b * (bottom - top);
  }
  return out;
}

// The level of detail of a footprint of rho level-0 texels (the SIMD sampler computes rho in
// lanes with lod()'s operations and finishes here).
template <class T>
T lod_of_rho(const Sampler& sampler, T rho) {
  const T lambda = std::log2(rho) + T(sampler.lod_bias);  // -inf for rho = 0
  if (!(lambda == lambda)) return T(0);                   // NaN derivatives
  return std::clamp(lambda, T(sampler.min_lod), T(sampler.max_lod));
}

// The lengths in level-0 texels of the footprint's two screen axes: |(du/dx w, dv/dx h)| and
// |(du/dy w, dv/dy h)|.
template <class T>
std::array<T, 2> axis_lengths(const Texture::Storage& s, T du_dx, T dv_dx, T du_dy, T dv_dy) {
  const T w = T(s.desc.width), h = T(s.desc.height);
  return {std::sqrt(du_dx * w * (du_dx * w) + dv_dx * h * (dv_dx * h)),
          std::sqrt(du_dy * w * (du_dy * w) + dv_dy * h * (dv_dy * h))};
}

template <class T>
T lod(const Texture::Storage& s, const Sampler& sampler, T du_dx, T dv_dx, T du_dy, T dv_dy) {
  const auto [x, y] = axis_lengths<T>(s, du_dx, dv_dx, du_dy, dv_dy);
  return lod_of_rho<T>(sampler, std::max(x, y));
}

// The most samples an anisotropic footprint takes: floor(max_anisotropy) in [1, 16].
inline uint32_t anisotropy_limit(const Sampler& sampler) {
  const float n = sampler.max_anisotropy;
  return n >= float(kMaxAnisotropy) ? kMaxAnisotropy : n >= 1.0f ? static_cast<uint32_t>(n) : 1u;
}

// The level(s) a sample at level of detail `lambda` reads, with which filter: `first` alone,
// or `first` and `second` blended by `weight` (a + weight (b - a)) when `blend`.
template <class T>
struct LevelChoice {
  uint32_t first = 0, second = 0;
  T weight = T(0);
  Filter filter = Filter::kNearest;
  bool blend = false;
};

template <class T>
LevelChoice<T> choose_levels(const Texture::Storage& s, const Sampler& sampler, T lambda) {
  if (!(lambda == lambda)) lambda = T(0);
  if (lambda <= T(0)) return {0, 0, T(0), sampler.mag_filter, false};
  const uint32_t last = static_cast<uint32_t>(s.levels.size()) - 1;
  switch (sampler.mip_filter) {
    case MipFilter::kNone:
      break;
    case MipFilter::kNearest: {
      // Level ceil(lambda + 1/2) - 1 (0 up to lambda = 1/2), clamped to the chain.
      const T d = lambda <= T(0.5) ? T(0) : std::ceil(lambda + T(0.5)) - T(1);
      const uint32_t level = d >= T(last) ? last : static_cast<uint32_t>(d);
      return {level, level, T(0), sampler.min_filter, false};
    }
    case MipFilter::kLinear: {
      if (lambda >= T(last)) return {last, last, T(0), sampler.min_filter, false};
      const T f = std::floor(lambda);
      const uint32_t d1 = static_cast<uint32_t>(f);
      return {d1, d1 + 1, lambda - f, sampler.min_filter, true};
    }
  }
  return {0, 0, T(0), sampler.min_filter, false};
}

template <class T>
std::array<T, 4> sample(const Texture::Storage& s, const Sampler& sampler, T u, T v, T lambda) {
  const LevelChoice<T> c = choose_levels<T>(s, sampler, lambda);
  const auto a = sample_level<T>(s, sampler, c.first, c.filter, u, v);
  if (!c.blend) return a;
  const auto b = sample_level<T>(s, sampler, c.second, c.filter, u, v);
  std::array<T, 4> out;
  for (int k = 0; k < 4; ++k)
    out[k] = a[k] + c.weight * (b[k] - a[k]);
  return out;
}

// The samples of a footprint with axis lengths px and py (axis_lengths()) and the scale factor
// whose level of detail they read: EXT_texture_filter_anisotropic's N = min(ceil(max / min),
// limit) (1 when the footprint is empty or NaN, or limit is 1) and max / N.
template <class T>
struct Anisotropy {
  uint32_t count = 1;
  T rho = T(0);
};

template <class T>
Anisotropy<T> anisotropy(uint32_t limit, T px, T py) {
  const T longer = std::max(px, py), shorter = std::min(px, py);
  uint32_t n = 1;
  if (limit > 1 && longer > T(0)) {
    const T ratio = std::ceil(longer / shorter);  // +inf for an empty shorter axis
    n = ratio >= T(limit) ? limit : ratio >= T(1) ? static_cast<uint32_t>(ratio) : 1u;
  }
  return {n, longer / T(n)};
}

// Sample i (1..n) of n along the longer axis: i / (n + 1) - 1/2 pixel steps from the centre.
template <class T>
T anisotropic_offset(uint32_t i, uint32_t n) {
  return T(i) / T(n + 1) - T(0.5);
}

// sample() with the level of detail from the footprint, anisotropic when the sampler allows
// more than one sample (EXT_texture_filter_anisotropic's formulation, core in OpenGL 4.6): with
// the axis lengths px and py, N samples (anisotropy()) at lambda = log2(max / N) + bias,
// clamped, spaced along the longer axis (x when px > py) at anisotropic_offset(), averaged
// (summed in order, then divided by N).
template <class T>
std::array<T, 4> sample_footprint(const Texture::Storage& s, const Sampler& sampler, T u, T v,
                                  T du_dx, T dv_dx, T du_dy, T dv_dy) {
  const auto [px, py] = axis_lengths<T>(s, du_dx, dv_dx, du_dy, dv_dy);
  const Anisotropy<T> aniso = anisotropy<T>(anisotropy_limit(sampler), px, py);
  const uint32_t n = aniso.count;
  const T lambda = lod_of_rho<T>(sampler, aniso.rho);
  if (n == 1) return sample<T>(s, sampler, u, v, lambda);
  const bool along_x = px > py;
  const T step_u = along_x ? du_dx : du_dy, step_v = along_x ? dv_dx : dv_dy;
  std::array<T, 4> sum;
  for (uint32_t i = 1; i <= n; ++i) {
    const T t = anisotropic_offset<T>(i, n);
    const auto c = sample<T>(s, sampler, u + t * step_u, v + t * step_v, lambda);
    for (int k = 0; k < 4; ++k)
      sum[k] = i == 1 ? c[k] : sum[k] + c[k];
  }
  for (int k = 0; k < 4; ++k)
    sum[k] /= T(n);
  return sum;
}

}  // namespace tessera::texture
