// The buffers of one batch of a user fragment shader (tessera/shading.hpp's FragmentBatch and
// FragmentOutput): both backends fill a batch quad by quad with the fragments' positions,
// masks, IDs, varyings and derivatives, run the function on it, and write what it returns.
// The layout of the arrays the function sees exists only here.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "tessera/framebuffer.hpp"
#include "tessera/shading.hpp"

namespace tessera::shade {

class UserBatch {
 public:
  static constexpr uint32_t kCapacity = kFragmentBatchStride;
  static constexpr uint32_t kStride = kFragmentBatchStride;

  // `varying_count` varyings reach the function; the framebuffer's extra targets have
  // `extra_formats` (the function writes them through FragmentOutput::extra and extra_uint).
  explicit UserBatch(uint32_t varying_count, std::span<const ColorFormat> extra_formats = {});

  uint32_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == kCapacity; }
  void clear() { count_ = 0; }

  // Appends a quad whose top-left pixel is (px, py), its pixels' masks in the order
  // top-left, top-right, bottom-left, bottom-right. Returns the index of its first fragment;
  // the caller then sets its values (set_value, set_derivatives). The batch must not be full.
  uint32_t add_quad(uint32_t px, uint32_t py, uint32_t primitive, const uint32_t (&masks)[4]);

  uint32_t mask(uint32_t i) const { return buffers_->mask[i]; }
  uint32_t primitive(uint32_t i) const { return buffers_->primitive[i]; }
  // Varying v of fragment i.
  void set_value(uint32_t v, uint32_t i, float value) {
    buffers_->varyings[v * kStride + i] = value;
  }
  float value(uint32_t v, uint32_t i) const { return buffers_->varyings[v * kStride + i]; }
  // Varying v's derivatives, for the four fragments of the quad that starts at fragment i.
  void set_derivatives(uint32_t v, uint32_t i, float ddx, float ddy);

  // The batch as a function sees it (its positions, masks, IDs, varyings and derivatives).
  FragmentBatch view() const;
  // Calls `function` on the batch, with every discard flag cleared first.
  void run(const FragmentFunction& function);
  // Clears every discard flag, for a batch no function runs on (built-in targets only).
  void keep_all();

  // After run: fragment i's colour channel c in target 0, and whether it was discarded.
  float color(uint32_t c, uint32_t i) const { return buffers_->color[0][c * kStride + i]; }
  bool discarded(uint32_t i) const { return buffers_->discard[i] != 0; }
  // Target t's values: channel c of fragment i at [c * kStride + i] (R32F: channel 0), and an
  // R32UI target's at id(t)[i]. The function's, or those a back end stores for a target the
  // function does not feed.
  float* target_color(uint32_t t) { return buffers_->color[t]; }
  const float* target_color(uint32_t t) const { return buffers_->color[t]; }
  uint32_t* target_id(uint32_t t) { return buffers_->id[t]; }
  const uint32_t* target_id(uint32_t t) const { return buffers_->id[t]; }

 private:
  struct Buffers {
    alignas(64) float x[kStride];
    alignas(64) float y[kStride];
    alignas(64) uint32_t mask[kStride];
    alignas(64) uint32_t primitive[kStride];
    alignas(64) float color[kMaxColorTargets][4 * kStride];
    alignas(64) uint32_t id[kMaxColorTargets][kStride];
    alignas(64) uint8_t discard[kStride];
    alignas(64) float varyings[kMaxVaryings * kStride];
    alignas(64) float ddx[kMaxVaryings * kStride];
    alignas(64) float ddy[kMaxVaryings * kStride];
  };
  uint32_t varying_count_;
  uint32_t extra_count_ = 0;
  std::array<ColorFormat, kMaxColorTargets - 1> extra_formats_{};
  uint32_t count_ = 0;
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace tessera::shade
