// A small camera and scene layer over GLM for samples and benchmarks: look-at cameras,
// perspective and orthographic projections, model transforms, per-vertex (Gouraud) Phong
// lighting, and the built-in demo scene. It follows the M_vp * M_per * M_cam * M_model chain
// of the lecture notes; M_vp (the viewport) is applied by the rasterizer.
#pragma once

#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "tessera/export.hpp"
#include "tessera/mesh.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"
#include "tessera/types.hpp"

namespace tessera {

struct TESSERA_API Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  bool orthographic = false;
  float fov_y_degrees = 45.0f;  // perspective
  float ortho_height = 2.0f;    // orthographic: visible height in world units
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  // Reversed Z: the near plane maps to depth 1 and the far plane to 0. Draw with
  // CompareOp::kGreater (or kGreaterEqual) into a depth buffer cleared to 0. With float depth
  // this matches float precision (finest near 0) to perspective depth (finest near the eye),
  // so precision is nearly even over distance (docs/TRADEOFFS.md).
  bool reversed_z = false;

  glm::mat4 view() const;
  glm::mat4 projection(float aspect, ClipDepth depth = ClipDepth::kZeroToOne) const;
};

// A camera looking at the bounds from `direction` (towards the eye), framing them with a small
// margin, near and far planes fitted around them.
TESSERA_API Camera frame_bounds(const Bounds& bounds, float aspect,
                                glm::vec3 direction = {0.55f, 0.45f, 1.0f},
                                float fov_y_degrees = 40.0f);

struct DirectionalLight {
  glm::vec3 direction{-0.4f, -0.8f, -0.5f};  // direction the light travels, world space
  glm::vec3 color{1.0f};
  float ambient = 0.18f;
  float specular = 0.35f;
  float shininess = 32.0f;
};

// Phong lighting (ambient + diffuse + specular) evaluated per vertex: the Gouraud colours of
// the mesh seen from `eye`. Positions and normals are transformed by `model` first.
TESSERA_API std::vector<float> shade_vertices(const Mesh& mesh, const glm::mat4& model,
                                              glm::vec3 eye, const DirectionalLight& light);

// Transforms positions to clip space by `mvp`.
TESSERA_API std::vector<Float4> to_clip_space(std::span<const glm::vec3> positions,
                                              const glm::mat4& mvp);

struct SceneObject {
  SceneObject() = default;
  SceneObject(Mesh m, const glm::mat4& model_matrix = glm::mat4(1.0f))
      : mesh(std::move(m)), model(model_matrix) {}

  Mesh mesh;
  glm::mat4 model{1.0f};
  // A base colour texture, sampled at mesh.texcoords (which the mesh must then have) and
  // multiplied by the lit vertex colour: textured objects are lit per vertex whatever the
  // SceneShading (FragmentShader::kTextured is unlit).
  std::shared_ptr<const Texture> texture;
  Sampler sampler;
};

struct TESSERA_API Scene {
  std::vector<SceneObject> objects;
  Camera camera;
  DirectionalLight light;
  size_t triangle_count() const noexcept;
  Bounds bounds() const;
};

// The built-in default scene: lit, overlapping objects on a ground plane, 49,920 triangles.
TESSERA_API Scene make_demo_scene();

// How draw_scene shades the objects' colour: lit per vertex (shade_vertices, Gouraud) or per
// pixel (FragmentShader::kPhong).
enum class SceneShading { kPerVertex, kPerPixel };

// Draws every object of the scene with the scene's camera and the given pipeline (its
// clip_depth selects the projection). With pipeline.output kColor the objects are lit as
// `shading` says; per pixel, by pipeline.phong's lights when it has any (in eye space, the
// eye at the origin), else by the scene's light, with each vertex's colour as the base. With a
// vision output (PipelineState::output) the objects go through the vertex stage's transform:
// normals and positions in eye space, object IDs 1, 2, ... in scene order (0 is left for the
// background), primitive IDs the triangle's index in its object's mesh. A framebuffer with
// extra targets gets each of them (PipelineState::extra_outputs) from the same pass.
TESSERA_API void draw_scene(Renderer& renderer, Framebuffer& target, const PipelineState& pipeline,
                            const Scene& scene, SceneShading shading = SceneShading::kPerVertex);

}  // namespace tessera
