// Primitive clipping in homogeneous clip space (Sutherland-Hodgman against one plane at a
// time; Blinn and Newell 1978). Clip space here is already in the 0 <= z <= w convention.
//
// A triangle is cut only by the planes it crosses:
//  - near (z >= 0) and far (z <= w): always, so nothing behind the eye ever wraps around;
//  - w >= kMinClipW: keeps the perspective divide finite for vertices at the eye;
//  - the guard band |x|, |y| <= g * w, where g puts the band kGuardBandPixels from the
//    viewport centre: triangles inside it are rasterized unclipped (their edges are the
//    original edges, so shared edges stay watertight), and everything that reaches setup has
//    window coordinates of magnitude below 2^16 pixels, which keeps 64-bit edge functions
//    exact (see reference_raster.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "tessera/types.hpp"

namespace tessera {

// Half-extent of the guard band around the viewport centre, in pixels.
inline constexpr double kGuardBandPixels = 32768.0;
inline constexpr double kMinClipW = 1e-30;

// The values a clipped vertex carries: a draw's varyings, and three more with which the
// reference carries each vertex's barycentric weights of the drawn triangle through clipping.
inline constexpr uint32_t kMaxClipValues = kMaxVaryings + 3;

struct ClipVertex {
  double x = 0, y = 0, z = 0, w = 0;
  std::array<double, kMaxClipValues> attributes{};
};

// A triangle cut by 7 planes has at most 3 + 7 vertices.
inline constexpr int kMaxClipVertices = 10;

struct ClipPolygon {
  int count = 0;
  std::array<ClipVertex, kMaxClipVertices> vertices;
};

struct ClipResult {
  bool visible = false;  // something is left inside all planes
  bool clipped = false;  // some plane cut the triangle
};

// Guard-band factors for a viewport: g = kGuardBandPixels / (size / 2).
struct GuardBand {
  double x = 1.0;
  double y = 1.0;
  static GuardBand for_viewport(uint32_t width, uint32_t height) {
    return {kGuardBandPixels * 2.0 / width, kGuardBandPixels * 2.0 / height};
  }
};

// s p + t q for position and the first `attribute_count` attributes: a point of segment p -> q
// with both weights given, the inside vertex's computed on its own rather than as 1 - t (see
// clip.cpp's intersect), so that a tiny distance next to a large one does not lose that vertex.
ClipVertex weighted_sum(const ClipVertex& p, double s, const ClipVertex& q, double t,
                        uint32_t attribute_count);

// Whether every point (x, y, z, w) lies inside every plane clip_triangle clips against (a
// triangle whose three vertices do is left uncut, with clipped = false).
bool inside_clip_planes(std::span<const std::array<double, 4>> points, GuardBand guard_band);

// Clips triangle `in` (3 vertices) into `out` (a convex polygon, same winding, to be drawn
// as the fan out[0], out[i], out[i+1]). Only the first `attribute_count` attributes are
// interpolated. An intersection is always computed from the inside vertex towards the outside
// one, so an edge shared by two triangles is cut at bit-identical points in both.
ClipResult clip_triangle(const std::array<ClipVertex, 3>& in, uint32_t attribute_count,
                         GuardBand guard_band, ClipPolygon& out);

}  // namespace tessera
