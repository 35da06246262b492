// Occlusion queries (tessera/occlusion.hpp): occluders through the fast engine's depth-only
// kernels, conservative answers from the Hi-Z bounds (fast/hiz.hpp), exact ones by drawing the
// query with depth writes off and counting the samples that pass.
#include "tessera/occlusion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/hiz.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "simd/dispatch.hpp"
#include "tessera/error.hpp"

namespace tessera {

namespace {

[[noreturn]] void fail(const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, message);
}

void check_mode(OcclusionMode mode, const char* function) {
  if (mode != OcclusionMode::kConservative && mode != OcclusionMode::kExact) {
    fail(std::string("OcclusionBuffer::") + function + ": mode " +
         std::to_string(static_cast<int>(mode)) + " is not an OcclusionMode");
  }
}

// A query's window-space bounds: the pixels [x0, x1) x [y0, y1) it may touch and its depth
// range, widened by a margin that covers the raster kernels' rounding of depth planes.
struct QueryBounds {
  double x0, y0, x1, y1;
  double z_lo, z_hi;
};

// Clip-space points against the view volume: how many lie outside each plane (x < -w, x > w,
// y < -w, y > w, z < 0, z > w), and whether any reaches behind the near plane (z < 0 or
// w <= 0).
struct ClipTally {
  std::array<uint32_t, 6> outside{};
  uint32_t points = 0;
  bool behind = false;
  void add(double x, double y, double z, double w) {
    outside[0] += x < -w;
    outside[1] += x > w;
    outside[2] += y < -w;
    outside[3] += y > w;
    outside[4] += z < 0;
    outside[5] += z > w;
    behind |= w <= 0 || z < 0;
    ++points;
  }
  // Every point outside one plane: nothing is seen.
  bool culled() const { return std::find(outside.begin(), outside.end(), points) != outside.end(); }
};

// The bounds of window-space points (x, y, depth), the depth range widened by `margin(lo, hi)`.
template <class Points, class Margin>
QueryBounds bounds_of(const Points& points, Margin margin) {
  QueryBounds q{INFINITY, INFINITY, -INFINITY, -INFINITY, INFINITY, -INFINITY};
  for (const auto& [x, y, z] : points) {
    q.x0 = std::min(q.x0, x);
    q.y0 = std::min(q.y0, y);
    q.x1 = std::max(q.x1, x);
    q.y1 = std::max(q.y1, y);
    q.z_lo = std::min(q.z_lo, z);
    q.z_hi = std::max(q.z_hi, z);
  }
  const double m = margin(q.z_lo, q.z_hi);
  q.z_lo -= m;
  q.z_hi += m;
  return q;
}

// The twelve triangles of a box's six faces over corners numbered by bits (x, y, z) of lo/hi.
constexpr std::array<uint32_t, 36> kBoxIndices = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5,
                                                  0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6,
                                                  0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};

}  // namespace

struct OcclusionBuffer::Impl {
  OcclusionDesc desc;
  // Written by clear() and draw_occluders() only; the exact queries draw into it with depth
  // and colour writes off, which reads it (the Hi-Z bounds are up to date, nothing is pending).
  mutable Framebuffer fb;
  Renderer occluders;
  PipelineState occluder_pipeline, query_pipeline;
  const fast::KernelTable* table;
  float far_depth;
  // Renderers for exact queries, one per query running at a time.
  mutable std::mutex pool_lock;
  mutable std::vector<std::unique_ptr<Renderer>> pool;

  explicit Impl(const OcclusionDesc& d)
      : desc(d),
        fb({d.width, d.height, d.samples, ColorFormat::kRGBA8, d.depth_format}),
        occluders([&] {
          RendererOptions o;
          o.threads = d.threads;
          o.simd = d.simd;
          o.raster_counters = false;
          return o;
        }()),
        table(&fast::kernel_table(simd::resolve_target(d.simd))),
        far_depth(d.reversed_z ? 0.0f : 1.0f) {
    occluder_pipeline.color_write = false;
    occluder_pipeline.depth_compare = d.reversed_z ? CompareOp::kGreater : CompareOp::kLess;
    query_pipeline = occluder_pipeline;
    query_pipeline.depth_write = false;
    query_pipeline.depth_compare = d.reversed_z ? CompareOp::kGreaterEqual : CompareOp::kLessEqual;
  }

  // Writes the pending clears and brings every Hi-Z block up to date: from then on queries
  // only read the storage.
  void settle() { fast::refresh_dirty_hiz(*table, detail::FramebufferAccess::storage(fb)); }

  bool exact(const DrawInput& input) const {
    std::unique_ptr<Renderer> renderer;
    {
      const std::lock_guard<std::mutex> hold(pool_lock);
      if (!pool.empty()) {
        renderer = std::move(pool.back());
        pool.pop_back();
      }
    }
    if (!renderer) {
      RendererOptions o;
      o.threads = 1;
      o.simd = desc.simd;
      o.raster_counters = true;
      renderer = std::make_unique<Renderer>(o);
    }
    renderer->reset_counters();
    renderer->draw(fb, query_pipeline, input);
    const bool visible = renderer->counters().samples_passed > 0;
    const std::lock_guard<std::mutex> hold(pool_lock);
    pool.push_back(std::move(renderer));
    return visible;
  }

  // What the Hi-Z blocks say of a query within bounds `q`: hidden when every block the bounds
  // touch rejects it (also for bounds past the buffer), visible when a block accepts it and
  // holds one of the pixels in `inside` (x0, y0, x1, y1, inclusive), whose every sample the
  // query surely covers; otherwise unknown.
  enum class Answer { kHidden, kVisible, kUnknown };
  Answer hiz_answer(const QueryBounds& q,
                    const std::array<double, 4>& inside = {1, 1, 0, 0}) const {
    const detail::FramebufferStorage& s = detail::FramebufferAccess::storage(std::as_const(fb));
    const double w = s.desc.width, h = s.desc.height;
    // The pixels the bounds overlap (a superset of those whose samples they cover).
    const double px0 = std::max(std::floor(q.x0), 0.0), py0 = std::max(std::floor(q.y0), 0.0);
    const double px1 = std::min(std::ceil(q.x1), w) - 1, py1 = std::min(std::ceil(q.y1), h) - 1;
    if (!(px0 <= px1 && py0 <= py1)) return Answer::kHidden;  // nothing on the buffer
    // The surely covered pixels on the buffer.
    const double ix0 = std::max(inside[0], 0.0), iy0 = std::max(inside[1], 0.0);
    const double ix1 = std::min(inside[2], w - 1), iy1 = std::min(inside[3], h - 1);
    float lo, hi;
    fast::hiz_range(static_cast<float>(detail::depth_scale(s.desc.depth_format)), q.z_lo, q.z_hi,
                    lo, hi);
    const uint32_t bx0 = static_cast<uint32_t>(px0) >> detail::kBlockSizeLog2;
    const uint32_t by0 = static_cast<uint32_t>(py0) >> detail::kBlockSizeLog2;
    const uint32_t bx1 = static_cast<uint32_t>(px1) >> detail::kBlockSizeLog2;
    const uint32_t by1 = static_cast<uint32_t>(py1) >> detail::kBlockSizeLog2;
    bool hidden = true;
    for (uint32_t by = by0; by <= by1; ++by) {
      for (uint32_t bx = bx0; bx <= bx1; ++bx) {
        const uint32_t x = bx << detail::kBlockSizeLog2, y = by << detail::kBlockSizeLog2;
        const size_t block = size_t{s.grid.tile_of(x, y)} * detail::kBlocksPerTile +
                             detail::in_tile(x, y) / detail::kBlockPixels;
        const float block_min = s.hiz_min[block], block_max = s.hiz_max[block];
        if (fast::hiz_dirty(block_min, block_max)) {
          hidden = false;
          continue;
        }
        const fast::HizVerdict verdict =
            fast::hiz_test(query_pipeline.depth_compare, lo, hi, block_min, block_max);
        if (verdict == fast::HizVerdict::kReject) continue;
        hidden = false;
        const double last = detail::kBlockSize - 1;
        if (verdict == fast::HizVerdict::kAccept &&
            std::max<double>(x, ix0) <= std::min(x + last, ix1) &&
            std::max<double>(y, iy0) <= std::min(y + last, iy1)) {
          return Answer::kVisible;
        }
      }
    }
    return hidden ? Answer::kHidden : Answer::kUnknown;
  }

  // Window x, y and depth of a clip-space point with w > 0.
  std::array<double, 3> to_window(double x, double y, double z, double w) const {
    return {(x / w + 1.0) * 0.5 * desc.width, (1.0 - y / w) * 0.5 * desc.height, z / w};
  }
};

OcclusionBuffer::OcclusionBuffer(const OcclusionDesc& desc) : impl_(std::make_unique<Impl>(desc)) {
  clear();
}
OcclusionBuffer::~OcclusionBuffer() = default;
OcclusionBuffer::OcclusionBuffer(OcclusionBuffer&&) noexcept = default;
OcclusionBuffer& OcclusionBuffer::operator=(OcclusionBuffer&&) noexcept = default;

const OcclusionDesc& OcclusionBuffer::desc() const noexcept {
  return impl_->desc;
}
const Framebuffer& OcclusionBuffer::framebuffer() const {
  return impl_->fb;
}

void OcclusionBuffer::clear() {
  impl_->fb.clear_depth(impl_->far_depth);
  impl_->settle();
}

void OcclusionBuffer::draw_occluders(const DrawInput& occluders) {
  DrawInput input = occluders;
  input.attributes = {};
  input.attribute_count = 0;
  impl_->occluders.draw(impl_->fb, impl_->occluder_pipeline, input);
  impl_->settle();
}

bool OcclusionBuffer::rect_visible(float x0, float y0, float x1, float y1, float nearest_depth,
                                   OcclusionMode mode) const {
  check_mode(mode, "rect_visible");
  if (std::isnan(x0) || std::isnan(y0) || std::isnan(x1) || std::isnan(y1) ||
      std::isnan(nearest_depth)) {
    fail("OcclusionBuffer::rect_visible: a bound or the depth is NaN");
  }
  const double z = std::clamp(double{nearest_depth}, 0.0, 1.0);
  if (!(x0 < x1 && y0 < y1)) return false;  // empty
  // The Hi-Z answer first, for both modes: the exact mode draws only what it leaves unknown.
  // A pixel whose every sample the rectangle covers lies an eighth of a pixel inside it (more
  // than the rounding of its corners through clip space and the raster's snapping).
  const double margin = fast::hiz_margin(z, 0.0f, 0.0f);
  const Impl::Answer answer =
      impl_->hiz_answer({x0, y0, x1, y1, z - margin, z + margin},
                        {std::ceil(x0 + 0.125), std::ceil(y0 + 0.125), std::floor(x1 - 0.125) - 1,
                         std::floor(y1 - 0.125) - 1});
  if (answer != Impl::Answer::kUnknown) return answer == Impl::Answer::kVisible;
  if (mode == OcclusionMode::kConservative) return true;
  // Two triangles at depth z (w = 1), the rectangle clamped a buffer's size beyond its edges
  // (inside the clipper's guard band).
  const double w = impl_->desc.width, h = impl_->desc.height;
  const auto cx = [&](double x) {
    return static_cast<float>(std::clamp(x, -w, 2 * w) / w * 2 - 1);
  };
  const auto cy = [&](double y) {
    return static_cast<float>(1 - std::clamp(y, -h, 2 * h) / h * 2);
  };
  const float zf = static_cast<float>(z);
  const Float4 corners[4] = {{cx(x0), cy(y0), zf, 1},
                             {cx(x1), cy(y0), zf, 1},
                             {cx(x1), cy(y1), zf, 1},
                             {cx(x0), cy(y1), zf, 1}};
  const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  DrawInput input;
  input.positions = corners;
  input.indices = indices;
  return impl_->exact(input);
}

bool OcclusionBuffer::box_visible(const glm::vec3& lo, const glm::vec3& hi,
                                  const glm::mat4& clip_from_object, OcclusionMode mode) const {
  check_mode(mode, "box_visible");
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || !(lo[k] <= hi[k])) {
      fail(
          "OcclusionBuffer::box_visible: the box's corners must be finite with lo <= hi, got "
          "lo[" +
          std::to_string(k) + "] = " + std::to_string(lo[k]) + ", hi[" + std::to_string(k) +
          "] = " + std::to_string(hi[k]));
    }
  }
  const glm::dmat4 m(clip_from_object);
  std::array<glm::dvec4, 8> clip;
  ClipTally tally;
  for (uint32_t c = 0; c < 8; ++c) {
    const glm::dvec4 p =
        m * glm::dvec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1.0);
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w))) {
      fail("OcclusionBuffer::box_visible: corner " + std::to_string(c) +
           " is not finite in clip space (the matrix holds a NaN or infinity?)");
    }
    clip[c] = p;
    tally.add(p.x, p.y, p.z, p.w);
  }
  if (tally.culled()) return false;
  if (tally.behind) return true;  // reaches behind the near plane: around the eye
  std::array<std::array<double, 3>, 8> window;
  for (uint32_t c = 0; c < 8; ++c)
    window[c] = impl_->to_window(clip[c].x, clip[c].y, clip[c].z, clip[c].w);
  if (impl_->hiz_answer(bounds_of(window, [](double z_lo, double z_hi) {
        return 1e-6 * (1.0 + std::abs(z_lo) + (z_hi - z_lo));
      })) == Impl::Answer::kHidden) {
    return false;
  }
  if (mode == OcclusionMode::kConservative) return true;
  std::array<Float4, 8> positions;
  for (uint32_t c = 0; c < 8; ++c) {
    positions[c] = {static_cast<float>(clip[c].x), static_cast<float>(clip[c].y),
                    static_cast<float>(clip[c].z), static_cast<float>(clip[c].w)};
  }
  DrawInput input;
  input.positions = positions;
  input.indices = kBoxIndices;
  return impl_->exact(input);
}

bool OcclusionBuffer::triangles_visible(const DrawInput& triangles, OcclusionMode mode) const {
  check_mode(mode, "triangles_visible");
  DrawInput input = triangles;
  input.attributes = {};
  input.attribute_count = 0;
  const size_t count = input.indices.empty() ? input.positions.size() : input.indices.size();
  if (count % 3 != 0) {
    throw Error(ErrorCode::kInvalidInput,
                "OcclusionBuffer::triangles_visible: " + std::to_string(count) +
                    (input.indices.empty() ? " positions" : " indices") +
                    " do not make whole triangles");
  }
  const auto vertex = [&](size_t i) -> const Float4& {
    const size_t v = input.indices.empty() ? i : input.indices[i];
    if (v >= input.positions.size()) {
      throw Error(ErrorCode::kInvalidInput,
                  "OcclusionBuffer::triangles_visible: index " + std::to_string(i) + " (" +
                      std::to_string(v) + ") is past the " +
                      std::to_string(input.positions.size()) + " positions");
    }
    const Float4& p = input.positions[v];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w))) {
      throw Error(ErrorCode::kInvalidInput, "OcclusionBuffer::triangles_visible: vertex " +
                                                std::to_string(v) + " is not finite");
    }
    return p;
  };
  bool visible = false;
  for (size_t t = 0; t < count; t += 3) {
    const Float4* p[3] = {&vertex(t), &vertex(t + 1), &vertex(t + 2)};
    if (visible) continue;  // the rest is only validated
    ClipTally tally;
    for (const Float4* v : p)
      tally.add(v->x, v->y, v->z, v->w);
    if (tally.culled()) continue;
    if (tally.behind) {
      visible = true;
      continue;
    }
    std::array<std::array<double, 3>, 3> win;
    for (int k = 0; k < 3; ++k)
      win[k] = impl_->to_window(p[k]->x, p[k]->y, p[k]->z, p[k]->w);
    // The depth plane's slopes per pixel (0 for a degenerate triangle), for the margin the
    // engine's Hi-Z gives its own triangles (fast::hiz_margin).
    const double ax = win[1][0] - win[0][0], ay = win[1][1] - win[0][1];
    const double bx = win[2][0] - win[0][0], by = win[2][1] - win[0][1];
    const double az = win[1][2] - win[0][2], bz = win[2][2] - win[0][2];
    const double area = ax * by - ay * bx;
    const double z_dx = area != 0 ? (az * by - bz * ay) / area : 0.0;
    const double z_dy = area != 0 ? (ax * bz - bx * az) / area : 0.0;
    visible = impl_->hiz_answer(bounds_of(win, [&](double lo, double) {
      return fast::hiz_margin(lo, static_cast<float>(z_dx), static_cast<float>(z_dy));
    })) != Impl::Answer::kHidden;
  }
  // What Hi-Z hides no sample can see; the rest is drawn.
  if (!visible || mode == OcclusionMode::kConservative) return visible;
  return impl_->exact(input);
}

}  // namespace tessera
