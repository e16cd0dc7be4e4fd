/* zshift in an OpenGL 3.3 core engine: the projection comes from zshift and reaches the vertex
 * shader through glUniformMatrix4fv. Renders the coplanar-decal scene (scene.h) headless for
 * several projections and checks the pixels: with zshift's offset no decal pixel is lost; without
 * one, the decal is lost to the base. Exits nonzero with a message on any failure.
 *
 * Every GL function comes from eglGetProcAddress, so this program links EGL and zshift only. */
#include <GL/glcorearb.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "headless.h"
#include "scene.h"
#include "zshift.h"

static PFNGLCREATESHADERPROC glCreateShader;
static PFNGLSHADERSOURCEPROC glShaderSource;
static PFNGLCOMPILESHADERPROC glCompileShader;
static PFNGLGETSHADERIVPROC glGetShaderiv;
static PFNGLGETSHADERINFOLOGPROC glGetShaderInfoLog;
static PFNGLCREATEPROGRAMPROC glCreateProgram;
static PFNGLATTACHSHADERPROC glAttachShader;
static PFNGLBINDATTRIBLOCATIONPROC glBindAttribLocation;
static PFNGLLINKPROGRAMPROC glLinkProgram;
static PFNGLGETPROGRAMIVPROC glGetProgramiv;
static PFNGLUSEPROGRAMPROC glUseProgram;
static PFNGLGETUNIFORMLOCATIONPROC glGetUniformLocation;
static PFNGLUNIFORMMATRIX4FVPROC glUniformMatrix4fv;
static PFNGLUNIFORM4FPROC glUniform4f;
static PFNGLGENVERTEXARRAYSPROC glGenVertexArrays;
static PFNGLBINDVERTEXARRAYPROC glBindVertexArray;
static PFNGLGENBUFFERSPROC glGenBuffers;
static PFNGLBINDBUFFERPROC glBindBuffer;
static PFNGLBUFFERDATAPROC glBufferData;
static PFNGLVERTEXATTRIBPOINTERPROC glVertexAttribPointer;
static PFNGLENABLEVERTEXATTRIBARRAYPROC glEnableVertexAttribArray;
static PFNGLDRAWARRAYSPROC glDrawArrays;
static PFNGLCLEARCOLORPROC glClearColor;
static PFNGLCLEARPROC glClear;
static PFNGLENABLEPROC glEnable;
static PFNGLDEPTHFUNCPROC glDepthFunc;
static PFNGLGETERRORPROC glGetError;
static PFNGLGETINTEGERVPROC glGetIntegerv;

static int load_gl(void) {
#define PFN_LOAD(type, name) \
  if ((name = (type)headless_proc(#name)) == NULL) return 1
  PFN_LOAD(PFNGLCREATESHADERPROC, glCreateShader);
  PFN_LOAD(PFNGLSHADERSOURCEPROC, glShaderSource);
  PFN_LOAD(PFNGLCOMPILESHADERPROC, glCompileShader);
  PFN_LOAD(PFNGLGETSHADERIVPROC, glGetShaderiv);
  PFN_LOAD(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog);
  PFN_LOAD(PFNGLCREATEPROGRAMPROC, glCreateProgram);
  PFN_LOAD(PFNGLATTACHSHADERPROC, glAttachShader);
  PFN_LOAD(PFNGLBINDATTRIBLOCATIONPROC, glBindAttribLocation);
  PFN_LOAD(PFNGLLINKPROGRAMPROC, glLinkProgram);
  PFN_LOAD(PFNGLGETPROGRAMIVPROC, glGetProgramiv);
  PFN_LOAD(PFNGLUSEPROGRAMPROC, glUseProgram);
  PFN_LOAD(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation);
  PFN_LOAD(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv);
  PFN_LOAD(PFNGLUNIFORM4FPROC, glUniform4f);
  PFN_LOAD(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays);
  PFN_LOAD(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray);
  PFN_LOAD(PFNGLGENBUFFERSPROC, glGenBuffers);
  PFN_LOAD(PFNGLBINDBUFFERPROC, glBindBuffer);
  PFN_LOAD(PFNGLBUFFERDATAPROC, glBufferData);
  PFN_LOAD(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer);
  PFN_LOAD(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray);
  PFN_LOAD(PFNGLDRAWARRAYSPROC, glDrawArrays);
  PFN_LOAD(PFNGLCLEARCOLORPROC, glClearColor);
  PFN_LOAD(PFNGLCLEARPROC, glClear);
  PFN_LOAD(PFNGLENABLEPROC, glEnable);
  PFN_LOAD(PFNGLDEPTHFUNCPROC, glDepthFunc);
  PFN_LOAD(PFNGLGETERRORPROC, glGetError);
  PFN_LOAD(PFNGLGETINTEGERVPROC, glGetIntegerv);
#undef PFN_LOAD
  return 0;
}

static const char *vertex_source =
    "#version 330 core\n"
    "uniform mat4 u_projection;\n"
    "in vec3 a_eye_position;\n"
    "void main() { gl_Position = u_projection * vec4(a_eye_position, 1.0); }\n";
static const char *fragment_source =
    "#version 330 core\n"
    "uniform vec4 u_color;\n"
    "out vec4 frag_color;\n"
    "void main() { frag_color = u_color; }\n";

static GLuint compile(GLenum kind, const char *source) {
  GLuint shader = glCreateShader(kind);
  GLint ok = 0;
  glShaderSource(shader, 1, &source, NULL);
  glCompileShader(shader);
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024];
    glGetShaderInfoLog(shader, sizeof log, NULL, log);
    fprintf(stderr, "FAIL: shader does not compile: %s\n", log);
    return 0;
  }
  return shader;
}

static GLuint link_program(void) {
  GLuint vs = compile(GL_VERTEX_SHADER, vertex_source), fs = compile(GL_FRAGMENT_SHADER, fragment_source);
  GLuint program;
  GLint ok = 0;
  if (vs == 0 || fs == 0) return 0;
  program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glBindAttribLocation(program, 0, "a_eye_position");
  glLinkProgram(program);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    fprintf(stderr, "FAIL: shader program does not link\n");
    return 0;
  }
  return program;
}

/* [quickstart-c-modern] */
/* Sets the projection uniform: the glFrustum matrix when delta == 0, else the matrix that moves
 * geometry at eye-space depth pz (negative) toward the camera by delta eye-space units. */
static int set_projection(GLint location, double l, double r, double b, double t, double n,
                          double f, double delta, double pz) {
  float m[16]; /* column-major: glUniformMatrix4fv with transpose = GL_FALSE */
  ZshiftStatus s = delta == 0.0 ? zshift_frustum(l, r, b, t, n, f, m)
                                : zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz, m);
  if (s != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_status_message(s));
    return 1;
  }
  glUniformMatrix4fv(location, 1, GL_FALSE, m);
  return 0;
}
/* [/quickstart-c-modern] */

struct renderer {
  GLuint program, buffer;
  GLint projection, color;
};

static int draw(const struct renderer *gl, float quad[6][3], float red, float blue) {
  glUniform4f(gl->color, red, 0.0f, blue, 1.0f);
  glBufferData(GL_ARRAY_BUFFER, 6 * 3 * sizeof(float), quad, GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, 6);
  return glGetError() == GL_NO_ERROR ? 0 : 1;
}

/* The projection as glm::perspective(fovy, aspect, n, f) builds it in float (right-handed,
 * NDC depth [-1, 1]), column-major: an engine's own matrix. */
static void glm_style_perspective(float fovy, float aspect, float n, float f, float m[16]) {
  const float tan_half = (float)tan(fovy / 2.0f);
  int i;
  for (i = 0; i < 16; i++) m[i] = 0.0f;
  m[0] = 1.0f / (aspect * tan_half);
  m[5] = 1.0f / tan_half;
  m[10] = -(f + n) / (f - n);
  m[11] = -1.0f;
  m[14] = -(2.0f * f * n) / (f - n);
}

/* The projection as glm::ortho(l, r, b, t, n, f) builds it (glOrtho), column-major. */
static void glm_style_ortho(float l, float r, float b, float t, float n, float f, float m[16]) {
  int i;
  for (i = 0; i < 16; i++) m[i] = 0.0f;
  m[0] = 2.0f / (r - l);
  m[5] = 2.0f / (t - b);
  m[10] = -2.0f / (f - n);
  m[12] = -(r + l) / (r - l);
  m[13] = -(t + b) / (t - b);
  m[14] = -(f + n) / (f - n);
  m[15] = 1.0f;
}

/* [quickstart-c-front-door] */
/* The base is drawn with the engine's own projection `proj` (16 floats, column-major, from GLM
 * or the engine's code), the decal with the same matrix carrying zshift's recommended offset in
 * one element: the engine never restates its frustum. Perspective or orthographic alike. */
static int decal_projection(const float proj[16], ZshiftFormat format, int subpixel_bits,
                            double decal_near, double decal_far, float decal[16]) {
  ZshiftDecal d;
  ZshiftStatus s;
  memset(&d, 0, sizeof d);
  d.viewport_width = SCENE_SIZE; /* glViewport */
  d.viewport_height = SCENE_SIZE;
  d.format = format;               /* the depth attachment, e.g. ZSHIFT_FORMAT_UNORM24 */
  d.subpixel_bits = subpixel_bits; /* glGetIntegerv(GL_SUBPIXEL_BITS) */
  d.decal_near = decal_near;       /* the decal's nearest and farthest eye distance */
  d.decal_far = decal_far;
  d.slope = 0.0;     /* |dz/dx| + |dz/dy| of its plane in eye space: facing the camera */
  d.exact_depth = 1; /* base and decal corners share one float z */
  s = zshift_decal_matrix(proj, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, decal);
  if (s != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_last_error()); /* names the input, its value, why */
    return 1;
  }
  return 0;
}
/* [/quickstart-c-front-door] */

/* Renders one case with the base drawn through `base` and the decal through `decal`. */
static int render_matrices(const struct renderer *gl, const struct scene_case *c, const float base[16],
                           const float decal[16], struct scene_tally *tally) {
  static unsigned char pixels[SCENE_SIZE * SCENE_SIZE * 4];
  float base_quad[6][3], decal_quad[6][3];
  double d = scene_distance(c);
  scene_quad(SCENE_BASE_HALF, d, base_quad);
  scene_quad(SCENE_DECAL_HALF, d, decal_quad);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUniformMatrix4fv(gl->projection, 1, GL_FALSE, base);
  if (draw(gl, base_quad, 0.0f, 1.0f) != 0) return 1;
  glUniformMatrix4fv(gl->projection, 1, GL_FALSE, decal);
  if (draw(gl, decal_quad, 1.0f, 0.0f) != 0 || headless_read_rgba(pixels) != 0) return 1;
  *tally = scene_check(pixels);
  return 0;
}

/* The front door on one case: the engine's GLM-style perspective (90°, square) and an
 * orthographic box that shows the scene's quads at the same place, each decal drawn with
 * zshift_decal_matrix of the engine's matrix. */
static int run_engine_matrices(const struct renderer *gl, const struct scene_case *c, int bits) {
  const double d = scene_distance(c);
  const float n = (float)c->n, f = (float)c->f, h = (float)d;
  const ZshiftFormat format = c->depth_bits == 16 ? ZSHIFT_FORMAT_UNORM16 : ZSHIFT_FORMAT_UNORM24;
  float engine[2][16], decal[16];
  const char *names[2] = {"glm::perspective", "glm::ortho"};
  int k, failures = 0;
  glm_style_perspective(3.14159265f / 2.0f, 1.0f, n, f, engine[0]);
  glm_style_ortho(-h, h, -h, h, n, f, engine[1]);
  for (k = 0; k < 2; k++) {
    struct scene_tally none, chosen;
    if (decal_projection(engine[k], format, bits, d, d, decal) != 0 ||
        render_matrices(gl, c, engine[k], engine[k], &none) != 0 ||
        render_matrices(gl, c, engine[k], decal, &chosen) != 0)
      return 1;
    printf("  engine's own %-16s lost of %d: none %4d  zshift_decal_matrix %4d\n", names[k],
           chosen.decal_total, none.decal_lost, chosen.decal_lost);
    failures += scene_verdict(none.wrong + chosen.wrong, &none, &chosen, 0.0);
  }
  return failures;
}

/* Renders one case with the decal shifted by `delta` (0: no offset) and tallies its pixels. */
static int render(const struct renderer *gl, const struct scene_case *c, double delta,
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
  if (set_projection(gl->projection, -n, n, -n, n, n, f, 0.0, -d) != 0 || draw(gl, base, 0.0f, 1.0f) != 0 ||
      set_projection(gl->projection, -n, n, -n, n, n, f, delta, -d) != 0 ||
      draw(gl, decal, 1.0f, 0.0f) != 0) {
    fprintf(stderr, "FAIL: drawing raised a GL error\n");
    return 1;
  }
  if (headless_read_rgba(pixels) != 0) return 1;
  *tally = scene_check(pixels);
  return 0;
}

static int setup(struct renderer *gl) {
  GLuint vertex_array;
  if (load_gl() != 0 || (gl->program = link_program()) == 0) return 1;
  glUseProgram(gl->program);
  gl->projection = glGetUniformLocation(gl->program, "u_projection");
  gl->color = glGetUniformLocation(gl->program, "u_color");
  glGenVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
  glGenBuffers(1, &gl->buffer);
  glBindBuffer(GL_ARRAY_BUFFER, gl->buffer);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
  glEnableVertexAttribArray(0);
  return glGetError() == GL_NO_ERROR ? 0 : 1;
}

/* What the rasterizer says about its sub-pixel precision, for zshift_recommend. */
static int subpixel_bits(void) {
  GLint bits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
  return bits;
}

static int run_case(const struct renderer *gl, const struct scene_case *c) {
  struct scene_tally none, one, chosen;
  double d = scene_distance(c), step, recommended;
  ZshiftStatus status = zshift_min_delta_toward(c->n, c->f, (uint32_t)c->depth_bits, -d, &step);
  if (status != ZSHIFT_OK) {
    fprintf(stderr, "zshift_min_delta_toward: %s\n", zshift_status_message(status));
    return 1;
  }
  if (scene_recommended_delta(c, subpixel_bits(), &recommended) != 0) return 1;
  if (render(gl, c, 0.0, &none) != 0 || render(gl, c, step, &one) != 0 ||
      render(gl, c, recommended, &chosen) != 0)
    return 1;
  printf("D%-3d n=%-5g f=%-7g d=%-9g step=%-10.4g lost of %d: none %4d  zshift 1 step %4d  "
         "zshift recommended (%.3g steps) %4d\n",
         c->depth_bits, c->n, c->f, d, step, chosen.decal_total, none.decal_lost, one.decal_lost,
         recommended / step, chosen.decal_lost);
  return scene_verdict(none.wrong + one.wrong + chosen.wrong, &none, &chosen, recommended / step) +
         run_engine_matrices(gl, c, subpixel_bits());
}

int main(void) {
  struct renderer gl;
  int failures = 0, i, depth_bits = -1;
  for (i = 0; i < scene_case_count; i++) {
    if (scene_cases[i].depth_bits != depth_bits) {
      if (depth_bits != -1) headless_close();
      depth_bits = scene_cases[i].depth_bits;
      if (headless_open(HEADLESS_CORE_3_3, SCENE_SIZE, SCENE_SIZE, depth_bits) != 0 || setup(&gl) != 0) {
        fprintf(stderr, "FAIL: no headless OpenGL 3.3 core context with the scene's shaders\n");
        return 1;
      }
    }
    failures += run_case(&gl, &scene_cases[i]);
  }
  headless_close();
  if (failures != 0) {
    fprintf(stderr, "modern_gl: %d of %d cases failed\n", failures, scene_case_count);
    return 1;
  }
  printf("modern_gl: all %d cases passed (zshift %s, ABI %d)\n", scene_case_count, zshift_version(),
         ZSHIFT_ABI_VERSION);
  return 0;
}
