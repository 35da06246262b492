/* Embedding Tessera in a C program through tessera/tessera.h: a renderer, a 4x MSAA
 * framebuffer, a triangle with a colour per vertex, its outline as a line loop and its corners
 * as round points, read back as RGBA8 and depth, written as a binary PPM image (no library
 * needed to view it). Prints and checks a few values: a pixel's colour is the vertex colours
 * weighted by its barycentric coordinates, a corner keeps the clear colour, the depth is the
 * triangle's.
 * Usage: tessera-embed-c [OUTPUT.ppm]   (default embed_c.ppm). Exits 1 on any failure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <tessera/tessera.h>

enum { kWidth = 160, kHeight = 120 };

/* Every call returns a tessera_result; on failure the thread's last message says what is
 * wrong, e.g. "tessera_draw_triangles: position of vertex 1 is not finite: (nan, 0, 0.5, 1)". */
#define TRY(call)                                                     \
  do {                                                                \
    if ((call) != TESSERA_OK) {                                       \
      fprintf(stderr, "embed_c: %s\n", tessera_last_error_message()); \
      goto done;                                                      \
    }                                                                 \
  } while (0)

static int write_ppm(const char* path, const uint8_t* rgba) {
  FILE* f = fopen(path, "wb");
  if (f == NULL) return 0;
  fprintf(f, "P6\n%d %d\n255\n", kWidth, kHeight);
  for (int i = 0; i < kWidth * kHeight; ++i)
    fwrite(rgba + 4 * i, 1, 3, f); /* RGB, alpha dropped */
  return fclose(f) == 0;
}

int main(int argc, char** argv) {
  const char* output = argc > 1 ? argv[1] : "embed_c.ppm";
  int status = 1;
  tessera_renderer* renderer = NULL;
  tessera_framebuffer* framebuffer = NULL;
  uint8_t* rgba = malloc((size_t)kWidth * kHeight * 4);
  float* depth = malloc((size_t)kWidth * kHeight * sizeof(float));
  if (rgba == NULL || depth == NULL) goto done;

  tessera_renderer_desc renderer_desc;
  TRY(tessera_renderer_desc_init(&renderer_desc)); /* 1 thread, the fast engine */
  renderer_desc.threads = 2;
  TRY(tessera_renderer_create(&renderer_desc, NULL, &renderer));
  const tessera_framebuffer_desc fb_desc = {.width = kWidth,
                                            .height = kHeight,
                                            .samples = 4,
                                            .color_format = TESSERA_COLOR_RGBA8,
                                            .depth_format = TESSERA_DEPTH_FLOAT32};
  TRY(tessera_framebuffer_create(&fb_desc, NULL, &framebuffer));
  TRY(tessera_framebuffer_clear_color(framebuffer, 0.1f, 0.1f, 0.15f, 1));
  TRY(tessera_framebuffer_clear_depth(framebuffer, 1));

  /* Clip-space positions (x, y, z, w): counter-clockwise, in front at depth 0.5. */
  const float positions[] = {-0.6f, -0.6f, 0.5f, 1, 0.6f, -0.6f, 0.5f, 1, 0, 0.6f, 0.5f, 1};
  const float colors[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1}; /* RGBA per vertex: varyings 0..3 */
  const tessera_draw_input triangle = {positions, 3, colors, 4, NULL, 0};
  tessera_pipeline_state pipeline;
  TRY(tessera_pipeline_state_init(&pipeline));
  TRY(tessera_draw_triangles(renderer, framebuffer, &pipeline, &triangle));

  /* The outline and corners drawn over the triangle: nearer (z 0.4) and white. */
  const float outline_positions[] = {-0.6f, -0.6f, 0.4f, 1, 0.6f, -0.6f, 0.4f, 1, 0, 0.6f, 0.4f, 1};
  const float white[] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  const tessera_draw_input outline = {outline_positions, 3, white, 4, NULL, 0};
  tessera_line_state lines;
  TRY(tessera_line_state_init(&lines));
  lines.topology = TESSERA_LINE_LOOP;
  lines.width = 2;
  lines.join = TESSERA_LINE_JOIN_ROUND;
  TRY(tessera_draw_lines(renderer, framebuffer, &pipeline, &lines, &outline));
  tessera_point_state points;
  TRY(tessera_point_state_init(&points));
  points.size = 9;
  points.shape = TESSERA_POINT_ROUND;
  TRY(tessera_draw_points(renderer, framebuffer, &pipeline, &points, &outline));

  TRY(tessera_framebuffer_read_rgba8(framebuffer, rgba, (size_t)kWidth * kHeight * 4));
  TRY(tessera_framebuffer_read_depth(framebuffer, depth, (size_t)kWidth * kHeight));
  if (!write_ppm(output, rgba)) {
    fprintf(stderr, "embed_c: cannot write %s\n", output);
    goto done;
  }

  /* Pixel (80, 72), beside the centroid: the vertices are at window (32, 96), (128, 96) and
   * (80, 24), so at the pixel's centre (80.5, 72.5) the blue vertex weighs (96 - 72.5) / 72,
   * the green one (80.5 - 32 - 48 * blue) / 96 and the red one the rest; each channel is its
   * weight times 255, rounded (one step of slack for the fast engine). The corner pixel (0, 0)
   * keeps the clear colour, round(0.1 * 255) = 26 and round(0.15 * 255) = 38, and depth 1. */
  const float blue = (96 - 72.5f) / 72, green = (80.5f - 32 - 48 * blue) / 96;
  const float weights[3] = {1 - blue - green, green, blue};
  const uint8_t* centre = rgba + (72 * kWidth + 80) * 4;
  const uint8_t* corner = rgba;
  const float centre_depth = depth[72 * kWidth + 80];
  printf(
      "embed_c: wrote %s (%dx%d, 4x MSAA); pixel (80, 72) (%d, %d, %d, %d) depth %.3f; "
      "corner (%d, %d, %d, %d) depth %.3f\n",
      output, kWidth, kHeight, centre[0], centre[1], centre[2], centre[3], (double)centre_depth,
      corner[0], corner[1], corner[2], corner[3], (double)depth[0]);
  int centre_ok = centre[3] == 255 && fabsf(centre_depth - 0.5f) < 1e-6f;
  for (int c = 0; c < 3; ++c)
    centre_ok = centre_ok && abs(centre[c] - (int)lroundf(weights[c] * 255)) <= 1;
  const int corner_ok =
      corner[0] == 26 && corner[1] == 26 && corner[2] == 38 && corner[3] == 255 && depth[0] == 1.0f;
  if (!centre_ok || !corner_ok) {
    fprintf(stderr, "embed_c: unexpected %s\n", centre_ok ? "corner" : "pixel (80, 72)");
    goto done;
  }
  status = 0;

done:
  tessera_framebuffer_destroy(framebuffer); /* NULL is ignored */
  tessera_renderer_destroy(renderer);
  free(depth);
  free(rgba);
  return status;
}
