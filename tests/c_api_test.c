/* The C API (tessera/tessera.h) from C: compiled as C11 with warnings as errors, it draws small
 * scenes through every draw and read-back call and checks the pixels, colours and depths
 * against values worked out here from the conventions (pixel centres at i + 0.5, the top-left
 * rule, the D3D 4x sample positions, OpenGL's diamond-exit lines), then calls every entry
 * point wrongly (NULL handles and pointers, bad sizes and enumeration values, NaN positions)
 * and checks the result code and that the message names the problem. Exits non-zero on any
 * failure; ctest runs it (tests/CMakeLists.txt). */
#include <math.h>
#include <stdalign.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tessera/tessera.h>

static int checks;
static int failures;

static void check(int ok, const char* what, int line) {
  ++checks;
  if (!ok) {
    ++failures;
    fprintf(stderr, "c_api_test.c:%d: FAILED: %s (last message: '%s')\n", line, what,
            tessera_last_error_message());
  }
}
#define CHECK(cond) check((cond) != 0, #cond, __LINE__)

/* A call that must succeed. */
#define OK(call) check((call) == TESSERA_OK, #call, __LINE__)

/* A call that must fail with `code`, recording it as the thread's last error, with a message
 * that starts with the function's name and contains `needle`. */
static void expect_error(tessera_result got, tessera_result code, const char* function,
                         const char* needle, int line) {
  char what[512];
  snprintf(what, sizeof what, "%s returns %s (got %s) with a message naming '%s'", function,
           tessera_result_name(code), tessera_result_name(got), needle);
  const char* message = tessera_last_error_message();
  check(got == code && tessera_last_error() == code &&
            strncmp(message, function, strlen(function)) == 0 && strstr(message, needle) != NULL,
        what, line);
}
#define EXPECT_ERROR(call, code, function, needle) \
  expect_error((call), (code), (function), (needle), __LINE__)

enum { kSize = 64 };

/* NDC coordinate of window coordinate w on an axis of kSize pixels (x right; y is flipped by
 * the caller, since window y grows downward). */
static float ndc(float w) {
  return w / (kSize / 2.0f) - 1.0f;
}

static const uint8_t* pixel8(const uint8_t* rgba, int x, int y) {
  return rgba + ((size_t)y * kSize + (size_t)x) * 4;
}

static int is_rgba8(const uint8_t* p, int r, int g, int b, int a) {
  return p[0] == r && p[1] == g && p[2] == b && p[3] == a;
}

static tessera_framebuffer* make_framebuffer(uint32_t samples, tessera_color_format color,
                                             tessera_depth_format depth) {
  const tessera_framebuffer_desc desc = {.width = kSize,
                                         .height = kSize,
                                         .samples = samples,
                                         .color_format = color,
                                         .depth_format = depth};
  tessera_framebuffer* fb = NULL;
  OK(tessera_framebuffer_create(&desc, NULL, &fb));
  return fb;
}

static tessera_renderer* make_renderer(tessera_backend backend, uint32_t threads) {
  tessera_renderer_desc desc;
  OK(tessera_renderer_desc_init(&desc));
  desc.backend = backend;
  desc.threads = threads;
  tessera_renderer* renderer = NULL;
  OK(tessera_renderer_create(&desc, NULL, &renderer));
  return renderer;
}

/* ---- The scene: background, quad, gradient triangle, points, a line --------------------- */

/* On a 64x64 RGBA8 framebuffer cleared to black and depth 1:
 *   a green triangle behind everything (z 0.75) covering the whole window;
 *   a red square (z 0.5), two indexed triangles over window [16, 48) x [16, 48);
 *   a triangle at z 0.25 over window (0, 0), (24, 0), (0, 24) with red, green and blue
 *   vertices, drawn in front;
 *   a 3-pixel square point centred on pixel (60, 5) and 1-pixel points on (60, 1) and (62, 1),
 *     white at z 0.1;
 *   a yellow line from the centre of pixel (30, 58) to that of (40, 58), z 0.1. */
static void draw_scene(tessera_renderer* renderer, tessera_framebuffer* fb) {
  OK(tessera_framebuffer_clear_color(fb, 0, 0, 0, 1));
  OK(tessera_framebuffer_clear_depth(fb, 1));
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));

  const float background[] = {-1, -1, 0.75f, 1, 3, -1, 0.75f, 1, -1, 3, 0.75f, 1};
  const float green[] = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  const tessera_draw_input back = {background, 3, green, 4, NULL, 0};
  OK(tessera_draw_triangles(renderer, fb, &pipeline, &back));

  const float lo = ndc(16), hi = ndc(48);
  const float square[] = {lo, -lo, 0.5f, 1, hi, -lo, 0.5f, 1, hi, -hi, 0.5f, 1, lo, -hi, 0.5f, 1};
  const float red[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const tessera_draw_input quad = {square, 4, red, 4, indices, 6};
  OK(tessera_draw_triangles(renderer, fb, &pipeline, &quad));

  const float corner[] = {-1, 1, 0.25f, 1, ndc(24), 1, 0.25f, 1, -1, -ndc(24), 0.25f, 1};
  const float rgb[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1};
  const tessera_draw_input gradient = {corner, 3, rgb, 4, NULL, 0};
  OK(tessera_draw_triangles(renderer, fb, &pipeline, &gradient));

  tessera_point_state point;
  OK(tessera_point_state_init(&point));
  const float white[] = {1, 1, 1, 1, 1, 1, 1, 1};
  const float small[] = {ndc(60.5f), -ndc(1.5f), 0.1f, 1, ndc(62.5f), -ndc(1.5f), 0.1f, 1};
  const tessera_draw_input small_points = {small, 2, white, 4, NULL, 0};
  OK(tessera_draw_points(renderer, fb, &pipeline, &point, &small_points));
  point.size = 3;
  const float big[] = {ndc(60.5f), -ndc(5.5f), 0.1f, 1};
  const tessera_draw_input big_point = {big, 1, white, 4, NULL, 0};
  OK(tessera_draw_points(renderer, fb, &pipeline, &point, &big_point));

  tessera_line_state line;
  OK(tessera_line_state_init(&line));
  const float ends[] = {ndc(30.5f), -ndc(58.5f), 0.1f, 1, ndc(40.5f), -ndc(58.5f), 0.1f, 1};
  const float yellow[] = {1, 1, 0, 1, 1, 1, 0, 1};
  const tessera_draw_input segment = {ends, 2, yellow, 4, NULL, 0};
  OK(tessera_draw_lines(renderer, fb, &pipeline, &line, &segment));
}

/* What draw_scene leaves at pixel (x, y): 'W' white, 'Y' yellow, 'R' red, 'G' green, or 'T'
 * the gradient triangle ('E' on its long edge, where the fill rule decides: not checked). */
static char expected_at(int x, int y) {
  if ((y == 1 && (x == 60 || x == 62)) || (x >= 59 && x <= 61 && y >= 4 && y <= 6)) return 'W';
  if (y == 58 && x >= 30 && x < 40) return 'Y';
  const int sum = 2 * (x + y) + 2; /* twice the sum of the centre's coordinates */
  if (sum < 48) return 'T';
  if (sum == 48) return 'E';
  if (x >= 16 && x < 48 && y >= 16 && y < 48) return 'R';
  return 'G';
}

static void check_scene(const char* name, tessera_backend backend) {
  tessera_renderer* renderer = make_renderer(backend, 2);
  tessera_framebuffer* fb = make_framebuffer(1, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_FLOAT32);
  draw_scene(renderer, fb);

  static uint8_t rgba[kSize * kSize * 4];
  static float depth[kSize * kSize];
  OK(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba));
  OK(tessera_framebuffer_read_depth(fb, depth, kSize * kSize));
  int wrong = 0, red = 0, white = 0, yellow = 0, worst_gradient = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const uint8_t* p = pixel8(rgba, x, y);
      const float z = depth[y * kSize + x];
      int ok = 1;
      switch (expected_at(x, y)) {
        case 'W':
          ok = is_rgba8(p, 255, 255, 255, 255) && fabsf(z - 0.1f) < 1e-6f;
          white += ok;
          break;
        case 'Y':
          ok = is_rgba8(p, 255, 255, 0, 255) && fabsf(z - 0.1f) < 1e-6f;
          yellow += ok;
          break;
        case 'R':
          ok = is_rgba8(p, 255, 0, 0, 255) && fabsf(z - 0.5f) < 1e-6f;
          red += ok;
          break;
        case 'G':
          ok = is_rgba8(p, 0, 255, 0, 255) && fabsf(z - 0.75f) < 1e-6f;
          break;
        case 'T': {
          /* Barycentric weights of the pixel centre: the green vertex is at window (24, 0), the
           * blue one at (0, 24), so their weights are x / 24 and y / 24 (w = 1: perspective and
           * affine agree). The engine rounds c * 255 to nearest; one step of slack for the
           * fast engine's float planes. */
          const float cx = (float)x + 0.5f, cy = (float)y + 0.5f;
          const float weights[3] = {1 - cx / 24 - cy / 24, cx / 24, cy / 24};
          for (int c = 0; c < 3; ++c) {
            const int want = (int)lroundf(weights[c] * 255);
            const int off = abs(p[c] - want);
            if (off > worst_gradient) worst_gradient = off;
            ok = ok && off <= 1;
          }
          ok = ok && p[3] == 255 && fabsf(z - 0.25f) < 1e-6f;
          break;
        }
        default:
          break;
      }
      if (!ok && wrong++ < 5) {
        fprintf(stderr, "%s: pixel (%d, %d) is (%d, %d, %d, %d) depth %g, expected '%c'\n", name, x,
                y, p[0], p[1], p[2], p[3], (double)z, expected_at(x, y));
      }
    }
  }
  CHECK(wrong == 0);
  CHECK(red == 32 * 32);
  CHECK(white == 2 + 9);
  CHECK(yellow == 10);
  CHECK(worst_gradient <= 1);
  printf("c_api_test: %s scene: %d red, %d white, %d yellow pixels; gradient within %d step\n",
         name, red, white, yellow, worst_gradient);

  /* The float read-back of an RGBA8 buffer is the bytes over 255. */
  static float rgba32f[kSize * kSize * 4];
  OK(tessera_framebuffer_read_rgba32f(fb, rgba32f, kSize * kSize * 4));
  CHECK(rgba32f[(20 * kSize + 20) * 4] == 1.0f && rgba32f[(20 * kSize + 20) * 4 + 1] == 0.0f);

  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- MSAA, float colour, per-sample depth ------------------------------------------------ */

/* A red rectangle over window x in [16.5, 64] at 4 samples: its left edge runs through the
 * centres of column 16, whose samples at x offsets -2/16, 6/16, -6/16, 2/16 (D3D's 4x
 * pattern) are outside, inside, outside, inside. The resolve averages them with the black,
 * transparent clear: 0.5 in red and alpha; sample 0's depth is the clear's, 1. */
static void check_msaa(tessera_backend backend) {
  tessera_renderer* renderer = make_renderer(backend, 1);
  tessera_framebuffer* fb = make_framebuffer(4, TESSERA_COLOR_RGBA32F, TESSERA_DEPTH_FLOAT32);
  OK(tessera_framebuffer_clear_color(fb, 0, 0, 0, 0));
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.samples = 4;
  const float l = ndc(16.5f);
  const float rect[] = {l, -1, 0.5f, 1, 1, -1, 0.5f, 1, 1, 1, 0.5f, 1, l, 1, 0.5f, 1};
  const float red[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const tessera_draw_input input = {rect, 4, red, 4, indices, 6};
  OK(tessera_draw_triangles(renderer, fb, &pipeline, &input));

  static float rgba[kSize * kSize * 4];
  static float depth[kSize * kSize];
  static float samples[kSize * kSize * 4];
  OK(tessera_framebuffer_read_rgba32f(fb, rgba, kSize * kSize * 4));
  OK(tessera_framebuffer_read_depth(fb, depth, kSize * kSize));
  OK(tessera_framebuffer_read_sample_depth(fb, samples, kSize * kSize * 4));
  const int y = 30;
  const float* p15 = rgba + (y * kSize + 15) * 4;
  const float* p16 = rgba + (y * kSize + 16) * 4;
  const float* p17 = rgba + (y * kSize + 17) * 4;
  CHECK(p15[0] == 0.0f && p15[3] == 0.0f);
  CHECK(p16[0] == 0.5f && p16[1] == 0.0f && p16[2] == 0.0f && p16[3] == 0.5f);
  CHECK(p17[0] == 1.0f && p17[3] == 1.0f);
  CHECK(depth[y * kSize + 16] == 1.0f && depth[y * kSize + 17] == 0.5f);
  const float* s16 = samples + (y * kSize + 16) * 4;
  CHECK(s16[0] == 1.0f && s16[1] == 0.5f && s16[2] == 1.0f && s16[3] == 0.5f);
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- Shading state: object IDs, eye depth, Phong, unorm16 depth ------------------------- */

/* A full-window quad as two triangles, with w = 2 (so eye depth 2) and z = w / 2 (depth 0.5),
 * carrying colour (0.5, 1, 0.25, 1), normal (0, 0, 1) and position (0, 0, -1) varyings in the
 * default roles 0..3, 4..6 and 7..9. */
static tessera_result draw_full_quad(tessera_renderer* renderer, tessera_framebuffer* fb,
                                     const tessera_pipeline_state* pipeline) {
  const float quad[] = {-2, -2, 1, 2, 2, -2, 1, 2, 2, 2, 1, 2, -2, 2, 1, 2};
  float varyings[4 * 10];
  for (int v = 0; v < 4; ++v) {
    const float one[10] = {0.5f, 1, 0.25f, 1, 0, 0, 1, 0, 0, -1};
    memcpy(varyings + v * 10, one, sizeof one);
  }
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const tessera_draw_input input = {quad, 4, varyings, 10, indices, 6};
  return tessera_draw_triangles(renderer, fb, pipeline, &input);
}

static void check_shading(void) {
  /* The vision outputs and Phong are drawn by the reference backend. */
  tessera_renderer* renderer = make_renderer(TESSERA_BACKEND_REFERENCE, 1);
  tessera_framebuffer* fb = make_framebuffer(1, TESSERA_COLOR_RGBA32F, TESSERA_DEPTH_FLOAT32);
  static float rgba[kSize * kSize * 4];
  const float* centre = rgba + (32 * kSize + 32) * 4;
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));

  pipeline.output = TESSERA_OUTPUT_OBJECT_ID;
  pipeline.object_id = 7;
  OK(draw_full_quad(renderer, fb, &pipeline));
  OK(tessera_framebuffer_read_rgba32f(fb, rgba, kSize * kSize * 4));
  CHECK(centre[0] == 7.0f && centre[1] == 7.0f && centre[2] == 7.0f && centre[3] == 1.0f);

  pipeline.output = TESSERA_OUTPUT_EYE_DEPTH;
  pipeline.depth_compare = TESSERA_COMPARE_LESS_EQUAL;
  OK(draw_full_quad(renderer, fb, &pipeline));
  OK(tessera_framebuffer_read_rgba32f(fb, rgba, kSize * kSize * 4));
  CHECK(fabsf(centre[0] - 2.0f) < 1e-6f && centre[3] == 1.0f);

  /* Phong without specular, a directional light straight down the normal: N.L = 1, so
   * I = ka + kd = 0.8 in every channel, times the base colour (1, 1, 1, 1) times the colour
   * varyings: (0.4, 0.8, 0.2) with the varyings' alpha 1. */
  pipeline.output = TESSERA_OUTPUT_COLOR;
  pipeline.shader = TESSERA_SHADER_PHONG;
  pipeline.phong.ks = 0;
  pipeline.phong.light_count = 1;
  pipeline.phong.lights[0].kind = TESSERA_LIGHT_DIRECTIONAL;
  pipeline.phong.lights[0].direction[0] = 0;
  pipeline.phong.lights[0].direction[1] = 0;
  pipeline.phong.lights[0].direction[2] = -1;
  OK(draw_full_quad(renderer, fb, &pipeline));
  OK(tessera_framebuffer_read_rgba32f(fb, rgba, kSize * kSize * 4));
  CHECK(fabsf(centre[0] - 0.4f) < 1e-5f && fabsf(centre[1] - 0.8f) < 1e-5f &&
        fabsf(centre[2] - 0.2f) < 1e-5f && centre[3] == 1.0f);
  tessera_framebuffer_destroy(fb);

  /* A unorm16 depth buffer stores round(0.5 * 65535) = 32768 (ties to even) steps of 1/65535. */
  fb = make_framebuffer(1, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_UNORM16);
  OK(tessera_pipeline_state_init(&pipeline));
  OK(draw_full_quad(renderer, fb, &pipeline));
  static float depth[kSize * kSize];
  OK(tessera_framebuffer_read_depth(fb, depth, kSize * kSize));
  CHECK(fabsf(depth[32 * kSize + 32] - (float)(32768.0 / 65535.0)) < 1e-7f);
  tessera_framebuffer_desc desc;
  OK(tessera_framebuffer_get_desc(fb, &desc));
  CHECK(desc.width == kSize && desc.height == kSize && desc.samples == 1 &&
        desc.color_format == TESSERA_COLOR_RGBA8 && desc.depth_format == TESSERA_DEPTH_UNORM16);
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- A user fragment shader --------------------------------------------------------------- */

/* The colour varyings times *(const float*)user_data; fragments left of x = 16 discarded.
 * Every batch is whole quads (a batch whose count is not a multiple of 4 turns alpha to 0). */
static void scaled_colour(const tessera_fragment_batch* batch, const tessera_fragment_output* out,
                          void* user_data) {
  const float scale = *(const float*)user_data;
  const uint32_t stride = TESSERA_FRAGMENT_BATCH_STRIDE;
  for (uint32_t i = 0; i < batch->count; ++i) {
    for (uint32_t c = 0; c < 4; ++c)
      out->color[c * stride + i] = batch->varyings[c * stride + i] * scale;
    if (batch->count % 4 != 0) out->color[3 * stride + i] = 0;
    out->discard[i] = batch->x[i] < 16.0f;
  }
}

static void check_user_shader(tessera_backend backend) {
  tessera_renderer* renderer = make_renderer(backend, 2);
  tessera_framebuffer* fb = make_framebuffer(1, TESSERA_COLOR_RGBA32F, TESSERA_DEPTH_FLOAT32);
  static float rgba[kSize * kSize * 4];
  static float depth[kSize * kSize];
  const float scale = 0.5f;
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.shader = TESSERA_SHADER_USER;
  EXPECT_ERROR(draw_full_quad(renderer, fb, &pipeline), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_draw_triangles", "fragment_function");
  pipeline.fragment_function = scaled_colour;
  pipeline.fragment_user_data = (void*)&scale;
  OK(draw_full_quad(renderer, fb, &pipeline));
  OK(tessera_framebuffer_read_rgba32f(fb, rgba, kSize * kSize * 4));
  OK(tessera_framebuffer_read_depth(fb, depth, kSize * kSize));
  const float* kept = rgba + (32 * kSize + 32) * 4;
  const float* dropped = rgba + (32 * kSize + 8) * 4;
  CHECK(kept[0] == 0.25f && kept[1] == 0.5f && kept[2] == 0.125f && kept[3] == 0.5f);
  CHECK(dropped[0] == 0.0f && dropped[3] == 0.0f);
  CHECK(depth[32 * kSize + 32] == 0.5f && depth[32 * kSize + 8] == 1.0f);
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- Multiple render targets --------------------------------------------------------------- */

/* Writes the colour varyings to target 0, one minus them to the RGBA32F target 3, the
 * fragment's x to the R32UI target 2 (through extra_uint; extra[1] is then NULL). Target 1
 * (R32F) has a built-in output: the engine fills it. */
static void colour_and_x(const tessera_fragment_batch* batch, const tessera_fragment_output* out,
                         void* user_data) {
  (void)user_data;
  const uint32_t stride = TESSERA_FRAGMENT_BATCH_STRIDE;
  if (out->extra[2] == NULL || out->extra[1] != NULL || out->extra_uint[1] == NULL) return;
  for (uint32_t i = 0; i < batch->count; ++i) {
    for (uint32_t c = 0; c < 4; ++c) {
      out->color[c * stride + i] = batch->varyings[c * stride + i];
      out->extra[2][c * stride + i] = 1.0f - batch->varyings[c * stride + i];
    }
    out->extra_uint[1][i] = (uint32_t)batch->x[i];
  }
}

static void check_targets(tessera_backend backend) {
  tessera_renderer* renderer = make_renderer(backend, 2);
  tessera_framebuffer_desc desc = {
      .width = kSize,
      .height = kSize,
      .samples = 4,
      .color_format = TESSERA_COLOR_RGBA8,
      .extra_targets = 3,
      .extra_formats = {TESSERA_COLOR_R32F, TESSERA_COLOR_R32UI, TESSERA_COLOR_RGBA32F}};
  tessera_framebuffer* fb = NULL;
  OK(tessera_framebuffer_create(&desc, NULL, &fb));
  tessera_framebuffer_desc got;
  OK(tessera_framebuffer_get_desc(fb, &got));
  CHECK(got.extra_targets == 3 && got.extra_formats[0] == TESSERA_COLOR_R32F &&
        got.extra_formats[1] == TESSERA_COLOR_R32UI &&
        got.extra_formats[2] == TESSERA_COLOR_RGBA32F);
  OK(tessera_framebuffer_clear_target_uint(fb, 2, 99));
  OK(tessera_framebuffer_clear_target(fb, 3, 0.5f, 0.5f, 0.5f, 0.5f));

  /* Eye depth 2 into target 1, an object ID past 2^24 exactly into target 2, normals into 3. */
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.extra_outputs[0] = TESSERA_OUTPUT_EYE_DEPTH;
  pipeline.extra_outputs[1] = TESSERA_OUTPUT_OBJECT_ID;
  pipeline.extra_outputs[2] = TESSERA_OUTPUT_NORMAL;
  pipeline.object_id = (1u << 24) + 1;
  OK(draw_full_quad(renderer, fb, &pipeline));
  static float depth[kSize * kSize], normals[kSize * kSize * 4];
  static uint32_t ids[kSize * kSize];
  static uint8_t rgba[kSize * kSize * 4];
  OK(tessera_framebuffer_read_target(fb, 1, depth, kSize * kSize));
  OK(tessera_framebuffer_read_target_uint(fb, 2, ids, kSize * kSize));
  OK(tessera_framebuffer_read_target(fb, 3, normals, kSize * kSize * 4));
  OK(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba));
  const size_t centre = 32 * kSize + 32;
  CHECK(fabsf(depth[centre] - 2.0f) < 1e-6f);
  CHECK(ids[centre] == (1u << 24) + 1);
  CHECK(normals[centre * 4 + 2] == 1.0f && normals[centre * 4] == 0.0f);
  CHECK(is_rgba8(pixel8(rgba, 32, 32), 128, 255, 64, 255));

  /* A user shader feeds targets 2 and 3; the engine computes target 1's eye depth. */
  pipeline.shader = TESSERA_SHADER_USER;
  pipeline.fragment_function = colour_and_x;
  pipeline.extra_outputs[1] = TESSERA_OUTPUT_COLOR;
  pipeline.extra_outputs[2] = TESSERA_OUTPUT_COLOR;
  pipeline.depth_compare = TESSERA_COMPARE_LESS_EQUAL;
  OK(draw_full_quad(renderer, fb, &pipeline));
  OK(tessera_framebuffer_read_target_uint(fb, 2, ids, kSize * kSize));
  OK(tessera_framebuffer_read_target(fb, 3, normals, kSize * kSize * 4));
  CHECK(ids[centre] == 32 && ids[32 * kSize + 5] == 5);
  CHECK(normals[centre * 4] == 0.5f && normals[centre * 4 + 1] == 0.0f &&
        normals[centre * 4 + 2] == 0.75f && normals[centre * 4 + 3] == 0.0f);

  /* Errors name what was wrong and write nothing. */
  EXPECT_ERROR(tessera_framebuffer_read_target_uint(fb, 1, ids, kSize * kSize),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_framebuffer_read_target_uint", "not R32UI");
  EXPECT_ERROR(tessera_framebuffer_read_target(fb, 2, depth, 1), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_read_target", "read_target_uint");
  EXPECT_ERROR(tessera_framebuffer_read_target(fb, 4, depth, kSize * kSize),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_framebuffer_read_target",
               "target 4 does not exist");
  EXPECT_ERROR(tessera_framebuffer_read_target(fb, 1, depth, 10), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_read_target", "needs 4096");
  EXPECT_ERROR(tessera_framebuffer_clear_target_uint(fb, 3, 1), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_clear_target_uint", "not R32UI");
  pipeline.extra_outputs[1] = TESSERA_OUTPUT_NORMAL;
  EXPECT_ERROR(draw_full_quad(renderer, fb, &pipeline), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_draw_triangles", "extra_outputs[1] kNormal");
  pipeline.extra_outputs[1] = (tessera_target_output)77;
  EXPECT_ERROR(draw_full_quad(renderer, fb, &pipeline), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_draw_triangles", "extra_outputs[1]");
  tessera_framebuffer_destroy(fb);
  desc.extra_targets = 4;
  EXPECT_ERROR(tessera_framebuffer_create(&desc, NULL, &fb), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_create", "extra_targets 4");
  CHECK(fb == NULL);
  desc.extra_targets = 1;
  desc.color_format = TESSERA_COLOR_R32UI;
  EXPECT_ERROR(tessera_framebuffer_create(&desc, NULL, &fb), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_create", "target 0");
  tessera_renderer_destroy(renderer);
}

/* ---- Textures -------------------------------------------------------------------------------- */

/* A kSize x kSize texture mapped one texel per pixel onto the whole window draws its texels,
 * with the nearest and the linear filter, on both backends; bad textures are errors. */
static void check_textures(tessera_backend backend) {
  static uint8_t texels[kSize * kSize * 4], rgba[kSize * kSize * 4];
  for (size_t i = 0; i < sizeof texels; ++i)
    texels[i] = (uint8_t)((i * 37 + i / 7) % 256);
  tessera_texture* texture = NULL;
  OK(tessera_texture_create(kSize, kSize, TESSERA_TEXTURE_RGBA8, texels, sizeof texels, true, NULL,
                            &texture));
  texels[0] ^= 0xFF; /* the texture holds a copy */
  tessera_renderer* renderer = make_renderer(backend, 2);
  tessera_framebuffer* fb = make_framebuffer(4, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_FLOAT32);
  const float quad[] = {-1, 1, 0.5f, 1, 1, 1, 0.5f, 1, 1, -1, 0.5f, 1, -1, -1, 0.5f, 1};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const tessera_draw_input input = {quad, 4, uv, 2, indices, 6};
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  CHECK(pipeline.sampler.mag_filter == TESSERA_FILTER_LINEAR &&
        pipeline.sampler.mip_filter == TESSERA_MIP_FILTER_LINEAR &&
        pipeline.sampler.wrap_u == TESSERA_WRAP_REPEAT && pipeline.texture == NULL &&
        pipeline.roles.texcoord == 10 && pipeline.sampler.max_anisotropy == 1.0f);
  pipeline.shader = TESSERA_SHADER_TEXTURED;
  pipeline.roles.texcoord = 0;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_draw_triangles", "needs a texture");
  pipeline.texture = texture;
  for (int filter = 0; filter < 2; ++filter) {
    pipeline.sampler.mag_filter = pipeline.sampler.min_filter = (tessera_filter)filter;
    pipeline.depth_compare = TESSERA_COMPARE_ALWAYS;
    OK(tessera_draw_triangles(renderer, fb, &pipeline, &input));
    OK(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba));
    texels[0] ^= 0xFF;
    CHECK(memcmp(rgba, texels, sizeof rgba) == 0);
    texels[0] ^= 0xFF;
  }
  pipeline.sampler.max_anisotropy = 0.0f;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_draw_triangles", "sampler.max_anisotropy");
  pipeline.sampler.max_anisotropy = 16.0f; /* a one-to-one mapping: one sample, the same texels */
  OK(tessera_draw_triangles(renderer, fb, &pipeline, &input));
  OK(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba));
  texels[0] ^= 0xFF;
  CHECK(memcmp(rgba, texels, sizeof rgba) == 0);
  texels[0] ^= 0xFF;
  pipeline.sampler.wrap_v = (tessera_wrap)9;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_draw_triangles", "sampler.wrap_v");
  tessera_texture* bad = texture;
  EXPECT_ERROR(
      tessera_texture_create(kSize, kSize, TESSERA_TEXTURE_RGBA8, texels, 10, false, NULL, &bad),
      TESSERA_ERROR_INVALID_ARGUMENT, "tessera_texture_create", "got 10");
  CHECK(bad == NULL);
  EXPECT_ERROR(tessera_texture_create(0, 4, TESSERA_TEXTURE_R8, texels, 0, false, NULL, &bad),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_texture_create", "size 0x4");
  EXPECT_ERROR(
      tessera_texture_create(4, 4, (tessera_texture_format)7, texels, 64, false, NULL, &bad),
      TESSERA_ERROR_INVALID_ARGUMENT, "tessera_texture_create", "format");
  tessera_texture_destroy(texture);
  tessera_texture_destroy(NULL);
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- Allocator callbacks ----------------------------------------------------------------- */

typedef struct counting_allocator {
  int allocations, frees, misaligned, fail;
} counting_allocator;

static void* counting_alloc(size_t size, size_t alignment, void* user) {
  counting_allocator* a = user;
  if (a->fail) return NULL;
  ++a->allocations;
  /* aligned_alloc needs a size that is a multiple of the alignment. */
  void* p = aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  if (p != NULL && (uintptr_t)p % alignment != 0) ++a->misaligned;
  return p;
}

static void counting_free(void* p, void* user) {
  counting_allocator* a = user;
  ++a->frees;
  free(p);
}

static void check_allocator(void) {
  counting_allocator counts = {0, 0, 0, 0};
  const tessera_allocator allocator = {counting_alloc, counting_free, &counts};
  const tessera_framebuffer_desc desc = {.width = kSize,
                                         .height = kSize,
                                         .samples = 1,
                                         .color_format = TESSERA_COLOR_RGBA8,
                                         .depth_format = TESSERA_DEPTH_FLOAT32};
  tessera_framebuffer* fb = NULL;
  OK(tessera_framebuffer_create(&desc, &allocator, &fb));
  tessera_renderer_desc rdesc;
  OK(tessera_renderer_desc_init(&rdesc));
  tessera_renderer* renderer = NULL;
  OK(tessera_renderer_create(&rdesc, &allocator, &renderer));
  CHECK(counts.allocations == 2 && counts.frees == 0 && counts.misaligned == 0);
  /* Handles from an allocator draw like any other. */
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  OK(draw_full_quad(renderer, fb, &pipeline));
  uint8_t centre[kSize * kSize * 4];
  OK(tessera_framebuffer_read_rgba8(fb, centre, sizeof centre));
  CHECK(is_rgba8(pixel8(centre, 32, 32), 128, 255, 64, 255));
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
  CHECK(counts.allocations == 2 && counts.frees == 2);

  /* An allocator that fails: out of memory, nothing created, nothing leaked. */
  counts.fail = 1;
  fb = (tessera_framebuffer*)&counts; /* overwritten with NULL */
  EXPECT_ERROR(tessera_framebuffer_create(&desc, &allocator, &fb), TESSERA_ERROR_OUT_OF_MEMORY,
               "tessera_framebuffer_create", "the allocator returned NULL");
  CHECK(fb == NULL);
  EXPECT_ERROR(tessera_renderer_create(&rdesc, &allocator, &renderer), TESSERA_ERROR_OUT_OF_MEMORY,
               "tessera_renderer_create", "the allocator returned NULL");
  CHECK(renderer == NULL);
  /* A creation that fails after the allocation gives the memory back. */
  counts.fail = 0;
  const tessera_framebuffer_desc empty = {.width = 0,
                                          .height = kSize,
                                          .samples = 1,
                                          .color_format = TESSERA_COLOR_RGBA8,
                                          .depth_format = TESSERA_DEPTH_FLOAT32};
  EXPECT_ERROR(tessera_framebuffer_create(&empty, &allocator, &fb), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_create", "width 0");
  CHECK(counts.allocations == counts.frees);
  const tessera_allocator half = {counting_alloc, NULL, &counts};
  EXPECT_ERROR(tessera_framebuffer_create(&desc, &half, &fb), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_framebuffer_create", "alloc and free must both be set");
}

/* ---- Errors ------------------------------------------------------------------------------ */

static void check_errors(void) {
  tessera_renderer* renderer = make_renderer(TESSERA_BACKEND_FAST, 1);
  tessera_framebuffer* fb = make_framebuffer(1, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_FLOAT32);
  OK(tessera_framebuffer_clear_color(fb, 0.2f, 0.4f, 0.6f, 1));
  tessera_pipeline_state pipeline;
  OK(tessera_pipeline_state_init(&pipeline));
  const float tri[] = {-1, -1, 0.5f, 1, 1, -1, 0.5f, 1, 0, 1, 0.5f, 1};
  const float colors[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const tessera_draw_input input = {tri, 3, colors, 4, NULL, 0};
  tessera_point_state point;
  OK(tessera_point_state_init(&point));
  tessera_line_state line;
  OK(tessera_line_state_init(&line));
  const tessera_draw_input two = {tri, 2, colors, 4, NULL, 0};
  static uint8_t rgba[kSize * kSize * 4];
  static float floats[kSize * kSize * 4];
  const tessera_result bad_arg = TESSERA_ERROR_INVALID_ARGUMENT;
  const tessera_result bad_input = TESSERA_ERROR_INVALID_INPUT;

  /* A success clears the last error. */
  CHECK(tessera_last_error() == TESSERA_OK && tessera_last_error_message()[0] == '\0');

  /* NULL handles and pointers. */
  EXPECT_ERROR(tessera_draw_triangles(NULL, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "renderer is NULL");
  CHECK(tessera_last_error_message()[0] != '\0');
  OK(tessera_framebuffer_clear_depth(fb, 1));
  CHECK(tessera_last_error() == TESSERA_OK && tessera_last_error_message()[0] == '\0');
  EXPECT_ERROR(tessera_draw_triangles(renderer, NULL, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "framebuffer is NULL");
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, NULL, &input), bad_arg,
               "tessera_draw_triangles", "pipeline is NULL");
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, NULL), bad_arg,
               "tessera_draw_triangles", "input is NULL");
  EXPECT_ERROR(tessera_draw_points(renderer, fb, &pipeline, NULL, &input), bad_arg,
               "tessera_draw_points", "state is NULL");
  EXPECT_ERROR(tessera_draw_points(NULL, fb, &pipeline, &point, &input), bad_arg,
               "tessera_draw_points", "renderer is NULL");
  EXPECT_ERROR(tessera_draw_lines(renderer, fb, &pipeline, NULL, &two), bad_arg,
               "tessera_draw_lines", "state is NULL");
  EXPECT_ERROR(tessera_draw_lines(renderer, NULL, &pipeline, &line, &two), bad_arg,
               "tessera_draw_lines", "framebuffer is NULL");
  EXPECT_ERROR(tessera_framebuffer_clear_color(NULL, 0, 0, 0, 0), bad_arg,
               "tessera_framebuffer_clear_color", "framebuffer is NULL");
  EXPECT_ERROR(tessera_framebuffer_clear_depth(NULL, 0), bad_arg, "tessera_framebuffer_clear_depth",
               "framebuffer is NULL");
  EXPECT_ERROR(tessera_framebuffer_read_rgba8(NULL, rgba, sizeof rgba), bad_arg,
               "tessera_framebuffer_read_rgba8", "framebuffer is NULL");
  EXPECT_ERROR(tessera_framebuffer_read_rgba8(fb, NULL, sizeof rgba), bad_arg,
               "tessera_framebuffer_read_rgba8", "dst is NULL");
  EXPECT_ERROR(tessera_framebuffer_read_depth(fb, NULL, kSize * kSize), bad_arg,
               "tessera_framebuffer_read_depth", "dst is NULL");
  EXPECT_ERROR(tessera_framebuffer_get_desc(NULL, NULL), bad_arg, "tessera_framebuffer_get_desc",
               "framebuffer is NULL");
  EXPECT_ERROR(tessera_framebuffer_get_desc(fb, NULL), bad_arg, "tessera_framebuffer_get_desc",
               "out is NULL");
  EXPECT_ERROR(tessera_pipeline_state_init(NULL), bad_arg, "tessera_pipeline_state_init",
               "state is NULL");
  EXPECT_ERROR(tessera_point_state_init(NULL), bad_arg, "tessera_point_state_init",
               "state is NULL");
  EXPECT_ERROR(tessera_line_state_init(NULL), bad_arg, "tessera_line_state_init", "state is NULL");
  EXPECT_ERROR(tessera_renderer_desc_init(NULL), bad_arg, "tessera_renderer_desc_init",
               "desc is NULL");
  tessera_framebuffer* created = NULL;
  EXPECT_ERROR(tessera_framebuffer_create(NULL, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "desc is NULL");
  const tessera_framebuffer_desc desc = {.width = 8,
                                         .height = 8,
                                         .samples = 1,
                                         .color_format = TESSERA_COLOR_RGBA8,
                                         .depth_format = TESSERA_DEPTH_FLOAT32};
  EXPECT_ERROR(tessera_framebuffer_create(&desc, NULL, NULL), bad_arg, "tessera_framebuffer_create",
               "out is NULL");
  EXPECT_ERROR(tessera_renderer_create(NULL, NULL, NULL), bad_arg, "tessera_renderer_create",
               "out is NULL");
  tessera_draw_input missing = input;
  missing.positions = NULL;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &missing), bad_arg,
               "tessera_draw_triangles", "positions is NULL, but vertex_count is 3");
  missing = input;
  missing.attributes = NULL;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &missing), bad_arg,
               "tessera_draw_triangles", "attributes is NULL");
  missing = input;
  missing.index_count = 3;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &missing), bad_arg,
               "tessera_draw_triangles", "indices is NULL, but index_count is 3");
  missing = input;
  missing.vertex_count = SIZE_MAX;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &missing), bad_arg,
               "tessera_draw_triangles", "is larger than any array");
  /* Destroying NULL does nothing. */
  tessera_framebuffer_destroy(NULL);
  tessera_renderer_destroy(NULL);

  /* Bad sizes. */
  tessera_framebuffer_desc bad = desc;
  bad.width = 0;
  EXPECT_ERROR(tessera_framebuffer_create(&bad, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "framebuffer width 0 is out of range");
  CHECK(created == NULL);
  bad = desc;
  bad.height = TESSERA_MAX_FRAMEBUFFER_SIZE + 1;
  EXPECT_ERROR(tessera_framebuffer_create(&bad, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "framebuffer height 16385 is out of range");
  bad = desc;
  bad.samples = 3;
  EXPECT_ERROR(tessera_framebuffer_create(&bad, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "sample count 3");
  EXPECT_ERROR(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba - 1), bad_arg,
               "tessera_framebuffer_read_rgba8",
               "dst holds 16383 bytes, but the 64x64 RGBA8 image needs 16384");
  EXPECT_ERROR(tessera_framebuffer_read_rgba32f(fb, floats, 100), bad_arg,
               "tessera_framebuffer_read_rgba32f", "needs 16384");
  EXPECT_ERROR(tessera_framebuffer_read_depth(fb, floats, kSize * kSize - 1), bad_arg,
               "tessera_framebuffer_read_depth", "needs 4096");
  EXPECT_ERROR(tessera_framebuffer_read_sample_depth(fb, floats, 0), bad_arg,
               "tessera_framebuffer_read_sample_depth", "needs 4096");
  const tessera_draw_input four = {tri, 2, colors, 4, NULL, 0};
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &four), bad_input,
               "tessera_draw_triangles", "multiple of 3 positions, got 2");
  const uint32_t far_index[] = {0, 1, 5};
  const tessera_draw_input indexed = {tri, 3, colors, 4, far_index, 3};
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &indexed), bad_input,
               "tessera_draw_triangles", "index 5 at position 2 is out of range");
  tessera_draw_input wide = input;
  wide.attribute_count = 33;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &wide), bad_arg,
               "tessera_draw_triangles", "attribute_count 33");
  const tessera_draw_input three = {tri, 3, colors, 4, NULL, 0};
  EXPECT_ERROR(tessera_draw_lines(renderer, fb, &pipeline, &line, &three), bad_input,
               "tessera_draw_lines", "even number of vertices, got 3");
  point.size = 0;
  EXPECT_ERROR(tessera_draw_points(renderer, fb, &pipeline, &point, &input), bad_arg,
               "tessera_draw_points", "point size 0");
  OK(tessera_point_state_init(&point));
  tessera_renderer_desc rdesc;
  OK(tessera_renderer_desc_init(&rdesc));
  rdesc.threads = 5000;
  tessera_renderer* made = NULL;
  EXPECT_ERROR(tessera_renderer_create(&rdesc, NULL, &made), bad_arg, "tessera_renderer_create",
               "thread count 5000");
  CHECK(made == NULL);
  pipeline.samples = 4;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "sample count 4 does not match");
  OK(tessera_pipeline_state_init(&pipeline));

  /* Bad enumeration values: values the C++ type holds are named by the C++ checks, wider ones
   * by the C layer, in the same words. */
  pipeline.cull = (tessera_cull_mode)7;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "pipeline cull has the invalid value 7");
  pipeline.cull = (tessera_cull_mode)0x7FFFFFFE;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "pipeline cull has the invalid value 2147483646");
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.shader = (tessera_fragment_shader)4;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "pipeline shader has the invalid value 4");
  pipeline.shader = (tessera_fragment_shader)259; /* would wrap to 3 in the C++ uint8_t */
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "pipeline shader has the invalid value 259");
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.varying_modes[5] = (tessera_varying_mode)9;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "varying_modes[5] has the invalid value 9");
  pipeline.varying_modes[5] = (tessera_varying_mode)257; /* would wrap to 1 */
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "varying_modes[5] has the invalid value 257");
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.output = (tessera_target_output)7;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "pipeline output has the invalid value 7");
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.depth_compare = (tessera_compare_op)8;
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "depth_compare has the invalid value 8");
  OK(tessera_pipeline_state_init(&pipeline));
  pipeline.phong.light_count = 4;
  pipeline.phong.lights[3].kind = (tessera_light_kind)0x100; /* would wrap to 0 */
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &input), bad_arg,
               "tessera_draw_triangles", "phong.lights[3].kind has the invalid value 256");
  OK(tessera_pipeline_state_init(&pipeline));
  point.shape = (tessera_point_shape)4;
  EXPECT_ERROR(tessera_draw_points(renderer, fb, &pipeline, &point, &input), bad_arg,
               "tessera_draw_points", "point shape has the invalid value 4");
  OK(tessera_point_state_init(&point));
  line.topology = (tessera_line_topology)9;
  EXPECT_ERROR(tessera_draw_lines(renderer, fb, &pipeline, &line, &two), bad_arg,
               "tessera_draw_lines", "line topology has the invalid value 9");
  OK(tessera_line_state_init(&line));
  line.join = (tessera_line_join)0x40000000;
  EXPECT_ERROR(tessera_draw_lines(renderer, fb, &pipeline, &line, &two), bad_arg,
               "tessera_draw_lines", "line join has the invalid value 1073741824");
  OK(tessera_line_state_init(&line));
  rdesc.threads = 1;
  rdesc.backend = (tessera_backend)9;
  EXPECT_ERROR(tessera_renderer_create(&rdesc, NULL, &made), bad_arg, "tessera_renderer_create",
               "backend");
  bad = desc;
  bad.color_format = (tessera_color_format)5;
  EXPECT_ERROR(tessera_framebuffer_create(&bad, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "colour format");
  bad = desc;
  bad.depth_format = (tessera_depth_format)3;
  EXPECT_ERROR(tessera_framebuffer_create(&bad, NULL, &created), bad_arg,
               "tessera_framebuffer_create", "depth format");
  CHECK(strcmp(tessera_result_name(TESSERA_ERROR_INVALID_INPUT), "TESSERA_ERROR_INVALID_INPUT") ==
        0);
  CHECK(strcmp(tessera_result_name((tessera_result)99), "unknown") == 0);

  /* Non-finite vertex data: rejected before anything is drawn, naming the vertex. */
  float nan_tri[12];
  memcpy(nan_tri, tri, sizeof nan_tri);
  nan_tri[4] = nanf("");
  const tessera_draw_input nan_input = {nan_tri, 3, colors, 4, NULL, 0};
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &nan_input), bad_input,
               "tessera_draw_triangles", "position of vertex 1 is not finite");
  EXPECT_ERROR(tessera_draw_points(renderer, fb, &pipeline, &point, &nan_input), bad_input,
               "tessera_draw_points", "position of vertex 1 is not finite");
  const tessera_draw_input nan_pair = {nan_tri, 2, colors, 4, NULL, 0};
  EXPECT_ERROR(tessera_draw_lines(renderer, fb, &pipeline, &line, &nan_pair), bad_input,
               "tessera_draw_lines", "position of vertex 1 is not finite");
  float inf_colors[12];
  memcpy(inf_colors, colors, sizeof inf_colors);
  inf_colors[9] = INFINITY;
  const tessera_draw_input inf_input = {tri, 3, inf_colors, 4, NULL, 0};
  EXPECT_ERROR(tessera_draw_triangles(renderer, fb, &pipeline, &inf_input), bad_input,
               "tessera_draw_triangles", "attribute 1 of vertex 2 is not finite");

  /* None of the failed draws touched the framebuffer: still the clear colour. */
  OK(tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba));
  int untouched = 1;
  for (int i = 0; i < kSize * kSize; ++i)
    untouched = untouched && is_rgba8(rgba + 4 * i, 51, 102, 153, 255);
  CHECK(untouched);
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
}

/* ---- Occlusion queries ------------------------------------------------------------------- */

/* A wall over the left half of a 64 x 48 buffer at depth 0.5: a rectangle and a box behind it
 * are hidden, beside it seen, in both modes; the depth reads back; bad calls are errors. */
static void check_occlusion(void) {
  tessera_occlusion_desc desc = {64, 48, 1, TESSERA_DEPTH_FLOAT32, false, 1};
  tessera_occlusion* occlusion = NULL;
  OK(tessera_occlusion_create(&desc, NULL, &occlusion));
  const float wall[] = {-1, 1, 0.5f, 1, 0, 1, 0.5f, 1, 0, -1, 0.5f, 1, -1, -1, 0.5f, 1};
  const uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const tessera_draw_input input = {wall, 4, NULL, 0, indices, 6};
  OK(tessera_occlusion_draw(occlusion, &input));
  static float depth[64 * 48];
  OK(tessera_occlusion_read_depth(occlusion, depth, 64 * 48));
  CHECK(depth[10 * 64 + 5] == 0.5f && depth[10 * 64 + 40] == 1.0f);
  /* The identity matrix: the box's corners are clip space with w = 1. */
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (int mode = 0; mode < 2; ++mode) {
    bool visible = true;
    OK(tessera_occlusion_rect_visible(occlusion, 2, 2, 30, 40, 0.7f, (tessera_occlusion_mode)mode,
                                      &visible));
    CHECK(!visible);
    OK(tessera_occlusion_rect_visible(occlusion, 34, 2, 60, 40, 0.7f, (tessera_occlusion_mode)mode,
                                      &visible));
    CHECK(visible);
    const float lo[3] = {-0.9f, -0.5f, 0.6f}, hi[3] = {-0.2f, 0.5f, 0.8f};
    OK(tessera_occlusion_box_visible(occlusion, lo, hi, identity, (tessera_occlusion_mode)mode,
                                     &visible));
    CHECK(!visible);
    const float lo2[3] = {0.2f, -0.5f, 0.6f}, hi2[3] = {0.9f, 0.5f, 0.8f};
    OK(tessera_occlusion_box_visible(occlusion, lo2, hi2, identity, (tessera_occlusion_mode)mode,
                                     &visible));
    CHECK(visible);
    const float behind[] = {-0.9f, 0.5f, 0.9f, 1, -0.2f, 0.5f, 0.9f, 1, -0.5f, -0.5f, 0.9f, 1};
    const tessera_draw_input query = {behind, 3, NULL, 0, NULL, 0};
    OK(tessera_occlusion_triangles_visible(occlusion, &query, (tessera_occlusion_mode)mode,
                                           &visible));
    CHECK(!visible);
  }
  bool visible = false;
  EXPECT_ERROR(tessera_occlusion_rect_visible(occlusion, 0, 0, 4, 4, 0.5f,
                                              (tessera_occlusion_mode)7, &visible),
               TESSERA_ERROR_INVALID_ARGUMENT, "tessera_occlusion_rect_visible", "mode");
  EXPECT_ERROR(
      tessera_occlusion_rect_visible(occlusion, 0, 0, 4, 4, 0.5f, TESSERA_OCCLUSION_EXACT, NULL),
      TESSERA_ERROR_INVALID_ARGUMENT, "tessera_occlusion_rect_visible", "visible");
  OK(tessera_occlusion_clear(occlusion));
  OK(tessera_occlusion_rect_visible(occlusion, 2, 2, 30, 40, 0.7f, TESSERA_OCCLUSION_EXACT,
                                    &visible));
  CHECK(visible);
  tessera_occlusion_destroy(occlusion);
  tessera_occlusion* bad = occlusion;
  desc.width = 0;
  EXPECT_ERROR(tessera_occlusion_create(&desc, NULL, &bad), TESSERA_ERROR_INVALID_ARGUMENT,
               "tessera_occlusion_create", "width");
  CHECK(bad == NULL);
  tessera_occlusion_destroy(NULL);
}

int main(void) {
  check_scene("fast", TESSERA_BACKEND_FAST);
  check_scene("reference", TESSERA_BACKEND_REFERENCE);
  check_msaa(TESSERA_BACKEND_FAST);
  check_msaa(TESSERA_BACKEND_REFERENCE);
  check_shading();
  check_user_shader(TESSERA_BACKEND_FAST);
  check_user_shader(TESSERA_BACKEND_REFERENCE);
  check_targets(TESSERA_BACKEND_FAST);
  check_targets(TESSERA_BACKEND_REFERENCE);
  check_textures(TESSERA_BACKEND_FAST);
  check_textures(TESSERA_BACKEND_REFERENCE);
  check_occlusion();
  check_allocator();
  check_errors();
  printf("c_api_test: %d checks, %d failed\n", checks, failures);
  return failures == 0 ? 0 : 1;
}
