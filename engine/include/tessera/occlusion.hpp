// Occlusion queries: occluders drawn into a depth buffer (with its Hi-Z) only, at a resolution
// of the caller's choice, then asked whether a screen rectangle, a box or a triangle list would
// be visible behind them (the job of Masked Software Occlusion Culling in an engine).
//
//   tessera::OcclusionBuffer occlusion({256, 128});
//   occlusion.draw_occluders(walls);                       // clip-space triangles
//   if (occlusion.box_visible(lo, hi, view_projection * model)) draw(object);
#pragma once

#include <cstdint>
#include <memory>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "tessera/export.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

enum class OcclusionMode : uint8_t {
  // From the Hi-Z blocks' depth bounds only (8x8 pixels each), against the query's bounding
  // rectangle and nearest depth: may answer visible for a hidden query, never hidden for a
  // visible one. Cheap: a few compares per block the rectangle touches.
  kConservative,
  // Every sample the query covers (the engine's coverage and fill rule) tested against the
  // depth buffer with LESS_EQUAL (GREATER_EQUAL reversed), depth writes off: visible when any
  // sample passes, like GL_ANY_SAMPLES_PASSED.
  kExact,
};

struct OcclusionDesc {
  uint32_t width = 0;   // the depth buffer's resolution: 1..kMaxFramebufferSize
  uint32_t height = 0;  // 1..kMaxFramebufferSize
  uint32_t samples = 1;
  DepthFormat depth_format = DepthFormat::kFloat32;
  // Reversed Z: depth cleared to 0, occluders drawn with GREATER, queries pass with
  // GREATER_EQUAL (nearer is larger).
  bool reversed_z = false;
  uint32_t threads = 0;                 // the occluder draws' worker threads (0: every core)
  SimdTarget simd = SimdTarget::kAuto;  // the kernels' target, as RendererOptions::simd
};

// A depth-only buffer of occluders. Clip space and window conventions are the renderer's
// (z/w in [0, 1], window y down, the whole buffer the viewport). Queries are const and may run
// from several threads at once while no clear() or draw_occluders() runs.
class TESSERA_API OcclusionBuffer {
 public:
  // Throws Error(kInvalidArgument) for a bad size or sample count (as Framebuffer does).
  explicit OcclusionBuffer(const OcclusionDesc& desc);
  ~OcclusionBuffer();
  OcclusionBuffer(OcclusionBuffer&&) noexcept;
  OcclusionBuffer& operator=(OcclusionBuffer&&) noexcept;
  OcclusionBuffer(const OcclusionBuffer&) = delete;
  OcclusionBuffer& operator=(const OcclusionBuffer&) = delete;

  const OcclusionDesc& desc() const noexcept;

  // Every sample at the far depth (1, or 0 reversed): nothing occludes.
  void clear();
  // Draws clip-space triangles (the positions, and the indices when given; attributes are
  // ignored) into the depth buffer with LESS (GREATER reversed), both faces. Validated as
  // Renderer::draw validates: a bad input is an Error and draws nothing.
  void draw_occluders(const DrawInput& occluders);

  // Whether the window rectangle [x0, x1) x [y0, y1) (pixels, y down) at window depth
  // `nearest_depth` (0..1; the rectangle's nearest point) would be visible. Parts outside the
  // buffer are not seen. Throws Error(kInvalidArgument) for a NaN bound or depth.
  bool rect_visible(float x0, float y0, float x1, float y1, float nearest_depth,
                    OcclusionMode mode = OcclusionMode::kConservative) const;
  // Whether the axis-aligned box [lo, hi] (object space), seen through `clip_from_object`
  // (projection * view * model), would be visible. A box reaching behind the near plane
  // (a corner with z < 0 or w <= 0 in clip space) is visible in both modes. Throws
  // Error(kInvalidArgument) for a non-finite corner or lo > hi.
  bool box_visible(const glm::vec3& lo, const glm::vec3& hi, const glm::mat4& clip_from_object,
                   OcclusionMode mode = OcclusionMode::kConservative) const;
  // Whether any of the clip-space triangles would be visible (both faces). Conservative: each
  // triangle's bounding rectangle at its nearest vertex depth; a triangle reaching behind the
  // near plane is visible. Validated as draw_occluders().
  bool triangles_visible(const DrawInput& triangles,
                         OcclusionMode mode = OcclusionMode::kConservative) const;

  // The depth buffer (read_depth() and the like); its colour target is unused.
  const Framebuffer& framebuffer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
