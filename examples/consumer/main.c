/* A program that uses an installed zshift (scripts/install PREFIX): the README's install section
 * builds it with cc, pkg-config and CMake (tests/packaging/run.sh runs those lines). It asks for
 * the decal matrix of a camera-facing decal 50 units away and prints what changed. */
#include <stdio.h>
#include <string.h>
#include <zshift.h>

int main(void) {
  float proj[16], decal[16];
  ZshiftDecal d;
  /* The projection the base is drawn with: glFrustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000). */
  if (zshift_frustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0, proj) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error());
    return 1;
  }
  memset(&d, 0, sizeof d);
  d.viewport_width = 800; /* glViewport */
  d.viewport_height = 600;
  d.format = ZSHIFT_FORMAT_UNORM24; /* GL_DEPTH_COMPONENT24 */
  d.subpixel_bits = 8;              /* glGetIntegerv(GL_SUBPIXEL_BITS) */
  d.decal_near = 50.0;              /* the decal's nearest and farthest eye distance */
  d.decal_far = 50.0;
  d.slope = 0.0; /* facing the camera */
  if (zshift_decal_matrix(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, decal) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error()); /* names the field, its value, the bound */
    return 1;
  }
  printf("zshift %s, C ABI %d: element 10 %.9g -> %.9g\n", zshift_version(), ZSHIFT_ABI_VERSION,
         (double)proj[10], (double)decal[10]);
  return decal[10] > proj[10] ? 0 : 1;
}
