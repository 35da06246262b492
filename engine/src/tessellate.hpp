// Tessellation of polygons into triangles (PolygonMethod::kTessellation): ear clipping
// (Meisters 1975) of each filled region, its holes first joined to its outline by bridges
// (Eberly, "Triangulation by Ear Clipping", 2002). Triangles use only the polygon's own
// vertices, so their edges are the polygon's edges and diagonals, and the triangle fill rule
// covers exactly the samples the scanline fill covers.
#pragma once

#include <array>
#include <vector>

#include "engine/src/line_clip.hpp"
#include "tessera/primitives.hpp"

namespace tessera {

// Triangles (indices into the concatenation of the contours' vertices, in contour order) that
// tile the region the fill rule selects. Contours must not cross themselves or each other.
// Degenerate input (fewer than three distinct vertices, no area) gives no triangles.
std::vector<std::array<size_t, 3>> tessellate(const std::vector<std::vector<WindowPoint>>& contours,
                                              FillRule rule);

}  // namespace tessera
