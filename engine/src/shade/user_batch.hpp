// The buffers of one batch of a user fragment shader (tessera/shading.hpp's FragmentBatch and
// FragmentOutput): both backends fill a batch quad by quad with the fragments' positions,
// masks, IDs, varyings and derivatives, run the function on it, and write what it returns.
// The layout of the arrays the function sees exists only here.
#pragma once

#include <cstdint>
#include <memory>

#include "tessera/shading.hpp"

namespace tessera::shade {

class UserBatch {
 public:
  static constexpr uint32_t kCapacity = kFragmentBatchStride;
  static constexpr uint32_t kStride = kFragmentBatchStride;

  explicit UserBatch(uint32_t varying_count);

  uint32_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == kCapacity; }
  void clear() { count_ = 0; }

  // Appends a quad whose top-left pixel is (px, py), its pixels' masks in the order
  // top-left, top-right, bottom-left, bottom-right. Returns the index of its first fragment;
  // the caller then sets its values (set_value, set_derivatives). The batch must not be full.
  uint32_t add_quad(uint32_t px, uint32_t py, uint32_t primitive, const uint32_t (&masks)[4]);

  uint32_t mask(uint32_t i) const { return buffers_->mask[i]; }
  // Varying v of fragment i.
  void set_value(uint32_t v, uint32_t i, float value) {
    buffers_->varyings[v * kStride + i] = value;
  }
  float value(uint32_t v, uint32_t i) const { return buffers_->varyings[v * kStride + i]; }
  // Varying v's derivatives, for the four fragments of the quad that starts at fragment i.
  void set_derivatives(uint32_t v, uint32_t i, float ddx, float ddy);

  // Calls `function` on the batch, with every discard flag cleared first.
  void run(const FragmentFunction& function);

  // After run: fragment i's colour channel c, and whether it was discarded.
  float color(uint32_t c, uint32_t i) const { return buffers_->color[c * kStride + i]; }
  bool discarded(uint32_t i) const { return buffers_->discard[i] != 0; }

 private:
  struct Buffers {
    alignas(64) float x[kStride];
    alignas(64) float y[kStride];
    alignas(64) uint32_t mask[kStride];
    alignas(64) uint32_t primitive[kStride];
    alignas(64) float color[4 * kStride];
    alignas(64) uint8_t discard[kStride];
    alignas(64) float varyings[kMaxVaryings * kStride];
    alignas(64) float ddx[kMaxVaryings * kStride];
    alignas(64) float ddy[kMaxVaryings * kStride];
  };
  uint32_t varying_count_;
  uint32_t count_ = 0;
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace tessera::shade
