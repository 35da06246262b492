// The Renderer: validates draws, owns the task arena, and hands draws to the chosen backend.
#include "tessera/renderer.hpp"

#include <string>

#include <tbb/task_arena.h>

#include "engine/src/draw_validation.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/reference/reference_raster.hpp"
#include "tessera/error.hpp"

namespace tessera {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& o)
      : options(o),
        arena(o.threads == 0 ? tbb::task_arena::automatic : static_cast<int>(o.threads)) {}
  RendererOptions options;
  tbb::task_arena arena;
  Counters counters;
};

namespace {
RendererOptions checked(const RendererOptions& o) {
  if (o.threads > 1024) {
    throw Error(ErrorCode::kInvalidArgument,
                "renderer thread count " + std::to_string(o.threads) + " is out of range (0..1024)");
  }
  if (o.backend != Backend::kReference) {
    throw Error(ErrorCode::kInvalidArgument, "renderer backend is not a Backend");
  }
  return o;
}
}  // namespace

Renderer::Renderer(const RendererOptions& options)
    : impl_(std::make_unique<Impl>(checked(options))) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

uint32_t Renderer::threads() const noexcept {
  return static_cast<uint32_t>(impl_->arena.max_concurrency());
}
Backend Renderer::backend() const noexcept { return impl_->options.backend; }
const Counters& Renderer::counters() const noexcept { return impl_->counters; }
void Renderer::reset_counters() noexcept { impl_->counters = {}; }

void Renderer::draw(Framebuffer& target, const PipelineState& pipeline, const DrawInput& input) {
  validate_draw(target, pipeline, input);
  detail::FramebufferStorage& storage = detail::FramebufferAccess::storage(target);
  reference::draw(storage, pipeline, input, impl_->counters);
}

}  // namespace tessera
