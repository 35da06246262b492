// The Renderer: validates draws, owns the task arena, and hands draws to the chosen backend.
#include "tessera/renderer.hpp"

#include <new>
#include <optional>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "engine/src/draw_validation.hpp"
#include "engine/src/fast/fast_raster.hpp"
#include "engine/src/fast/line_raster.hpp"
#include "engine/src/fast/point_raster.hpp"
#include "engine/src/fast/polygon_raster.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/primitive_draw.hpp"
#include "engine/src/reference/reference_raster.hpp"
#include "engine/src/vertex/vertex_stage.hpp"
#include "simd/dispatch.hpp"
#include "tessera/error.hpp"

namespace tessera {

namespace {

// Smallest accepted bin memory budget: room for a few hundred triangles and their references.
constexpr uint64_t kMinBinMemoryBudget = uint64_t{64} << 10;

// A draw that cannot allocate what it needs ends with Error(kOutOfMemory) rather than
// std::bad_alloc. Only the fast engine's setup and binning is bounded by the bin budget
// (fast::BinMemoryError): that message names the budget, and says a smaller one would draw in
// more passes unless it is the minimum already. Anything else (a reference draw, the triangles
// a line, point or polygon draw becomes, a scanline polygon's spans) is reported as such.
template <typename Body>
void out_of_memory_as_error(const char* call, const RendererOptions& options, const Body& body) {
  try {
    body();
  } catch (const fast::BinMemoryError&) {
    const uint64_t budget = options.bin_memory_budget;
    std::string message = std::string(call) + ": out of memory for the bins (bin memory budget " +
                          (budget % (uint64_t{1} << 20) == 0 ? std::to_string(budget >> 20) + " MiB"
                                                             : std::to_string(budget) + " bytes") +
                          ")";
    if (budget > kMinBinMemoryBudget) {
      message += "; a smaller budget draws in more passes with less memory";
    }
    throw Error(ErrorCode::kOutOfMemory, message);
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::kOutOfMemory, std::string(call) + ": out of memory");
  }
}

RendererOptions checked(const RendererOptions& o) {
  if (o.threads > 1024) {
    throw Error(ErrorCode::kInvalidArgument, "renderer thread count " + std::to_string(o.threads) +
                                                 " is out of range (0..1024)");
  }
  if (o.backend != Backend::kReference && o.backend != Backend::kFast) {
    throw Error(ErrorCode::kInvalidArgument, "renderer backend is not a Backend");
  }
  if (o.bin_memory_budget < kMinBinMemoryBudget) {
    throw Error(ErrorCode::kInvalidArgument,
                "bin memory budget " + std::to_string(o.bin_memory_budget) +
                    " bytes is below the minimum of " + std::to_string(kMinBinMemoryBudget));
  }
  if (o.bin_tile_size != 32 && o.bin_tile_size != 64 && o.bin_tile_size != 128) {
    throw Error(ErrorCode::kInvalidArgument,
                "bin tile size " + std::to_string(o.bin_tile_size) + " is not one of 32, 64, 128");
  }
  if (o.non_finite != NonFiniteVertices::kError && o.non_finite != NonFiniteVertices::kCull) {
    throw Error(ErrorCode::kInvalidArgument, "renderer non_finite is not a NonFiniteVertices");
  }
  if (o.block_size != 8 && o.block_size != 16 && o.block_size != 32) {
    throw Error(ErrorCode::kInvalidArgument,
                "block size " + std::to_string(o.block_size) + " is not one of 8, 16, 32");
  }
  return o;
}

}  // namespace

struct Renderer::Impl {
  explicit Impl(const RendererOptions& o)
      : options(checked(o)),
        arena(o.threads == 0 ? tbb::task_arena::automatic : static_cast<int>(o.threads)),
        fast(simd::resolve_target(o.simd), o),
        target_name(simd::target_name(fast.simd_target())) {}
  RendererOptions options;
  tbb::task_arena arena;
  fast::FastRasterizer fast;
  fast::LineScratch lines;
  std::string target_name;
  Counters counters;
  // The vertex stage's output, kept between draws.
  std::vector<Float4> shaded_positions;
  std::vector<float> shaded_varyings;
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

uint32_t Renderer::threads() const noexcept {
  return static_cast<uint32_t>(impl_->arena.max_concurrency());
}
Backend Renderer::backend() const noexcept {
  return impl_->options.backend;
}
const char* Renderer::simd_target() const noexcept {
  return impl_->target_name.c_str();
}
const Counters& Renderer::counters() const noexcept {
  return impl_->counters;
}
void Renderer::reset_counters() noexcept {
  impl_->counters = {};
}

void Renderer::draw(Framebuffer& target, const PipelineState& pipeline, const DrawInput& input) {
  out_of_memory_as_error("draw", impl_->options, [&] {
    const bool cull_non_finite = impl_->options.non_finite == NonFiniteVertices::kCull;
    // The fast engine's setup checks the draws it can (triangle soups with at most four
    // attributes) for NaN and infinity as it reads them, in cache, rather than in a pass of their
    // own over the arrays first, and throws the same error before drawing anything. The others
    // are checked here: an indexed draw's vertices must all be finite, also those no index uses.
    const bool check_in_setup =
        !cull_non_finite && impl_->options.backend == Backend::kFast &&
        fast::FastRasterizer::checks_finite_values(input, pipeline, target.desc());
    validate_draw(target, pipeline, input, !cull_non_finite && !check_in_setup, &impl_->arena);
    // Pending clears are left to the fast engine's tiles (draw_triangles writes them for the
    // reference).
    detail::FramebufferStorage& storage = detail::FramebufferAccess::deferred_storage(target);
    if (!cull_non_finite) {
      draw_triangles(storage, pipeline, input, check_in_setup);
      return;
    }
    const std::vector<bool> finite = finite_vertices(input);
    if (finite.empty()) {
      draw_triangles(storage, pipeline, input);
      return;
    }
    // The triangles whose three vertices are finite, as an index list into the caller's data.
    const size_t triangles =
        (input.indices.empty() ? input.positions.size() : input.indices.size()) / 3;
    std::vector<uint32_t> kept, kept_ids;  // kept_ids: their indices in the caller's draw
    kept.reserve(triangles * 3);
    for (size_t t = 0; t < triangles; ++t) {
      uint32_t v[3];
      for (size_t k = 0; k < 3; ++k)
        v[k] = input.indices.empty() ? static_cast<uint32_t>(3 * t + k) : input.indices[3 * t + k];
      if (finite[v[0]] && finite[v[1]] && finite[v[2]]) {
        kept.insert(kept.end(), v, v + 3);
        kept_ids.push_back(static_cast<uint32_t>(t));  // primitive IDs stay the caller's
      } else {
        ++impl_->counters.triangles_invalid;
      }
    }
    DrawInput valid = input;
    valid.indices = kept;
    if (!kept.empty()) draw_triangles(storage, pipeline, valid, false, kept_ids);
  });
}

void Renderer::draw_vertices(Framebuffer& target, const PipelineState& pipeline,
                             const VertexShader& shader, const VertexInput& input) {
  const uint32_t per_vertex = vertex::validate(shader, input);
  // The shading state against the varyings the stage will write, before the stage runs.
  const size_t triangles = (input.indices.empty() ? input.vertex_count : input.indices.size()) / 3;
  validate_shading(target, pipeline, {{}, {}, per_vertex, {}}, triangles);
  out_of_memory_as_error("draw_vertices", impl_->options, [&] {
    vertex::shade(impl_->arena, impl_->fast.simd_target(), shader, input, per_vertex,
                  impl_->shaded_positions, impl_->shaded_varyings);
  });
  draw(target, pipeline,
       {impl_->shaded_positions, impl_->shaded_varyings, per_vertex, input.indices});
}

void Renderer::draw_triangles(detail::FramebufferStorage& storage, const PipelineState& pipeline,
                              const DrawInput& input, bool check_finite,
                              std::span<const uint32_t> primitive_ids, bool all_targets) {
  if (impl_->options.backend == Backend::kReference) {
    storage.write_all_pending();
    // The reference writes depth without maintaining the fast engine's Hi-Z bounds.
    if (pipeline.depth_test && pipeline.depth_write) storage.hiz_valid = false;
    reference::draw(storage, pipeline, input, impl_->counters, primitive_ids, all_targets);
  } else {
    impl_->fast.draw(impl_->arena, storage, pipeline, input, impl_->counters, check_finite,
                     primitive_ids, all_targets);
  }
}

void Renderer::draw_points(Framebuffer& target, const PipelineState& pipeline,
                           const PointState& state, const DrawInput& input) {
  out_of_memory_as_error("draw_points", impl_->options, [&] {
    validate_points(target, pipeline, state, input);
    detail::FramebufferStorage& storage = detail::FramebufferAccess::storage(target);
    tessera::draw_points(
        storage, pipeline, state, input,
        [&](const PipelineState& p, const DrawInput& t) {
          draw_triangles(storage, p, t, false, {}, false);
        },
        [&](std::span<const WindowPoint> points, float size) {
          if (impl_->options.backend == Backend::kReference) {
            draw_reference_round_points(storage, pipeline, points, size, impl_->counters);
          } else {
            fast::draw_round_points(impl_->arena, storage, pipeline, points, size, impl_->counters);
          }
        },
        impl_->counters);
  });
}

void Renderer::draw_lines(Framebuffer& target, const PipelineState& pipeline,
                          const LineState& state, const DrawInput& input) {
  out_of_memory_as_error("draw_lines", impl_->options, [&] {
    validate_lines(target, pipeline, state, input);
    detail::FramebufferStorage& storage = detail::FramebufferAccess::storage(target);
    tessera::draw_lines(
        storage, pipeline, state, input,
        [&](const PipelineState& p, const DrawInput& t) {
          draw_triangles(storage, p, t, false, {}, false);
        },
        [&](const LineState& s, std::span<const WindowSegment> segments) {
          if (impl_->options.backend == Backend::kReference) {
            draw_reference_thin_lines(storage, pipeline, s, segments, impl_->counters);
          } else {
            fast::draw_thin_lines(impl_->arena, impl_->fast.simd_target(), impl_->lines, storage,
                                  pipeline, s, segments, impl_->counters);
          }
        },
        impl_->counters);
  });
}

void Renderer::draw_polygon(Framebuffer& target, const PipelineState& pipeline,
                            const PolygonState& state, const DrawInput& input,
                            std::span<const uint32_t> contour_sizes) {
  out_of_memory_as_error("draw_polygon", impl_->options, [&] {
    validate_polygon(target, pipeline, state, input, contour_sizes);
    detail::FramebufferStorage& storage = detail::FramebufferAccess::storage(target);
    tessera::draw_polygon(
        storage, pipeline, state, input, contour_sizes,
        [&](const PipelineState& p, const DrawInput& t) {
          draw_triangles(storage, p, t, false, {}, false);
        },
        [&](const std::vector<std::vector<WindowPoint>>& contours, FillRule rule) {
          if (impl_->options.backend == Backend::kReference) {
            draw_reference_scanline_polygon(storage, pipeline, contours, rule, impl_->counters);
          } else {
            fast::draw_scanline_polygon(impl_->arena, storage, pipeline, contours, rule,
                                        impl_->counters);
          }
        },
        impl_->counters);
  });
}

}  // namespace tessera
