/* A program that uses an installed zshift (scripts/install PREFIX): the README's install section
 * builds it with cc, pkg-config and CMake (tests/packaging/run.sh runs those lines). It asks for
 * the decal matrix of a camera-facing decal 50 units away and prints what changed. */
#include <stdio.h>
#include <string.h>
#include <zshift.h>

static int ground_decal(const float proj[16], float decal_out[16]); /* below */
static int terrain_decal(const float proj[16], float decal_out[16]); /* below */
static int decal_entity(const float proj[16], float decal_out[16]);  /* below */
static int cut_ground(const float proj[16], float decal_out[16]);    /* below */


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
  if (decal[10] <= proj[10]) return 1;
  if (ground_decal(proj, decal) != 0) return 1;
  printf("ground decal: element 10 %.9g -> %.9g\n", (double)proj[10], (double)decal[10]);
  if (decal[10] <= proj[10]) return 1;
  if (terrain_decal(proj, decal) != 0) return 1;
  printf("terrain decal: element 10 %.9g -> %.9g\n", (double)proj[10], (double)decal[10]);
  if (decal[10] <= proj[10]) return 1;
  if (decal_entity(proj, decal) != 0) return 1;
  printf("decal entity: element 10 %.9g -> %.9g\n", (double)proj[10], (double)decal[10]);
  if (decal[10] <= proj[10]) return 1;
  if (cut_ground(proj, decal) != 0) return 1;
  printf("cut ground: element 10 %.9g -> %.9g\n", (double)proj[10], (double)decal[10]);
  return decal[10] > proj[10] ? 0 : 1;
}

/* [quickstart-ground-c] */
/* A 2x2 decal on the ground, 10 units ahead of a level camera 1.7 units above it; the ground
   (+-1000 units, drawn as one quad) runs behind the camera. `proj` is the engine's projection. */
static int ground_decal(const float proj[16], float decal_out[16]) {
  const float corners[12] = {-1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -9.0f, /* eye space: after the view matrix */
                             1.0f, -1.7f, -11.0f, -1.0f, -1.7f, -11.0f};
  ZshiftDecal d;
  memset(&d, 0, sizeof d);
  d.viewport_width = 1920; /* glViewport(x, y, w, h): x, y in d.pipeline if not 0 */
  d.viewport_height = 1080;
  d.format = ZSHIFT_FORMAT_UNORM24_STENCIL8; /* GL_DEPTH24_STENCIL8, as attached */
  d.subpixel_bits = 8;                       /* glGetIntegerv(GL_SUBPIXEL_BITS) */
  d.depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;   /* the decal pass's glDepthFunc */
  d.decal_corners = corners;                 /* any plane, level ground included */
  d.decal_corner_count = 4;
  d.base_reach = 1415.0; /* the ground's largest eye-space |x|, |y|, |z|: the rasterizer clips it */
  if (zshift_decal_matrix(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, decal_out) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error()); /* the field, its value, what to do */
    return 1;
  }
  return 0;
}
/* [/quickstart-ground-c] */

/* [quickstart-terrain-c] */
/* A mesh decal over terrain with hills: the decal system cut it from two terrain triangles, one
   flat and one rising 0.5 per unit; one ZshiftDecal per plane, asked for in one call. */
static int terrain_decal(const float proj[16], float decal_out[16]) {
  const float flat[9] = {-1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -9.0f, -1.0f, -1.7f, -11.0f};
  const float rising[9] = {1.0f, -1.7f, -9.0f, 1.0f, -1.2f, -11.0f, -1.0f, -1.7f, -11.0f};
  ZshiftDecal planes[2];
  int i;
  memset(planes, 0, sizeof planes);
  for (i = 0; i < 2; i++) {
    planes[i].viewport_width = 1920;
    planes[i].viewport_height = 1080;
    planes[i].format = ZSHIFT_FORMAT_UNORM24_STENCIL8;
    planes[i].subpixel_bits = 8;
    planes[i].depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;
    planes[i].decal_corners = i == 0 ? flat : rising; /* the terrain triangle's eye-space corners */
    planes[i].decal_corner_count = 3;
    planes[i].base_reach = 0.0; /* this triangle lies inside the frustum */
  }
  if (zshift_decal_matrix_planes(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, planes, 2, decal_out) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error()); /* "plane 1: ..." names the plane */
    return 1;
  }
  return 0;
}
/* [/quickstart-terrain-c] */

/* [quickstart-entity-c] */
/* A decal entity 5000 units from the world's origin: a unit quad through its own model matrix,
   laid 2x2 on the ground 10 units ahead of a level camera 1.7 units above it. The engine
   multiplies its model-view V*M in double and rounds it once to float (glm::dmat4), so zshift
   is told the camera's view matrix and a world box that holds the ground's cells under the
   decal and the decal's world corners. (V*M multiplied in float: pass world_reach, no view.) */
static int decal_entity(const float proj[16], float decal_out[16]) {
  /* The camera at (5000, 1.7, 5000), level, looking down -z; column-major. */
  static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -5000.0f, -1.7f, -5000.0f, 1};
  /* min x, y, z, max x, y, z: the ground's 4-unit cells under the decal (it spans x 4999..5001,
     z 4989..4991). */
  static const double box[6] = {4996.0, 0.0, 4988.0, 5004.0, 0.0, 4992.0};
  const float corners[12] = {-1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -9.0f, /* eye space */
                             1.0f, -1.7f, -11.0f, -1.0f, -1.7f, -11.0f};
  ZshiftDecal d;
  memset(&d, 0, sizeof d);
  d.viewport_width = 1920;
  d.viewport_height = 1080;
  d.format = ZSHIFT_FORMAT_UNORM24_STENCIL8;
  d.subpixel_bits = 8;
  d.depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;
  d.decal_corners = corners;
  d.decal_corner_count = 4;
  d.base_reach = 0.0;                 /* those cells lie inside the frustum */
  d.pipeline.world_reach = 5000.0;    /* the camera's largest world coordinate */
  d.pipeline.eye_first = 1;           /* the shader computes proj * (modelView * p) */
  d.pipeline.view_matrix = view;      /* the camera's view, not the decal's model-view */
  memcpy(d.pipeline.world_box, box, sizeof box);
  if (zshift_decal_matrix(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, decal_out) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error());
    return 1;
  }
  return 0;
}
/* [/quickstart-entity-c] */

/* [quickstart-cut-c] */
/* The ground of ground_decal cut to the frustum in double, so that the rasterizer clips none of
   it, and stored in world space as the engine keeps it: the camera at (5000, 1.7, 5000), level,
   looking down -z. zshift_clip_to_frustum_stored cuts it inside by what that storage and the
   float view matrix can move a vertex (zshift_clip_to_frustum would leave a vertex close to the
   camera outside the screen, where a rasterizer that clips at the sides makes a sliver). */
static int cut_ground(const float proj[16], float decal_out[16]) {
  static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -5000.0f, -1.7f, -5000.0f, 1};
  static const double box[6] = {4000.0, 0.0, 4000.0, 6000.0, 0.0, 6000.0}; /* the ground's corners */
  const double ground[12] = {-1000.0, -1.7, 1000.0, 1000.0, -1.7, 1000.0, /* eye space */
                             1000.0, -1.7, -1000.0, -1000.0, -1.7, -1000.0};
  const float corners[12] = {-1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -9.0f, /* the decal, eye space */
                             1.0f, -1.7f, -11.0f, -1.0f, -1.7f, -11.0f};
  double cut[3 * 10];
  float world[3 * 10]; /* what the engine draws as a triangle fan */
  uint32_t count = 0, i;
  ZshiftDecal d;
  memset(&d, 0, sizeof d);
  d.pipeline.world_reach = 5000.0; /* the camera's largest world coordinate */
  d.pipeline.eye_first = 1;        /* the shader computes proj * (view * p) */
  d.pipeline.view_matrix = view;
  memcpy(d.pipeline.world_box, box, sizeof box);
  /* The frustum of main's proj: glFrustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000). */
  if (zshift_clip_to_frustum_stored(-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0, &d.pipeline, ground, 4, cut, 10,
                                    &count) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error());
    return 1;
  }
  for (i = 0; i < count; i++) { /* eye space -> world space: a level camera adds its position */
    world[3 * i] = (float)(cut[3 * i] + 5000.0);
    world[3 * i + 1] = (float)(cut[3 * i + 1] + 1.7);
    world[3 * i + 2] = (float)(cut[3 * i + 2] + 5000.0);
  }
  (void)world; /* the engine uploads it: glBufferData(GL_ARRAY_BUFFER, 12 * count, world, ...) */
  d.viewport_width = 1920;
  d.viewport_height = 1080;
  d.format = ZSHIFT_FORMAT_UNORM24_STENCIL8;
  d.subpixel_bits = 8;
  d.depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;
  d.decal_corners = corners;
  d.decal_corner_count = 4;
  d.base_reach = 0.0; /* the cut ground lies inside the frustum */
  if (zshift_decal_matrix(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, decal_out) != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error());
    return 1;
  }
  return count >= 3 ? 0 : 1;
}
/* [/quickstart-cut-c] */
