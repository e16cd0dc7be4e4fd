/* zshift in a fixed-function (OpenGL 1.x) engine: the projection comes from zshift and is loaded
 * with glMatrixMode(GL_PROJECTION) + glLoadMatrixf, replacing glFrustum and the seed's
 * LoadOffsetMatrix. Renders the coplanar-decal scene (scene.h) headless for several projections
 * and checks the pixels: with zshift's offset no decal pixel is lost; without one, the decal is
 * lost to the base. Exits nonzero with a message on any failure. */
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>

#include "headless.h"
#include "scene.h"
#include "zshift.h"

/* [quickstart-c-legacy] */
/* Replaces glFrustum(l, r, b, t, n, f) when delta == 0, and Lengyel's
 * LoadOffsetMatrix(l, r, b, t, n, f, delta, pz) otherwise: loads the projection that moves
 * geometry at eye-space depth pz (negative) toward the camera by delta eye-space units. */
static int load_projection(double l, double r, double b, double t, double n, double f,
                           double delta, double pz) {
  float m[16]; /* column-major, as glLoadMatrixf takes it */
  ZshiftStatus s = delta == 0.0 ? zshift_frustum(l, r, b, t, n, f, m)
                                : zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz, m);
  if (s != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_status_message(s));
    return 1;
  }
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(m);
  return 0;
}
/* [/quickstart-c-legacy] */

/* The seed's LoadOffsetMatrix (000, 4.1), verbatim but for names: glFrustum, read back, scale
 * element 10 by 1 + epsilon in float. Kept to show what zshift replaces; only printed. */
static void seed_load_offset_matrix(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n,
                                    GLdouble f, GLfloat delta, GLfloat pz) {
  GLfloat matrix[16];
  GLfloat epsilon;
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(l, r, b, t, n, f);
  glGetFloatv(GL_PROJECTION_MATRIX, matrix);
  epsilon = (GLfloat)(-2.0F * f * n * delta / ((f + n) * pz * (pz + delta)));
  matrix[10] *= 1.0F + epsilon;
  glLoadMatrixf(matrix);
}

static void draw(float quad[6][3], GLubyte red, GLubyte blue) {
  int i;
  glColor3ub(red, 0, blue);
  glBegin(GL_TRIANGLES);
  for (i = 0; i < 6; i++) glVertex3fv(quad[i]);
  glEnd();
}

/* How the decal's projection is made. */
enum decal_projection { PLAIN, ZSHIFT, SEED };

/* Renders one case with the decal shifted by `delta` and tallies its pixels. */
static int render(const struct scene_case *c, enum decal_projection how, double delta,
                  struct scene_tally *tally) {
  static unsigned char pixels[SCENE_SIZE * SCENE_SIZE * 4];
  double n = c->n, f = c->f, d = scene_distance(c);
  float base[6][3], decal[6][3];
  scene_quad(SCENE_BASE_HALF, d, base);
  scene_quad(SCENE_DECAL_HALF, d, decal);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity(); /* the quads are given in eye space */
  if (load_projection(-n, n, -n, n, n, f, 0.0, -d) != 0) return 1;
  draw(base, 0, 255);
  if (how == SEED)
    seed_load_offset_matrix(-n, n, -n, n, n, f, (GLfloat)delta, (GLfloat)-d);
  else if (load_projection(-n, n, -n, n, n, f, how == ZSHIFT ? delta : 0.0, -d) != 0)
    return 1;
  draw(decal, 255, 0);
  if (headless_read_rgba(pixels) != 0) return 1;
  *tally = scene_check(pixels);
  return 0;
}

/* zshift_frustum must be the matrix glFrustum builds, in the layout glLoadMatrixf takes. Mesa
 * computes glFrustum in float, so allow a few ulp; a transposed or mis-signed matrix is off by
 * far more. */
static int check_matches_gl_frustum(const struct scene_case *c) {
  float ours[16], gl[16];
  int i;
  ZshiftStatus status = zshift_frustum(-c->n, c->n, -c->n, c->n, c->n, c->f, ours);
  if (status != ZSHIFT_OK) {
    fprintf(stderr, "zshift_frustum: %s\n", zshift_status_message(status));
    return 1;
  }
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-c->n, c->n, -c->n, c->n, c->n, c->f);
  glGetFloatv(GL_PROJECTION_MATRIX, gl);
  for (i = 0; i < 16; i++) {
    if (fabsf(ours[i] - gl[i]) > 8.0f * 1.2e-7f * fabsf(gl[i])) {
      fprintf(stderr, "FAIL: n=%g f=%g element %d: zshift_frustum %.9g, glFrustum %.9g\n", c->n,
              c->f, i, (double)ours[i], (double)gl[i]);
      return 1;
    }
  }
  return 0;
}

/* The minimum delta toward the camera as seed 000 prints it (eq. 4.1.9 with 4.1.11's
 * k = (f - n)/(2fn(2^m - 1)), before the errata of seed 002 doubled k): half a depth step. */
static double seed_min_delta(const struct scene_case *c, double pz) {
  double k = (c->f - c->n) / (2.0 * c->f * c->n * (ldexp(1.0, c->depth_bits) - 1.0));
  return k * pz * pz / (1.0 - k * pz);
}

/* What the rasterizer says about its sub-pixel precision, for zshift_recommend. */
static int subpixel_bits(void) {
  GLint bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
  return bits;
}

static int run_case(const struct scene_case *c) {
  struct scene_tally none, seed, one, chosen;
  double d = scene_distance(c), step, recommended;
  ZshiftStatus status = zshift_min_delta_toward(c->n, c->f, (uint32_t)c->depth_bits, -d, &step);
  if (status != ZSHIFT_OK) {
    fprintf(stderr, "zshift_min_delta_toward: %s\n", zshift_status_message(status));
    return 1;
  }
  if (scene_recommended_delta(c, subpixel_bits(), &recommended) != 0) return 1;
  if (check_matches_gl_frustum(c) != 0 || render(c, PLAIN, 0.0, &none) != 0 ||
      render(c, SEED, seed_min_delta(c, -d), &seed) != 0 || render(c, ZSHIFT, step, &one) != 0 ||
      render(c, ZSHIFT, recommended, &chosen) != 0)
    return 1;
  printf("D%-3d n=%-5g f=%-7g d=%-9g step=%-10.4g lost of %d: none %4d  seed (its own min) %4d  "
         "zshift 1 step %4d  zshift recommended (%.3g steps) %4d\n",
         c->depth_bits, c->n, c->f, d, step, chosen.decal_total, none.decal_lost, seed.decal_lost,
         one.decal_lost, recommended / step, chosen.decal_lost);
  return scene_verdict(none.wrong + seed.wrong + one.wrong + chosen.wrong, &none, &chosen,
                       recommended / step);
}

int main(void) {
  int failures = 0, i, depth_bits = -1;
  for (i = 0; i < scene_case_count; i++) {
    if (scene_cases[i].depth_bits != depth_bits) {
      if (depth_bits != -1) headless_close();
      depth_bits = scene_cases[i].depth_bits;
      if (headless_open(HEADLESS_COMPATIBILITY, SCENE_SIZE, SCENE_SIZE, depth_bits) != 0) {
        fprintf(stderr, "FAIL: no headless OpenGL compatibility context\n");
        return 1;
      }
    }
    failures += run_case(&scene_cases[i]);
  }
  headless_close();
  if (failures != 0) {
    fprintf(stderr, "legacy_gl: %d of %d cases failed\n", failures, scene_case_count);
    return 1;
  }
  printf("legacy_gl: all %d cases passed (zshift %s, ABI %d)\n", scene_case_count, zshift_version(),
         ZSHIFT_ABI_VERSION);
  return 0;
}
