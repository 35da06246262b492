/* The package test's C application (scripts/check-package.sh): one red triangle through the C
 * API, tessera/tessera.h, compiled as C11; checks the pixel at its centre and that a bad call
 * returns an error with a message. Exits non-zero on failure. */
#include <stdio.h>
#include <string.h>

#include <tessera/tessera.h>

int main(void) {
  enum { kSize = 32 };
  const tessera_framebuffer_desc desc = {.width = kSize,
                                         .height = kSize,
                                         .samples = 1,
                                         .color_format = TESSERA_COLOR_RGBA8,
                                         .depth_format = TESSERA_DEPTH_FLOAT32};
  tessera_renderer_desc renderer_desc;
  tessera_pipeline_state pipeline;
  tessera_framebuffer* fb = NULL;
  tessera_renderer* renderer = NULL;
  const float positions[] = {-0.5f, -0.5f, 0.5f, 1, 0.5f, -0.5f, 0.5f, 1, 0, 0.5f, 0.5f, 1};
  const float colors[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  const tessera_draw_input input = {positions, 3, colors, 4, NULL, 0};
  static uint8_t rgba[kSize * kSize * 4];
  int ok = tessera_renderer_desc_init(&renderer_desc) == TESSERA_OK &&
           tessera_renderer_create(&renderer_desc, NULL, &renderer) == TESSERA_OK &&
           tessera_framebuffer_create(&desc, NULL, &fb) == TESSERA_OK &&
           tessera_pipeline_state_init(&pipeline) == TESSERA_OK &&
           tessera_draw_triangles(renderer, fb, &pipeline, &input) == TESSERA_OK &&
           tessera_framebuffer_read_rgba8(fb, rgba, sizeof rgba) == TESSERA_OK;
  if (!ok) fprintf(stderr, "consumer_c: %s\n", tessera_last_error_message());
  const uint8_t* centre = rgba + (kSize / 2 * kSize + kSize / 2) * 4;
  ok = ok && centre[0] == 255 && centre[1] == 0 && centre[3] == 255;
  ok = ok &&
       tessera_draw_triangles(NULL, fb, &pipeline, &input) == TESSERA_ERROR_INVALID_ARGUMENT &&
       strstr(tessera_last_error_message(), "renderer is NULL") != NULL;
  tessera_framebuffer_destroy(fb);
  tessera_renderer_destroy(renderer);
  if (!ok) {
    fprintf(stderr, "consumer_c: the C API did not draw the triangle as expected\n");
    return 1;
  }
  printf("consumer_c: the C API drew the triangle\n");
  return 0;
}
