/* Headless OpenGL through Mesa's surfaceless EGL platform; see headless.h. Every GL function is
 * fetched with eglGetProcAddress, so this file links EGL only. */
#define EGL_NO_X11 /* keep eglplatform.h from pulling in X11 headers */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <stdio.h>

#include "headless.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef EGL_NO_CONFIG_KHR
#define EGL_NO_CONFIG_KHR ((EGLConfig)0)
#endif

static EGLDisplay display = EGL_NO_DISPLAY;
static EGLContext context = EGL_NO_CONTEXT;
static GLuint framebuffer, color_buffer, depth_buffer;
static int fb_width, fb_height;

headless_fn headless_proc(const char *name) {
  headless_fn fn = (headless_fn)eglGetProcAddress(name);
  if (fn == NULL) fprintf(stderr, "headless: eglGetProcAddress(\"%s\") found nothing\n", name);
  return fn;
}

/* Loads one GL function into a local of its PFN type, or fails the enclosing function. */
#define LOAD(type, name)                          \
  type name = (type)headless_proc(#name);         \
  if (name == NULL) return 1

static int open_display(void) {
  static const EGLAttrib no_attribs[] = {EGL_NONE};
  EGLint major = 0, minor = 0;
  display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, no_attribs);
  if (display == EGL_NO_DISPLAY) {
    fprintf(stderr, "headless: no EGL display on the surfaceless Mesa platform (is libegl-mesa0 installed?)\n");
    return 1;
  }
  if (!eglInitialize(display, &major, &minor)) {
    fprintf(stderr, "headless: eglInitialize failed (EGL error 0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    fprintf(stderr, "headless: eglBindAPI(EGL_OPENGL_API) failed (EGL error 0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  return 0;
}

static int create_context(enum headless_profile profile) {
  static const EGLint core[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                EGL_NONE};
  static const EGLint compatibility[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  /* eglChooseConfig finds no config without a surface type on Mesa; a config-less context
   * (EGL_KHR_no_config_context) needs none, since it only ever renders into an FBO. */
  context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                             profile == HEADLESS_CORE_3_3 ? core : compatibility);
  if (context == EGL_NO_CONTEXT) {
    fprintf(stderr, "headless: eglCreateContext failed (EGL error 0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    fprintf(stderr, "headless: eglMakeCurrent failed (EGL error 0x%x)\n", (unsigned)eglGetError());
    return 1;
  }
  return 0;
}

static GLenum depth_format(int depth_bits) {
  switch (depth_bits) {
    case 16: return GL_DEPTH_COMPONENT16;
    case 24: return GL_DEPTH_COMPONENT24;
    case 32: return GL_DEPTH_COMPONENT32F;
    default: return 0;
  }
}

static int create_framebuffer(int width, int height, int depth_bits) {
  LOAD(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers);
  LOAD(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer);
  LOAD(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers);
  LOAD(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer);
  LOAD(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage);
  LOAD(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer);
  LOAD(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus);
  LOAD(PFNGLVIEWPORTPROC, glViewport);
  GLenum format = depth_format(depth_bits);
  GLenum status;
  if (format == 0) {
    fprintf(stderr, "headless: depth_bits must be 16, 24 or 32, not %d\n", depth_bits);
    return 1;
  }
  glGenRenderbuffers(1, &color_buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, color_buffer);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &depth_buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer);
  glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_buffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
  status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fprintf(stderr, "headless: framebuffer incomplete (status 0x%x)\n", (unsigned)status);
    return 1;
  }
  /* With no surface the viewport starts at 0x0, and nothing would be drawn. */
  glViewport(0, 0, width, height);
  fb_width = width;
  fb_height = height;
  return 0;
}

int headless_open(enum headless_profile profile, int width, int height, int depth_bits) {
  if (open_display() != 0 || create_context(profile) != 0) return 1;
  return create_framebuffer(width, height, depth_bits);
}

int headless_read_rgba(unsigned char *pixels) {
  LOAD(PFNGLREADPIXELSPROC, glReadPixels);
  LOAD(PFNGLPIXELSTOREIPROC, glPixelStorei);
  LOAD(PFNGLGETERRORPROC, glGetError);
  GLenum error;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  error = glGetError();
  if (error != GL_NO_ERROR) {
    fprintf(stderr, "headless: glReadPixels raised GL error 0x%x\n", (unsigned)error);
    return 1;
  }
  return 0;
}

void headless_close(void) {
  PFNGLDELETEFRAMEBUFFERSPROC delete_framebuffers =
      (PFNGLDELETEFRAMEBUFFERSPROC)headless_proc("glDeleteFramebuffers");
  PFNGLDELETERENDERBUFFERSPROC delete_renderbuffers =
      (PFNGLDELETERENDERBUFFERSPROC)headless_proc("glDeleteRenderbuffers");
  if (context != EGL_NO_CONTEXT && delete_framebuffers != NULL && delete_renderbuffers != NULL) {
    GLuint renderbuffers[2];
    renderbuffers[0] = color_buffer;
    renderbuffers[1] = depth_buffer;
    delete_framebuffers(1, &framebuffer);
    delete_renderbuffers(2, renderbuffers);
  }
  if (display != EGL_NO_DISPLAY) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
  context = EGL_NO_CONTEXT;
  display = EGL_NO_DISPLAY;
}
