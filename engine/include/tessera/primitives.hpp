// The primitives besides triangle lists: points, lines and polygons, and their state.
// Their rules (docs/PRIMITIVES.md) follow OpenGL 4.6 section 14.4-14.6 (point size, the
// diamond-exit line rule, glLineStipple) and the lecture notes' line and polygon algorithms
// (DDA, midpoint/Bresenham, sorted-intersection scanline fill, tessellation).
#pragma once

#include <cstdint>

namespace tessera {

// ---- Points ---------------------------------------------------------------------------------

enum class PointShape {
  // The pixels (or samples) whose centres lie in the square of side `size` centred on the
  // point, with the triangles' top-left rule on its border: left and top edges inside.
  kSquare,
  // A disc of diameter `size`, antialiased: each pixel's coverage clamp(r + 0.5 - d, 0, 1)
  // (d the distance of the pixel centre from the point) multiplies the fragment's alpha, which
  // is then blended source-over into the colour buffer.
  kRound,
};

inline constexpr float kMaxPointSize = 1024.0f;
inline constexpr float kMaxLineWidth = 1024.0f;

struct PointState {
  float size = 1.0f;  // pixels, in [1, kMaxPointSize]
  PointShape shape = PointShape::kSquare;
};

// ---- Lines ----------------------------------------------------------------------------------

// How one-pixel-wide lines (width == 1, not antialiased) choose their pixels.
enum class LineAlgorithm {
  // OpenGL's and D3D's rule: a pixel is drawn when the segment leaves the pixel's diamond
  // |x - xc| + |y - yc| < 1/2; endpoints are nudged by an infinitesimal (e, e^2) so that no
  // endpoint lies on a diamond's border. Segments of a polyline hit their shared pixel once.
  kDiamondExit,
  // Midpoint / Bresenham: endpoints are moved to the centres of the pixels holding them, then
  // integer-only stepping, one pixel per major-axis step, both end pixels drawn. On a tie (the
  // midpoint exactly on the line) the minor coordinate does not step. Endpoints are ordered so
  // that the major coordinate increases, so a->b and b->a draw the same pixels.
  kBresenham,
  // DDA: endpoints as for kBresenham, then floating-point (double) slope stepping along the
  // major axis, minor coordinate rounded half up (floor(v + 0.5)). Same order as kBresenham.
  kDDA,
};

enum class LineTopology {
  kList,   // vertices (or indices) two at a time
  kStrip,  // a polyline through every vertex
  kLoop,   // a closed polyline: a strip plus the segment from the last vertex to the first
};

// How the segments of a wide strip or loop meet at their shared vertices.
enum class LineJoin {
  kNone,   // butt ends only (the rectangles of the two segments)
  kMiter,  // extended outer edges meeting at a point; bevel when longer than miter_limit
  kRound,  // a disc of the line's width at the vertex
  kBevel,  // the triangle between the two outer corners
};

// glLineStipple: fragment number s of a line (counted along the major axis from the start of
// the segment for lists, of the whole strip or loop otherwise) is drawn when bit
// (s / factor) % 16 of the pattern is set, bit 0 first. pattern 0xFFFF draws everything.
struct LineStipple {
  uint16_t pattern = 0xFFFF;
  uint32_t factor = 1;  // 1..256, as in OpenGL
};

struct LineState {
  LineTopology topology = LineTopology::kList;
  LineAlgorithm algorithm = LineAlgorithm::kDiamondExit;
  // Pixels. 1 draws with `algorithm`; wider lines are rectangles of this width centred on the
  // segment (no end caps), point-sampled with the triangles' fill rule. In [1, kMaxLineWidth].
  float width = 1.0f;
  LineJoin join = LineJoin::kMiter;
  float miter_limit = 4.0f;  // longest miter, in half line widths (SVG's stroke-miterlimit)
  LineStipple stipple;
  // Coverage of the pixel by the line (width `width`, butt ends) multiplies the fragment's
  // alpha, which is blended source-over into the colour buffer.
  bool antialiased = false;
};

// ---- Polygons -------------------------------------------------------------------------------

enum class FillRule {
  kEvenOdd,  // inside when a ray from the sample crosses the outline an odd number of times
  kNonZero,  // inside when the outline's winding number around the sample is not zero
};

enum class PolygonMethod {
  // The lectures' scanline fill: for each row of samples, the crossings with every edge,
  // sorted by x, and the fill rule applied along the row. Any polygon: concave,
  // self-intersecting, with holes.
  kScanline,
  // Ear clipping into triangles (holes joined to their outline by bridges), drawn as a
  // triangle list through the triangle pipeline. Contours must not cross each other or
  // themselves; for such polygons the coverage equals kScanline's.
  kTessellation,
};

// Most vertices a polygon drawn with PolygonMethod::kTessellation may have (ear clipping takes
// time quadratic in the vertex count); larger ones are an Error(kInvalidInput).
inline constexpr uint32_t kMaxTessellationVertices = 16384;

struct PolygonState {
  FillRule fill_rule = FillRule::kEvenOdd;
  PolygonMethod method = PolygonMethod::kScanline;
};

}  // namespace tessera
