// The built-in demo scene: parametric surfaces (a rolling heightfield, a torus, a trefoil-knot
// tube, spheres) that overlap in depth, lit per vertex, so one image shows perspective,
// Gouraud colour, depth testing and antialiased silhouettes; the heightfield is tiled with a
// procedural texture (trilinear, so its far tiles do not alias).
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "tessera/scene.hpp"

namespace tessera {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A grid of (nu x nv) quads over (u, v) in [0, 1]^2, two triangles each. Wrapped directions
// reuse the first row/column of vertices so seams share vertices (and smooth normals).
Mesh parametric(int nu, int nv, bool wrap_u, bool wrap_v,
                const std::function<glm::vec3(float, float)>& position,
                const std::function<glm::vec4(float, float)>& color) {
  Mesh m;
  const int cols = wrap_u ? nu : nu + 1;
  const int rows = wrap_v ? nv : nv + 1;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(nu);
      const float v = static_cast<float>(j) / static_cast<float>(nv);
      m.positions.push_back(position(u, v));
      m.colors.push_back(color(u, v));
      m.texcoords.emplace_back(u, v);
    }
  }
  auto index = [&](int i, int j) { return static_cast<uint32_t>((j % rows) * cols + (i % cols)); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1),
                     d = index(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  }
  compute_normals(m);
  return m;
}

glm::vec4 hue(float h) {
  const float r = 0.5f + 0.5f * std::cos(2.0f * kPi * h);
  const float g = 0.5f + 0.5f * std::cos(2.0f * kPi * (h - 1.0f / 3.0f));
  const float b = 0.5f + 0.5f * std::cos(2.0f * kPi * (h - 2.0f / 3.0f));
  return {r, g, b, 1.0f};
}

// Square stone tiles with darker joints and a little variation per tile, 256x256 sRGB texels
// with their mip chain.
std::shared_ptr<const Texture> tile_texture() {
  constexpr uint32_t kSize = 256, kTile = 64;
  std::vector<uint8_t> texels;
  texels.reserve(kSize * kSize * 4);
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const uint32_t tx = x % kTile, ty = y % kTile;
      const bool joint = tx < 3 || ty < 3;
      const uint32_t tile = (x / kTile) * 7 + (y / kTile) * 13;
      const auto shade = static_cast<uint8_t>(joint ? 120 : 215 + (tile * 37) % 40);
      const auto grain = static_cast<uint8_t>(((x * 31) ^ (y * 17)) % 12);
      texels.insert(texels.end(), {static_cast<uint8_t>(shade - grain),
                                   static_cast<uint8_t>(shade - grain), shade, 255});
    }
  }
  return std::make_shared<Texture>(TextureDesc{kSize, kSize, TextureFormat::kRGBA8Srgb},
                                   std::as_bytes(std::span<const uint8_t>(texels)), true);
}

Mesh sphere(int segments, glm::vec4 top, glm::vec4 bottom) {
  return parametric(
      segments, segments / 2, true, false,
      [](float u, float v) {
        const float theta = 2.0f * kPi * u, phi = kPi * v;
        return glm::vec3(std::sin(phi) * std::cos(theta), std::cos(phi),
                         std::sin(phi) * std::sin(theta));
      },
      [=](float, float v) { return glm::mix(top, bottom, v); });
}

}  // namespace

Scene make_demo_scene() {
  Scene scene;

  // A rolling heightfield, coloured by height from deep teal to sand.
  scene.objects.push_back({parametric(
      96, 96, false, false,
      [](float u, float v) {
        const float x = (u - 0.5f) * 12.0f, z = (v - 0.5f) * 12.0f;
        const float y =
            0.25f * std::sin(1.3f * x) * std::cos(1.1f * z) + 0.12f * std::sin(2.7f * x + 1.7f * z);
        return glm::vec3(x, y - 1.0f, z);
      },
      [](float u, float v) {
        const float x = (u - 0.5f) * 12.0f, z = (v - 0.5f) * 12.0f;
        const float h = 0.5f + 1.1f * (0.25f * std::sin(1.3f * x) * std::cos(1.1f * z) +
                                       0.12f * std::sin(2.7f * x + 1.7f * z));
        return glm::mix(glm::vec4(0.05f, 0.35f, 0.40f, 1.0f), glm::vec4(0.90f, 0.80f, 0.55f, 1.0f),
                        glm::clamp(h, 0.0f, 1.0f));
      })});
  // Twelve tiles across (one per unit), repeated.
  SceneObject& ground = scene.objects.back();
  for (glm::vec2& uv : ground.mesh.texcoords)
    uv *= 12.0f;
  ground.texture = tile_texture();

  // A torus standing on edge, hue running around it.
  scene.objects.push_back(
      {parametric(
           128, 48, true, true,
           [](float u, float v) {
             const float a = 2.0f * kPi * u, b = 2.0f * kPi * v;
             const float R = 1.0f, r = 0.38f;
             return glm::vec3((R + r * std::cos(b)) * std::cos(a),
                              (R + r * std::cos(b)) * std::sin(a), r * std::sin(b));
           },
           [](float u, float) { return hue(u); }),
       glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, 0.55f, 0.0f)), 0.5f,
                   glm::vec3(0.0f, 1.0f, 0.0f))});

  // A trefoil-knot tube threaded through the torus's hole.
  scene.objects.push_back({parametric(
                               320, 20, true, true,
                               [](float u, float v) {
                                 auto curve = [](float t) {
                                   return 0.42f * glm::vec3(std::sin(t) + 2.0f * std::sin(2.0f * t),
                                                            std::cos(t) - 2.0f * std::cos(2.0f * t),
                                                            -std::sin(3.0f * t));
                                 };
                                 const float t = 2.0f * kPi * u;
                                 const glm::vec3 p = curve(t);
                                 const glm::vec3 tangent =
                                     glm::normalize(curve(t + 1e-3f) - curve(t - 1e-3f));
                                 const glm::vec3 side =
                                     glm::normalize(glm::cross(tangent, glm::vec3(0, 0, 1)));
                                 const glm::vec3 normal = glm::cross(side, tangent);
                                 const float b = 2.0f * kPi * v;
                                 return p + 0.16f * (std::cos(b) * side + std::sin(b) * normal);
                               },
                               [](float u, float) {
                                 return glm::mix(glm::vec4(0.95f, 0.75f, 0.2f, 1.0f),
                                                 glm::vec4(0.85f, 0.25f, 0.15f, 1.0f),
                                                 0.5f + 0.5f * std::sin(6.0f * kPi * u));
                               }),
                           glm::translate(glm::mat4(1.0f), glm::vec3(2.3f, 0.55f, -1.2f))});

  // Spheres, one sunk into the ground and the torus, one floating behind.
  scene.objects.push_back(
      {sphere(64, {0.55f, 0.75f, 1.0f, 1.0f}, {0.10f, 0.20f, 0.60f, 1.0f}),
       glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-1.9f, -0.35f, 0.9f)),
                  glm::vec3(0.9f))});
  scene.objects.push_back(
      {sphere(48, {0.70f, 1.0f, 0.60f, 1.0f}, {0.10f, 0.45f, 0.20f, 1.0f}),
       glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 1.9f, -3.0f)), glm::vec3(0.7f))});

  scene.camera.eye = {1.2f, 2.4f, 6.8f};
  scene.camera.target = {0.3f, 0.2f, -0.3f};
  scene.camera.fov_y_degrees = 45.0f;
  scene.camera.near_plane = 0.5f;
  scene.camera.far_plane = 40.0f;
  return scene;
}

}  // namespace tessera
