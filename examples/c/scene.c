/* The coplanar-decal scene and its pixel check; see scene.h. */
#include "scene.h"

#include <stdio.h>
#include <string.h>

#include "zshift.h"

/* f/n from 1e3 to 1e6, planes near and far in the range, 16- and 24-bit depth buffers. */
const struct scene_case scene_cases[] = {
    {0.1, 1000.0, 0.5, 24}, {1.0, 1e5, 0.2, 24},  {0.01, 1e4, 0.9, 24},
    {1.0, 1e6, 0.9, 24},    {0.5, 500.0, 0.5, 16}, {1.0, 1e4, 0.2, 16},
};
const int scene_case_count = (int)(sizeof scene_cases / sizeof scene_cases[0]);

double scene_distance(const struct scene_case *c) { return c->n + c->at * (c->f - c->n); }

void scene_quad(double half, double d, float out[6][3]) {
  /* Under glFrustum(-n, n, -n, n, n, f), eye x at depth d maps to NDC x / d. */
  static const int corner[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
  int i;
  for (i = 0; i < 6; i++) {
    out[i][0] = (float)(corner[i][0] * half * d);
    out[i][1] = (float)(corner[i][1] * half * d);
    out[i][2] = (float)(-d);
  }
}

/* [quickstart-c-recommend] */
/* What the engine knows about the decal goes in; the shift toward the camera that zshift's
 * error model of the rasterizer guarantees comes out. */
int scene_recommended_delta(const struct scene_case *c, int subpixel_bits, double *delta) {
  double d = scene_distance(c);
  ZshiftScene scene;
  ZshiftRecommendation rec;
  ZshiftStatus s;
  memset(&scene, 0, sizeof scene);
  scene.l = -c->n; /* the glFrustum(l, r, b, t, n, f) the base is drawn with */
  scene.r = c->n;
  scene.b = -c->n;
  scene.t = c->n;
  scene.n = c->n;
  scene.f = c->f;
  scene.viewport_width = SCENE_SIZE;
  scene.viewport_height = SCENE_SIZE;
  scene.depth_format = c->depth_bits == 16 ? 0x81A5 : 0x81A6; /* GL_DEPTH_COMPONENT16 or 24 */
  scene.decal_near = d; /* the decal's nearest and farthest eye distance */
  scene.decal_far = d;
  scene.slope = 0.0;     /* |dz/dx| + |dz/dy| of its plane in eye space: facing the camera */
  scene.exact_depth = 1; /* base and decal corners share one float z */
  scene.subpixel_bits = subpixel_bits;
  s = zshift_recommend(&scene, &rec);
  if (s != ZSHIFT_OK) {
    fprintf(stderr, "zshift_recommend: %s\n", zshift_status_message(s));
    return 1;
  }
  *delta = rec.delta_at_far; /* applies at pz = -decal_far */
  return 0;
}
/* [/quickstart-c-recommend] */

/* Whether pixel index i (center i + 0.5) lies inside NDC [-half, half]. */
static int inside(int i, double half) {
  double ndc = (i + 0.5) / SCENE_SIZE * 2.0 - 1.0;
  return ndc > -half && ndc < half;
}

static int is_color(const unsigned char *p, int r, int g, int b) {
  return p[0] == r && p[1] == g && p[2] == b;
}

struct scene_tally scene_check(const unsigned char *rgba) {
  struct scene_tally tally = {0, 0, 0};
  int x, y;
  for (y = 0; y < SCENE_SIZE; y++) {
    for (x = 0; x < SCENE_SIZE; x++) {
      const unsigned char *p = rgba + 4 * (y * SCENE_SIZE + x);
      if (inside(x, SCENE_DECAL_HALF) && inside(y, SCENE_DECAL_HALF)) {
        tally.decal_total++;
        if (is_color(p, 0, 0, 255)) tally.decal_lost++;
        else if (!is_color(p, 255, 0, 0)) tally.wrong++;
      } else if (inside(x, SCENE_BASE_HALF) && inside(y, SCENE_BASE_HALF)) {
        if (!is_color(p, 0, 0, 255)) tally.wrong++;
      } else if (!is_color(p, 0, 0, 0)) {
        tally.wrong++;
      }
    }
  }
  return tally;
}

int scene_verdict(int wrong, const struct scene_tally *none, const struct scene_tally *chosen,
                  double steps) {
  if (wrong != 0) {
    fprintf(stderr, "FAIL: %d pixels show neither the base, the decal nor the background\n", wrong);
    return 1;
  }
  if (none->decal_lost == 0) {
    fprintf(stderr, "FAIL: without an offset no decal pixel was lost: the scene does not z-fight\n");
    return 1;
  }
  if (chosen->decal_lost != 0) {
    fprintf(stderr, "FAIL: with zshift's offset of %g steps, %d decal pixels were lost\n", steps,
            chosen->decal_lost);
    return 1;
  }
  return 0;
}
