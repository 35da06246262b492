// Bin sets (binning/bins.hpp): references laid out tile by tile in recording order, undone
// triangles forgotten, and the split of a pass's room between triangles and references, which
// never asks one bin set for more references than its 32-bit lists hold.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "binning/bins.hpp"

namespace tessera::binning {
namespace {

std::vector<uint32_t> list(const Bins& bins, uint32_t t) {
  const std::span<const uint32_t> s = bins.tile(t);
  return {s.begin(), s.end()};
}

TEST(Bins, EachTileListsItsTrianglesInRecordingOrder) {
  Bins bins;
  bins.reset(6, 3);               // 3 x 2 tiles
  bins.record({0, 0, 1, 1}, 10);  // tiles 0, 1, 3, 4
  bins.record({2, 1, 2, 1}, 11);  // tile 5
  bins.record({1, 0, 2, 0}, 12);  // tiles 1, 2
  bins.record({0, 0, 2, 1}, 13);  // all
  bins.truncate(3);               // the last one is undone
  bins.record({1, 1, 1, 1}, 14);  // tile 4
  bins.place();
  EXPECT_EQ(bins.triangles(), 4u);
  EXPECT_EQ(bins.references(), 8u);
  EXPECT_EQ(list(bins, 0), (std::vector<uint32_t>{10}));
  EXPECT_EQ(list(bins, 1), (std::vector<uint32_t>{10, 12}));
  EXPECT_EQ(list(bins, 2), (std::vector<uint32_t>{12}));
  EXPECT_EQ(list(bins, 3), (std::vector<uint32_t>{10}));
  EXPECT_EQ(list(bins, 4), (std::vector<uint32_t>{10, 14}));
  EXPECT_EQ(list(bins, 5), (std::vector<uint32_t>{11}));
}

TEST(SplitBinRoom, TrianglesTakeTheirShareAndReferencesTheRest) {
  // 1 MiB, 200 bytes a triangle and 3 references (12 bytes) each: 4946 triangles.
  const uint64_t room = 1 << 20;
  const BinRoom r = split_bin_room(room, 200, 3.0, 8, 1u << 31, 510);
  EXPECT_EQ(r.triangles, room / 212);
  EXPECT_EQ(r.references, (room - r.triangles * 200) / Bins::kBytesPerReference);
  EXPECT_LE(r.triangles * 200 + r.references * Bins::kBytesPerReference, room);
}

TEST(SplitBinRoom, EveryTileHasRoomForAReferenceAndTheTrianglesStayInTheirBounds) {
  const BinRoom tight = split_bin_room(1000, 200, 50.0, 8, 1u << 31, 4096);
  EXPECT_EQ(tight.triangles, 8u);
  EXPECT_EQ(tight.references, 4096u);
  const BinRoom roomy = split_bin_room(uint64_t{1} << 40, 16, 0.0, 8, 1000, 4);
  EXPECT_EQ(roomy.triangles, 1000u);
}

// 64 GiB for a 16384 x 16384 image of 32-pixel tiles (262,144 tiles) and full-screen triangles:
// the references the room holds are about 16 billion. A bin set lays its lists out with 32-bit
// starts, so the split stops at kMaxReferences and the draw takes more passes. (Before, the
// starts wrapped and place() wrote past the end of the lists.)
TEST(SplitBinRoom, ReferencesStopAtWhatOneBinSetHolds) {
  const uint64_t tiles = 262144;
  const BinRoom r =
      split_bin_room(uint64_t{64} << 30, 200, static_cast<double>(tiles), 8, 1u << 31, tiles);
  EXPECT_EQ(r.references, Bins::kMaxReferences);
  // As many triangles as those references hold (65,522 would fit the room's bytes).
  EXPECT_EQ(r.triangles, Bins::kMaxReferences / tiles);
}

}  // namespace
}  // namespace tessera::binning
