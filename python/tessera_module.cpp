// The Python module `tessera`: the C++ API's renderer, framebuffer and pipeline state bound with
// pybind11, vertex data read from NumPy arrays in place and images returned as NumPy arrays.
// The checks are the C++ API's own (tessera::Error becomes ValueError, MemoryError or
// RuntimeError with its message); this layer adds only what Python can get wrong and C++
// cannot: an array's dtype, dimensions, memory layout, and enumerations given as strings.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "tessera/error.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/mesh.hpp"
#include "tessera/occlusion.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"
#include "tessera/shading.hpp"
#include "tessera/texture.hpp"
#include "tessera/types.hpp"
#include "tessera/version.hpp"
#if TESSERA_PYTHON_IO
#include "tessera/image_io.hpp"
#include "tessera/mesh_io.hpp"
#endif

namespace py = pybind11;

namespace {

using tessera::Backend;
using tessera::ColorFormat;
using tessera::CompareOp;
using tessera::CullMode;
using tessera::DepthFormat;
using tessera::Error;
using tessera::ErrorCode;
using tessera::FragmentShader;
using tessera::Framebuffer;
using tessera::FrontFace;
using tessera::Interpolation;
using tessera::Light;
using tessera::LightKind;
using tessera::PhongState;
using tessera::PipelineState;
using tessera::Renderer;
using tessera::TargetOutput;
using tessera::VaryingMode;
using tessera::VaryingRoles;

// ---- Enumerations as strings -------------------------------------------------------------

template <class E>
using Names = std::span<const std::pair<std::string_view, E>>;

constexpr std::pair<std::string_view, Backend> kBackendNames[] = {
    {"fast", Backend::kFast}, {"reference", Backend::kReference}};
constexpr std::pair<std::string_view, ColorFormat> kColorNames[] = {
    {"rgba8", ColorFormat::kRGBA8},
    {"rgba32f", ColorFormat::kRGBA32F},
    {"r32f", ColorFormat::kR32F},
    {"r32ui", ColorFormat::kR32UI}};
constexpr std::pair<std::string_view, DepthFormat> kDepthNames[] = {
    {"float32", DepthFormat::kFloat32},
    {"unorm24", DepthFormat::kUnorm24},
    {"unorm16", DepthFormat::kUnorm16}};
constexpr std::pair<std::string_view, CompareOp> kCompareNames[] = {
    {"never", CompareOp::kNever},
    {"less", CompareOp::kLess},
    {"equal", CompareOp::kEqual},
    {"less_equal", CompareOp::kLessEqual},
    {"greater", CompareOp::kGreater},
    {"not_equal", CompareOp::kNotEqual},
    {"greater_equal", CompareOp::kGreaterEqual},
    {"always", CompareOp::kAlways}};
constexpr std::pair<std::string_view, CullMode> kCullNames[] = {
    {"none", CullMode::kNone}, {"front", CullMode::kFront}, {"back", CullMode::kBack}};
constexpr std::pair<std::string_view, FrontFace> kFrontFaceNames[] = {
    {"ccw", FrontFace::kCounterClockwise}, {"cw", FrontFace::kClockwise}};
constexpr std::pair<std::string_view, tessera::ClipDepth> kClipDepthNames[] = {
    {"zero_to_one", tessera::ClipDepth::kZeroToOne},
    {"negative_one_to_one", tessera::ClipDepth::kNegativeOneToOne}};
constexpr std::pair<std::string_view, Interpolation> kInterpolationNames[] = {
    {"perspective", Interpolation::kPerspective}, {"affine", Interpolation::kAffine}};
constexpr std::pair<std::string_view, VaryingMode> kVaryingModeNames[] = {
    {"default", VaryingMode::kDefault},
    {"perspective", VaryingMode::kPerspective},
    {"affine", VaryingMode::kAffine},
    {"flat", VaryingMode::kFlat}};
constexpr std::pair<std::string_view, FragmentShader> kShaderNames[] = {
    {"gouraud", FragmentShader::kGouraud},
    {"phong", FragmentShader::kPhong},
    {"textured", FragmentShader::kTextured}};
constexpr std::pair<std::string_view, tessera::Filter> kFilterNames[] = {
    {"nearest", tessera::Filter::kNearest}, {"linear", tessera::Filter::kLinear}};
constexpr std::pair<std::string_view, tessera::MipFilter> kMipFilterNames[] = {
    {"none", tessera::MipFilter::kNone},
    {"nearest", tessera::MipFilter::kNearest},
    {"linear", tessera::MipFilter::kLinear}};
constexpr std::pair<std::string_view, tessera::Wrap> kWrapNames[] = {
    {"repeat", tessera::Wrap::kRepeat},
    {"clamp_to_edge", tessera::Wrap::kClampToEdge},
    {"mirrored_repeat", tessera::Wrap::kMirroredRepeat},
    {"clamp_to_border", tessera::Wrap::kClampToBorder}};
constexpr std::pair<std::string_view, tessera::TextureFormat> kTextureFormatNames[] = {
    {"rgba8", tessera::TextureFormat::kRGBA8},
    {"rgba8_srgb", tessera::TextureFormat::kRGBA8Srgb},
    {"rgba32f", tessera::TextureFormat::kRGBA32F},
    {"r8", tessera::TextureFormat::kR8},
    {"r32f", tessera::TextureFormat::kR32F}};
constexpr std::pair<std::string_view, TargetOutput> kOutputNames[] = {
    {"color", TargetOutput::kColor},
    {"eye_depth", TargetOutput::kEyeDepth},
    {"normal", TargetOutput::kNormal},
    {"position", TargetOutput::kPosition},
    {"barycentrics", TargetOutput::kBarycentrics},
    {"primitive_id", TargetOutput::kPrimitiveId},
    {"object_id", TargetOutput::kObjectId}};
constexpr std::pair<std::string_view, tessera::OcclusionMode> kOcclusionModeNames[] = {
    {"conservative", tessera::OcclusionMode::kConservative},
    {"exact", tessera::OcclusionMode::kExact}};
constexpr std::pair<std::string_view, tessera::BlendFactor> kBlendFactorNames[] = {
    {"zero", tessera::BlendFactor::kZero},
    {"one", tessera::BlendFactor::kOne},
    {"src_color", tessera::BlendFactor::kSrcColor},
    {"one_minus_src_color", tessera::BlendFactor::kOneMinusSrcColor},
    {"dst_color", tessera::BlendFactor::kDstColor},
    {"one_minus_dst_color", tessera::BlendFactor::kOneMinusDstColor},
    {"src_alpha", tessera::BlendFactor::kSrcAlpha},
    {"one_minus_src_alpha", tessera::BlendFactor::kOneMinusSrcAlpha},
    {"dst_alpha", tessera::BlendFactor::kDstAlpha},
    {"one_minus_dst_alpha", tessera::BlendFactor::kOneMinusDstAlpha},
    {"constant_color", tessera::BlendFactor::kConstantColor},
    {"one_minus_constant_color", tessera::BlendFactor::kOneMinusConstantColor},
    {"constant_alpha", tessera::BlendFactor::kConstantAlpha},
    {"one_minus_constant_alpha", tessera::BlendFactor::kOneMinusConstantAlpha},
    {"src_alpha_saturate", tessera::BlendFactor::kSrcAlphaSaturate}};
constexpr std::pair<std::string_view, tessera::BlendOp> kBlendOpNames[] = {
    {"add", tessera::BlendOp::kAdd},
    {"subtract", tessera::BlendOp::kSubtract},
    {"reverse_subtract", tessera::BlendOp::kReverseSubtract},
    {"min", tessera::BlendOp::kMin},
    {"max", tessera::BlendOp::kMax}};
constexpr std::pair<std::string_view, LightKind> kLightKindNames[] = {
    {"directional", LightKind::kDirectional},
    {"point", LightKind::kPoint},
    {"spot", LightKind::kSpot}};

template <class E>
E parse(Names<E> names, std::string_view what, std::string_view value) {
  std::string choices;
  for (const auto& [name, e] : names) {
    if (name == value) return e;
    choices += (choices.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  }
  throw py::value_error(std::string(what) + " \"" + std::string(value) + "\" is not one of " +
                        choices);
}

template <class E>
std::string name_of(Names<E> names, E value) {
  for (const auto& [name, e] : names) {
    if (e == value) return std::string(name);
  }
  return "invalid";
}

// A read-write string property for an enumeration member of a bound struct.
template <class E, class Class>
void def_enum(py::class_<Class>& cls, const char* field, E Class::*member, Names<E> names) {
  cls.def_property(
      field, [member, names](const Class& self) { return name_of(names, self.*member); },
      [member, names, field](Class& self, std::string_view value) {
        self.*member = parse(names, field, value);
      });
}

// A bound struct built from keyword arguments: each sets the attribute of that name, so an
// unknown name is an AttributeError and a bad value the attribute's own error.
template <class T>
T from_kwargs(const py::kwargs& kwargs) {
  T value{};
  py::object self = py::cast(&value, py::return_value_policy::reference);
  for (const auto& [key, item] : kwargs)
    py::setattr(self, key, item);
  return value;
}

// Rows of float32 arrays are read in place as these types.
static_assert(sizeof(tessera::Float4) == 4 * sizeof(float));
static_assert(sizeof(glm::vec3) == 3 * sizeof(float));

// ---- NumPy arrays --------------------------------------------------------------------------

// Checks what only Python can get wrong about a vertex array: its dtype, its number of
// dimensions and (for `columns` > 0) its row length, and a layout the renderer can read in
// place (C-contiguous and aligned). Counts and values are the C++ API's checks.
template <class T>
void check_array(const py::array& array, const char* name, const char* dtype, int ndim,
                 py::ssize_t columns) {
  if (!py::isinstance<py::array_t<T>>(array)) {
    throw py::type_error(std::string(name) + " must be a " + dtype + " array, got dtype " +
                         py::str(array.dtype()).cast<std::string>());
  }
  if (array.ndim() != ndim || (columns > 0 && array.shape(ndim - 1) != columns)) {
    std::string shape = "(";
    for (py::ssize_t i = 0; i < array.ndim(); ++i) {
      if (i > 0) shape += ", ";
      shape += std::to_string(array.shape(i));
    }
    shape += array.ndim() == 1 ? ",)" : ")";
    std::string expected = ndim == 1     ? "(n,)"
                           : columns > 0 ? "(n, " + std::to_string(columns) + ")"
                                         : "(n, k)";
    throw py::value_error(std::string(name) + " must have shape " + expected + ", got " + shape);
  }
  if (!(array.flags() & py::array::c_style) ||
      !(array.flags() & py::detail::npy_api::NPY_ARRAY_ALIGNED_)) {
    throw py::value_error(std::string(name) +
                          " must be C-contiguous and aligned (numpy.ascontiguousarray)");
  }
}

// Takes ownership of `values` without copying: the array frees them when it is collected.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto owner = std::make_unique<std::vector<T>>(std::move(values));
  T* data = owner->data();
  py::capsule capsule(owner.get(), [](void* p) { delete static_cast<std::vector<T>*>(p); });
  owner.release();
  return py::array_t<T>(std::move(shape), data, std::move(capsule));
}

// A GLM matrix (column-major) as a 4x4 float32 array indexed [row, column], so that
// `matrix @ vector` transforms a column vector as in GLM.
py::array_t<float> to_numpy(const glm::mat4& matrix) {
  std::vector<float> values(16);
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column)
      values[row * 4 + column] = matrix[column][row];
  }
  return to_numpy(std::move(values), {4, 4});
}

glm::mat4 to_mat4(const py::array& array, const char* name) {
  check_array<float>(array, name, "float32", 2, 0);
  if (array.shape(0) != 4 || array.shape(1) != 4) {
    throw py::value_error(std::string(name) + " must have shape (4, 4), got (" +
                          std::to_string(array.shape(0)) + ", " + std::to_string(array.shape(1)) +
                          ")");
  }
  const float* values = static_cast<const float*>(array.data());
  glm::mat4 matrix;
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column)
      matrix[column][row] = values[row * 4 + column];
  }
  return matrix;
}

// A glm::vec3 member as a read-write tuple property.
template <class Class>
void def_vec3(py::class_<Class>& cls, const char* field, glm::vec3 Class::*member) {
  cls.def_property(
      field,
      [member](const Class& self) {
        const glm::vec3& v = self.*member;
        return std::array<float, 3>{v.x, v.y, v.z};
      },
      [member](Class& self, const std::array<float, 3>& v) {
        self.*member = {v[0], v[1], v[2]};
      });
}

// Copies `count` rows of `columns` floats (glm vectors) into an (count, columns) array.
template <class Vector>
py::array_t<float> rows_to_numpy(const std::vector<Vector>& rows, py::ssize_t columns) {
  static_assert(sizeof(Vector) % sizeof(float) == 0);
  std::vector<float> values(rows.size() * sizeof(Vector) / sizeof(float));
  std::memcpy(values.data(), rows.data(), values.size() * sizeof(float));
  return to_numpy(std::move(values), {static_cast<py::ssize_t>(rows.size()), columns});
}

// The depth of sample 0 of each pixel as an HxW float32 array, read without the GIL.
py::array_t<float> depth_image(const Framebuffer& fb) {
  std::vector<float> depth;
  {
    py::gil_scoped_release release;
    depth = fb.read_depth();
  }
  return to_numpy(std::move(depth), {fb.height(), fb.width()});
}

// An (n,) bool array of answer(i) for each i, computed without the GIL (answer must not touch
// Python objects).
template <class Answer>
py::array_t<bool> answers(size_t n, Answer answer) {
  py::array_t<bool> out(static_cast<py::ssize_t>(n));
  bool* data = out.mutable_data();
  py::gil_scoped_release release;
  for (size_t i = 0; i < n; ++i)
    data[i] = answer(i);
  return out;
}

// A draw's input read in place from the arrays, which must outlive it.
tessera::DrawInput draw_input(const py::array& positions, const std::optional<py::array>& varyings,
                              const std::optional<py::array>& indices) {
  check_array<float>(positions, "positions", "float32", 2, 4);
  tessera::DrawInput input;
  input.positions = {static_cast<const tessera::Float4*>(positions.data()),
                     static_cast<size_t>(positions.shape(0))};
  if (varyings) {
    check_array<float>(*varyings, "varyings", "float32", 2, 0);
    input.attributes = {static_cast<const float*>(varyings->data()),
                        static_cast<size_t>(varyings->size())};
    input.attribute_count = static_cast<uint32_t>(varyings->shape(1));
  }
  if (indices) {
    if (indices->ndim() == 2) {
      check_array<uint32_t>(*indices, "indices", "uint32", 2, 3);
    } else {
      check_array<uint32_t>(*indices, "indices", "uint32", 1, 0);
    }
    input.indices = {static_cast<const uint32_t*>(indices->data()),
                     static_cast<size_t>(indices->size())};
  }
  return input;
}

void draw(Renderer& renderer, Framebuffer& target, const py::array& positions,
          const std::optional<py::array>& varyings, const std::optional<py::array>& indices,
          const PipelineState* pipeline) {
  const tessera::DrawInput input = draw_input(positions, varyings, indices);
  const PipelineState state = pipeline ? *pipeline : PipelineState{};
  // The arrays stay referenced by this call's arguments while the GIL is released.
  py::gil_scoped_release release;
  renderer.draw(target, state, input);
}

}  // namespace

PYBIND11_MODULE(tessera, m) {
  m.doc() =
      "Tessera, a software rasterizer: draw clip-space triangles from NumPy arrays and read "
      "the images back as NumPy arrays.";
  m.attr("__version__") = TESSERA_VERSION_STRING;
  m.attr("MAX_VARYINGS") = tessera::kMaxVaryings;
  m.attr("MAX_LIGHTS") = tessera::kMaxLights;

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      switch (e.code()) {
        case ErrorCode::kInvalidArgument:
        case ErrorCode::kInvalidInput:
          PyErr_SetString(PyExc_ValueError, e.what());
          return;
        case ErrorCode::kOutOfMemory:
          PyErr_SetString(PyExc_MemoryError, e.what());
          return;
        default:
          PyErr_SetString(PyExc_RuntimeError, e.what());
          return;
      }
    }
  });

  py::class_<VaryingRoles> roles(m, "Roles",
                                 "Index of the first varying of each group the built-in shaders "
                                 "read: color (4), normal (3), position (3).");
  roles.def(py::init(&from_kwargs<VaryingRoles>))
      .def_readwrite("color", &VaryingRoles::color)
      .def_readwrite("normal", &VaryingRoles::normal)
      .def_readwrite("position", &VaryingRoles::position)
      .def_readwrite("texcoord", &VaryingRoles::texcoord);

  py::class_<tessera::Texture, std::shared_ptr<tessera::Texture>>(
      m, "Texture",
      "A 2D texture and its mip chain (tessera/texture.hpp): texel (0, 0) is the top-left one, "
      "u runs right and v down.")
      .def(py::init([](const py::array& pixels, bool srgb, bool mipmaps) {
             // uint8 (h, w, 4) or (h, w); float32 (h, w, 4) or (h, w).
             const bool bytes = py::isinstance<py::array_t<uint8_t>>(pixels);
             if (!bytes && !py::isinstance<py::array_t<float>>(pixels)) {
               throw py::type_error("pixels must be a uint8 or float32 array, got dtype " +
                                    py::str(pixels.dtype()).cast<std::string>());
             }
             if ((pixels.ndim() != 2 && pixels.ndim() != 3) ||
                 (pixels.ndim() == 3 && pixels.shape(2) != 4)) {
               throw py::value_error("pixels must have shape (h, w, 4) or (h, w)");
             }
             if (!(pixels.flags() & py::array::c_style)) {
               throw py::value_error("pixels must be C-contiguous (numpy.ascontiguousarray)");
             }
             const bool red = pixels.ndim() == 2;
             using F = tessera::TextureFormat;
             const F format = bytes ? (red    ? F::kR8
                                       : srgb ? F::kRGBA8Srgb
                                              : F::kRGBA8)
                                    : (red ? F::kR32F : F::kRGBA32F);
             // Sides past 2^32 - 1 are out of range anyway: the texture names the clamped size.
             const auto side = [](py::ssize_t n) {
               return static_cast<uint32_t>(std::min<py::ssize_t>(n, UINT32_MAX));
             };
             const tessera::TextureDesc desc{side(pixels.shape(1)), side(pixels.shape(0)), format};
             const std::span<const std::byte> data(static_cast<const std::byte*>(pixels.data()),
                                                   static_cast<size_t>(pixels.nbytes()));
             return std::make_shared<tessera::Texture>(desc, data, mipmaps);
           }),
           py::arg("pixels"), py::arg("srgb") = false, py::arg("mipmaps") = true,
           "The caller's texels copied: uint8 (h, w, 4) as rgba8 (rgba8_srgb with srgb) or "
           "(h, w) as r8, float32 as rgba32f or r32f; the mip chain generated with mipmaps.")
      .def_property_readonly("width", [](const tessera::Texture& t) { return t.desc().width; })
      .def_property_readonly("height", [](const tessera::Texture& t) { return t.desc().height; })
      .def_property_readonly("levels", &tessera::Texture::levels)
      .def_property_readonly("format", [](const tessera::Texture& t) {
        return name_of<tessera::TextureFormat>(kTextureFormatNames, t.desc().format);
      });

  py::class_<tessera::Sampler> sampler(
      m, "Sampler",
      "How a texture is sampled: filters (\"nearest\", \"linear\"), mip_filter (\"none\", "
      "\"nearest\", \"linear\"), wraps (\"repeat\", \"clamp_to_edge\", \"mirrored_repeat\", "
      "\"clamp_to_border\"), border_color, lod_bias, min_lod, max_lod, max_anisotropy (1 to 16).");
  sampler.def(py::init(&from_kwargs<tessera::Sampler>))
      .def_readwrite("border_color", &tessera::Sampler::border_color)
      .def_readwrite("lod_bias", &tessera::Sampler::lod_bias)
      .def_readwrite("min_lod", &tessera::Sampler::min_lod)
      .def_readwrite("max_lod", &tessera::Sampler::max_lod)
      .def_readwrite("max_anisotropy", &tessera::Sampler::max_anisotropy);
  def_enum<tessera::Filter>(sampler, "mag_filter", &tessera::Sampler::mag_filter, kFilterNames);
  def_enum<tessera::Filter>(sampler, "min_filter", &tessera::Sampler::min_filter, kFilterNames);
  def_enum<tessera::MipFilter>(sampler, "mip_filter", &tessera::Sampler::mip_filter,
                               kMipFilterNames);
  def_enum<tessera::Wrap>(sampler, "wrap_u", &tessera::Sampler::wrap_u, kWrapNames);
  def_enum<tessera::Wrap>(sampler, "wrap_v", &tessera::Sampler::wrap_v, kWrapNames);

  py::class_<Light> light(m, "Light", "A light of the Phong model (tessera/shading.hpp).");
  light.def(py::init(&from_kwargs<Light>))
      .def_readwrite("position", &Light::position)
      .def_readwrite("direction", &Light::direction)
      .def_readwrite("diffuse", &Light::diffuse)
      .def_readwrite("specular", &Light::specular)
      .def_readwrite("c0", &Light::c0)
      .def_readwrite("c1", &Light::c1)
      .def_readwrite("c2", &Light::c2)
      .def_readwrite("spot_cos_cutoff", &Light::spot_cos_cutoff)
      .def_readwrite("spot_exponent", &Light::spot_exponent);
  def_enum<LightKind>(light, "kind", &Light::kind, kLightKindNames);

  py::class_<PhongState> phong(m, "Phong", "Per-pixel Phong material and lights.");
  phong.def(py::init(&from_kwargs<PhongState>))
      .def_readwrite("base_color", &PhongState::base_color)
      .def_readwrite("ka", &PhongState::ka)
      .def_readwrite("kd", &PhongState::kd)
      .def_readwrite("ks", &PhongState::ks)
      .def_readwrite("shininess", &PhongState::shininess)
      .def_readwrite("ambient", &PhongState::ambient)
      .def_readwrite("eye", &PhongState::eye)
      .def_readwrite("two_sided", &PhongState::two_sided)
      .def_property(
          "lights",
          [](const PhongState& self) {
            const uint32_t count = std::min(self.light_count, tessera::kMaxLights);
            return std::vector<Light>(self.lights.begin(), self.lights.begin() + count);
          },
          [](PhongState& self, const std::vector<Light>& lights) {
            if (lights.size() > tessera::kMaxLights) {
              throw py::value_error("phong.lights holds " + std::to_string(lights.size()) +
                                    " lights, more than the maximum of " +
                                    std::to_string(tessera::kMaxLights));
            }
            std::copy(lights.begin(), lights.end(), self.lights.begin());
            self.light_count = static_cast<uint32_t>(lights.size());
          },
          "The lights (a list of up to 8 Light); assigning a list replaces them.");

  py::class_<tessera::BlendState> blend(
      m, "Blend",
      "Blend state of colour target 0 (tessera::BlendState): factor and op names as OpenGL's, "
      "lower case (\"src_alpha\", \"one_minus_src_alpha\", ...; ops \"add\", "
      "\"subtract\", \"reverse_subtract\", \"min\", \"max\"); write_mask bits 1 R, 2 G, 4 "
      "B, 8 A.");
  blend.def(py::init(&from_kwargs<tessera::BlendState>))
      .def_readwrite("enable", &tessera::BlendState::enable)
      .def_property(
          "write_mask", [](const tessera::BlendState& self) { return self.write_mask; },
          [](tessera::BlendState& self, uint32_t mask) {
            if (mask > tessera::kWriteAll) {
              throw py::value_error("write_mask " + std::to_string(mask) +
                                    " has bits beyond the four channels (0..15)");
            }
            self.write_mask = static_cast<uint8_t>(mask);
          })
      .def_static("over", &tessera::BlendState::over,
                  "(src_alpha, one_minus_src_alpha); alpha (one, one_minus_src_alpha)")
      .def_static("additive", &tessera::BlendState::additive, "(one, one)")
      .def_static("multiply", &tessera::BlendState::multiply, "(dst_color, zero)")
      .def_static("premultiplied_over", &tessera::BlendState::premultiplied_over,
                  "(one, one_minus_src_alpha)");
  def_enum<tessera::BlendFactor>(blend, "src_color", &tessera::BlendState::src_color,
                                 kBlendFactorNames);
  def_enum<tessera::BlendFactor>(blend, "dst_color", &tessera::BlendState::dst_color,
                                 kBlendFactorNames);
  def_enum<tessera::BlendOp>(blend, "color_op", &tessera::BlendState::color_op, kBlendOpNames);
  def_enum<tessera::BlendFactor>(blend, "src_alpha", &tessera::BlendState::src_alpha,
                                 kBlendFactorNames);
  def_enum<tessera::BlendFactor>(blend, "dst_alpha", &tessera::BlendState::dst_alpha,
                                 kBlendFactorNames);
  def_enum<tessera::BlendOp>(blend, "alpha_op", &tessera::BlendState::alpha_op, kBlendOpNames);

  py::class_<PipelineState> pipeline(m, "Pipeline",
                                     "Everything about a draw that is not its vertex data; "
                                     "keyword arguments set the attributes of the same names.");
  pipeline.def(py::init(&from_kwargs<PipelineState>))
      .def_readwrite("depth_test", &PipelineState::depth_test)
      .def_readwrite("depth_write", &PipelineState::depth_write)
      .def_readwrite("color_write", &PipelineState::color_write)
      .def_readwrite("samples", &PipelineState::samples)
      .def_readwrite("subpixel_bits", &PipelineState::subpixel_bits)
      .def_readwrite("roles", &PipelineState::roles)
      .def_readwrite("phong", &PipelineState::phong)
      .def_readwrite("object_id", &PipelineState::object_id)
      .def_readwrite("blend_constant", &PipelineState::blend_constant)
      .def_readwrite("depth_bias_constant", &PipelineState::depth_bias_constant)
      .def_readwrite("depth_bias_slope", &PipelineState::depth_bias_slope)
      .def_readwrite("depth_bias_clamp", &PipelineState::depth_bias_clamp)
      .def_readwrite("scissor_test", &PipelineState::scissor_test)
      .def_property(
          "scissor",
          [](const PipelineState& self) {
            const tessera::Rect& r = self.scissor;
            return std::make_tuple(r.x, r.y, r.width, r.height);
          },
          [](PipelineState& self, std::tuple<int32_t, int32_t, uint32_t, uint32_t> r) {
            self.scissor = {std::get<0>(r), std::get<1>(r), std::get<2>(r), std::get<3>(r)};
          },
          "The scissor rectangle (x, y, width, height) in window pixels from the top-left; "
          "drawn only with scissor_test.")
      .def_property(
          "blend", [](const PipelineState& self) { return self.blend[0]; },
          [](PipelineState& self, const tessera::BlendState& b) { self.blend[0] = b; },
          "Colour target 0's Blend (a copy: assign a Blend to change it).")
      .def_property(
          "varying_modes",
          [](const PipelineState& self) {
            std::vector<std::string> modes;
            for (VaryingMode mode : self.varying_modes)
              modes.push_back(name_of<VaryingMode>(kVaryingModeNames, mode));
            return modes;
          },
          [](PipelineState& self, const std::vector<std::string>& modes) {
            if (modes.size() > tessera::kMaxVaryings) {
              throw py::value_error("varying_modes holds " + std::to_string(modes.size()) +
                                    " modes, more than the maximum of " +
                                    std::to_string(tessera::kMaxVaryings));
            }
            self.varying_modes.fill(VaryingMode::kDefault);
            for (size_t i = 0; i < modes.size(); ++i)
              self.varying_modes[i] =
                  parse<VaryingMode>(kVaryingModeNames, "varying_modes", modes[i]);
          },
          "Per-varying interpolation (\"default\", \"perspective\", \"affine\", \"flat\"); a "
          "shorter list leaves the rest \"default\".");
  def_enum<CompareOp>(pipeline, "depth_compare", &PipelineState::depth_compare, kCompareNames);
  def_enum<CullMode>(pipeline, "cull", &PipelineState::cull, kCullNames);
  def_enum<FrontFace>(pipeline, "front_face", &PipelineState::front_face, kFrontFaceNames);
  def_enum<tessera::ClipDepth>(pipeline, "clip_depth", &PipelineState::clip_depth, kClipDepthNames);
  def_enum<Interpolation>(pipeline, "interpolation", &PipelineState::interpolation,
                          kInterpolationNames);
  def_enum<FragmentShader>(pipeline, "shader", &PipelineState::shader, kShaderNames);
  def_enum<TargetOutput>(pipeline, "output", &PipelineState::output, kOutputNames);
  pipeline.def_readwrite("sampler", &PipelineState::sampler)
      .def_property(
          "texture",
          [](const PipelineState& self) {
            return std::const_pointer_cast<tessera::Texture>(self.texture);
          },
          [](PipelineState& self, std::shared_ptr<tessera::Texture> texture) {
            self.texture = std::move(texture);
          },
          "shader \"textured\": the Texture (or None) sampled at roles.texcoord.");
  pipeline.def_property(
      "extra_outputs",
      [](const PipelineState& self) {
        std::vector<std::string> outputs;
        for (TargetOutput output : self.extra_outputs)
          outputs.push_back(name_of<TargetOutput>(kOutputNames, output));
        return outputs;
      },
      [](PipelineState& self, const std::vector<std::string>& outputs) {
        if (outputs.size() > self.extra_outputs.size()) {
          throw py::value_error("extra_outputs holds " + std::to_string(outputs.size()) +
                                " outputs, more than the " +
                                std::to_string(self.extra_outputs.size()) + " extra targets");
        }
        self.extra_outputs.fill(TargetOutput::kColor);
        for (size_t i = 0; i < outputs.size(); ++i)
          self.extra_outputs[i] = parse<TargetOutput>(kOutputNames, "extra_outputs", outputs[i]);
      },
      "What extra targets 1, 2, 3 receive (output names, as output); a shorter list leaves the "
      "rest \"color\".");

  py::class_<Framebuffer>(m, "Framebuffer",
                          "Colour and depth of every sample of every pixel; cleared to colour 0 "
                          "and depth 1.")
      .def(py::init([](uint32_t width, uint32_t height, uint32_t samples, std::string_view color,
                       std::string_view depth, const std::vector<std::string>& targets) {
             tessera::FramebufferDesc desc;
             desc.width = width;
             desc.height = height;
             desc.samples = samples;
             desc.color_format = parse<ColorFormat>(kColorNames, "color", color);
             desc.depth_format = parse<DepthFormat>(kDepthNames, "depth", depth);
             if (targets.size() > desc.extra_formats.size()) {
               throw py::value_error(
                   "targets holds " + std::to_string(targets.size()) + " formats, more than the " +
                   std::to_string(desc.extra_formats.size()) + " extra targets a framebuffer has");
             }
             desc.extra_targets = static_cast<uint32_t>(targets.size());
             for (size_t i = 0; i < targets.size(); ++i)
               desc.extra_formats[i] = parse<ColorFormat>(kColorNames, "targets", targets[i]);
             return Framebuffer(desc);
           }),
           py::arg("width"), py::arg("height"), py::arg("samples") = 1, py::arg("color") = "rgba8",
           py::arg("depth") = "float32", py::arg("targets") = std::vector<std::string>{},
           "color: target 0's format (\"rgba8\", \"rgba32f\"); targets: the formats of extra "
           "targets 1..3 (\"rgba8\", \"rgba32f\", \"r32f\", \"r32ui\"), written in the same "
           "pass as target 0 (Pipeline.extra_outputs says what each receives).")
      .def_property_readonly("target_count", &Framebuffer::target_count)
      .def(
          "target_format",
          [](const Framebuffer& self, uint32_t target) {
            return name_of<ColorFormat>(kColorNames, self.target_format(target));
          },
          py::arg("target"))
      .def(
          "read_target",
          [](const Framebuffer& self, uint32_t target) -> py::array {
            const ColorFormat format = self.target_format(target);
            if (format == ColorFormat::kR32UI) {
              std::vector<uint32_t> ids;
              {
                py::gil_scoped_release release;
                ids = self.read_target_uint(target);
              }
              return to_numpy(std::move(ids), {self.height(), self.width()});
            }
            std::vector<float> values;
            {
              py::gil_scoped_release release;
              values = self.read_target(target);
            }
            if (format == ColorFormat::kR32F)
              return to_numpy(std::move(values), {self.height(), self.width()});
            return to_numpy(std::move(values), {self.height(), self.width(), 4});
          },
          py::arg("target"),
          "Colour target `target`, resolved, top row first: HxWx4 float32 (rgba8 divided by 255, "
          "rgba32f), HxW float32 (r32f), or HxW uint32 (r32ui: sample 0 of each pixel).")
      .def(
          "clear_target",
          [](Framebuffer& self, uint32_t target, py::object value) {
            if (self.target_format(target) == ColorFormat::kR32UI) {
              self.clear_target_uint(target, value.cast<uint32_t>());
            } else {
              self.clear_target(target, value.cast<std::array<float, 4>>());
            }
          },
          py::arg("target"), py::arg("value"),
          "Clears a target: to an RGBA tuple (an r32f target keeps r), or an r32ui one to an "
          "integer.")
      .def_property_readonly("width", &Framebuffer::width)
      .def_property_readonly("height", &Framebuffer::height)
      .def_property_readonly("samples", &Framebuffer::samples)
      .def_property_readonly("color",
                             [](const Framebuffer& self) {
                               return name_of<ColorFormat>(kColorNames, self.desc().color_format);
                             })
      .def_property_readonly("depth",
                             [](const Framebuffer& self) {
                               return name_of<DepthFormat>(kDepthNames, self.desc().depth_format);
                             })
      .def("clear_color", &Framebuffer::clear_color, py::arg("rgba"))
      .def("clear_depth", &Framebuffer::clear_depth, py::arg("depth"))
      .def(
          "read_rgba8",
          [](const Framebuffer& self) {
            std::vector<uint8_t> pixels;
            {
              py::gil_scoped_release release;
              pixels = self.read_rgba8();
            }
            return to_numpy(std::move(pixels), {self.height(), self.width(), 4});
          },
          "Resolved colour, top row first: an HxWx4 uint8 array.")
      .def(
          "read_rgba32f",
          [](const Framebuffer& self) {
            std::vector<float> pixels;
            {
              py::gil_scoped_release release;
              pixels = self.read_rgba32f();
            }
            return to_numpy(std::move(pixels), {self.height(), self.width(), 4});
          },
          "Resolved colour, top row first: an HxWx4 float32 array.")
      .def(
          "read_color",
          [](const Framebuffer& self) -> py::array {
            if (self.desc().color_format == ColorFormat::kRGBA8) {
              std::vector<uint8_t> pixels;
              {
                py::gil_scoped_release release;
                pixels = self.read_rgba8();
              }
              return to_numpy(std::move(pixels), {self.height(), self.width(), 4});
            }
            std::vector<float> pixels;
            {
              py::gil_scoped_release release;
              pixels = self.read_rgba32f();
            }
            return to_numpy(std::move(pixels), {self.height(), self.width(), 4});
          },
          "Resolved colour in the framebuffer's format: HxWx4 uint8 (rgba8) or float32 "
          "(rgba32f).")
      .def(
          "read_depth", [](const Framebuffer& self) { return depth_image(self); },
          "Depth of sample 0 of each pixel in [0, 1], top row first: an HxW float32 array.")
      .def(
          "read_sample_depth",
          [](const Framebuffer& self) {
            std::vector<float> depth;
            {
              py::gil_scoped_release release;
              depth = self.read_sample_depth();
            }
            return to_numpy(std::move(depth), {self.height(), self.width(), self.samples()});
          },
          "Every sample's depth: an HxWxS float32 array.");

  py::class_<tessera::Camera> camera(
      m, "Camera",
      "A look-at camera with a perspective or orthographic projection (tessera/scene.hpp); "
      "view() and projection() are 4x4 float32 matrices for column vectors.");
  camera.def(py::init(&from_kwargs<tessera::Camera>))
      .def_readwrite("orthographic", &tessera::Camera::orthographic)
      .def_readwrite("fov_y_degrees", &tessera::Camera::fov_y_degrees)
      .def_readwrite("ortho_height", &tessera::Camera::ortho_height)
      .def_readwrite("near_plane", &tessera::Camera::near_plane)
      .def_readwrite("far_plane", &tessera::Camera::far_plane)
      .def_readwrite("reversed_z", &tessera::Camera::reversed_z)
      .def("view", [](const tessera::Camera& self) { return to_numpy(self.view()); })
      .def(
          "projection",
          [](const tessera::Camera& self, float aspect, std::string_view clip_depth) {
            return to_numpy(self.projection(
                aspect, parse<tessera::ClipDepth>(kClipDepthNames, "clip_depth", clip_depth)));
          },
          py::arg("aspect"), py::arg("clip_depth") = "zero_to_one");
  def_vec3(camera, "eye", &tessera::Camera::eye);
  def_vec3(camera, "target", &tessera::Camera::target);
  def_vec3(camera, "up", &tessera::Camera::up);

  m.def(
      "to_clip_space",
      [](const py::array& positions, const py::array& mvp) {
        check_array<float>(positions, "positions", "float32", 2, 3);
        const glm::mat4 matrix = to_mat4(mvp, "mvp");
        std::span<const glm::vec3> points{static_cast<const glm::vec3*>(positions.data()),
                                          static_cast<size_t>(positions.shape(0))};
        std::vector<tessera::Float4> clip;
        {
          py::gil_scoped_release release;
          clip = tessera::to_clip_space(points, matrix);
        }
        std::vector<float> values(clip.size() * 4);
        std::memcpy(values.data(), clip.data(), values.size() * sizeof(float));
        return to_numpy(std::move(values), {static_cast<py::ssize_t>(clip.size()), 4});
      },
      py::arg("positions"), py::arg("mvp"),
      "Transforms (n, 3) float32 positions by a 4x4 float32 matrix to (n, 4) clip space, as the "
      "C++ scene layer does.");

  py::class_<tessera::Mesh>(m, "Mesh",
                            "A triangle mesh; its arrays are copies: positions and normals "
                            "(n, 3) float32, colors (n, 4) float32, indices (m, 3) uint32.")
      .def_property_readonly(
          "positions", [](const tessera::Mesh& self) { return rows_to_numpy(self.positions, 3); })
      .def_property_readonly(
          "normals", [](const tessera::Mesh& self) { return rows_to_numpy(self.normals, 3); })
      .def_property_readonly(
          "colors", [](const tessera::Mesh& self) { return rows_to_numpy(self.colors, 4); })
      .def_property_readonly("indices",
                             [](const tessera::Mesh& self) {
                               std::vector<uint32_t> indices = self.indices;
                               const auto rows = static_cast<py::ssize_t>(indices.size() / 3);
                               return to_numpy(std::move(indices), {rows, 3});
                             })
      .def_property_readonly("triangle_count", &tessera::Mesh::triangle_count)
      .def(
          "bounds",
          [](const tessera::Mesh& self) {
            const tessera::Bounds b = tessera::mesh_bounds(self);
            return std::pair(std::array<float, 3>{b.min.x, b.min.y, b.min.z},
                             std::array<float, 3>{b.max.x, b.max.y, b.max.z});
          },
          "The mesh's axis-aligned box as ((min x, y, z), (max x, y, z)).");
#if TESSERA_PYTHON_IO
  m.def(
      "load_mesh",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return tessera::load_mesh(path);
      },
      py::arg("path"),
      "Loads every triangle of a Wavefront OBJ, glTF 2.0 or PLY file into one Mesh (Assimp).");
  m.def(
      "load_texture",
      [](const std::filesystem::path& path, bool srgb, bool mipmaps) {
        py::gil_scoped_release release;
        return std::make_shared<tessera::Texture>(tessera::load_texture(path, srgb, mipmaps));
      },
      py::arg("path"), py::arg("srgb") = false, py::arg("mipmaps") = true,
      "A Texture from an image file (OpenImageIO: PNG, JPEG, EXR, TIFF, ...).");
#endif

  using tessera::OcclusionBuffer;
  using tessera::OcclusionMode;
  py::class_<OcclusionBuffer>(
      m, "OcclusionBuffer",
      "Occluders drawn into a depth buffer only, then queries: would a window rectangle, a box "
      "or a triangle list be visible behind them (tessera/occlusion.hpp, docs/OCCLUSION.md). "
      "mode \"conservative\" answers from the 8x8 blocks' depth bounds (may say visible for a "
      "hidden query, never hidden for a visible one); \"exact\" tests every covered sample. "
      "Queries release the GIL and may run from several threads while no occluders are drawn.")
      .def(py::init([](uint32_t width, uint32_t height, uint32_t samples, std::string_view depth,
                       bool reversed_z, uint32_t threads) {
             tessera::OcclusionDesc desc;
             desc.width = width;
             desc.height = height;
             desc.samples = samples;
             desc.depth_format = parse<DepthFormat>(kDepthNames, "depth", depth);
             desc.reversed_z = reversed_z;
             desc.threads = threads;
             return std::make_unique<OcclusionBuffer>(desc);
           }),
           py::arg("width"), py::arg("height"), py::arg("samples") = 1,
           py::arg("depth") = "float32", py::arg("reversed_z") = false, py::arg("threads") = 0)
      .def_property_readonly("width", [](const OcclusionBuffer& self) { return self.desc().width; })
      .def_property_readonly("height",
                             [](const OcclusionBuffer& self) { return self.desc().height; })
      .def_property_readonly("samples",
                             [](const OcclusionBuffer& self) { return self.desc().samples; })
      .def("clear", &OcclusionBuffer::clear, py::call_guard<py::gil_scoped_release>(),
           "Every sample at the far depth: nothing occludes.")
      .def(
          "draw_occluders",
          [](OcclusionBuffer& self, const py::array& positions,
             const std::optional<py::array>& indices) {
            const tessera::DrawInput input = draw_input(positions, std::nullopt, indices);
            py::gil_scoped_release release;
            self.draw_occluders(input);
          },
          py::arg("positions"), py::arg("indices") = py::none(),
          "Draws clip-space triangles ((n, 4) float32 positions, uint32 indices of shape (3m,) "
          "or (m, 3)) into the depth buffer, both faces.")
      .def(
          "rect_visible",
          [](const OcclusionBuffer& self, float x0, float y0, float x1, float y1,
             float nearest_depth, std::string_view mode) {
            const OcclusionMode how = parse<OcclusionMode>(kOcclusionModeNames, "mode", mode);
            py::gil_scoped_release release;
            return self.rect_visible(x0, y0, x1, y1, nearest_depth, how);
          },
          py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"), py::arg("nearest_depth"),
          py::arg("mode") = "conservative",
          "Whether the window rectangle [x0, x1) x [y0, y1) (pixels, y down) at window depth "
          "nearest_depth (0..1) would be visible.")
      .def(
          "rects_visible",
          [](const OcclusionBuffer& self, const py::array& rects, const py::array& depths,
             std::string_view mode) {
            check_array<float>(rects, "rects", "float32", 2, 4);
            check_array<float>(depths, "depths", "float32", 1, 0);
            if (depths.shape(0) != rects.shape(0)) {
              throw py::value_error("depths holds " + std::to_string(depths.shape(0)) +
                                    " values for " + std::to_string(rects.shape(0)) + " rects");
            }
            const OcclusionMode how = parse<OcclusionMode>(kOcclusionModeNames, "mode", mode);
            const auto n = static_cast<size_t>(rects.shape(0));
            const float* r = static_cast<const float*>(rects.data());
            const float* z = static_cast<const float*>(depths.data());
            return answers(n, [&](size_t i) {
              return self.rect_visible(r[4 * i], r[4 * i + 1], r[4 * i + 2], r[4 * i + 3], z[i],
                                       how);
            });
          },
          py::arg("rects"), py::arg("depths"), py::arg("mode") = "conservative",
          "rect_visible for each row (x0, y0, x1, y1) of an (n, 4) float32 array and each "
          "nearest depth of an (n,) float32 array: an (n,) bool array.")
      .def(
          "box_visible",
          [](const OcclusionBuffer& self, const std::array<float, 3>& lo,
             const std::array<float, 3>& hi, const py::array& clip_from_object,
             std::string_view mode) {
            const glm::mat4 matrix = to_mat4(clip_from_object, "clip_from_object");
            const OcclusionMode how = parse<OcclusionMode>(kOcclusionModeNames, "mode", mode);
            py::gil_scoped_release release;
            return self.box_visible({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, matrix, how);
          },
          py::arg("lo"), py::arg("hi"), py::arg("clip_from_object"),
          py::arg("mode") = "conservative",
          "Whether the axis-aligned box [lo, hi] (object space) seen through the 4x4 float32 "
          "matrix clip_from_object (projection @ view @ model) would be visible; a box reaching "
          "behind the near plane is visible.")
      .def(
          "boxes_visible",
          [](const OcclusionBuffer& self, const py::array& lo, const py::array& hi,
             const py::array& clip_from_object, std::string_view mode) {
            check_array<float>(lo, "lo", "float32", 2, 3);
            check_array<float>(hi, "hi", "float32", 2, 3);
            if (hi.shape(0) != lo.shape(0)) {
              throw py::value_error("hi holds " + std::to_string(hi.shape(0)) + " corners for " +
                                    std::to_string(lo.shape(0)) + " in lo");
            }
            const glm::mat4 matrix = to_mat4(clip_from_object, "clip_from_object");
            const OcclusionMode how = parse<OcclusionMode>(kOcclusionModeNames, "mode", mode);
            const auto n = static_cast<size_t>(lo.shape(0));
            const glm::vec3* l = static_cast<const glm::vec3*>(lo.data());
            const glm::vec3* h = static_cast<const glm::vec3*>(hi.data());
            return answers(n, [&](size_t i) { return self.box_visible(l[i], h[i], matrix, how); });
          },
          py::arg("lo"), py::arg("hi"), py::arg("clip_from_object"),
          py::arg("mode") = "conservative",
          "box_visible for each row of (n, 3) float32 arrays lo and hi through one matrix: an "
          "(n,) bool array.")
      .def(
          "triangles_visible",
          [](const OcclusionBuffer& self, const py::array& positions,
             const std::optional<py::array>& indices, std::string_view mode) {
            const tessera::DrawInput input = draw_input(positions, std::nullopt, indices);
            const OcclusionMode how = parse<OcclusionMode>(kOcclusionModeNames, "mode", mode);
            py::gil_scoped_release release;
            return self.triangles_visible(input, how);
          },
          py::arg("positions"), py::arg("indices") = py::none(), py::arg("mode") = "conservative",
          "Whether any of the clip-space triangles would be visible (arrays as draw_occluders).")
      .def(
          "read_depth", [](const OcclusionBuffer& self) { return depth_image(self.framebuffer()); },
          "Depth of sample 0 of each pixel: an HxW float32 array.");

  py::class_<Renderer>(m, "Renderer",
                       "Draws triangles into framebuffers on its own threads (0: all cores). "
                       "Images are the same bytes for any thread count.")
      .def(py::init([](uint32_t threads, std::string_view backend) {
             tessera::RendererOptions options;
             options.threads = threads;
             options.backend = parse<Backend>(kBackendNames, "backend", backend);
             return Renderer(options);
           }),
           py::arg("threads") = 0, py::arg("backend") = "fast")
      .def_property_readonly("threads", &Renderer::threads)
      .def_property_readonly(
          "backend",
          [](const Renderer& self) { return name_of<Backend>(kBackendNames, self.backend()); })
      .def_property_readonly("simd_target", &Renderer::simd_target)
      .def("draw", &draw, py::arg("framebuffer"), py::arg("positions"),
           py::arg("varyings") = py::none(), py::arg("indices") = py::none(),
           py::arg("pipeline") = py::none(),
           "Draws a triangle list: positions an (n, 4) float32 array in clip space, varyings an "
           "(n, k) float32 array, indices a uint32 array of shape (3m,) or (m, 3), all "
           "C-contiguous and read in place. The GIL is released during the draw.");
}
