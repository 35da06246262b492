// TRI1 and TRI2 captures: exactly the triangles another renderer drew, to replay them here.
// TRI1 (little-endian): "TRI1"; uint32 width, height, triangle_count; then 3 x count vertices
// of 8 float32: clip-space x, y, z, w in the OpenGL convention (-w <= z <= w, NDC y up) and
// colour r, g, b, a.
// TRI2 (little-endian): "TRI2"; uint32 width, height, triangle_count, varying count K (0 to
// 32); then 3 x count vertices of 4 + K float32: clip-space x, y, z, w as in TRI1, then the K
// varyings, all perspective-correct. A TRI1 capture is a TRI2 capture with K = 4, RGBA.
// tessera-render reads a TRI2 capture's varyings 0..3 as RGBA for Gouraud shading and, for
// per-pixel Phong, 0..2 as the eye-space normal, 3..5 as the eye-space position and 6..9 (when
// K >= 10) as the base colour.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "tessera/export.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/types.hpp"

namespace tessera {

struct Capture {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<Float4> positions;  // 3 per triangle
  uint32_t varying_count = 4;     // per vertex: 4 (TRI1's colour), or TRI2's K
  std::vector<float> varyings;    // varying_count per vertex, vertex-major
};

// Reads a TRI1 or TRI2 capture. Throws Error(kIo) when the file cannot be read,
// Error(kInvalidInput) for a wrong magic, a truncated file, a count that does not match the
// file size, a varying count above 32, a zero or oversized frame, or a NaN/Inf position or
// varying, Error(kOutOfMemory) when the triangles do not fit in memory; the message names the
// file.
TESSERA_API Capture load_capture(const std::filesystem::path& path);
// Writes a TRI1 capture when varying_count is 4 (the same data), TRI2 otherwise, and only what
// load_capture accepts: Error(kInvalidArgument) for sizes that do not match, a varying count
// above 32 or a frame size out of 1..kMaxFramebufferSize, Error(kInvalidInput) for a NaN/Inf
// value, all before the file is touched; Error(kIo) when it cannot be written.
TESSERA_API void save_capture(const std::filesystem::path& path, const Capture& capture);

// The state a capture is replayed with: OpenGL depth convention, depth test LESS, depth
// cleared to far, no culling.
TESSERA_API PipelineState capture_pipeline();

}  // namespace tessera
