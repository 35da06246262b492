// Cameras, projections, per-vertex Phong lighting and scene drawing over GLM. The chain is the
// lecture notes' M_vp * M_per * M_cam * M_model; the rasterizer applies M_vp.
#include "tessera/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "engine/src/shading_state.hpp"
#include "engine/src/vertex/vertex_stage.hpp"
#include "tessera/error.hpp"

namespace tessera {

glm::mat4 Camera::view() const {
  return glm::lookAtRH(eye, target, up);
}

glm::mat4 Camera::projection(float aspect, ClipDepth depth) const {
  const bool zo = depth == ClipDepth::kZeroToOne;
  // GLM's projections map the first depth given to 0 and the second to 1 (-1 and 1 for the
  // OpenGL range): reversed Z swaps them, mapping the far plane to 0 and the near plane to 1.
  const float to_zero = reversed_z ? far_plane : near_plane;
  const float to_one = reversed_z ? near_plane : far_plane;
  if (orthographic) {
    const float h = 0.5f * ortho_height;
    const float w = h * aspect;
    return zo ? glm::orthoRH_ZO(-w, w, -h, h, to_zero, to_one)
              : glm::orthoRH_NO(-w, w, -h, h, to_zero, to_one);
  }
  const float fovy = glm::radians(fov_y_degrees);
  return zo ? glm::perspectiveRH_ZO(fovy, aspect, to_zero, to_one)
            : glm::perspectiveRH_NO(fovy, aspect, to_zero, to_one);
}

Camera frame_bounds(const Bounds& bounds, float aspect, glm::vec3 direction, float fov_y_degrees) {
  const glm::vec3 center = 0.5f * (bounds.min + bounds.max);
  const float radius = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
  const float half_y = 0.5f * glm::radians(fov_y_degrees);
  const float half_x = std::atan(std::tan(half_y) * aspect);
  const float distance = radius / std::sin(std::min(half_x, half_y)) * 1.05f;
  Camera c;
  c.fov_y_degrees = fov_y_degrees;
  const float len = glm::length(direction);
  const glm::vec3 dir = len > 0.0f ? direction / len : glm::vec3(0.0f, 0.0f, 1.0f);
  c.eye = center + dir * distance;
  c.target = center;
  c.up = std::abs(dir.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  c.near_plane = std::max(distance - 1.2f * radius, 0.01f * radius);
  c.far_plane = distance + 1.2f * radius;
  c.ortho_height = 2.2f * radius;
  return c;
}

std::vector<float> shade_vertices(const Mesh& mesh, const glm::mat4& model, glm::vec3 eye,
                                  const DirectionalLight& light) {
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(model)));
  const glm::vec3 to_light = -glm::normalize(light.direction);
  std::vector<float> out(mesh.positions.size() * 4);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = glm::vec3(model * glm::vec4(mesh.positions[i], 1.0f));
    glm::vec3 n = i < mesh.normals.size() ? normal_matrix * mesh.normals[i] : glm::vec3(0, 0, 1);
    const float n_len = glm::length(n);
    n = n_len > 0.0f ? n / n_len : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec3 to_eye = eye - p;
    const float e_len = glm::length(to_eye);
    to_eye = e_len > 0.0f ? to_eye / e_len : glm::vec3(0.0f, 0.0f, 1.0f);
    // Light the side that faces the viewer, so meshes with inconsistent winding look right.
    if (glm::dot(n, to_eye) < 0.0f) n = -n;
    const glm::vec4 base = i < mesh.colors.size() ? mesh.colors[i] : glm::vec4(1.0f);
    const float diffuse = std::max(glm::dot(n, to_light), 0.0f);
    const glm::vec3 reflected = glm::reflect(-to_light, n);
    const float specular =
        diffuse > 0.0f ? std::pow(std::max(glm::dot(reflected, to_eye), 0.0f), light.shininess)
                       : 0.0f;
    const glm::vec3 rgb =
        glm::vec3(base) * (light.ambient + (1.0f - light.ambient) * diffuse) * light.color +
        light.specular * specular * light.color;
    out[i * 4 + 0] = std::min(rgb.r, 1.0f);
    out[i * 4 + 1] = std::min(rgb.g, 1.0f);
    out[i * 4 + 2] = std::min(rgb.b, 1.0f);
    out[i * 4 + 3] = base.a;
  }
  return out;
}

std::vector<Float4> to_clip_space(std::span<const glm::vec3> positions, const glm::mat4& mvp) {
  std::vector<Float4> out(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::vec4 c = mvp * glm::vec4(positions[i], 1.0f);
    out[i] = {c.x, c.y, c.z, c.w};
  }
  return out;
}

size_t Scene::triangle_count() const noexcept {
  size_t n = 0;
  for (const SceneObject& o : objects)
    n += o.mesh.triangle_count();
  return n;
}

Bounds Scene::bounds() const {
  Bounds b{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
  for (const SceneObject& o : objects) {
    for (const glm::vec3& p : o.mesh.positions) {
      const glm::vec3 q = glm::vec3(o.model * glm::vec4(p, 1.0f));
      b.min = glm::min(b.min, q);
      b.max = glm::max(b.max, q);
    }
  }
  if (objects.empty()) return {};
  return b;
}

namespace {

std::array<float, 16> to_array(const glm::mat4& m) {
  std::array<float, 16> a;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r)
      a[c * 4 + r] = m[c][r];
  }
  return a;
}

// The objects through the vertex stage's transform: eye-space position (varyings 0..2) and
// normal (3..5), the vertex colour (6..9): lit per vertex when a Gouraud colour is drawn per
// vertex beside other targets, and for textured objects, whose texture coordinates follow
// (10..11) and whose colour is the texel times that lit colour.
void draw_transformed(Renderer& renderer, Framebuffer& target, PipelineState pipeline,
                      const Scene& scene, SceneShading shading) {
  const float aspect = static_cast<float>(target.width()) / static_cast<float>(target.height());
  pipeline.roles = {6, 3, 0};
  VertexShader shader;
  shader.kind = VertexShaderKind::kTransform;
  shader.transform.view = to_array(scene.camera.view());
  shader.transform.projection = to_array(scene.camera.projection(aspect, pipeline.clip_depth));
  // The normal stream only where a normal is read (a model whose 3x3 part is singular has no
  // normal matrix, which other outputs do not need).
  bool normals =
      pipeline.shader == FragmentShader::kPhong && pipeline.output == TargetOutput::kColor;
  for (uint32_t t = 0; t < target.target_count(); ++t)
    normals = normals || output_of(pipeline, t) == TargetOutput::kNormal;
  const bool lit_vertices =
      shading == SceneShading::kPerVertex && pipeline.shader == FragmentShader::kGouraud;
  shader.transform.normal_stream = normals ? 1 : -1;
  shader.transform.space = VaryingSpace::kEye;
  // Both faces lit, as shade_vertices lights them (meshes with inconsistent winding).
  pipeline.phong.two_sided = true;
  if (pipeline.shader == FragmentShader::kPhong && pipeline.phong.light_count == 0) {
    // The scene's directional light, in eye space.
    const glm::vec3 d = glm::mat3(scene.camera.view()) * scene.light.direction;
    Light light;
    light.kind = LightKind::kDirectional;
    light.direction = {d.x, d.y, d.z};
    light.diffuse = {scene.light.color.r, scene.light.color.g, scene.light.color.b};
    light.specular = light.diffuse;
    pipeline.phong.lights[0] = light;
    pipeline.phong.light_count = 1;
    pipeline.phong.ambient = {scene.light.ambient, scene.light.ambient, scene.light.ambient};
    pipeline.phong.ka = 1.0f;
    pipeline.phong.kd = 1.0f - scene.light.ambient;
    pipeline.phong.ks = scene.light.specular;
    pipeline.phong.shininess = scene.light.shininess;
  }
  // Every object's vertex shader and streams are checked before any object is drawn, so that a
  // bad object leaves the target as it was.
  std::vector<Mesh> computed(scene.objects.size());  // smooth normals for meshes without
  std::vector<std::vector<glm::vec4>> colours(scene.objects.size());
  // Position, normal and colour, and for a textured object its texture coordinates.
  constexpr size_t kTexturedStreams = 4;
  std::vector<std::vector<VertexStream>> streams(scene.objects.size());
  bool colour = false;  // a target receives the shader's colour
  for (uint32_t t = 0; t < target.target_count(); ++t)
    colour = colour || output_of(pipeline, t) == TargetOutput::kColor;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const Mesh* mesh = &o.mesh;
    const bool textured = colour && o.texture != nullptr;
    if (textured && o.mesh.texcoords.size() != o.mesh.positions.size()) {
      throw Error(ErrorCode::kInvalidArgument,
                  "scene object " + std::to_string(i) + " has a texture but " +
                      std::to_string(o.mesh.texcoords.size()) + " texture coordinates for " +
                      std::to_string(o.mesh.positions.size()) + " vertices");
    }
    if (o.mesh.normals.size() != o.mesh.positions.size()) {
      computed[i] = o.mesh;
      compute_normals(computed[i]);
      mesh = &computed[i];
    }
    if (lit_vertices || textured) {
      const std::vector<float> lit = shade_vertices(o.mesh, o.model, scene.camera.eye, scene.light);
      colours[i].resize(lit.size() / 4);
      std::memcpy(&colours[i].data()->x, lit.data(), lit.size() * sizeof(float));
    } else {
      colours[i] = mesh->colors;
    }
    colours[i].resize(mesh->positions.size(), glm::vec4(1.0f));
    streams[i] = {VertexStream{{&mesh->positions.data()->x, mesh->positions.size() * 3}, 3},
                  VertexStream{{&mesh->normals.data()->x, mesh->normals.size() * 3}, 3},
                  VertexStream{{&colours[i].data()->x, colours[i].size() * 4}, 4}};
    if (textured) {
      streams[i].push_back(
          VertexStream{{&o.mesh.texcoords.data()->x, o.mesh.texcoords.size() * 2}, 2});
    }
    shader.transform.model = to_array(o.model);
    vertex::validate(shader, {streams[i], mesh->positions.size(), mesh->indices});
  }
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const Mesh* mesh = computed[i].positions.empty() ? &o.mesh : &computed[i];
    shader.transform.model = to_array(o.model);
    PipelineState p = pipeline;
    p.object_id = static_cast<uint32_t>(i + 1);
    if (streams[i].size() == kTexturedStreams) {
      p.shader = FragmentShader::kTextured;
      p.roles.texcoord = 10;
      p.texture = o.texture;
      p.sampler = o.sampler;
    }
    renderer.draw_vertices(target, p, shader, {streams[i], mesh->positions.size(), mesh->indices});
  }
}

}  // namespace

void draw_scene(Renderer& renderer, Framebuffer& target, const PipelineState& pipeline,
                const Scene& scene, SceneShading shading) {
  const bool textured = std::any_of(scene.objects.begin(), scene.objects.end(),
                                    [](const SceneObject& o) { return o.texture != nullptr; });
  if (shading == SceneShading::kPerPixel || pipeline.output != TargetOutput::kColor ||
      target.target_count() > 1 || textured) {
    PipelineState p = pipeline;
    if (shading == SceneShading::kPerPixel) p.shader = FragmentShader::kPhong;
    draw_transformed(renderer, target, p, scene, shading);
    return;
  }
  const float aspect = static_cast<float>(target.width()) / static_cast<float>(target.height());
  const glm::mat4 view_projection =
      scene.camera.projection(aspect, pipeline.clip_depth) * scene.camera.view();
  for (const SceneObject& o : scene.objects) {
    const std::vector<Float4> clip = to_clip_space(o.mesh.positions, view_projection * o.model);
    const std::vector<float> colors =
        shade_vertices(o.mesh, o.model, scene.camera.eye, scene.light);
    DrawInput input;
    input.positions = clip;
    input.attributes = colors;
    input.attribute_count = 4;
    input.indices = o.mesh.indices;
    renderer.draw(target, pipeline, input);
  }
}

}  // namespace tessera
