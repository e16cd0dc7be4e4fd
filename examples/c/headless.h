/* A headless OpenGL context for the zshift C examples: Mesa's surfaceless EGL platform, a
 * config-less context (EGL_KHR_no_config_context) and an offscreen framebuffer object, since
 * there is no window and so no default framebuffer. Nothing here knows about zshift.
 *
 * Every failure prints the reason to stderr and returns nonzero: the examples are tests, and a
 * test that cannot make a context must fail, not skip. */
#ifndef ZSHIFT_EXAMPLES_HEADLESS_H
#define ZSHIFT_EXAMPLES_HEADLESS_H

/* Which OpenGL profile to ask for: the compatibility profile (glFrustum, glLoadMatrixf, glBegin)
 * or a 3.3 core profile (shaders and glUniformMatrix4fv only). */
enum headless_profile { HEADLESS_COMPATIBILITY, HEADLESS_CORE_3_3 };

/* An OpenGL entry point as eglGetProcAddress returns it; cast to the PFNGL...PROC type. */
typedef void (*headless_fn)(void);

/* Creates the context, makes it current, and binds a width x height framebuffer with an RGBA8
 * color buffer and a depth buffer of `depth_bits` (16, 24 or 32 for 32F) bits; sets the viewport
 * to cover it. Returns 0 on success. */
int headless_open(enum headless_profile profile, int width, int height, int depth_bits);

/* The address of an OpenGL function by name, or NULL (with a message on stderr). */
headless_fn headless_proc(const char *name);

/* Reads the bound framebuffer as width*height RGBA bytes, bottom row first. Returns 0 on success. */
int headless_read_rgba(unsigned char *pixels);

/* Releases the framebuffer, the context and the display. */
void headless_close(void);

#endif /* ZSHIFT_EXAMPLES_HEADLESS_H */
