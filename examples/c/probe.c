/* Measures the rasterizer of the current OpenGL context with zshift_probe and prints the
 * profile: what an engine does once after creating its context. GL reaches zshift only through
 * the loader below (eglGetProcAddress here; glfwGetProcAddress, SDL_GL_GetProcAddress or
 * wglGetProcAddress in a windowed engine): the library links no GL.
 *
 * Also checks, as a test: the probe leaves the engine's framebuffer binding and viewport as they
 * were, a loader that finds nothing gives ZSHIFT_ERR_GL with `out` untouched, and a NULL output
 * gives ZSHIFT_ERR_NULL_POINTER. Runs on a 3.3 core and a compatibility context. */
#define EGL_NO_X11
#include <EGL/egl.h>
#include <GL/glcorearb.h>

#include <stdio.h>
#include <string.h>

#include "headless.h"
#include "zshift.h"

/* The loader zshift calls: eglGetProcAddress with a `user` argument (unused here). */
static ZshiftGlProc egl_loader(const char *name, void *user) {
  (void)user;
  return (ZshiftGlProc)eglGetProcAddress(name);
}

static ZshiftGlProc no_loader(const char *name, void *user) {
  (void)name;
  (void)user;
  return NULL;
}

static int probe_once(enum headless_profile kind, const char *label) {
  if (headless_open(kind, 32, 32, 24) != 0) return 1;
  PFNGLGETINTEGERVPROC get_integerv = (PFNGLGETINTEGERVPROC)headless_proc("glGetIntegerv");
  if (get_integerv == NULL) return 1;
  GLint fbo_before = -1, fbo_after = -2, viewport_before[4], viewport_after[4];
  get_integerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo_before);
  get_integerv(GL_VIEWPORT, viewport_before);

  ZshiftProfile profile;
  ZshiftStatus status = zshift_probe(egl_loader, NULL, &profile);
  if (status != ZSHIFT_OK) {
    fprintf(stderr, "%s: zshift_probe failed: %s: %s\n", label, zshift_status_message(status),
            zshift_last_error());
    return 1;
  }
  get_integerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo_after);
  get_integerv(GL_VIEWPORT, viewport_after);
  if (fbo_after != fbo_before || memcmp(viewport_before, viewport_after, sizeof viewport_after) != 0) {
    fprintf(stderr, "%s: the probe changed the framebuffer binding or viewport\n", label);
    return 1;
  }

  static const char *const names[4] = {"D16", "D24", "D32", "D32F"};
  printf("%s: probed in %.1f ms; depth plane %s", label, profile.probe_seconds * 1e3,
         profile.subpixel_bits == ZSHIFT_SUBPIXEL_UNSNAPPED ? "unsnapped" : "snapped");
  if (profile.subpixel_bits != ZSHIFT_SUBPIXEL_UNSNAPPED) printf(" to 2^-%d pixel", profile.subpixel_bits);
  printf("; near plane %s\n", profile.near_clip == ZSHIFT_NEAR_CLIP_CLIPPED_F32 ? "clipped in float"
                                                                               : "plane-preserving");
  for (int i = 0; i < 4; i++)
    printf("  %-4s  r = %.3f quanta, plane error %.2f quanta\n", names[i], profile.resolvable[i],
           profile.plane_error[i]);
  printf("  D32F reversed Z: plane error %.2f quanta; error %.2f ulps of 1 + M\n",
         profile.plane_error_reversed, profile.error_ulps);

  /* Errors: out untouched, a status that says what was wrong. */
  ZshiftProfile untouched = profile;
  if (zshift_probe(no_loader, NULL, &untouched) != ZSHIFT_ERR_GL ||
      memcmp(&untouched, &profile, sizeof profile) != 0) {
    fprintf(stderr, "%s: a loader that finds nothing must give ZSHIFT_ERR_GL and leave out alone\n", label);
    return 1;
  }
  if (strstr(zshift_last_error(), "glGetError") == NULL) {
    fprintf(stderr, "%s: the detail must name the first missing entry point: \"%s\"\n", label,
            zshift_last_error());
    return 1;
  }
  printf("  a loader that finds nothing: %s\n", zshift_last_error());
  if (zshift_probe(egl_loader, NULL, NULL) != ZSHIFT_ERR_NULL_POINTER ||
      zshift_probe(NULL, NULL, &untouched) != ZSHIFT_ERR_NULL_POINTER) {
    fprintf(stderr, "%s: NULL loader or output must give ZSHIFT_ERR_NULL_POINTER\n", label);
    return 1;
  }
  if (profile.measured != 1) {
    fprintf(stderr, "%s: a probed profile must say measured\n", label);
    return 1;
  }
  headless_close();
  return 0;
}

int main(void) {
  if (probe_once(HEADLESS_CORE_3_3, "core 3.3") != 0) return 1;
  if (probe_once(HEADLESS_COMPATIBILITY, "compatibility") != 0) return 1;
  return 0;
}
