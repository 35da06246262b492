// Per-worker tile lists for primitives binned to any set of tiles (lines visit only the tiles
// near them, not their bounding box): for every screen tile, the primitives of one worker's
// contiguous range of the draw that touch it, in submission order, appended as they come.
// Triangles use the counting-sort bins of bins.hpp, which hold a memory budget.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tessera::binning {

class TileLists {
 public:
  // Empties every list for a grid of `tile_count` tiles, keeping allocated capacity.
  void reset(uint32_t tile_count) {
    if (lists_.size() != tile_count) lists_.assign(tile_count, {});
    for (auto& list : lists_)
      list.clear();
    references_ = 0;
  }
  void add(uint32_t tile, uint32_t triangle) {
    lists_[tile].push_back(triangle);
    ++references_;
  }
  std::span<const uint32_t> tile(uint32_t t) const { return lists_[t]; }
  uint64_t references() const { return references_; }
  // Bytes the references occupy (what the bin memory budget counts).
  uint64_t bytes() const { return references_ * sizeof(uint32_t); }

 private:
  std::vector<std::vector<uint32_t>> lists_;
  uint64_t references_ = 0;
};

}  // namespace tessera::binning
