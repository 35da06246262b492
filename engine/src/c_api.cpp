// The C API (tessera/tessera.h): a translation layer over the C++ API and nothing more. Each
// entry point checks what only C can get wrong (NULL pointers, counts, enumeration values too
// wide for the C++ type, read-back buffer sizes), converts the plain C structs into the C++
// ones, calls the C++ API, which validates everything else, and turns any exception into a
// result code and the calling thread's last message. Defaults come from the C++ structs, and
// the C enumerations have the C++ values (checked below), so neither is written twice.
#include "tessera/tessera.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tessera/error.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/occlusion.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"
#include "tessera/texture.hpp"
#include "tessera/types.hpp"

// The handles: the C++ object and the allocator it was created with (alloc == nullptr: plain
// new and delete).
struct tessera_framebuffer {
  tessera_framebuffer(const tessera::FramebufferDesc& desc, const tessera_allocator& a)
      : framebuffer(desc), allocator(a) {}
  tessera::Framebuffer framebuffer;
  tessera_allocator allocator;
};

struct tessera_texture {
  tessera_texture(const tessera::TextureDesc& desc, std::span<const std::byte> texels, bool mipmaps,
                  const tessera_allocator& a)
      : texture(std::make_shared<const tessera::Texture>(desc, texels, mipmaps)), allocator(a) {}
  std::shared_ptr<const tessera::Texture> texture;  // shared with the draws' pipelines
  tessera_allocator allocator;
};

struct tessera_occlusion {
  tessera_occlusion(const tessera::OcclusionDesc& desc, const tessera_allocator& a)
      : occlusion(desc), allocator(a) {}
  tessera::OcclusionBuffer occlusion;
  tessera_allocator allocator;
};

struct tessera_renderer {
  tessera_renderer(const tessera::RendererOptions& options, const tessera_allocator& a)
      : renderer(options), allocator(a) {}
  tessera::Renderer renderer;
  tessera_allocator allocator;
};

namespace {

using tessera::Error;
using tessera::ErrorCode;

// ---- The C enumerations have the C++ values -------------------------------------------------

template <typename C, typename E>
constexpr bool same(C c, E e) {
  return static_cast<long long>(c) == static_cast<long long>(e);
}
static_assert(TESSERA_MAX_VARYINGS == tessera::kMaxVaryings);
static_assert(TESSERA_MAX_LIGHTS == tessera::kMaxLights);
static_assert(TESSERA_MAX_FRAMEBUFFER_SIZE == tessera::kMaxFramebufferSize);
static_assert(same(TESSERA_OCCLUSION_CONSERVATIVE, tessera::OcclusionMode::kConservative) &&
              same(TESSERA_OCCLUSION_EXACT, tessera::OcclusionMode::kExact));
static_assert(TESSERA_MAX_COLOR_TARGETS == tessera::kMaxColorTargets);
static_assert(same(TESSERA_COLOR_RGBA8, tessera::ColorFormat::kRGBA8) &&
              same(TESSERA_COLOR_RGBA32F, tessera::ColorFormat::kRGBA32F) &&
              same(TESSERA_COLOR_R32F, tessera::ColorFormat::kR32F) &&
              same(TESSERA_COLOR_R32UI, tessera::ColorFormat::kR32UI));
static_assert(same(TESSERA_DEPTH_FLOAT32, tessera::DepthFormat::kFloat32) &&
              same(TESSERA_DEPTH_UNORM24, tessera::DepthFormat::kUnorm24) &&
              same(TESSERA_DEPTH_UNORM16, tessera::DepthFormat::kUnorm16));
static_assert(same(TESSERA_BACKEND_REFERENCE, tessera::Backend::kReference) &&
              same(TESSERA_BACKEND_FAST, tessera::Backend::kFast));
static_assert(same(TESSERA_COMPARE_NEVER, tessera::CompareOp::kNever) &&
              same(TESSERA_COMPARE_LESS, tessera::CompareOp::kLess) &&
              same(TESSERA_COMPARE_EQUAL, tessera::CompareOp::kEqual) &&
              same(TESSERA_COMPARE_LESS_EQUAL, tessera::CompareOp::kLessEqual) &&
              same(TESSERA_COMPARE_GREATER, tessera::CompareOp::kGreater) &&
              same(TESSERA_COMPARE_NOT_EQUAL, tessera::CompareOp::kNotEqual) &&
              same(TESSERA_COMPARE_GREATER_EQUAL, tessera::CompareOp::kGreaterEqual) &&
              same(TESSERA_COMPARE_ALWAYS, tessera::CompareOp::kAlways));
static_assert(same(TESSERA_BLEND_ZERO, tessera::BlendFactor::kZero) &&
              same(TESSERA_BLEND_ONE_MINUS_DST_COLOR, tessera::BlendFactor::kOneMinusDstColor) &&
              same(TESSERA_BLEND_ONE_MINUS_DST_ALPHA, tessera::BlendFactor::kOneMinusDstAlpha) &&
              same(TESSERA_BLEND_ONE_MINUS_CONSTANT_ALPHA,
                   tessera::BlendFactor::kOneMinusConstantAlpha) &&
              same(TESSERA_BLEND_SRC_ALPHA_SATURATE, tessera::BlendFactor::kSrcAlphaSaturate));
static_assert(same(TESSERA_BLEND_OP_ADD, tessera::BlendOp::kAdd) &&
              same(TESSERA_BLEND_OP_SUBTRACT, tessera::BlendOp::kSubtract) &&
              same(TESSERA_BLEND_OP_REVERSE_SUBTRACT, tessera::BlendOp::kReverseSubtract) &&
              same(TESSERA_BLEND_OP_MIN, tessera::BlendOp::kMin) &&
              same(TESSERA_BLEND_OP_MAX, tessera::BlendOp::kMax));
static_assert(TESSERA_WRITE_RED == tessera::kWriteRed &&
              TESSERA_WRITE_GREEN == tessera::kWriteGreen &&
              TESSERA_WRITE_BLUE == tessera::kWriteBlue &&
              TESSERA_WRITE_ALPHA == tessera::kWriteAlpha &&
              TESSERA_WRITE_ALL == tessera::kWriteAll);
static_assert(same(TESSERA_CULL_NONE, tessera::CullMode::kNone) &&
              same(TESSERA_CULL_FRONT, tessera::CullMode::kFront) &&
              same(TESSERA_CULL_BACK, tessera::CullMode::kBack));
static_assert(same(TESSERA_FRONT_FACE_COUNTER_CLOCKWISE, tessera::FrontFace::kCounterClockwise) &&
              same(TESSERA_FRONT_FACE_CLOCKWISE, tessera::FrontFace::kClockwise));
static_assert(same(TESSERA_CLIP_DEPTH_ZERO_TO_ONE, tessera::ClipDepth::kZeroToOne) &&
              same(TESSERA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE, tessera::ClipDepth::kNegativeOneToOne));
static_assert(same(TESSERA_INTERPOLATION_PERSPECTIVE, tessera::Interpolation::kPerspective) &&
              same(TESSERA_INTERPOLATION_AFFINE, tessera::Interpolation::kAffine));
static_assert(same(TESSERA_VARYING_DEFAULT, tessera::VaryingMode::kDefault) &&
              same(TESSERA_VARYING_PERSPECTIVE, tessera::VaryingMode::kPerspective) &&
              same(TESSERA_VARYING_AFFINE, tessera::VaryingMode::kAffine) &&
              same(TESSERA_VARYING_FLAT, tessera::VaryingMode::kFlat));
static_assert(same(TESSERA_SHADER_GOURAUD, tessera::FragmentShader::kGouraud) &&
              same(TESSERA_SHADER_PHONG, tessera::FragmentShader::kPhong) &&
              same(TESSERA_SHADER_USER, tessera::FragmentShader::kUser) &&
              same(TESSERA_SHADER_TEXTURED, tessera::FragmentShader::kTextured));
static_assert(same(TESSERA_TEXTURE_RGBA8, tessera::TextureFormat::kRGBA8) &&
              same(TESSERA_TEXTURE_RGBA8_SRGB, tessera::TextureFormat::kRGBA8Srgb) &&
              same(TESSERA_TEXTURE_RGBA32F, tessera::TextureFormat::kRGBA32F) &&
              same(TESSERA_TEXTURE_R8, tessera::TextureFormat::kR8) &&
              same(TESSERA_TEXTURE_R32F, tessera::TextureFormat::kR32F));
static_assert(same(TESSERA_FILTER_NEAREST, tessera::Filter::kNearest) &&
              same(TESSERA_FILTER_LINEAR, tessera::Filter::kLinear));
static_assert(same(TESSERA_MIP_FILTER_NONE, tessera::MipFilter::kNone) &&
              same(TESSERA_MIP_FILTER_NEAREST, tessera::MipFilter::kNearest) &&
              same(TESSERA_MIP_FILTER_LINEAR, tessera::MipFilter::kLinear));
static_assert(same(TESSERA_WRAP_REPEAT, tessera::Wrap::kRepeat) &&
              same(TESSERA_WRAP_CLAMP_TO_EDGE, tessera::Wrap::kClampToEdge) &&
              same(TESSERA_WRAP_MIRRORED_REPEAT, tessera::Wrap::kMirroredRepeat) &&
              same(TESSERA_WRAP_CLAMP_TO_BORDER, tessera::Wrap::kClampToBorder));
static_assert(TESSERA_FRAGMENT_BATCH_STRIDE == tessera::kFragmentBatchStride);
static_assert(same(TESSERA_OUTPUT_COLOR, tessera::TargetOutput::kColor) &&
              same(TESSERA_OUTPUT_EYE_DEPTH, tessera::TargetOutput::kEyeDepth) &&
              same(TESSERA_OUTPUT_NORMAL, tessera::TargetOutput::kNormal) &&
              same(TESSERA_OUTPUT_POSITION, tessera::TargetOutput::kPosition) &&
              same(TESSERA_OUTPUT_BARYCENTRICS, tessera::TargetOutput::kBarycentrics) &&
              same(TESSERA_OUTPUT_PRIMITIVE_ID, tessera::TargetOutput::kPrimitiveId) &&
              same(TESSERA_OUTPUT_OBJECT_ID, tessera::TargetOutput::kObjectId));
static_assert(same(TESSERA_LIGHT_DIRECTIONAL, tessera::LightKind::kDirectional) &&
              same(TESSERA_LIGHT_POINT, tessera::LightKind::kPoint) &&
              same(TESSERA_LIGHT_SPOT, tessera::LightKind::kSpot));
static_assert(same(TESSERA_POINT_SQUARE, tessera::PointShape::kSquare) &&
              same(TESSERA_POINT_ROUND, tessera::PointShape::kRound));
static_assert(same(TESSERA_LINE_LIST, tessera::LineTopology::kList) &&
              same(TESSERA_LINE_STRIP, tessera::LineTopology::kStrip) &&
              same(TESSERA_LINE_LOOP, tessera::LineTopology::kLoop));
static_assert(same(TESSERA_LINE_DIAMOND_EXIT, tessera::LineAlgorithm::kDiamondExit) &&
              same(TESSERA_LINE_BRESENHAM, tessera::LineAlgorithm::kBresenham) &&
              same(TESSERA_LINE_DDA, tessera::LineAlgorithm::kDDA));
static_assert(same(TESSERA_LINE_JOIN_NONE, tessera::LineJoin::kNone) &&
              same(TESSERA_LINE_JOIN_MITER, tessera::LineJoin::kMiter) &&
              same(TESSERA_LINE_JOIN_ROUND, tessera::LineJoin::kRound) &&
              same(TESSERA_LINE_JOIN_BEVEL, tessera::LineJoin::kBevel));
// Positions are read in place as Float4s.
static_assert(sizeof(tessera::Float4) == 4 * sizeof(float) &&
              alignof(tessera::Float4) == alignof(float));

// ---- Errors ---------------------------------------------------------------------------------

// The calling thread's last result and message: fixed storage, so that recording an error
// cannot itself fail (the message is cut at kMessageSize - 1 bytes).
constexpr size_t kMessageSize = 1024;
thread_local tessera_result t_last_result = TESSERA_OK;
thread_local char t_last_message[kMessageSize] = "";

tessera_result record(tessera_result result, const char* function, const char* message) noexcept {
  t_last_result = result;
  if (result == TESSERA_OK) {
    t_last_message[0] = '\0';
  } else {
    std::snprintf(t_last_message, kMessageSize, "%s: %s", function, message);
  }
  return result;
}

tessera_result result_of(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return TESSERA_ERROR_INVALID_ARGUMENT;
    case ErrorCode::kInvalidInput:
      return TESSERA_ERROR_INVALID_INPUT;
    case ErrorCode::kIo:
      return TESSERA_ERROR_IO;
    case ErrorCode::kOutOfMemory:
      return TESSERA_ERROR_OUT_OF_MEMORY;
    case ErrorCode::kUnsupported:
      return TESSERA_ERROR_UNSUPPORTED;
  }
  return TESSERA_ERROR_INTERNAL;
}

// Runs `body` and records its outcome for `function`: every exception becomes a result code
// and message here, the one place where the C API catches.
template <typename Body>
tessera_result guarded(const char* function, const Body& body) noexcept {
  try {
    body();
    return record(TESSERA_OK, function, "");
  } catch (const Error& e) {
    return record(result_of(e.code()), function, e.what());
  } catch (const std::bad_alloc&) {
    return record(TESSERA_ERROR_OUT_OF_MEMORY, function, "out of memory");
  } catch (const std::exception& e) {
    return record(TESSERA_ERROR_INTERNAL, function, e.what());
  } catch (...) {
    return record(TESSERA_ERROR_INTERNAL, function, "an unknown exception");
  }
}

[[noreturn]] void invalid(const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, message);
}

template <typename T>
T& deref(T* pointer, const char* name) {
  if (pointer == nullptr) invalid(std::string(name) + " is NULL");
  return *pointer;
}

// A C enumeration value as the C++ enumeration E with the same values. Whether the value
// names an enumerator is the C++ API's check (with the same message); only a value that E's
// underlying type cannot hold is rejected here, since the cast would wrap it onto another,
// possibly valid, one. `name` names the field: a string, or a callable that makes it, called
// only for the message.
template <typename E, typename C, typename Name>
E to_cpp_enum(C value, const Name& name) {
  const auto v = static_cast<std::underlying_type_t<C>>(value);
  using U = std::underlying_type_t<E>;
  if (std::cmp_less(v, std::numeric_limits<U>::min()) ||
      std::cmp_greater(v, std::numeric_limits<U>::max())) {
    std::string field;
    if constexpr (std::is_invocable_v<const Name&>) {
      field = name();
    } else {
      field = name;
    }
    invalid(field + " has the invalid value " + std::to_string(v));
  }
  return static_cast<E>(v);
}

template <typename C, typename E>
C to_c_enum(E value) {
  return static_cast<C>(static_cast<std::underlying_type_t<E>>(value));
}

void copy3(const float (&from)[3], std::array<float, 3>& to) {
  std::copy(from, from + 3, to.begin());
}
void copy3(const std::array<float, 3>& from, float (&to)[3]) {
  std::copy(from.begin(), from.end(), to);
}

// ---- Conversions between the C and C++ structs ------------------------------------------------

tessera::PipelineState to_cpp(const tessera_pipeline_state& c) {
  tessera::PipelineState p;
  p.depth_test = c.depth_test;
  p.depth_write = c.depth_write;
  p.depth_compare = to_cpp_enum<tessera::CompareOp>(c.depth_compare, "pipeline depth_compare");
  p.color_write = c.color_write;
  p.cull = to_cpp_enum<tessera::CullMode>(c.cull, "pipeline cull");
  p.front_face = to_cpp_enum<tessera::FrontFace>(c.front_face, "pipeline front_face");
  p.clip_depth = to_cpp_enum<tessera::ClipDepth>(c.clip_depth, "pipeline clip_depth");
  p.interpolation = to_cpp_enum<tessera::Interpolation>(c.interpolation, "pipeline interpolation");
  p.samples = c.samples;
  p.subpixel_bits = c.subpixel_bits;
  for (uint32_t i = 0; i < tessera::kMaxVaryings; ++i) {
    p.varying_modes[i] = to_cpp_enum<tessera::VaryingMode>(
        c.varying_modes[i], [i] { return "pipeline varying_modes[" + std::to_string(i) + "]"; });
  }
  p.shader = to_cpp_enum<tessera::FragmentShader>(c.shader, "pipeline shader");
  p.output = to_cpp_enum<tessera::TargetOutput>(c.output, "pipeline output");
  for (uint32_t t = 0; t + 1 < tessera::kMaxColorTargets; ++t) {
    p.extra_outputs[t] = to_cpp_enum<tessera::TargetOutput>(
        c.extra_outputs[t], [t] { return "pipeline extra_outputs[" + std::to_string(t) + "]"; });
  }
  p.roles = {c.roles.color, c.roles.normal, c.roles.position, c.roles.texcoord};
  for (uint32_t t = 0; t < tessera::kMaxColorTargets; ++t) {
    const tessera_blend_state& from = c.blend[t];
    tessera::BlendState& to = p.blend[t];
    const std::string name = "pipeline blend[" + std::to_string(t) + "].";
    to.enable = from.enable;
    to.src_color = to_cpp_enum<tessera::BlendFactor>(from.src_color, name + "src_color");
    to.dst_color = to_cpp_enum<tessera::BlendFactor>(from.dst_color, name + "dst_color");
    to.color_op = to_cpp_enum<tessera::BlendOp>(from.color_op, name + "color_op");
    to.src_alpha = to_cpp_enum<tessera::BlendFactor>(from.src_alpha, name + "src_alpha");
    to.dst_alpha = to_cpp_enum<tessera::BlendFactor>(from.dst_alpha, name + "dst_alpha");
    to.alpha_op = to_cpp_enum<tessera::BlendOp>(from.alpha_op, name + "alpha_op");
    if (from.write_mask > tessera::kWriteAll) {
      throw tessera::Error(tessera::ErrorCode::kInvalidArgument,
                           name + "write_mask " + std::to_string(from.write_mask) +
                               " has bits beyond the four channels (0..15)");
    }
    to.write_mask = static_cast<uint8_t>(from.write_mask);
  }
  std::copy(c.blend_constant, c.blend_constant + 4, p.blend_constant.begin());
  p.depth_bias_constant = c.depth_bias_constant;
  p.depth_bias_slope = c.depth_bias_slope;
  p.depth_bias_clamp = c.depth_bias_clamp;
  p.scissor_test = c.scissor_test;
  p.scissor = {c.scissor.x, c.scissor.y, c.scissor.width, c.scissor.height};
  if (c.texture != nullptr) p.texture = c.texture->texture;
  tessera::Sampler& sampler = p.sampler;
  sampler.mag_filter =
      to_cpp_enum<tessera::Filter>(c.sampler.mag_filter, "pipeline sampler.mag_filter");
  sampler.min_filter =
      to_cpp_enum<tessera::Filter>(c.sampler.min_filter, "pipeline sampler.min_filter");
  sampler.mip_filter =
      to_cpp_enum<tessera::MipFilter>(c.sampler.mip_filter, "pipeline sampler.mip_filter");
  sampler.wrap_u = to_cpp_enum<tessera::Wrap>(c.sampler.wrap_u, "pipeline sampler.wrap_u");
  sampler.wrap_v = to_cpp_enum<tessera::Wrap>(c.sampler.wrap_v, "pipeline sampler.wrap_v");
  std::copy(c.sampler.border_color, c.sampler.border_color + 4, sampler.border_color.begin());
  sampler.lod_bias = c.sampler.lod_bias;
  sampler.min_lod = c.sampler.min_lod;
  sampler.max_lod = c.sampler.max_lod;
  sampler.max_anisotropy = c.sampler.max_anisotropy;
  tessera::PhongState& phong = p.phong;
  std::copy(c.phong.base_color, c.phong.base_color + 4, phong.base_color.begin());
  phong.ka = c.phong.ka;
  phong.kd = c.phong.kd;
  phong.ks = c.phong.ks;
  phong.shininess = c.phong.shininess;
  copy3(c.phong.ambient, phong.ambient);
  copy3(c.phong.eye, phong.eye);
  phong.two_sided = c.phong.two_sided;
  phong.light_count = c.phong.light_count;
  // The lights in use; the others are never read (a light_count past the maximum is the C++
  // API's error).
  for (uint32_t l = 0; l < std::min(c.phong.light_count, tessera::kMaxLights); ++l) {
    const tessera_light& from = c.phong.lights[l];
    tessera::Light& to = phong.lights[l];
    to.kind = to_cpp_enum<tessera::LightKind>(
        from.kind, [l] { return "pipeline phong.lights[" + std::to_string(l) + "].kind"; });
    copy3(from.position, to.position);
    copy3(from.direction, to.direction);
    copy3(from.diffuse, to.diffuse);
    copy3(from.specular, to.specular);
    to.c0 = from.c0;
    to.c1 = from.c1;
    to.c2 = from.c2;
    to.spot_cos_cutoff = from.spot_cos_cutoff;
    to.spot_exponent = from.spot_exponent;
  }
  p.object_id = c.object_id;
  if (c.fragment_function != nullptr) {
    p.fragment_function = [function = c.fragment_function, user_data = c.fragment_user_data](
                              const tessera::FragmentBatch& b, const tessera::FragmentOutput& o) {
      const tessera_fragment_batch batch{b.count,    b.varying_count, b.x,
                                         b.y,        b.sample_mask,   b.primitive_id,
                                         b.varyings, b.ddx,           b.ddy};
      tessera_fragment_output output{o.color, o.discard, {}, {}};
      std::copy(o.extra.begin(), o.extra.end(), output.extra);
      std::copy(o.extra_uint.begin(), o.extra_uint.end(), output.extra_uint);
      function(&batch, &output, user_data);
    };
  }
  return p;
}

tessera_pipeline_state to_c(const tessera::PipelineState& p) {
  tessera_pipeline_state c{};
  c.depth_test = p.depth_test;
  c.depth_write = p.depth_write;
  c.depth_compare = to_c_enum<tessera_compare_op>(p.depth_compare);
  c.color_write = p.color_write;
  c.cull = to_c_enum<tessera_cull_mode>(p.cull);
  c.front_face = to_c_enum<tessera_front_face>(p.front_face);
  c.clip_depth = to_c_enum<tessera_clip_depth>(p.clip_depth);
  c.interpolation = to_c_enum<tessera_interpolation>(p.interpolation);
  c.samples = p.samples;
  c.subpixel_bits = p.subpixel_bits;
  for (uint32_t i = 0; i < tessera::kMaxVaryings; ++i)
    c.varying_modes[i] = to_c_enum<tessera_varying_mode>(p.varying_modes[i]);
  c.shader = to_c_enum<tessera_fragment_shader>(p.shader);
  c.output = to_c_enum<tessera_target_output>(p.output);
  for (uint32_t t = 0; t + 1 < tessera::kMaxColorTargets; ++t)
    c.extra_outputs[t] = to_c_enum<tessera_target_output>(p.extra_outputs[t]);
  c.roles = {p.roles.color, p.roles.normal, p.roles.position, p.roles.texcoord};
  for (uint32_t t = 0; t < tessera::kMaxColorTargets; ++t) {
    const tessera::BlendState& from = p.blend[t];
    c.blend[t] = {from.enable,
                  to_c_enum<tessera_blend_factor>(from.src_color),
                  to_c_enum<tessera_blend_factor>(from.dst_color),
                  to_c_enum<tessera_blend_op>(from.color_op),
                  to_c_enum<tessera_blend_factor>(from.src_alpha),
                  to_c_enum<tessera_blend_factor>(from.dst_alpha),
                  to_c_enum<tessera_blend_op>(from.alpha_op),
                  from.write_mask};
  }
  std::copy(p.blend_constant.begin(), p.blend_constant.end(), c.blend_constant);
  c.depth_bias_constant = p.depth_bias_constant;
  c.depth_bias_slope = p.depth_bias_slope;
  c.depth_bias_clamp = p.depth_bias_clamp;
  c.scissor_test = p.scissor_test;
  c.scissor = {p.scissor.x, p.scissor.y, p.scissor.width, p.scissor.height};
  c.texture = nullptr;  // a C++ pipeline's texture has no C handle
  c.sampler.mag_filter = to_c_enum<tessera_filter>(p.sampler.mag_filter);
  c.sampler.min_filter = to_c_enum<tessera_filter>(p.sampler.min_filter);
  c.sampler.mip_filter = to_c_enum<tessera_mip_filter>(p.sampler.mip_filter);
  c.sampler.wrap_u = to_c_enum<tessera_wrap>(p.sampler.wrap_u);
  c.sampler.wrap_v = to_c_enum<tessera_wrap>(p.sampler.wrap_v);
  std::copy(p.sampler.border_color.begin(), p.sampler.border_color.end(), c.sampler.border_color);
  c.sampler.lod_bias = p.sampler.lod_bias;
  c.sampler.min_lod = p.sampler.min_lod;
  c.sampler.max_lod = p.sampler.max_lod;
  c.sampler.max_anisotropy = p.sampler.max_anisotropy;
  const tessera::PhongState& phong = p.phong;
  std::copy(phong.base_color.begin(), phong.base_color.end(), c.phong.base_color);
  c.phong.ka = phong.ka;
  c.phong.kd = phong.kd;
  c.phong.ks = phong.ks;
  c.phong.shininess = phong.shininess;
  copy3(phong.ambient, c.phong.ambient);
  copy3(phong.eye, c.phong.eye);
  c.phong.two_sided = phong.two_sided;
  c.phong.light_count = phong.light_count;
  for (uint32_t l = 0; l < tessera::kMaxLights; ++l) {
    const tessera::Light& from = phong.lights[l];
    tessera_light& to = c.phong.lights[l];
    to.kind = to_c_enum<tessera_light_kind>(from.kind);
    copy3(from.position, to.position);
    copy3(from.direction, to.direction);
    copy3(from.diffuse, to.diffuse);
    copy3(from.specular, to.specular);
    to.c0 = from.c0;
    to.c1 = from.c1;
    to.c2 = from.c2;
    to.spot_cos_cutoff = from.spot_cos_cutoff;
    to.spot_exponent = from.spot_exponent;
  }
  c.object_id = p.object_id;
  return c;
}

// Largest vertex count whose positions and largest attribute array have a size in bytes that
// a size_t holds; a larger count cannot describe memory, and would overflow the products below.
constexpr size_t kMaxVertexCount =
    std::numeric_limits<size_t>::max() / (sizeof(float) * tessera::kMaxVaryings);

tessera::DrawInput to_cpp(const tessera_draw_input& c) {
  if (c.vertex_count > kMaxVertexCount) {
    invalid("input vertex_count " + std::to_string(c.vertex_count) + " is larger than any array");
  }
  if (c.positions == nullptr && c.vertex_count != 0) {
    invalid("input positions is NULL, but vertex_count is " + std::to_string(c.vertex_count));
  }
  if (c.indices == nullptr && c.index_count != 0) {
    invalid("input indices is NULL, but index_count is " + std::to_string(c.index_count));
  }
  tessera::DrawInput input;
  input.positions = {reinterpret_cast<const tessera::Float4*>(c.positions), c.vertex_count};
  input.attribute_count = c.attribute_count;
  // Past the maximum the C++ API rejects the count (naming it) before it reads any attribute.
  if (c.attribute_count <= tessera::kMaxVaryings) {
    const size_t floats = c.vertex_count * c.attribute_count;
    if (c.attributes == nullptr && floats != 0) {
      invalid("input attributes is NULL, but " + std::to_string(c.vertex_count) +
              " vertices with attribute_count " + std::to_string(c.attribute_count) + " need " +
              std::to_string(floats) + " floats");
    }
    input.attributes = {c.attributes, floats};
  }
  input.indices = {c.indices, c.index_count};
  return input;
}

tessera::PointState to_cpp(const tessera_point_state& c) {
  return {c.size, to_cpp_enum<tessera::PointShape>(c.shape, "point shape")};
}

tessera::LineState to_cpp(const tessera_line_state& c) {
  tessera::LineState s;
  s.topology = to_cpp_enum<tessera::LineTopology>(c.topology, "line topology");
  s.algorithm = to_cpp_enum<tessera::LineAlgorithm>(c.algorithm, "line algorithm");
  s.width = c.width;
  s.join = to_cpp_enum<tessera::LineJoin>(c.join, "line join");
  s.miter_limit = c.miter_limit;
  s.stipple = {c.stipple_pattern, c.stipple_factor};
  s.antialiased = c.antialiased;
  return s;
}

// ---- Handles --------------------------------------------------------------------------------

// A Handle constructed from `args`, in memory from `allocator` when there is one (the
// allocator is kept in the handle for its destruction), else from operator new.
template <typename Handle, typename... Args>
Handle* create_handle(const tessera_allocator* allocator, const Args&... args) {
  if (allocator == nullptr) return new Handle(args..., tessera_allocator{});
  if (allocator->alloc == nullptr || allocator->free == nullptr) {
    invalid("allocator alloc and free must both be set");
  }
  void* memory = allocator->alloc(sizeof(Handle), alignof(Handle), allocator->user);
  if (memory == nullptr) {
    throw Error(ErrorCode::kOutOfMemory,
                "the allocator returned NULL for " + std::to_string(sizeof(Handle)) + " bytes");
  }
  if (reinterpret_cast<uintptr_t>(memory) % alignof(Handle) != 0) {
    allocator->free(memory, allocator->user);
    invalid("the allocator returned memory not aligned to " + std::to_string(alignof(Handle)) +
            " bytes");
  }
  try {
    return new (memory) Handle(args..., *allocator);
  } catch (...) {
    allocator->free(memory, allocator->user);
    throw;
  }
}

template <typename Handle>
void destroy_handle(Handle* handle) noexcept {
  if (handle == nullptr) return;
  const tessera_allocator allocator = handle->allocator;
  if (allocator.alloc == nullptr) {
    delete handle;
    return;
  }
  handle->~Handle();
  allocator.free(handle, allocator.user);
}

// Writes `image` (`count` values, the size `what` was checked to need) to `dst`, after
// checking `dst` and `capacity` and before computing the image, so that a bad buffer costs no
// resolve.
template <typename T, typename Read>
void read_image(T* dst, size_t capacity, uint64_t count, const char* unit, const char* what,
                const Read& read) {
  if (dst == nullptr) invalid("dst is NULL");
  if (capacity < count) {
    invalid("dst holds " + std::to_string(capacity) + " " + unit + ", but " + what + " needs " +
            std::to_string(count));
  }
  const std::vector<T> image = read();
  std::memcpy(dst, image.data(), image.size() * sizeof(T));
}

std::string image_name(const tessera::FramebufferDesc& d, const char* kind) {
  return "the " + std::to_string(d.width) + "x" + std::to_string(d.height) + " " + kind;
}

uint64_t pixels(const tessera::FramebufferDesc& d) {
  return uint64_t{d.width} * d.height;
}

}  // namespace

extern "C" {

tessera_result tessera_last_error(void) {
  return t_last_result;
}

const char* tessera_last_error_message(void) {
  return t_last_message;
}

const char* tessera_result_name(tessera_result result) {
  switch (result) {
    case TESSERA_OK:
      return "TESSERA_OK";
    case TESSERA_ERROR_INVALID_ARGUMENT:
      return "TESSERA_ERROR_INVALID_ARGUMENT";
    case TESSERA_ERROR_INVALID_INPUT:
      return "TESSERA_ERROR_INVALID_INPUT";
    case TESSERA_ERROR_IO:
      return "TESSERA_ERROR_IO";
    case TESSERA_ERROR_OUT_OF_MEMORY:
      return "TESSERA_ERROR_OUT_OF_MEMORY";
    case TESSERA_ERROR_UNSUPPORTED:
      return "TESSERA_ERROR_UNSUPPORTED";
    case TESSERA_ERROR_INTERNAL:
      return "TESSERA_ERROR_INTERNAL";
    case TESSERA_RESULT_MAX_ENUM:
      break;
  }
  return "unknown";
}

// ---- Framebuffers ---------------------------------------------------------------------------

tessera_result tessera_framebuffer_create(const tessera_framebuffer_desc* desc,
                                          const tessera_allocator* allocator,
                                          tessera_framebuffer** out) {
  if (out != nullptr) *out = nullptr;
  return guarded(__func__, [&] {
    tessera_framebuffer*& result = deref(out, "out");
    const tessera_framebuffer_desc& d = deref(desc, "desc");
    tessera::FramebufferDesc cpp{
        d.width, d.height, d.samples,
        to_cpp_enum<tessera::ColorFormat>(d.color_format, "framebuffer color_format"),
        to_cpp_enum<tessera::DepthFormat>(d.depth_format, "framebuffer depth_format")};
    cpp.extra_targets = d.extra_targets;
    for (uint32_t t = 0; t + 1 < tessera::kMaxColorTargets; ++t) {
      cpp.extra_formats[t] = to_cpp_enum<tessera::ColorFormat>(d.extra_formats[t], [t] {
        return "framebuffer extra_formats[" + std::to_string(t) + "]";
      });
    }
    result = create_handle<tessera_framebuffer>(allocator, cpp);
  });
}

void tessera_framebuffer_destroy(tessera_framebuffer* framebuffer) {
  destroy_handle(framebuffer);
}

// ---- Textures -------------------------------------------------------------------------------

tessera_result tessera_texture_create(uint32_t width, uint32_t height,
                                      tessera_texture_format format, const void* texels,
                                      size_t size, bool mipmaps, const tessera_allocator* allocator,
                                      tessera_texture** out) {
  if (out != nullptr) *out = nullptr;
  return guarded(__func__, [&] {
    tessera_texture*& result = deref(out, "out");
    if (texels == nullptr && size != 0)
      invalid("texels is NULL, but size is " + std::to_string(size));
    const tessera::TextureDesc desc{width, height,
                                    to_cpp_enum<tessera::TextureFormat>(format, "texture format")};
    const std::span<const std::byte> bytes(static_cast<const std::byte*>(texels), size);
    result = create_handle<tessera_texture>(allocator, desc, bytes, mipmaps);
  });
}

void tessera_texture_destroy(tessera_texture* texture) {
  destroy_handle(texture);
}

tessera_result tessera_framebuffer_get_desc(const tessera_framebuffer* framebuffer,
                                            tessera_framebuffer_desc* out) {
  return guarded(__func__, [&] {
    const tessera::FramebufferDesc& d = deref(framebuffer, "framebuffer").framebuffer.desc();
    tessera_framebuffer_desc& c = deref(out, "out");
    c = {d.width,
         d.height,
         d.samples,
         to_c_enum<tessera_color_format>(d.color_format),
         to_c_enum<tessera_depth_format>(d.depth_format),
         d.extra_targets,
         {}};
    for (uint32_t t = 0; t + 1 < tessera::kMaxColorTargets; ++t)
      c.extra_formats[t] = to_c_enum<tessera_color_format>(d.extra_formats[t]);
  });
}

tessera_result tessera_framebuffer_clear_color(tessera_framebuffer* framebuffer, float r, float g,
                                               float b, float a) {
  return guarded(__func__, [&] {
    deref(framebuffer, "framebuffer").framebuffer.clear_color({r, g, b, a});
  });
}

tessera_result tessera_framebuffer_clear_depth(tessera_framebuffer* framebuffer, float depth) {
  return guarded(__func__,
                 [&] { deref(framebuffer, "framebuffer").framebuffer.clear_depth(depth); });
}

tessera_result tessera_framebuffer_read_rgba8(const tessera_framebuffer* framebuffer, uint8_t* dst,
                                              size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    read_image(dst, capacity, pixels(fb.desc()) * 4, "bytes",
               image_name(fb.desc(), "RGBA8 image").c_str(), [&] { return fb.read_rgba8(); });
  });
}

tessera_result tessera_framebuffer_read_rgba32f(const tessera_framebuffer* framebuffer, float* dst,
                                                size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    read_image(dst, capacity, pixels(fb.desc()) * 4, "floats",
               image_name(fb.desc(), "RGBA32F image").c_str(), [&] { return fb.read_rgba32f(); });
  });
}

tessera_result tessera_framebuffer_read_depth(const tessera_framebuffer* framebuffer, float* dst,
                                              size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    read_image(dst, capacity, pixels(fb.desc()), "floats",
               image_name(fb.desc(), "depth image").c_str(), [&] { return fb.read_depth(); });
  });
}

tessera_result tessera_framebuffer_read_target(const tessera_framebuffer* framebuffer,
                                               uint32_t target, float* dst, size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    const tessera::ColorFormat format = fb.target_format(target);
    if (format == tessera::ColorFormat::kR32UI) (void)fb.read_target(target);  // its error
    const uint32_t channels = format == tessera::ColorFormat::kR32F ? 1 : 4;
    const std::string what =
        image_name(fb.desc(), "image") + " of target " + std::to_string(target);
    read_image(dst, capacity, pixels(fb.desc()) * channels, "floats", what.c_str(),
               [&] { return fb.read_target(target); });
  });
}

tessera_result tessera_framebuffer_read_target_uint(const tessera_framebuffer* framebuffer,
                                                    uint32_t target, uint32_t* dst,
                                                    size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    if (fb.target_format(target) != tessera::ColorFormat::kR32UI) {
      (void)fb.read_target_uint(target);  // its error
    }
    const std::string what =
        image_name(fb.desc(), "image") + " of target " + std::to_string(target);
    read_image(dst, capacity, pixels(fb.desc()), "values", what.c_str(),
               [&] { return fb.read_target_uint(target); });
  });
}

tessera_result tessera_framebuffer_clear_target(tessera_framebuffer* framebuffer, uint32_t target,
                                                float r, float g, float b, float a) {
  return guarded(__func__, [&] {
    deref(framebuffer, "framebuffer").framebuffer.clear_target(target, {r, g, b, a});
  });
}

tessera_result tessera_framebuffer_clear_target_uint(tessera_framebuffer* framebuffer,
                                                     uint32_t target, uint32_t value) {
  return guarded(__func__, [&] {
    deref(framebuffer, "framebuffer").framebuffer.clear_target_uint(target, value);
  });
}

tessera_result tessera_framebuffer_read_sample_depth(const tessera_framebuffer* framebuffer,
                                                     float* dst, size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    const std::string what = image_name(fb.desc(), "depth image") + " of " +
                             std::to_string(fb.samples()) + " samples per pixel";
    read_image(dst, capacity, pixels(fb.desc()) * fb.samples(), "floats", what.c_str(),
               [&] { return fb.read_sample_depth(); });
  });
}

// ---- Renderers ------------------------------------------------------------------------------

tessera_result tessera_renderer_desc_init(tessera_renderer_desc* desc) {
  return guarded(__func__, [&] {
    const tessera::RendererOptions defaults;
    deref(desc, "desc") = {defaults.threads, to_c_enum<tessera_backend>(defaults.backend)};
  });
}

tessera_result tessera_renderer_create(const tessera_renderer_desc* desc,
                                       const tessera_allocator* allocator, tessera_renderer** out) {
  if (out != nullptr) *out = nullptr;
  return guarded(__func__, [&] {
    tessera_renderer*& result = deref(out, "out");
    const tessera_renderer_desc& d = deref(desc, "desc");
    tessera::RendererOptions options;
    options.threads = d.threads;
    options.backend = to_cpp_enum<tessera::Backend>(d.backend, "renderer backend");
    result = create_handle<tessera_renderer>(allocator, options);
  });
}

void tessera_renderer_destroy(tessera_renderer* renderer) {
  destroy_handle(renderer);
}

// ---- Pipeline state and draws ---------------------------------------------------------------

tessera_result tessera_pipeline_state_init(tessera_pipeline_state* state) {
  return guarded(__func__, [&] { deref(state, "state") = to_c(tessera::PipelineState{}); });
}

tessera_result tessera_draw_triangles(tessera_renderer* renderer, tessera_framebuffer* framebuffer,
                                      const tessera_pipeline_state* pipeline,
                                      const tessera_draw_input* input) {
  return guarded(__func__, [&] {
    tessera::Renderer& r = deref(renderer, "renderer").renderer;
    tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    r.draw(fb, to_cpp(deref(pipeline, "pipeline")), to_cpp(deref(input, "input")));
  });
}

tessera_result tessera_point_state_init(tessera_point_state* state) {
  return guarded(__func__, [&] {
    const tessera::PointState defaults;
    deref(state, "state") = {defaults.size, to_c_enum<tessera_point_shape>(defaults.shape)};
  });
}

tessera_result tessera_draw_points(tessera_renderer* renderer, tessera_framebuffer* framebuffer,
                                   const tessera_pipeline_state* pipeline,
                                   const tessera_point_state* state,
                                   const tessera_draw_input* input) {
  return guarded(__func__, [&] {
    tessera::Renderer& r = deref(renderer, "renderer").renderer;
    tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    r.draw_points(fb, to_cpp(deref(pipeline, "pipeline")), to_cpp(deref(state, "state")),
                  to_cpp(deref(input, "input")));
  });
}

tessera_result tessera_line_state_init(tessera_line_state* state) {
  return guarded(__func__, [&] {
    const tessera::LineState d;
    deref(state, "state") = {to_c_enum<tessera_line_topology>(d.topology),
                             to_c_enum<tessera_line_algorithm>(d.algorithm),
                             d.width,
                             to_c_enum<tessera_line_join>(d.join),
                             d.miter_limit,
                             d.stipple.pattern,
                             d.stipple.factor,
                             d.antialiased};
  });
}

tessera_result tessera_draw_lines(tessera_renderer* renderer, tessera_framebuffer* framebuffer,
                                  const tessera_pipeline_state* pipeline,
                                  const tessera_line_state* state,
                                  const tessera_draw_input* input) {
  return guarded(__func__, [&] {
    tessera::Renderer& r = deref(renderer, "renderer").renderer;
    tessera::Framebuffer& fb = deref(framebuffer, "framebuffer").framebuffer;
    r.draw_lines(fb, to_cpp(deref(pipeline, "pipeline")), to_cpp(deref(state, "state")),
                 to_cpp(deref(input, "input")));
  });
}

// ---- Occlusion queries ----------------------------------------------------------------------

tessera_result tessera_occlusion_create(const tessera_occlusion_desc* desc,
                                        const tessera_allocator* allocator,
                                        tessera_occlusion** out) {
  if (out != nullptr) *out = nullptr;
  return guarded(__func__, [&] {
    tessera_occlusion*& result = deref(out, "out");
    const tessera_occlusion_desc& c = deref(desc, "desc");
    tessera::OcclusionDesc cpp;
    cpp.width = c.width;
    cpp.height = c.height;
    cpp.samples = c.samples == 0 ? 1 : c.samples;
    cpp.depth_format = to_cpp_enum<tessera::DepthFormat>(c.depth_format, "depth_format");
    cpp.reversed_z = c.reversed_z;
    cpp.threads = c.threads;
    result = create_handle<tessera_occlusion>(allocator, cpp);
  });
}

void tessera_occlusion_destroy(tessera_occlusion* occlusion) {
  destroy_handle(occlusion);
}

tessera_result tessera_occlusion_clear(tessera_occlusion* occlusion) {
  return guarded(__func__, [&] { deref(occlusion, "occlusion").occlusion.clear(); });
}

tessera_result tessera_occlusion_draw(tessera_occlusion* occlusion,
                                      const tessera_draw_input* occluders) {
  return guarded(__func__, [&] {
    tessera::OcclusionBuffer& o = deref(occlusion, "occlusion").occlusion;
    o.draw_occluders(to_cpp(deref(occluders, "occluders")));
  });
}

tessera_result tessera_occlusion_rect_visible(const tessera_occlusion* occlusion, float x0,
                                              float y0, float x1, float y1, float nearest_depth,
                                              tessera_occlusion_mode mode, bool* visible) {
  return guarded(__func__, [&] {
    const tessera::OcclusionBuffer& o = deref(occlusion, "occlusion").occlusion;
    bool& v = deref(visible, "visible");
    v = o.rect_visible(x0, y0, x1, y1, nearest_depth,
                       to_cpp_enum<tessera::OcclusionMode>(mode, "mode"));
  });
}

tessera_result tessera_occlusion_box_visible(const tessera_occlusion* occlusion, const float lo[3],
                                             const float hi[3], const float clip_from_object[16],
                                             tessera_occlusion_mode mode, bool* visible) {
  return guarded(__func__, [&] {
    const tessera::OcclusionBuffer& o = deref(occlusion, "occlusion").occlusion;
    bool& v = deref(visible, "visible");
    const float* l = &deref(lo, "lo");
    const float* h = &deref(hi, "hi");
    const float* m = &deref(clip_from_object, "clip_from_object");
    glm::mat4 matrix;
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row)
        matrix[column][row] = m[column * 4 + row];
    }
    v = o.box_visible({l[0], l[1], l[2]}, {h[0], h[1], h[2]}, matrix,
                      to_cpp_enum<tessera::OcclusionMode>(mode, "mode"));
  });
}

tessera_result tessera_occlusion_triangles_visible(const tessera_occlusion* occlusion,
                                                   const tessera_draw_input* triangles,
                                                   tessera_occlusion_mode mode, bool* visible) {
  return guarded(__func__, [&] {
    const tessera::OcclusionBuffer& o = deref(occlusion, "occlusion").occlusion;
    bool& v = deref(visible, "visible");
    v = o.triangles_visible(to_cpp(deref(triangles, "triangles")),
                            to_cpp_enum<tessera::OcclusionMode>(mode, "mode"));
  });
}

tessera_result tessera_occlusion_read_depth(const tessera_occlusion* occlusion, float* dst,
                                            size_t capacity) {
  return guarded(__func__, [&] {
    const tessera::Framebuffer& fb = deref(occlusion, "occlusion").occlusion.framebuffer();
    read_image(dst, capacity, pixels(fb.desc()), "floats",
               image_name(fb.desc(), "depth image").c_str(), [&] { return fb.read_depth(); });
  });
}

}  // extern "C"
