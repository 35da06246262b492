// Per-worker bins: for every screen tile, the triangles of one worker's contiguous range of the
// draw that touch it, in submission order. A tile's work is the workers' lists read in worker
// order, which is submission order, so no sorting and no locks are needed (the llvmpipe
// scene/bin design, with one bin set per setup worker).
//
// The lists live in one flat array, built in two steps (a counting sort): while triangles are
// set up, each one's tile rectangle and reference (the value its tiles' lists hold for it: an
// index into the worker's records) are recorded and its tiles' counts raised; then place()
// lays the references out tile by tile into an array of exactly their number. The
// memory a bin set holds is therefore known (bytes()) and its user can keep it within a budget.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace tessera::binning {

// The tiles a triangle's bounding box touches, inclusive.
struct TileRect {
  uint16_t x0, y0, x1, y1;
  uint32_t count() const { return (uint32_t{x1} - x0 + 1) * (uint32_t{y1} - y0 + 1); }
};

// The tiles of side 2^log2 pixels under a bounding box's pixels x0..x1, y0..y1 (on screen: not
// negative).
inline TileRect tile_rect(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t log2) {
  return {static_cast<uint16_t>(x0 >> log2), static_cast<uint16_t>(y0 >> log2),
          static_cast<uint16_t>(x1 >> log2), static_cast<uint16_t>(y1 >> log2)};
}

class Bins {
 public:
  // Bytes held per tile of the grid (its count and its list's start), whatever is binned.
  static constexpr uint64_t kBytesPerTile = 2 * sizeof(uint32_t);
  // Bytes held per binned triangle besides its references (its tile rectangle and reference).
  static constexpr uint64_t kBytesPerTriangle = sizeof(TileRect) + sizeof(uint32_t);
  static constexpr uint64_t kBytesPerReference = sizeof(uint32_t);
  // The most references one bin set holds: place() lays its lists out with 32-bit starts.
  static constexpr uint64_t kMaxReferences = UINT32_MAX;

  // Starts an empty bin set for a grid of `tiles_x` x `tile_count / tiles_x` tiles (allocated
  // capacity is kept).
  void reset(uint32_t tile_count, uint32_t tiles_x) {
    tiles_x_ = tiles_x;
    counts_.assign(tile_count, 0);
    starts_.resize(size_t{tile_count} + 1);
    rects_.clear();
    refs_.clear();
    lists_.clear();
    references_ = 0;
  }
  // Room for `triangles` recorded triangles without reallocating while recording them.
  void reserve_triangles(size_t triangles) {
    rects_.reserve(triangles);
    refs_.reserve(triangles);
  }
  // Frees the triangle and reference arrays (after reset()).
  void release() {
    std::vector<TileRect>().swap(rects_);
    std::vector<uint32_t>().swap(refs_);
    std::vector<uint32_t>().swap(lists_);
  }
  size_t reference_capacity() const { return lists_.capacity(); }
  // Records the next triangle, which the lists of the tiles in `r` will name by `reference`.
  void record(TileRect r, uint32_t reference) {
    rects_.push_back(r);
    refs_.push_back(reference);
    references_ += r.count();
    for_each_tile(r, [&](uint32_t t) { ++counts_[t]; });
  }
  // Forgets the triangles recorded after the first `triangles`.
  void truncate(size_t triangles) {
    for (size_t i = triangles; i < rects_.size(); ++i) {
      references_ -= rects_[i].count();
      for_each_tile(rects_[i], [&](uint32_t t) { --counts_[t]; });
    }
    rects_.resize(triangles);
    refs_.resize(triangles);
  }
  // Lays the recorded triangles' references out, tile by tile, in recording order (each tile's
  // count kept as they were recorded).
  void place() {
    uint32_t start = 0;
    for (size_t t = 0; t < counts_.size(); ++t) {
      starts_[t] = start;
      start += counts_[t];
    }
    starts_[counts_.size()] = start;
    lists_.resize(start);  // from empty: allocates exactly `start` when it must grow
    std::vector<uint32_t>& next = counts_;  // reused as each tile's write position
    for (size_t t = 0; t < next.size(); ++t)
      next[t] = starts_[t];
    for (uint32_t i = 0; i < rects_.size(); ++i) {
      const uint32_t reference = refs_[i];
      for_each_tile(rects_[i], [&](uint32_t t) { lists_[next[t]++] = reference; });
    }
  }
  // Tile t's triangles' references, in submission order (after place()).
  std::span<const uint32_t> tile(uint32_t t) const {
    return {lists_.data() + starts_[t], starts_[t + 1] - starts_[t]};
  }
  uint64_t references() const { return references_; }
  size_t triangles() const { return rects_.size(); }
  // Bytes the bin set holds (allocated capacity, not only what is in use).
  uint64_t bytes() const {
    return counts_.capacity() * sizeof(uint32_t) + starts_.capacity() * sizeof(uint32_t) +
           rects_.capacity() * sizeof(TileRect) + refs_.capacity() * sizeof(uint32_t) +
           lists_.capacity() * sizeof(uint32_t);
  }

 private:
  // Calls visit(t) for each tile t of `r`, row by row. Most triangles of a dense scene touch
  // one tile: they skip the loops.
  template <class Visit>
  void for_each_tile(TileRect r, const Visit& visit) const {
    if (r.x0 == r.x1 && r.y0 == r.y1) {
      visit(r.y0 * tiles_x_ + r.x0);
      return;
    }
    for (uint32_t ty = r.y0; ty <= r.y1; ++ty) {
      for (uint32_t tx = r.x0; tx <= r.x1; ++tx)
        visit(ty * tiles_x_ + tx);
    }
  }

  uint32_t tiles_x_ = 0;
  std::vector<uint32_t> counts_;
  std::vector<uint32_t> starts_;
  std::vector<TileRect> rects_;
  std::vector<uint32_t> refs_;  // per recorded triangle
  std::vector<uint32_t> lists_;
  uint64_t references_ = 0;
};

// How a bin set's room (bytes) splits between triangles (each `triangle_bytes`: its setup, its
// record and its bin entry) and references, for `references_per_triangle` references a
// triangle: as many triangles as the room (and kMaxReferences) holds at that rate, clamped to
// [min_triangles, max_triangles], and the rest for references, at least one a tile and at most
// kMaxReferences.
struct BinRoom {
  uint64_t triangles;
  uint64_t references;
};
inline BinRoom split_bin_room(uint64_t room, uint64_t triangle_bytes,
                              double references_per_triangle, uint64_t min_triangles,
                              uint64_t max_triangles, uint64_t tiles) {
  const double references_each = std::max(references_per_triangle, 1.0);
  const double per_triangle = static_cast<double>(triangle_bytes) +
                              references_each * static_cast<double>(Bins::kBytesPerReference);
  // No more triangles than kMaxReferences holds at that rate either.
  const double fit = std::min(static_cast<double>(room) / per_triangle,
                              static_cast<double>(Bins::kMaxReferences) / references_each);
  const uint64_t triangles =
      std::clamp<uint64_t>(static_cast<uint64_t>(fit), min_triangles, max_triangles);
  const uint64_t rest = room > triangles * triangle_bytes ? room - triangles * triangle_bytes : 0;
  const uint64_t references =
      std::min(std::max(rest / Bins::kBytesPerReference, tiles), Bins::kMaxReferences);
  return {triangles, references};
}

}  // namespace tessera::binning
