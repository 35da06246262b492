// The shading layout of a fast-engine draw (layout.hpp).
#include "engine/src/shade/layout.hpp"

#include <cmath>

#include "engine/src/shading_state.hpp"

namespace tessera::shade {

namespace {

// Unit vector of v, in double, rounded to float (0 for a zero vector), as the reference's
// normalized() forms it.
std::array<float, 3> unit(double x, double y, double z) {
  const double length = std::sqrt(x * x + y * y + z * z);
  if (!(length > 0.0)) return {0.0f, 0.0f, 0.0f};
  return {static_cast<float>(x / length), static_cast<float>(y / length),
          static_cast<float>(z / length)};
}

}  // namespace

// The layout of one output for a single colour target; with `own_planes` false (the quad back
// end's targets), the plain Gouraud colour is made of interpolants too rather than left to the
// setup's colour planes.
Layout single_layout(const PipelineState& pipeline, TargetOutput output, uint32_t attribute_count,
                     bool own_planes) {
  Layout layout;
  const auto add = [&](Source source, uint32_t index, VaryingMode mode) {
    layout.values[layout.count++] = {source, index, mode};
    layout.needs_q = layout.needs_q || mode == VaryingMode::kPerspective;
  };
  const auto add_varyings = [&](uint32_t first, uint32_t n) {
    for (uint32_t i = first; i < first + n; ++i)
      add(Source::kVarying, i, resolved_mode(pipeline, i));
  };
  const auto channels = [&](std::array<uint8_t, 4> channel, std::array<float, 4> constant) {
    layout.shader = Shader::kInterpolated;
    layout.channel = channel;
    layout.constant = constant;
  };
  constexpr uint8_t k = Layout::kConstant;
  const uint32_t color = pipeline.roles.color;
  const uint32_t color_count = attribute_count > color ? std::min(attribute_count - color, 4u) : 0u;
  switch (output) {
    case TargetOutput::kEyeDepth:
      add(Source::kClipW, 0, VaryingMode::kPerspective);
      channels({0, 0, 0, k}, {0, 0, 0, 1});
      return layout;
    case TargetOutput::kNormal:
      add_varyings(pipeline.roles.normal, 3);
      layout.shader = Shader::kNormalized;
      return layout;
    case TargetOutput::kPosition:
      add_varyings(pipeline.roles.position, 3);
      channels({0, 1, 2, k}, {0, 0, 0, 1});
      return layout;
    case TargetOutput::kBarycentrics:
      for (uint32_t v = 0; v < 3; ++v)
        add(Source::kBarycentric, v, VaryingMode::kPerspective);
      channels({0, 1, 2, k}, {0, 0, 0, 1});
      return layout;
    case TargetOutput::kPrimitiveId:
      add(Source::kPrimitive, 0, VaryingMode::kFlat);
      channels({0, 0, 0, k}, {0, 0, 0, 1});
      return layout;
    case TargetOutput::kObjectId: {
      const float id = static_cast<float>(pipeline.object_id);
      channels({k, k, k, k}, {id, id, id, 1});
      return layout;
    }
    case TargetOutput::kColor:
      break;
  }
  if (pipeline.shader == FragmentShader::kPhong) {
    layout.shader = Shader::kPhong;
    add_varyings(pipeline.roles.normal, 3);
    add_varyings(pipeline.roles.position, 3);
    layout.has_color = color_count == 4;
    if (layout.has_color) add_varyings(color, 4);
    layout.phong = pipeline.phong;
    for (uint32_t l = 0; l < pipeline.phong.light_count; ++l) {
      const Light& in = pipeline.phong.lights[l];
      PreparedLight& out = layout.lights[l];
      out.kind = in.kind;
      out.position = in.position;
      out.to_light =
          unit(-double{in.direction[0]}, -double{in.direction[1]}, -double{in.direction[2]});
      out.axis = unit(in.direction[0], in.direction[1], in.direction[2]);
      out.diffuse = in.diffuse;
      out.specular = in.specular;
      out.c0 = in.c0;
      out.c1 = in.c1;
      out.c2 = in.c2;
      out.constant_attenuation = in.c1 == 0.0f && in.c2 == 0.0f;
      out.attenuation = 1.0f / in.c0;
      out.spot_cos_cutoff = in.spot_cos_cutoff;
      out.spot_exponent = in.spot_exponent;
    }
    return layout;
  }
  if (pipeline.shader == FragmentShader::kTextured) {
    // The colour the texel is multiplied by (the quad back end samples the texture): the
    // colour varyings when the draw has all four, else white.
    if (color_count == 4) {
      add_varyings(color, 4);
      channels({0, 1, 2, 3}, {0, 0, 0, 1});
    } else {
      channels({k, k, k, k}, {1, 1, 1, 1});
    }
    return layout;
  }
  // Gouraud: the setup's own colour planes when every colour varying is interpolated as the
  // pipeline's interpolation says (the setup interpolates all four alike).
  bool uniform = true;
  for (uint32_t c = color; c < color + color_count; ++c)
    uniform = uniform && resolved_mode(pipeline, c) == default_mode(pipeline.interpolation);
  if (uniform && own_planes) return layout;
  add_varyings(color, color_count);
  std::array<uint8_t, 4> channel{k, k, k, k};
  for (uint32_t c = 0; c < color_count; ++c)
    channel[c] = static_cast<uint8_t>(c);
  channels(channel, {0, 0, 0, 1});
  return layout;
}

Layout layout_for(const PipelineState& pipeline, uint32_t attribute_count,
                  const FramebufferDesc& desc) {
  if (!pipeline.color_write) return {};
  const bool user = pipeline.shader == FragmentShader::kUser;
  const bool textured = pipeline.shader == FragmentShader::kTextured;
  if (desc.extra_targets == 0 && !((user || textured) && pipeline.output == TargetOutput::kColor)) {
    return single_layout(pipeline, pipeline.output, attribute_count, true);
  }
  // The texture as the sampler's lanes read it, when they take it.
  std::shared_ptr<texture::LaneTexture> lanes;
  if (textured && pipeline.texture != nullptr) {
    lanes = std::make_shared<texture::LaneTexture>();
    if (!texture::lanes_apply(detail::TextureAccess::storage(*pipeline.texture), pipeline.sampler,
                              *lanes)) {
      lanes.reset();
    }
  }
  if (desc.extra_targets == 0 && lanes != nullptr) {
    // The textured shader in the raster kernels' lanes: the texture coordinates, then the
    // colour varyings when the draw has all four.
    Layout layout;
    const uint32_t color = pipeline.roles.color;
    const uint32_t colours = attribute_count > color && attribute_count - color >= 4 ? 4 : 0;
    const auto add = [&](uint32_t varying) {
      const VaryingMode mode = resolved_mode(pipeline, varying);
      layout.values[layout.count++] = {Source::kVarying, varying, mode};
      layout.needs_q = layout.needs_q || mode == VaryingMode::kPerspective;
    };
    add(pipeline.roles.texcoord);
    add(pipeline.roles.texcoord + 1);
    for (uint32_t c = 0; c < colours; ++c)
      add(pipeline.roles.color + c);
    layout.shader = Shader::kTextured;
    layout.has_color = colours == 4;
    layout.texture = std::move(lanes);
    return layout;
  }
  // The quad back end: the varyings (for the function, or the texture coordinates and their
  // derivatives), then each built-in target's interpolants, then the primitive index's bits.
  Layout layout;
  layout.shader = Shader::kUser;
  auto targets = std::make_shared<Targets>();
  targets->count = 1 + desc.extra_targets;
  targets->object_id = pipeline.object_id;
  bool function = false, sampled = false;
  for (uint32_t t = 0; t < targets->count; ++t) {
    TargetShading& target = targets->target[t];
    target.output = output_of(pipeline, t);
    target.format = t == 0 ? desc.color_format : desc.extra_formats[t - 1];
    target.from_function = user && target.output == TargetOutput::kColor;
    target.textured = textured && target.output == TargetOutput::kColor;
    function = function || target.from_function;
    sampled = sampled || target.textured;
  }
  const auto add = [&](const Interpolant& value) {
    layout.values[layout.count++] = value;
    layout.needs_q = layout.needs_q || value.mode == VaryingMode::kPerspective;
  };
  if (function || sampled) {
    for (uint32_t i = 0; i < attribute_count; ++i)
      add({Source::kVarying, i, resolved_mode(pipeline, i)});
    layout.function_varyings = attribute_count;
  }
  if (function) layout.function = &pipeline.fragment_function;
  if (sampled) {
    targets->texture = pipeline.texture.get();
    targets->sampler = pipeline.sampler;
    targets->lanes = std::move(lanes);
    targets->texcoord = pipeline.roles.texcoord;
  }
  for (uint32_t t = 0; t < targets->count; ++t) {
    TargetShading& target = targets->target[t];
    if (target.from_function || target.output == TargetOutput::kPrimitiveId ||
        target.output == TargetOutput::kObjectId) {
      continue;
    }
    target.layout = single_layout(pipeline, target.output, attribute_count, false);
    target.first = layout.count;
    for (uint32_t j = 0; j < target.layout.count; ++j)
      add(target.layout.values[j]);
  }
  add({Source::kPrimitiveBits, 0, VaryingMode::kFlat});
  layout.targets = std::move(targets);
  return layout;
}

}  // namespace tessera::shade
