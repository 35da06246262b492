// Line clipping, in two stages: in homogeneous clip space against the near, far, w and
// guard-band planes (Liang and Barsky 1984, the planes of clip.hpp), which moves endpoints;
// then in window space Cohen-Sutherland outcodes against the viewport (lecture 002), which
// only reject lines or narrow the range of pixels visited, so that the pixels of a visible
// line never depend on where the viewport cuts it.
#pragma once

#include <array>
#include <cstdint>

#include "engine/src/clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

// Vertex `v` of a validated draw as a ClipVertex: z mapped to the 0 <= z <= w convention,
// attributes copied (the first attribute_count).
ClipVertex load_clip_vertex(const DrawInput& input, const PipelineState& pipeline, size_t v);

// Clips segment a-b to the near, far, w >= kMinClipW and guard-band planes. Returns false when
// nothing is left. Endpoints inside all planes are left untouched (bit for bit), so polylines
// stay connected. Attributes are interpolated in clip space (perspective-correct), or as a * w
// then divided (affine), as the triangle clipper does.
bool clip_line(ClipVertex& a, ClipVertex& b, uint32_t attribute_count, GuardBand guard_band,
               Interpolation interpolation);

// A clipped vertex in window space.
struct WindowPoint {
  double x = 0, y = 0;     // window pixels, y down: the snapped position, x = X / 2^bits
  int64_t fx = 0, fy = 0;  // snapped fixed point (ARCHITECTURE.md section 2)
  double z = 0;            // z / w in [0, 1]
  double inv_w = 1;        // 1 / w
  std::array<float, 4> color{0, 0, 0, 1};  // attributes 0..3; missing ones (0, 0, 0, 1)
};

// The viewport transform and snapping of the triangle rasterizers.
WindowPoint to_window_point(const ClipVertex& v, uint32_t attribute_count, uint32_t width,
                            uint32_t height, uint32_t subpixel_bits);

// Cohen-Sutherland against the rectangle [x0, x1] x [y0, y1] (window pixels): false when the
// segment lies wholly outside it; otherwise [t0, t1] is the part of a + t (b - a) inside it.
bool cohen_sutherland(double ax, double ay, double bx, double by, double x0, double y0, double x1,
                      double y1, double& t0, double& t1);

}  // namespace tessera
