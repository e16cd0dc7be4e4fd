/* The coplanar-decal scene shared by the zshift C examples, and the check of its pixels.
 *
 * A base quad and a smaller decal quad lie in the same plane z = -d, facing the camera of a 90°
 * symmetric frustum (l = b = -n, r = t = n), so the base covers NDC x, y in [-0.75, 0.75] and the
 * decal [-0.5, 0.5]: on a 64 x 64 framebuffer their edges fall on pixel boundaries and every
 * pixel center lies clearly inside or outside each quad. The base is drawn first in blue, the
 * decal second in red, with glDepthFunc(GL_LESS): without an offset the decal's depth equals the
 * base's and the decal is lost. */
#ifndef ZSHIFT_EXAMPLES_SCENE_H
#define ZSHIFT_EXAMPLES_SCENE_H

#define SCENE_SIZE 64
#define SCENE_BASE_HALF 0.75
#define SCENE_DECAL_HALF 0.5

/* One projection and plane depth: clip planes n, f, the plane at d = n + at * (f - n). */
struct scene_case {
  double n, f, at;
  int depth_bits;
};

extern const struct scene_case scene_cases[];
extern const int scene_case_count;

/* The eye distance of the plane, positive. */
double scene_distance(const struct scene_case *c);

/* Two triangles (6 vertices, x y z) of a square facing the camera at eye z = -d that covers
 * NDC x, y in [-half, half] under the 90° frustum. */
void scene_quad(double half, double d, float out[6][3]);

/* What the pixels show: decal pixels lost to the base, and pixels that are neither what the
 * scene should show nor a lost decal pixel (which would mean the scene itself is wrong). */
struct scene_tally {
  int decal_lost;
  int decal_total;
  int wrong;
};

/* zshift's recommended shift toward the camera for the case's decal (zshift_recommend), for
 * zshift_load_offset_matrix(..., *delta, -scene_distance(c), m); `subpixel_bits` is what
 * glGetIntegerv(GL_SUBPIXEL_BITS) reports. Returns 0, or prints the status and returns 1. */
int scene_recommended_delta(const struct scene_case *c, int subpixel_bits, double *delta);

/* The verdict on one case: 0 when the picture is sound (`wrong` pixels: none), the scene z-fights
 * without an offset, and zshift's offset of `steps` depth steps keeps every decal pixel; otherwise
 * prints why and returns 1. */
int scene_verdict(int wrong, const struct scene_tally *none, const struct scene_tally *chosen,
                  double steps);

/* Classifies a SCENE_SIZE x SCENE_SIZE RGBA readback (black clear, blue base, red decal). */
struct scene_tally scene_check(const unsigned char *rgba);

#endif /* ZSHIFT_EXAMPLES_SCENE_H */
