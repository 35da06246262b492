// Fuzzes the public draw API with hostile state and vertex data on the fast and reference backends:
// both throw the same tessera::Error or both draw, a failed draw changes nothing, coverage agrees
// for every primitive.
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tessera/tessera.hpp"

namespace {

using namespace tessera;

[[noreturn]] void broken(const char* rule, const std::string& detail = {}) {
  std::fprintf(stderr, "draw_api_fuzzer: %s %s\n", rule, detail.c_str());
  std::abort();
}

// A value of the enum's underlying type, most often in range, sometimes just past it.
template <typename E>
E some_enum(FuzzedDataProvider& in, E last) {
  const auto v = in.ConsumeIntegralInRange<unsigned>(0, static_cast<unsigned>(last) + 8);
  return static_cast<E>(
      v <= static_cast<unsigned>(last) + 1 ? v : v % (static_cast<unsigned>(last) + 1));
}

template <typename T, size_t N>
T pick(FuzzedDataProvider& in, const T (&values)[N]) {
  return values[in.ConsumeIntegralInRange<size_t>(0, N - 1)];
}

// A float that is usually a plausible coordinate or colour and sometimes anything at all.
float hostile_float(FuzzedDataProvider& in, float scale) {
  static constexpr float kSpecial[] = {0.0f,
                                       -0.0f,
                                       1.0f,
                                       -1.0f,
                                       0.5f,
                                       std::numeric_limits<float>::quiet_NaN(),
                                       std::numeric_limits<float>::infinity(),
                                       -std::numeric_limits<float>::infinity(),
                                       std::numeric_limits<float>::max(),
                                       -std::numeric_limits<float>::max(),
                                       std::numeric_limits<float>::min(),
                                       std::numeric_limits<float>::denorm_min(),
                                       1e-30f,
                                       16777216.0f,
                                       1e10f,
                                       -1e10f,
                                       65536.0f,
                                       1.0000001f};
  switch (in.ConsumeIntegralInRange<int>(0, 7)) {
    case 0:
      return std::bit_cast<float>(in.ConsumeIntegral<uint32_t>());
    case 1:
      return pick(in, kSpecial);
    default:
      return static_cast<float>(in.ConsumeIntegral<int8_t>()) * scale;
  }
}

// Byte equality (NaN, which the fuzzer passes, is not equal to itself as a float).
template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

struct Contents {
  std::vector<uint8_t> rgba8;
  std::vector<float> rgba32f;
  std::vector<float> depth;
  bool operator==(const Contents& o) const {
    return rgba8 == o.rgba8 && same_bytes(rgba32f, o.rgba32f) && same_bytes(depth, o.depth);
  }
};

Contents snapshot(const Framebuffer& fb) {
  Contents i;
  i.rgba8 = fb.read_rgba8();
  if (fb.desc().color_format == ColorFormat::kRGBA32F) i.rgba32f = fb.read_rgba32f();
  i.depth = fb.read_sample_depth();
  return i;
}

enum class Primitive { kTriangles, kPoints, kLines, kPolygon };

// One draw call, decoded from the fuzz input.
struct Call {
  Primitive primitive = Primitive::kTriangles;
  PipelineState pipeline;
  PointState point;
  LineState line;
  PolygonState polygon;
  std::vector<Float4> positions;
  std::vector<float> attributes;
  uint32_t attribute_count = 4;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> contours;
  // Coverage comparison: a flat depth per primitive (one for the whole draw where strips, loops,
  // polygons and indexed draws share vertices between primitives) under compare ALWAYS, or
  // with a depth per primitive any compare op (decode_call), so a sample's final depth names
  // the primitive that won it (tests/fast_engine_test.cpp, tests/primitive_engine_test.cpp).
  bool compare = false;
  // Colours are compared too (within one 8-bit step) when the vertices are tame.
  bool compare_color = false;
  // The depth the comparison's framebuffers are cleared to.
  float compare_clear_depth = 1.0f;

  DrawInput input() const { return {positions, attributes, attribute_count, indices}; }
};

Call decode_call(FuzzedDataProvider& in, uint32_t fb_samples) {
  Call c;
  c.compare = in.ConsumeBool();
  c.primitive = some_enum(in, Primitive::kPolygon);

  PipelineState& p = c.pipeline;
  p.depth_test = in.ConsumeBool();
  p.depth_write = in.ConsumeBool();
  p.color_write = in.ConsumeBool();
  p.depth_compare = some_enum(in, CompareOp::kAlways);
  p.cull = some_enum(in, CullMode::kBack);
  p.front_face = some_enum(in, FrontFace::kClockwise);
  p.clip_depth = some_enum(in, ClipDepth::kNegativeOneToOne);
  p.interpolation = some_enum(in, Interpolation::kAffine);
  const uint32_t samples[] = {0, 0, 0, fb_samples, 1, 2, 4, 8, 16, 3};
  p.samples = pick(in, samples);
  const uint32_t bits[] = {8, 8, 4, 5, 6, 7, 3, 9, 0};
  p.subpixel_bits = pick(in, bits);

  c.point.size = in.ConsumeBool() ? hostile_float(in, 1.0f)
                                  : static_cast<float>(in.ConsumeIntegralInRange<int>(1, 40));
  c.point.shape = some_enum(in, PointShape::kRound);
  c.line.topology = some_enum(in, LineTopology::kLoop);
  c.line.algorithm = some_enum(in, LineAlgorithm::kDDA);
  c.line.width = in.ConsumeBool() ? hostile_float(in, 1.0f)
                                  : static_cast<float>(in.ConsumeIntegralInRange<int>(1, 12));
  c.line.join = some_enum(in, LineJoin::kBevel);
  c.line.miter_limit = in.ConsumeBool() ? hostile_float(in, 1.0f) : 4.0f;
  // A quarter of the patterns solid (0xFFFF, the default: no stipple), whose lines take the
  // fast engine's run writer and the wide lines' whole rectangles; the others any pattern.
  c.line.stipple.pattern =
      in.ConsumeIntegralInRange<int>(0, 3) == 0 ? uint16_t{0xFFFF} : in.ConsumeIntegral<uint16_t>();
  c.line.stipple.factor = in.ConsumeIntegralInRange<uint32_t>(0, 257);
  c.line.antialiased = in.ConsumeBool();
  c.polygon.fill_rule = some_enum(in, FillRule::kNonZero);
  c.polygon.method = some_enum(in, PolygonMethod::kTessellation);

  const size_t vertices = in.ConsumeIntegralInRange<size_t>(0, 48);
  const bool tame = in.ConsumeBool();
  for (size_t v = 0; v < vertices; ++v) {
    Float4 pos;
    if (tame) {
      pos.x = static_cast<float>(in.ConsumeIntegral<int8_t>()) / 64.0f;
      pos.y = static_cast<float>(in.ConsumeIntegral<int8_t>()) / 64.0f;
      pos.z = static_cast<float>(in.ConsumeIntegral<uint8_t>()) / 200.0f;
      pos.w = 0.25f + static_cast<float>(in.ConsumeIntegral<uint8_t>()) / 64.0f;
      pos.x *= pos.w, pos.y *= pos.w, pos.z *= pos.w;
    } else {
      pos.x = hostile_float(in, 1.0f / 64.0f);
      pos.y = hostile_float(in, 1.0f / 64.0f);
      pos.z = hostile_float(in, 1.0f / 128.0f);
      pos.w = in.ConsumeBool() ? 1.0f : hostile_float(in, 1.0f / 32.0f);
    }
    c.positions.push_back(pos);
  }
  c.attribute_count =
      in.ConsumeBool() ? 4 : in.ConsumeIntegralInRange<uint32_t>(0, kMaxVaryings + 1);
  size_t floats = vertices * c.attribute_count;
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0)
    floats = in.ConsumeIntegralInRange<size_t>(0, floats + 2);
  for (size_t i = 0; i < floats; ++i) {
    c.attributes.push_back(tame ? static_cast<float>(in.ConsumeIntegral<uint8_t>()) / 255.0f
                                : hostile_float(in, 1.0f / 100.0f));
  }
  if (in.ConsumeBool()) {
    const size_t count = in.ConsumeIntegralInRange<size_t>(0, 60);
    for (size_t i = 0; i < count; ++i) {
      c.indices.push_back(
          in.ConsumeIntegralInRange<int>(0, 31) == 0
              ? in.ConsumeIntegral<uint32_t>()
              : in.ConsumeIntegralInRange<uint32_t>(0, static_cast<uint32_t>(vertices)));
    }
  }
  if (c.primitive == Primitive::kPolygon && in.ConsumeBool()) {
    const size_t count = in.ConsumeIntegralInRange<size_t>(1, 4);
    for (size_t i = 0; i < count; ++i)
      c.contours.push_back(in.ConsumeIntegralInRange<uint32_t>(0, 24));
  }

  if (c.compare) {
    p.depth_test = true;
    p.depth_write = true;
    size_t per_primitive = c.positions.size() + 1;  // one depth for the whole draw
    if (c.indices.empty()) {
      if (c.primitive == Primitive::kTriangles) per_primitive = 3;
      if (c.primitive == Primitive::kPoints) per_primitive = 1;
      if (c.primitive == Primitive::kLines && c.line.topology == LineTopology::kList)
        per_primitive = 2;
    }
    // Primitive t at depth level[t] / 64 in window space, whatever clip-depth convention. Under
    // ALWAYS the last primitive over a sample wins, and the levels are 1, 2, 3, ... With tame
    // vertices and a depth of its own for each primitive, any compare op, the levels distinct
    // and in an order from the input. As no primitive covers a sample twice (a wide segment's
    // or square point's two triangles share an edge), a primitive's depth is compared only with
    // the clear depth and other levels, 1/128 or more from it, far beyond the engines' rounding,
    // so both pass the same samples, and Hi-Z, its whole-tile test and the depth formats take
    // part. One clear in four is a primitive's level instead, a tie: for tame vertices the
    // window depth is exactly the level (d w and then (d w) / w are exact in float, and a flat
    // plane rounds to its value), so the compare ops' ties and Hi-Z at equal bounds are
    // compared too.
    const CompareOp ops[] = {CompareOp::kAlways,       CompareOp::kLess,  CompareOp::kLessEqual,
                             CompareOp::kGreater,      CompareOp::kEqual, CompareOp::kNotEqual,
                             CompareOp::kGreaterEqual, CompareOp::kNever};
    const bool own_depths = per_primitive <= c.positions.size();
    p.depth_compare = tame && own_depths ? pick(in, ops) : CompareOp::kAlways;
    std::array<uint32_t, 63> level;  // at most 48 primitives
    for (uint32_t i = 0; i < level.size(); ++i)
      level[i] = i + 1;
    if (p.depth_compare != CompareOp::kAlways) {
      const size_t primitives = (c.positions.size() + per_primitive - 1) / per_primitive;
      for (size_t i = 0; i < primitives; ++i)
        std::swap(level[i], level[in.ConsumeIntegralInRange<size_t>(i, level.size() - 1)]);
      const size_t clear = in.ConsumeIntegralInRange<size_t>(0, 3);
      if (clear < 3) {
        const float clears[] = {1.0f, 0.0f, 0.5f + 1.0f / 128.0f};
        c.compare_clear_depth = clears[clear];
      } else {  // a tie with a primitive's level
        const size_t tied = in.ConsumeIntegralInRange<size_t>(0, primitives - 1);
        c.compare_clear_depth = static_cast<float>(level[tied]) / 64.0f;
      }
    }
    for (size_t v = 0; v < c.positions.size(); ++v) {
      const float d = static_cast<float>(level[v / per_primitive]) / 64.0f;
      Float4& pos = c.positions[v];
      pos.z = (p.clip_depth == ClipDepth::kNegativeOneToOne ? 2.0f * d - 1.0f : d) * pos.w;
    }
    c.compare_color = tame && c.attribute_count == 4;
  }
  return c;
}

// With TESSERA_FUZZ_VERBOSE set, each draw is printed before it runs (to read a reproducer).
void print_call(const Call& c) {
  if (std::getenv("TESSERA_FUZZ_VERBOSE") == nullptr) return;
  const PipelineState& p = c.pipeline;
  std::fprintf(stderr,
               "draw: primitive %d compare %d depth_test %d write %d compare_op %d cull %d "
               "front %d clip_depth %d interpolation %d samples %u bits %u attributes %u\n",
               static_cast<int>(c.primitive), c.compare, p.depth_test, p.depth_write,
               static_cast<int>(p.depth_compare), static_cast<int>(p.cull),
               static_cast<int>(p.front_face), static_cast<int>(p.clip_depth),
               static_cast<int>(p.interpolation), p.samples, p.subpixel_bits, c.attribute_count);
  for (const Float4& v : c.positions)
    std::fprintf(stderr, "  position %a %a %a %a\n", v.x, v.y, v.z, v.w);
  for (float a : c.attributes)
    std::fprintf(stderr, "  attribute %a\n", a);
  for (uint32_t i : c.indices)
    std::fprintf(stderr, "  index %u\n", i);
}

// Draws `call`; the error it threw, if any.
std::optional<Error> run(Renderer& r, Framebuffer& fb, const Call& call) {
  print_call(call);
  try {
    switch (call.primitive) {
      case Primitive::kTriangles:
        r.draw(fb, call.pipeline, call.input());
        break;
      case Primitive::kPoints:
        r.draw_points(fb, call.pipeline, call.point, call.input());
        break;
      case Primitive::kLines:
        r.draw_lines(fb, call.pipeline, call.line, call.input());
        break;
      case Primitive::kPolygon:
        r.draw_polygon(fb, call.pipeline, call.polygon, call.input(), call.contours);
        break;
    }
  } catch (const Error& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) broken("error spans lines");
    return e;
  }
  return std::nullopt;
}

// A sample's depth names the primitive whose depth it holds, or the clear (the last over it under
// ALWAYS, the compare's winner otherwise; distinct depths are 1/128 or more apart).
void expect_same_coverage(const Contents& fast, const Contents& ref, const Counters& fc,
                          const Counters& rc, bool raster_counters) {
  if (fast.depth.size() != ref.depth.size()) broken("depth sizes differ");
  for (size_t i = 0; i < ref.depth.size(); ++i) {
    const float a = fast.depth[i], b = ref.depth[i];
    if (std::isnan(a) != std::isnan(b) || std::abs(a - b) > 1.0f / 256.0f) {
      broken("fast and reference coverage differ at sample",
             std::to_string(i) + ": " + std::to_string(a) + " vs " + std::to_string(b));
    }
  }
  if (raster_counters && fc.samples_covered != rc.samples_covered) {
    broken("samples_covered differ",
           std::to_string(fc.samples_covered) + " vs " + std::to_string(rc.samples_covered));
  }
}

void expect_same_color(const Contents& fast, const Contents& ref) {
  for (size_t i = 0; i < ref.rgba8.size(); ++i) {
    if (std::abs(int{fast.rgba8[i]} - int{ref.rgba8[i]}) > 1)
      broken("fast and reference colour differ at byte", std::to_string(i));
  }
  for (size_t i = 0; i < ref.rgba32f.size(); ++i) {
    if (!(std::abs(fast.rgba32f[i] - ref.rgba32f[i]) <= 1.0f / 255.0f))
      broken("fast and reference colour differ at value", std::to_string(i));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);

  FramebufferDesc desc;
  // Mostly 64x48 (one bin tile); sometimes a single pixel, a tile edge or several tiles.
  const uint32_t widths[] = {64, 64, 64, 64, 1, 65, 136, 7, 129};
  const uint32_t heights[] = {48, 48, 48, 48, 1, 72, 3, 65};
  desc.width = pick(in, widths);
  desc.height = pick(in, heights);
  const uint32_t samples[] = {1, 1, 1, 2, 4, 4, 8, 16, 0, 3, 5, 32};
  desc.samples = pick(in, samples);
  desc.color_format = some_enum(in, ColorFormat::kRGBA32F);
  desc.depth_format = some_enum(in, DepthFormat::kUnorm16);

  RendererOptions options;
  // One thread mostly; two for one input in eight (tasks drawing tiles side by side).
  const int threads = in.ConsumeIntegralInRange<int>(0, 63);
  options.threads = threads == 0 ? 1025 : (threads % 8 == 1 ? 2 : 1);
  const SimdTarget targets[] = {SimdTarget::kAuto, SimdTarget::kScalar, SimdTarget::kAVX2};
  options.simd = pick(in, targets);
  // TESSERA_FUZZ_SKIP_SCALAR leaves the scalar kernels out, to look past a known report there.
  if (options.simd == SimdTarget::kScalar && std::getenv("TESSERA_FUZZ_SKIP_SCALAR") != nullptr)
    options.simd = SimdTarget::kAuto;
  const uint64_t budgets[] = {kDefaultBinMemoryBudget, 64 << 10, 100 << 10, (64 << 10) - 1};
  options.bin_memory_budget = pick(in, budgets);
  options.raster_counters = in.ConsumeBool();
  options.hiz = in.ConsumeBool();
  const uint32_t tiles[] = {64, 32, 128, 48};
  options.bin_tile_size = pick(in, tiles);
  options.non_finite = some_enum(in, NonFiniteVertices::kCull);
  const uint32_t blocks[] = {8, 16, 32, 4};
  options.block_size = pick(in, blocks);
  options.sub_block_tests = in.ConsumeBool();
  options.tiny_triangle_records = in.ConsumeBool();

  const bool clear_color = in.ConsumeBool();
  std::array<float, 4> clear_rgba{};
  for (float& f : clear_rgba)
    f = hostile_float(in, 1.0f / 100.0f);
  const bool clear_depth = in.ConsumeBool();
  const float clear_z = hostile_float(in, 1.0f / 100.0f);

  const size_t draws = in.ConsumeIntegralInRange<size_t>(1, 3);
  std::vector<Call> calls;
  for (size_t d = 0; d < draws; ++d)
    calls.push_back(decode_call(in, desc.samples));

  if (std::getenv("TESSERA_FUZZ_VERBOSE") != nullptr) {
    std::fprintf(
        stderr,
        "framebuffer %ux%u samples %u colour %d depth %d; threads %u simd %d budget %llu "
        "counters %d hiz %d tile %u non_finite %d block %u sub_blocks %d records %d\n",
        desc.width, desc.height, desc.samples, static_cast<int>(desc.color_format),
        static_cast<int>(desc.depth_format), options.threads, static_cast<int>(options.simd),
        static_cast<unsigned long long>(options.bin_memory_budget), options.raster_counters,
        options.hiz, options.bin_tile_size, static_cast<int>(options.non_finite),
        options.block_size, options.sub_block_tests, options.tiny_triangle_records);
  }
  std::optional<Framebuffer> fbs[2];
  std::optional<Renderer> renderers[2];
  for (int b = 0; b < 2; ++b) {
    try {
      fbs[b].emplace(desc);
    } catch (const Error&) {
      return 0;  // an invalid framebuffer description
    }
    options.backend = b == 0 ? Backend::kFast : Backend::kReference;
    try {
      renderers[b].emplace(options);
    } catch (const Error&) {
      if (b == 1) broken("only the reference renderer rejected the options");
      return 0;
    }
    Framebuffer& fb = *fbs[b];
    if (clear_color) fb.clear_color(clear_rgba);
    if (clear_depth) fb.clear_depth(clear_z);
  }

  for (const Call& call : calls) {
    if (call.compare) {
      for (auto& fb : fbs) {
        fb->clear_depth(call.compare_clear_depth);
        fb->clear_color({0.1f, 0.2f, 0.3f, 1.0f});
      }
      renderers[0]->reset_counters();
      renderers[1]->reset_counters();
    }
    std::optional<Error> errors[2];
    for (int b = 0; b < 2; ++b) {
      const Contents before = snapshot(*fbs[b]);
      const Counters counters_before = renderers[b]->counters();
      const Call copy = call;
      errors[b] = run(*renderers[b], *fbs[b], call);
      const Contents after = snapshot(*fbs[b]);
      if (errors[b] && !(after == before)) broken("a rejected draw changed the image");
      // What the pipeline leaves off is left as it was, whatever the primitive.
      if (!errors[b] && !call.pipeline.color_write &&
          !(after.rgba8 == before.rgba8 && same_bytes(after.rgba32f, before.rgba32f))) {
        broken("a draw with colour writes off changed the colour");
      }
      if (!errors[b] && !(call.pipeline.depth_test && call.pipeline.depth_write) &&
          !same_bytes(after.depth, before.depth)) {
        broken("a draw without depth writes changed the depth");
      }
      if (errors[b] &&
          std::memcmp(&counters_before, &renderers[b]->counters(), sizeof(Counters)) != 0) {
        broken("a rejected draw changed the counters");
      }
      if (!same_bytes(copy.positions, call.positions) ||
          !same_bytes(copy.attributes, call.attributes) || copy.indices != call.indices) {
        broken("a draw changed the caller's vertex data");
      }
    }
    if (errors[0].has_value() != errors[1].has_value()) {
      broken(errors[0] ? "only the fast engine threw:" : "only the reference threw:",
             errors[0] ? errors[0]->what() : errors[1]->what());
    }
    if (errors[0]) {
      if (errors[0]->code() != errors[1]->code() ||
          std::string(errors[0]->what()) != errors[1]->what()) {
        broken("the two engines threw different errors:",
               std::string(errors[0]->what()) + " | " + errors[1]->what());
      }
      continue;
    }
    if (call.compare) {
      const Contents fast = snapshot(*fbs[0]), ref = snapshot(*fbs[1]);
      // With Hi-Z (for the ordering compare ops) the fast engine does not count the covered
      // samples of blocks it rejects.
      const CompareOp op = call.pipeline.depth_compare;
      const bool ordering = op == CompareOp::kLess || op == CompareOp::kLessEqual ||
                            op == CompareOp::kGreater || op == CompareOp::kGreaterEqual;
      const bool same_counts = options.raster_counters && !(options.hiz && ordering);
      expect_same_coverage(fast, ref, renderers[0]->counters(), renderers[1]->counters(),
                           same_counts);
      if (call.compare_color) expect_same_color(fast, ref);
    }
  }
  return 0;
}
