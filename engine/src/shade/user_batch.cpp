// A user fragment shader's batch (user_batch.hpp).
#include "engine/src/shade/user_batch.hpp"

#include <algorithm>

namespace tessera::shade {

UserBatch::UserBatch(uint32_t varying_count, std::span<const ColorFormat> extra_formats)
    : varying_count_(varying_count),
      extra_count_(static_cast<uint32_t>(extra_formats.size())),
      buffers_(std::make_unique<Buffers>()) {
  std::copy(extra_formats.begin(), extra_formats.end(), extra_formats_.begin());
}

uint32_t UserBatch::add_quad(uint32_t px, uint32_t py, uint32_t primitive,
                             const uint32_t (&masks)[4]) {
  const uint32_t first = count_;
  Buffers& b = *buffers_;
  for (uint32_t k = 0; k < 4; ++k) {
    const uint32_t i = first + k;
    b.x[i] = static_cast<float>(px + (k & 1)) + 0.5f;
    b.y[i] = static_cast<float>(py + (k >> 1)) + 0.5f;
    b.mask[i] = masks[k];
    b.primitive[i] = primitive;
  }
  count_ += 4;
  return first;
}

void UserBatch::set_derivatives(uint32_t v, uint32_t i, float ddx, float ddy) {
  std::fill_n(buffers_->ddx + v * kStride + i, 4, ddx);
  std::fill_n(buffers_->ddy + v * kStride + i, 4, ddy);
}

void UserBatch::keep_all() {
  std::fill_n(buffers_->discard, count_, uint8_t{0});
}

FragmentBatch UserBatch::view() const {
  const Buffers& b = *buffers_;
  FragmentBatch batch;
  batch.count = count_;
  batch.varying_count = varying_count_;
  batch.x = b.x;
  batch.y = b.y;
  batch.sample_mask = b.mask;
  batch.primitive_id = b.primitive;
  batch.varyings = b.varyings;
  batch.ddx = b.ddx;
  batch.ddy = b.ddy;
  return batch;
}

void UserBatch::run(const FragmentFunction& function) {
  Buffers& b = *buffers_;
  keep_all();
  const FragmentBatch batch = view();
  FragmentOutput output;
  output.color = b.color[0];
  output.discard = b.discard;
  for (uint32_t t = 0; t < extra_count_; ++t) {
    if (extra_formats_[t] == ColorFormat::kR32UI) {
      output.extra_uint[t] = b.id[t + 1];
    } else {
      output.extra[t] = b.color[t + 1];
    }
  }
  function(batch, output);
}

}  // namespace tessera::shade
