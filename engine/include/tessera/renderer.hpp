// The renderer: owns its threads (a oneTBB task_arena) and draws triangles into framebuffers.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/types.hpp"

namespace tessera {

enum class Backend {
  kReference,  // the scalar reference rasterizer (ARCHITECTURE.md section 3): the oracle
};

struct RendererOptions {
  uint32_t threads = 1;  // worker threads of the renderer's arena; 1 = fully serial, 0 = all cores
  Backend backend = Backend::kReference;
};

// One draw call's vertex data, all in caller-owned memory that the renderer only reads.
struct DrawInput {
  std::span<const Float4> positions;  // clip space
  // attribute_count floats per vertex, vertex-major. Attributes 0..3 are the colour RGBA;
  // missing colour components read as (0, 0, 0, 1).
  std::span<const float> attributes;
  uint32_t attribute_count = 0;
  // Triangle list indices; empty means positions are taken three at a time.
  std::span<const uint32_t> indices;
};

// Counts of what the renderer did since construction or the last reset_counters().
struct Counters {
  uint64_t triangles_submitted = 0;
  uint64_t triangles_culled = 0;   // back-face, front-face or zero area after snapping
  uint64_t triangles_clipped = 0;  // crossed a clip plane and were cut
  uint64_t triangles_rasterized = 0;
  uint64_t samples_covered = 0;
  uint64_t samples_passed = 0;     // covered and passed the depth test
};

class Renderer {
 public:
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  uint32_t threads() const noexcept;
  Backend backend() const noexcept;

  // Draws a triangle list. All input is validated before anything is drawn: on
  // Error(kInvalidArgument / kInvalidInput) the framebuffer is left as it was.
  void draw(Framebuffer& target, const PipelineState& pipeline, const DrawInput& input);

  const Counters& counters() const noexcept;
  void reset_counters() noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
