// Draws whose allocations fail, one allocation after another: the N-th call of operator new
// from the start of the draw throws std::bad_alloc, for N = 0, 1, 2, ... until the draw needs
// fewer than N. Every failure must end the draw with Error(kOutOfMemory), whose message names
// the bin budget only when the bins were what failed, and leave a renderer and a framebuffer
// that draw the next scene exactly as a fresh renderer draws it on a framebuffer holding the
// same pixels (no Hi-Z bounds left stale by the failed draw's tiles, no scratch left half
// made). Its own executable: it replaces the global operator new.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <new>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/tessera.hpp"

namespace {

// Allocations left before the one that fails; negative: none fails.
std::atomic<int64_t> g_allocations_left{-1};

void* allocate(size_t bytes, size_t alignment) {
  if (g_allocations_left.load(std::memory_order_relaxed) >= 0 &&
      g_allocations_left.fetch_sub(1, std::memory_order_relaxed) == 0) {
    throw std::bad_alloc();
  }
  if (bytes == 0) bytes = 1;
  if (alignment > alignof(std::max_align_t) && bytes > SIZE_MAX - alignment) throw std::bad_alloc();
  void* p = alignment <= alignof(std::max_align_t)
                ? std::malloc(bytes)
                : std::aligned_alloc(alignment, (bytes + alignment - 1) / alignment * alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace

void* operator new(size_t bytes) {
  return allocate(bytes, 0);
}
void* operator new[](size_t bytes) {
  return allocate(bytes, 0);
}
void* operator new(size_t bytes, std::align_val_t alignment) {
  return allocate(bytes, static_cast<size_t>(alignment));
}
void* operator new[](size_t bytes, std::align_val_t alignment) {
  return allocate(bytes, static_cast<size_t>(alignment));
}
// The nothrow forms too, so that no allocation reaches another allocator's new (the
// sanitizer's) and comes back through this delete.
static void* allocate_or_null(size_t bytes, size_t alignment) noexcept {
  try {
    return allocate(bytes, alignment);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new(size_t bytes, const std::nothrow_t&) noexcept {
  return allocate_or_null(bytes, 0);
}
void* operator new[](size_t bytes, const std::nothrow_t&) noexcept {
  return allocate_or_null(bytes, 0);
}
void* operator new(size_t bytes, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate_or_null(bytes, static_cast<size_t>(alignment));
}
void* operator new[](size_t bytes, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return allocate_or_null(bytes, static_cast<size_t>(alignment));
}
// The deletes free what the news above malloc'd. GCC 12 at -O1 sees a delete inlined where
// the replaced operator new was called and warns of a mismatch (-Wmismatched-new-delete): a
// false positive for replacement functions.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, size_t, std::align_val_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace tessera {
namespace {

constexpr uint32_t kSize = 256;
constexpr uint64_t kMinBudget = uint64_t{64} << 10;  // the smallest the renderer accepts

struct Soup {
  std::vector<Float4> positions;
  std::vector<float> colors;
  DrawInput input() const { return {positions, colors, 4, {}}; }
};

// count triangles (or count * 3 vertices) of about `extent` in clip space, depth in [lo, hi].
Soup soup(uint32_t seed, size_t count, float extent, float lo, float hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), depth(lo, hi), channel(0.0f, 1.0f);
  Soup s;
  for (size_t i = 0; i < count; ++i) {
    const float cx = unit(rng), cy = unit(rng), z = depth(rng);
    for (int k = 0; k < 3; ++k) {
      s.positions.push_back(
          {cx + extent * unit(rng), cy + extent * unit(rng), z + 0.05f * unit(rng), 1.0f});
      for (int c = 0; c < 4; ++c)
        s.colors.push_back(channel(rng));
    }
  }
  return s;
}

PipelineState depth_tested() {
  PipelineState p;
  p.depth_test = true;
  p.depth_write = true;
  p.depth_compare = CompareOp::kLess;
  return p;
}

struct Case {
  const char* name;
  Backend backend;
  uint32_t samples;
  uint64_t budget;
  const char* call;  // the message's first word
  bool may_fail_in_bins;
  size_t triangles;  // of the failing draw (three vertices each)
  std::function<void(Renderer&, Framebuffer&, const DrawInput&)> draw;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

void draw_triangles(Renderer& r, Framebuffer& fb, const DrawInput& input) {
  r.draw(fb, depth_tested(), input);
}

std::vector<Case> cases() {
  return {
      {"FastTriangles", Backend::kFast, 1, kMinBudget, "draw", true, 4000, draw_triangles},
      {"FastTrianglesFourSamples", Backend::kFast, 4, uint64_t{1} << 20, "draw", true, 4000,
       draw_triangles},
      {"ScanlinePolygon", Backend::kFast, 1, kMinBudget, "draw_polygon", false, 1000,
       [](Renderer& r, Framebuffer& fb, const DrawInput& input) {
         PolygonState state;
         state.method = PolygonMethod::kScanline;
         r.draw_polygon(fb, depth_tested(), state, input);
       }},
      {"WideLineStrip", Backend::kFast, 1, kMinBudget, "draw_lines", true, 400,
       [](Renderer& r, Framebuffer& fb, const DrawInput& input) {
         LineState state;
         state.width = 3.0f;
         state.topology = LineTopology::kStrip;
         r.draw_lines(fb, depth_tested(), state, input);
       }},
      {"ThinLines", Backend::kFast, 1, kMinBudget, "draw_lines", false, 4000,
       [](Renderer& r, Framebuffer& fb, const DrawInput& input) {
         LineState state;
         r.draw_lines(fb, depth_tested(), state, input);
       }},
      {"RoundPoints", Backend::kFast, 1, kMinBudget, "draw_points", false, 4000,
       [](Renderer& r, Framebuffer& fb, const DrawInput& input) {
         PointState state;
         state.size = 5.0f;
         state.shape = PointShape::kRound;
         r.draw_points(fb, depth_tested(), state, input);
       }},
  };
}

// A framebuffer holding `from`'s colour and depth, with its Hi-Z bounds to be recomputed.
void copy_pixels(Framebuffer& from, Framebuffer& to) {
  detail::FramebufferStorage& a = detail::FramebufferAccess::storage(from);
  detail::FramebufferStorage& b = detail::FramebufferAccess::storage(to);
  b.rgba8 = a.rgba8;
  b.rgba32f = a.rgba32f;
  b.depth = a.depth;
  b.hiz_valid = false;
}

class OutOfMemory : public testing::TestWithParam<Case> {};

TEST_P(OutOfMemory, EveryFailedAllocationEndsTheDrawWithAnErrorAndLeavesItUsable) {
  const Case& c = GetParam();
  RendererOptions options;
  options.threads = 2;
  options.backend = c.backend;
  options.bin_memory_budget = c.budget;
  options.bin_tile_size = 32;
  RendererOptions fresh_options = options;
  fresh_options.hiz = false;
  const FramebufferDesc desc{kSize, kSize, c.samples};
  // Even vertex counts, so that a soup is also a line list.
  // The first draw is far smaller than the failing one (40 triangles against thousands), so
  // the failing draw must grow the bin memory the first left, also at the smallest budget.
  const Soup first = soup(1, 40, 0.4f, 0.1f, 0.9f);
  const Soup failing = soup(2, c.triangles, 0.06f, 0.2f, 0.8f);
  const Soup next = soup(3, 400, 0.4f, 0.1f, 0.9f);
  const std::string prefix = std::string(c.call) + ": out of memory";
  const std::string bins_prefix = prefix + " for the bins (bin memory budget ";

  int64_t failures = 0, bin_failures = 0;
  for (int64_t n = 0;; ++n) {
    ASSERT_LT(n, 20000) << "the draw never succeeded";
    Renderer renderer(options);
    Framebuffer fb(desc);
    fb.clear_color({0.0f, 0.0f, 0.0f, 1.0f});
    draw_triangles(renderer, fb, first.input());  // Hi-Z bounds to go stale
    bool failed = false;
    g_allocations_left = n;
    try {
      c.draw(renderer, fb, failing.input());
    } catch (const Error& e) {
      g_allocations_left = -1;
      failed = true;
      SCOPED_TRACE("allocation " + std::to_string(n) + ": " + e.what());
      ASSERT_EQ(e.code(), ErrorCode::kOutOfMemory);
      const std::string message = e.what();
      ASSERT_EQ(message.rfind(prefix, 0), 0u);
      if (message != prefix) {
        ASSERT_TRUE(c.may_fail_in_bins);
        ASSERT_EQ(message.rfind(bins_prefix, 0), 0u);
        // The advice to lower the budget only where it can be lowered.
        EXPECT_EQ(message.find("a smaller budget") != std::string::npos, c.budget > kMinBudget);
        ++bin_failures;
      }
    } catch (...) {
      g_allocations_left = -1;
      FAIL() << "allocation " << n << ": the draw threw something other than tessera::Error";
    }
    g_allocations_left = -1;
    if (!failed) break;
    ++failures;

    Framebuffer copy(desc);
    copy_pixels(fb, copy);
    Renderer fresh(fresh_options);
    // The next draws: triangles, then the failed draw's kind again.
    draw_triangles(renderer, fb, next.input());
    draw_triangles(fresh, copy, next.input());
    c.draw(renderer, fb, next.input());
    c.draw(fresh, copy, next.input());
    ASSERT_EQ(fb.read_rgba8(), copy.read_rgba8()) << "allocation " << n;
    ASSERT_EQ(fb.read_sample_depth(), copy.read_sample_depth()) << "allocation " << n;
  }
  RecordProperty("failed_draws", std::to_string(failures));
  RecordProperty("bin_failures", std::to_string(bin_failures));
  EXPECT_GT(failures, 0);
  if (c.may_fail_in_bins && c.backend == Backend::kFast) {
    EXPECT_GT(bin_failures, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Draws, OutOfMemory, testing::ValuesIn(cases()),
                         [](const testing::TestParamInfo<Case>& param) {
                           return param.param.name;
                         });

}  // namespace
}  // namespace tessera
