// Checks every argument of Renderer::draw; see draw_validation.hpp.
#include "engine/src/draw_validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "engine/src/finite_scan.hpp"
#include "engine/src/shading_state.hpp"
#include "tessera/error.hpp"

namespace tessera {

namespace {

[[noreturn]] void fail(ErrorCode code, const std::string& message) {
  throw Error(code, message);
}

template <typename E>
void check_enum(E value, E last, const char* name) {
  if (static_cast<unsigned>(value) > static_cast<unsigned>(last)) {
    fail(ErrorCode::kInvalidArgument, std::string("pipeline ") + name + " has the invalid value " +
                                          std::to_string(static_cast<unsigned>(value)));
  }
}

std::string describe(const Float4& p) {
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ", " << p.w << ")";
  return s.str();
}

// `scan` (begin, end) -> uint32_t over [0, n), its results combined by `|` or max (`combine`):
// in pieces on the arena's threads when there is one and n is large (a scan of a million-triangle
// draw's vertices takes a few milliseconds on one core), else in one piece.
template <typename Scan, typename Combine>
uint32_t reduce(tbb::task_arena* arena, size_t n, Scan scan, Combine combine) {
  constexpr size_t kPiece = size_t{1} << 16;
  if (arena == nullptr || n < 4 * kPiece) return scan(size_t{0}, n);
  return arena->execute([&] {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, kPiece), uint32_t{0},
        [&](const tbb::blocked_range<size_t>& r, uint32_t found) {
          return combine(found, scan(r.begin(), r.end()));
        },
        combine);
  });
}

uint32_t either(uint32_t a, uint32_t b) {
  return a | b;
}

bool all_finite(std::span<const float> values, tbb::task_arena* arena = nullptr) {
  return reduce(
             arena, values.size(),
             [&](size_t begin, size_t end) {
               return values_finite(values.data() + begin, end - begin) ? 0u : 1u;
             },
             either) == 0;
}

bool all_finite(std::span<const Float4> positions, tbb::task_arena* arena = nullptr) {
  // A Float4 is four floats, without padding: the array is scanned as one array of floats.
  static_assert(sizeof(Float4) == 4 * sizeof(float));
  if (positions.empty()) return true;
  return all_finite(std::span<const float>(&positions.data()->x, positions.size() * 4), arena);
}

// The blend state (enums in range, a write mask of four bits, a finite constant, and only
// target 0 blending or masking channels) and a finite depth bias.
void validate_blend(const PipelineState& pipeline) {
  for (uint32_t t = 0; t < kMaxColorTargets; ++t) {
    const BlendState& b = pipeline.blend[t];
    const std::string name = "blend[" + std::to_string(t) + "].";
    check_enum(b.src_color, BlendFactor::kSrcAlphaSaturate, (name + "src_color").c_str());
    check_enum(b.dst_color, BlendFactor::kSrcAlphaSaturate, (name + "dst_color").c_str());
    check_enum(b.src_alpha, BlendFactor::kSrcAlphaSaturate, (name + "src_alpha").c_str());
    check_enum(b.dst_alpha, BlendFactor::kSrcAlphaSaturate, (name + "dst_alpha").c_str());
    check_enum(b.color_op, BlendOp::kMax, (name + "color_op").c_str());
    check_enum(b.alpha_op, BlendOp::kMax, (name + "alpha_op").c_str());
    if (b.write_mask > kWriteAll) {
      fail(ErrorCode::kInvalidArgument, "pipeline " + name + "write_mask " +
                                            std::to_string(b.write_mask) +
                                            " has bits beyond the four channels (0..15)");
    }
    if (t > 0 && !b.replaces()) {
      fail(ErrorCode::kInvalidArgument,
           "pipeline blend[" + std::to_string(t) +
               "] blends or masks channels: only colour target 0 blends; the extra targets "
               "take BlendState{}");
    }
  }
  const std::pair<const char*, float> bias[] = {
      {"depth_bias_constant", pipeline.depth_bias_constant},
      {"depth_bias_slope", pipeline.depth_bias_slope},
      {"depth_bias_clamp", pipeline.depth_bias_clamp}};
  for (const auto& [name, value] : bias) {
    if (!std::isfinite(value)) {
      fail(ErrorCode::kInvalidArgument,
           std::string("pipeline ") + name + " " + std::to_string(value) + " is not finite");
    }
  }
  for (int c = 0; c < 4; ++c) {
    if (!std::isfinite(pipeline.blend_constant[c])) {
      fail(ErrorCode::kInvalidArgument,
           "pipeline blend_constant[" + std::to_string(c) + "] is not finite");
    }
  }
}

}  // namespace

void validate_vertices(const Framebuffer& target, const PipelineState& pipeline,
                       const DrawInput& input, bool finite_values, tbb::task_arena* arena) {
  check_enum(pipeline.depth_compare, CompareOp::kAlways, "depth_compare");
  check_enum(pipeline.cull, CullMode::kBack, "cull");
  check_enum(pipeline.front_face, FrontFace::kClockwise, "front_face");
  check_enum(pipeline.clip_depth, ClipDepth::kNegativeOneToOne, "clip_depth");
  check_enum(pipeline.interpolation, Interpolation::kAffine, "interpolation");
  validate_blend(pipeline);
  if (pipeline.samples != 0 && pipeline.samples != target.samples()) {
    fail(ErrorCode::kInvalidArgument, "pipeline sample count " + std::to_string(pipeline.samples) +
                                          " does not match the framebuffer's " +
                                          std::to_string(target.samples()));
  }
  if (pipeline.subpixel_bits < kMinSubpixelBits || pipeline.subpixel_bits > kMaxSubpixelBits) {
    fail(ErrorCode::kInvalidArgument,
         "pipeline subpixel_bits " + std::to_string(pipeline.subpixel_bits) + " is out of range (" +
             std::to_string(kMinSubpixelBits) + ".." + std::to_string(kMaxSubpixelBits) + ")");
  }

  const size_t vertices = input.positions.size();
  if (input.attribute_count > kMaxVaryings) {
    fail(ErrorCode::kInvalidArgument, "attribute_count " + std::to_string(input.attribute_count) +
                                          " is more than the maximum of " +
                                          std::to_string(kMaxVaryings));
  }
  if (input.attributes.size() != vertices * input.attribute_count) {
    fail(ErrorCode::kInvalidInput,
         "attributes hold " + std::to_string(input.attributes.size()) + " floats, but " +
             std::to_string(vertices) + " vertices with " + std::to_string(input.attribute_count) +
             " attributes need " + std::to_string(vertices * input.attribute_count));
  }
  if (!input.indices.empty()) {
    // A branch-free maximum first (it vectorizes); the slow search only names the bad index.
    const uint32_t largest = reduce(
        arena, input.indices.size(),
        [&](size_t begin, size_t end) {
          uint32_t most = 0;
          for (size_t i = begin; i < end; ++i)
            most = std::max(most, input.indices[i]);
          return most;
        },
        [](uint32_t a, uint32_t b) { return std::max(a, b); });
    for (size_t i = 0; largest >= vertices && i < input.indices.size(); ++i) {
      if (input.indices[i] >= vertices) {
        fail(ErrorCode::kInvalidInput,
             "index " + std::to_string(input.indices[i]) + " at position " + std::to_string(i) +
                 " is out of range: there are " + std::to_string(vertices) + " vertices");
      }
    }
  }
  if (finite_values) check_finite_values(input, arena);
}

void check_finite_values(const DrawInput& input, tbb::task_arena* arena) {
  // Branch-free scans first (they vectorize); the loops that name the culprit run only when
  // something is not finite.
  const bool positions_finite = all_finite(input.positions, arena);
  for (size_t v = 0; !positions_finite && v < input.positions.size(); ++v) {
    const Float4& p = input.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) {
      fail(ErrorCode::kInvalidInput,
           "position of vertex " + std::to_string(v) + " is not finite: " + describe(p));
    }
  }
  const bool attributes_finite = all_finite(input.attributes, arena);
  for (size_t i = 0; !attributes_finite && i < input.attributes.size(); ++i) {
    if (!std::isfinite(input.attributes[i])) {
      fail(ErrorCode::kInvalidInput, "attribute " + std::to_string(i % input.attribute_count) +
                                         " of vertex " + std::to_string(i / input.attribute_count) +
                                         " is not finite");
    }
  }
}

std::vector<bool> finite_vertices(const DrawInput& input) {
  if (all_finite(input.positions) && all_finite(input.attributes)) return {};
  std::vector<bool> finite(input.positions.size());
  for (size_t v = 0; v < finite.size(); ++v) {
    const Float4& p = input.positions[v];
    bool ok = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
    for (uint32_t a = 0; a < input.attribute_count; ++a)
      ok = ok && std::isfinite(input.attributes[v * input.attribute_count + a]);
    finite[v] = ok;
  }
  return finite;
}

namespace {

void check_finite(float value, const std::string& name) {
  if (!std::isfinite(value)) {
    std::ostringstream s;
    s << name << " " << value << " is not finite";
    fail(ErrorCode::kInvalidArgument, s.str());
  }
}

void check_finite(const std::array<float, 3>& v, const std::string& name) {
  for (int i = 0; i < 3; ++i)
    check_finite(v[i], name + "[" + std::to_string(i) + "]");
}

// The `count` varyings from `first` on, which `what` reads, exist in the draw.
void check_group(uint32_t first, uint32_t count, uint32_t attribute_count, const char* role,
                 const char* what) {
  if (first > kMaxVaryings || attribute_count < count || first > attribute_count - count) {
    fail(ErrorCode::kInvalidArgument,
         std::string(what) + " reads varyings " + std::to_string(first) + ".." +
             std::to_string(uint64_t{first} + count - 1) + " (roles." + role +
             "), but the draw has " + std::to_string(attribute_count));
  }
}

void validate_phong(const PhongState& phong) {
  for (int c = 0; c < 4; ++c)
    check_finite(phong.base_color[c], "phong.base_color[" + std::to_string(c) + "]");
  check_finite(phong.ka, "phong.ka");
  check_finite(phong.kd, "phong.kd");
  check_finite(phong.ks, "phong.ks");
  check_finite(phong.ambient, "phong.ambient");
  check_finite(phong.eye, "phong.eye");
  if (!(phong.shininess >= 0.0f && std::isfinite(phong.shininess))) {
    fail(ErrorCode::kInvalidArgument, "phong.shininess " + std::to_string(phong.shininess) +
                                          " is not a finite value of at least 0");
  }
  if (phong.light_count > kMaxLights) {
    fail(ErrorCode::kInvalidArgument, "phong.light_count " + std::to_string(phong.light_count) +
                                          " is more than the maximum of " +
                                          std::to_string(kMaxLights));
  }
  for (uint32_t l = 0; l < phong.light_count; ++l) {
    const Light& light = phong.lights[l];
    const std::string name = "phong.lights[" + std::to_string(l) + "]";
    check_enum(light.kind, LightKind::kSpot, (name + ".kind").c_str());
    check_finite(light.position, name + ".position");
    check_finite(light.direction, name + ".direction");
    check_finite(light.diffuse, name + ".diffuse");
    check_finite(light.specular, name + ".specular");
    if (!(light.spot_cos_cutoff >= -1.0f && light.spot_cos_cutoff <= 1.0f)) {
      fail(ErrorCode::kInvalidArgument, name + ".spot_cos_cutoff " +
                                            std::to_string(light.spot_cos_cutoff) +
                                            " is not a cosine (-1..1)");
    }
    if (!(light.spot_exponent >= 0.0f && std::isfinite(light.spot_exponent))) {
      fail(ErrorCode::kInvalidArgument, name + ".spot_exponent " +
                                            std::to_string(light.spot_exponent) +
                                            " is not a finite value of at least 0");
    }
    if (light.kind != LightKind::kPoint && light.direction == std::array<float, 3>{0, 0, 0}) {
      fail(ErrorCode::kInvalidArgument, name + ".direction is zero");
    }
    // 1 / (c0 + c1 d + c2 d^2) must stay finite and positive for every distance d >= 0.
    if (!(light.c0 > 0.0f && light.c1 >= 0.0f && light.c2 >= 0.0f) || !std::isfinite(light.c1) ||
        !std::isfinite(light.c2) || !std::isfinite(light.c0)) {
      std::ostringstream s;
      s << name << " attenuation (c0 " << light.c0 << ", c1 " << light.c1 << ", c2 " << light.c2
        << ") needs c0 > 0 and c1, c2 >= 0, all finite";
      fail(ErrorCode::kInvalidArgument, s.str());
    }
  }
}

// The sampler of FragmentShader::kTextured.
void validate_sampler(const Sampler& s) {
  check_enum(s.mag_filter, Filter::kLinear, "sampler.mag_filter");
  check_enum(s.min_filter, Filter::kLinear, "sampler.min_filter");
  check_enum(s.mip_filter, MipFilter::kLinear, "sampler.mip_filter");
  check_enum(s.wrap_u, Wrap::kClampToBorder, "sampler.wrap_u");
  check_enum(s.wrap_v, Wrap::kClampToBorder, "sampler.wrap_v");
  for (float c : s.border_color) {
    if (!std::isfinite(c)) {
      fail(ErrorCode::kInvalidArgument,
           "pipeline sampler.border_color holds " + std::to_string(c) + ", not a finite number");
    }
  }
  const std::pair<float, const char*> values[] = {
      {s.lod_bias, "lod_bias"}, {s.min_lod, "min_lod"}, {s.max_lod, "max_lod"}};
  for (const auto& [value, name] : values) {
    if (std::isnan(value)) {
      fail(ErrorCode::kInvalidArgument, std::string("pipeline sampler.") + name + " is NaN");
    }
  }
  if (!(s.max_anisotropy >= 1.0f && s.max_anisotropy <= float(kMaxAnisotropy))) {
    fail(ErrorCode::kInvalidArgument, "pipeline sampler.max_anisotropy " +
                                          std::to_string(s.max_anisotropy) + " is not in [1, " +
                                          std::to_string(kMaxAnisotropy) + "]");
  }
  if (!(s.min_lod <= s.max_lod)) {
    fail(ErrorCode::kInvalidArgument, "pipeline sampler.min_lod " + std::to_string(s.min_lod) +
                                          " is above max_lod " + std::to_string(s.max_lod));
  }
}

const char* output_name(TargetOutput output) {
  switch (output) {
    case TargetOutput::kColor:
      return "kColor";
    case TargetOutput::kEyeDepth:
      return "kEyeDepth";
    case TargetOutput::kNormal:
      return "kNormal";
    case TargetOutput::kPosition:
      return "kPosition";
    case TargetOutput::kBarycentrics:
      return "kBarycentrics";
    case TargetOutput::kPrimitiveId:
      return "kPrimitiveId";
    case TargetOutput::kObjectId:
      return "kObjectId";
  }
  return "?";
}

}  // namespace

void validate_shading(const Framebuffer& target, const PipelineState& pipeline,
                      const DrawInput& input, size_t triangles) {
  for (uint32_t i = 0; i < kMaxVaryings; ++i) {
    check_enum(pipeline.varying_modes[i], VaryingMode::kFlat,
               ("varying_modes[" + std::to_string(i) + "]").c_str());
  }
  check_enum(pipeline.shader, FragmentShader::kTextured, "shader");
  const uint32_t count = input.attribute_count;
  const VaryingRoles& roles = pipeline.roles;
  bool phong_checked = false, textured_checked = false;
  // Each colour target's output (target 0's `output`, the extra targets' extra_outputs).
  const FramebufferDesc& desc = target.desc();
  for (uint32_t t = 0; t <= desc.extra_targets; ++t) {
    const TargetOutput output = output_of(pipeline, t);
    const ColorFormat format = t == 0 ? desc.color_format : desc.extra_formats[t - 1];
    const std::string name =
        t == 0 ? std::string("output") : "extra_outputs[" + std::to_string(t - 1) + "]";
    check_enum(output, TargetOutput::kObjectId, name.c_str());
    const std::string what = name + " " + output_name(output);
    if (output == TargetOutput::kNormal)
      check_group(roles.normal, 3, count, "normal", what.c_str());
    if (output == TargetOutput::kPosition)
      check_group(roles.position, 3, count, "position", what.c_str());
    if (output == TargetOutput::kColor && pipeline.shader == FragmentShader::kPhong) {
      check_group(roles.normal, 3, count, "normal", "shader kPhong");
      check_group(roles.position, 3, count, "position", "shader kPhong");
      if (!phong_checked) validate_phong(pipeline.phong);
      phong_checked = true;
    }
    if (output == TargetOutput::kColor && pipeline.shader == FragmentShader::kTextured &&
        !textured_checked) {
      textured_checked = true;
      if (pipeline.texture == nullptr) {
        fail(ErrorCode::kInvalidArgument, "shader kTextured needs a texture, which is null");
      }
      check_group(roles.texcoord, 2, count, "texcoord", "shader kTextured");
      validate_sampler(pipeline.sampler);
    }
    const bool user = output == TargetOutput::kColor && pipeline.shader == FragmentShader::kUser;
    if (user && pipeline.color_write && !pipeline.fragment_function) {
      fail(ErrorCode::kInvalidArgument, "shader kUser needs a fragment_function, which is empty");
    }
    if (!pipeline.color_write) continue;
    const bool ids = output == TargetOutput::kPrimitiveId || output == TargetOutput::kObjectId;
    if (format == ColorFormat::kR32UI) {
      // An integer target holds IDs exactly, and a user shader's integers; nothing else.
      if (!ids && !user) {
        fail(ErrorCode::kInvalidArgument,
             what + " cannot go to colour target " + std::to_string(t) +
                 ", which is R32UI (it takes kPrimitiveId, kObjectId or a user shader's kColor)");
      }
      continue;
    }
    if (!ids) continue;
    // IDs written as floats: exact below 2^24, and only a float target keeps them.
    constexpr uint64_t kExactIds = uint64_t{1} << 24;
    if (format == ColorFormat::kRGBA8) {
      fail(ErrorCode::kInvalidArgument,
           what + " needs an RGBA32F, R32F or R32UI colour target (target " + std::to_string(t) +
               " is RGBA8, which would clamp the IDs to 0..1)");
    }
    if (output == TargetOutput::kPrimitiveId && triangles > kExactIds) {
      fail(ErrorCode::kInvalidArgument,
           what + ": the draw has " + std::to_string(triangles) +
               " triangles, more than the 2^24 a float target holds exactly (use an R32UI target)");
    }
    if (output == TargetOutput::kObjectId && pipeline.object_id >= kExactIds) {
      fail(ErrorCode::kInvalidArgument,
           "object_id " + std::to_string(pipeline.object_id) +
               " is not below 2^24 (exact in a float target; use an R32UI target)");
    }
  }
}

void validate_draw(const Framebuffer& target, const PipelineState& pipeline, const DrawInput& input,
                   bool finite_values, tbb::task_arena* arena) {
  if (input.indices.empty()) {
    if (input.positions.size() % 3 != 0) {
      fail(ErrorCode::kInvalidInput,
           "a non-indexed triangle list needs a multiple of 3 positions, got " +
               std::to_string(input.positions.size()));
    }
  } else if (input.indices.size() % 3 != 0) {
    fail(ErrorCode::kInvalidInput, "a triangle list needs a multiple of 3 indices, got " +
                                       std::to_string(input.indices.size()));
  }
  validate_vertices(target, pipeline, input, finite_values, arena);
  validate_shading(target, pipeline, input,
                   (input.indices.empty() ? input.positions.size() : input.indices.size()) / 3);
}

namespace {

void check_finite_range(float value, float lo, float hi, const std::string& name) {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream s;
    s << name << " " << value << " is out of range (" << lo << ".." << hi << ")";
    fail(ErrorCode::kInvalidArgument, s.str());
  }
}

size_t vertex_count(const DrawInput& input) {
  return input.indices.empty() ? input.positions.size() : input.indices.size();
}

template <typename E>
void check_state_enum(E value, E last, const char* name) {
  if (static_cast<unsigned>(value) > static_cast<unsigned>(last)) {
    fail(ErrorCode::kInvalidArgument, std::string(name) + " has the invalid value " +
                                          std::to_string(static_cast<unsigned>(value)));
  }
}

}  // namespace

void validate_points(const Framebuffer& target, const PipelineState& pipeline,
                     const PointState& state, const DrawInput& input) {
  check_finite_range(state.size, 1.0f, kMaxPointSize, "point size");
  check_state_enum(state.shape, PointShape::kRound, "point shape");
  validate_vertices(target, pipeline, input);
}

void validate_lines(const Framebuffer& target, const PipelineState& pipeline,
                    const LineState& state, const DrawInput& input) {
  check_state_enum(state.topology, LineTopology::kLoop, "line topology");
  check_state_enum(state.algorithm, LineAlgorithm::kDDA, "line algorithm");
  check_state_enum(state.join, LineJoin::kBevel, "line join");
  check_finite_range(state.width, 1.0f, kMaxLineWidth, "line width");
  check_finite_range(state.miter_limit, 1.0f, 1e6f, "line miter limit");
  if (state.stipple.factor < 1 || state.stipple.factor > 256) {
    fail(ErrorCode::kInvalidArgument, "line stipple factor " +
                                          std::to_string(state.stipple.factor) +
                                          " is out of range (1..256)");
  }
  if (state.topology == LineTopology::kList && vertex_count(input) % 2 != 0) {
    fail(ErrorCode::kInvalidInput, "a line list needs an even number of vertices, got " +
                                       std::to_string(vertex_count(input)));
  }
  validate_vertices(target, pipeline, input);
}

void validate_polygon(const Framebuffer& target, const PipelineState& pipeline,
                      const PolygonState& state, const DrawInput& input,
                      std::span<const uint32_t> contour_sizes) {
  check_state_enum(state.fill_rule, FillRule::kNonZero, "polygon fill rule");
  check_state_enum(state.method, PolygonMethod::kTessellation, "polygon method");
  if (state.method == PolygonMethod::kTessellation &&
      vertex_count(input) > kMaxTessellationVertices) {
    fail(ErrorCode::kInvalidInput, "a polygon of " + std::to_string(vertex_count(input)) +
                                       " vertices is too large to tessellate (at most " +
                                       std::to_string(kMaxTessellationVertices) +
                                       "); draw it with the scanline method");
  }
  if (!contour_sizes.empty()) {
    uint64_t total = 0;
    for (uint32_t size : contour_sizes)
      total += size;
    if (total != vertex_count(input)) {
      fail(ErrorCode::kInvalidInput, "polygon contour sizes add up to " + std::to_string(total) +
                                         " vertices, but the draw has " +
                                         std::to_string(vertex_count(input)));
    }
  }
  validate_vertices(target, pipeline, input);
}

}  // namespace tessera
