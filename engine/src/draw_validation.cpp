// Checks every argument of Renderer::draw; see draw_validation.hpp.
#include "engine/src/draw_validation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>

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

// 1 when a value is an infinity or a NaN (all exponent bits set marks both), else 0.
uint32_t non_finite(float value) {
  return (std::bit_cast<uint32_t>(value) & 0x7f800000u) == 0x7f800000u ? 1u : 0u;
}

bool all_finite(std::span<const float> values) {
  uint32_t found = 0;
  for (const float value : values)
    found |= non_finite(value);
  return found == 0;
}

bool all_finite(std::span<const Float4> positions) {
  uint32_t found = 0;
  for (const Float4& p : positions)
    found |= non_finite(p.x) | non_finite(p.y) | non_finite(p.z) | non_finite(p.w);
  return found == 0;
}

}  // namespace

void validate_draw(const Framebuffer& target, const PipelineState& pipeline,
                   const DrawInput& input) {
  check_enum(pipeline.depth_compare, CompareOp::kAlways, "depth_compare");
  check_enum(pipeline.cull, CullMode::kBack, "cull");
  check_enum(pipeline.front_face, FrontFace::kClockwise, "front_face");
  check_enum(pipeline.clip_depth, ClipDepth::kNegativeOneToOne, "clip_depth");
  check_enum(pipeline.interpolation, Interpolation::kAffine, "interpolation");
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
  if (input.attribute_count > kMaxAttributes) {
    fail(ErrorCode::kInvalidArgument, "attribute_count " + std::to_string(input.attribute_count) +
                                          " is more than the maximum of " +
                                          std::to_string(kMaxAttributes));
  }
  if (input.attributes.size() != vertices * input.attribute_count) {
    fail(ErrorCode::kInvalidInput,
         "attributes hold " + std::to_string(input.attributes.size()) + " floats, but " +
             std::to_string(vertices) + " vertices with " + std::to_string(input.attribute_count) +
             " attributes need " + std::to_string(vertices * input.attribute_count));
  }
  if (input.indices.empty()) {
    if (vertices % 3 != 0) {
      fail(ErrorCode::kInvalidInput,
           "a non-indexed triangle list needs a multiple of 3 positions, got " +
               std::to_string(vertices));
    }
  } else {
    if (input.indices.size() % 3 != 0) {
      fail(ErrorCode::kInvalidInput, "a triangle list needs a multiple of 3 indices, got " +
                                         std::to_string(input.indices.size()));
    }
    // A branch-free maximum first (it vectorizes); the slow search only names the bad index.
    uint32_t largest = 0;
    for (const uint32_t index : input.indices)
      largest = std::max(largest, index);
    for (size_t i = 0; largest >= vertices && i < input.indices.size(); ++i) {
      if (input.indices[i] >= vertices) {
        fail(ErrorCode::kInvalidInput,
             "index " + std::to_string(input.indices[i]) + " at position " + std::to_string(i) +
                 " is out of range: there are " + std::to_string(vertices) + " vertices");
      }
    }
  }
  // Branch-free scans first (they vectorize); the loops that name the culprit run only when
  // something is not finite.
  const bool positions_finite = all_finite(input.positions);
  for (size_t v = 0; !positions_finite && v < vertices; ++v) {
    const Float4& p = input.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) {
      fail(ErrorCode::kInvalidInput,
           "position of vertex " + std::to_string(v) + " is not finite: " + describe(p));
    }
  }
  const bool attributes_finite = all_finite(input.attributes);
  for (size_t i = 0; !attributes_finite && i < input.attributes.size(); ++i) {
    if (!std::isfinite(input.attributes[i])) {
      fail(ErrorCode::kInvalidInput, "attribute " + std::to_string(i % input.attribute_count) +
                                         " of vertex " + std::to_string(i / input.attribute_count) +
                                         " is not finite");
    }
  }
}

}  // namespace tessera
