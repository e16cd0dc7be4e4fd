/* The C ABI contract of include/zshift.h, exercised from C: every function with valid inputs
 * (against the seed formulas evaluated here in long double, independent of zshift's code), NULL
 * output pointers, NaN and infinite inputs, domain errors, the output left untouched on every
 * error, the status messages and the version strings. Prints each failure and exits nonzero if
 * any check failed. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "zshift.h"

#ifndef EXPECTED_VERSION
#error "build with -DEXPECTED_VERSION=\"x.y.z\" (the version in Cargo.toml)"
#endif

static int checks, failures;

#define CHECK(cond, ...)                                   \
  do {                                                     \
    checks++;                                              \
    if (!(cond)) {                                         \
      failures++;                                          \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
      fprintf(stderr, __VA_ARGS__);                        \
      fputc('\n', stderr);                                 \
    }                                                      \
  } while (0)

/* A status must be exactly `expected`; names both in words on failure. Every failing call must
 * leave a detail in zshift_last_error(), every successful one an empty string. */
#define CHECK_STATUS(call, expected)                                                        \
  do {                                                                                      \
    ZshiftStatus got_ = (call);                                                             \
    const char *detail_ = zshift_last_error();                                              \
    CHECK(got_ == (expected), "%s returned %d (%s: %s), expected %d (%s)", #call, (int)got_, \
          zshift_status_message(got_), detail_, (int)(expected), zshift_status_message(expected)); \
    CHECK(detail_ != NULL && (got_ == ZSHIFT_OK ? detail_[0] == '\0' : strlen(detail_) > 10), \
          "%s: zshift_last_error() is \"%s\" after status %d", #call, detail_ ? detail_ : "(null)", (int)got_); \
  } while (0)

/* ---- output left untouched on error: fill with a pattern, call, compare ---- */

static const unsigned char PATTERN = 0xA5;

static int untouched(const void *out, size_t size) {
  const unsigned char *bytes = out;
  size_t i;
  for (i = 0; i < size; i++)
    if (bytes[i] != PATTERN) return 0;
  return 1;
}

/* Runs a matrix call on a pattern-filled buffer; it must fail with `expected` and write nothing. */
#define CHECK_MATRIX_ERROR(expected, fn, ...)                                           \
  do {                                                                                  \
    float out_[16];                                                                     \
    memset(out_, PATTERN, sizeof out_);                                                 \
    CHECK_STATUS(fn(__VA_ARGS__, out_), expected);                                      \
    CHECK(untouched(out_, sizeof out_), "%s(%s) wrote its output on error", #fn, #__VA_ARGS__); \
  } while (0)

#define CHECK_SCALAR_ERROR(expected, fn, ...)                                           \
  do {                                                                                  \
    double out_;                                                                        \
    memset(&out_, PATTERN, sizeof out_);                                                \
    CHECK_STATUS(fn(__VA_ARGS__, &out_), expected);                                     \
    CHECK(untouched(&out_, sizeof out_), "%s(%s) wrote its output on error", #fn, #__VA_ARGS__); \
  } while (0)

/* ---- references: the seed formulas in long double ---- */

static long double steps(unsigned bits) { return ldexpl(1.0L, (int)bits) - 1.0L; }

/* Argument values that are not one of the header's constants (each is ZSHIFT_ERR_DOMAIN): a
 * caller can only make them by filling the struct by hand. */
static ZshiftClip clip_value(int32_t v) {
  ZshiftClip c;
  c.value = v;
  return c;
}
static ZshiftFormat format_value(uint32_t v) {
  ZshiftFormat f;
  f.value = v;
  return f;
}
static ZshiftBiasApi api_value(int32_t v) {
  ZshiftBiasApi a;
  a.value = v;
  return a;
}
static ZshiftOffsetKind kind_value(int32_t v) {
  ZshiftOffsetKind k;
  k.value = v;
  return k;
}

/* glFrustum's matrix (seed 000, eq. 4.1.1), column-major. */
static void reference_frustum(long double l, long double r, long double b, long double t,
                              long double n, long double f, long double m[16]) {
  int i;
  for (i = 0; i < 16; i++) m[i] = 0.0L;
  m[0] = 2.0L * n / (r - l);
  m[5] = 2.0L * n / (t - b);
  m[8] = (r + l) / (r - l);
  m[9] = (t + b) / (t - b);
  m[10] = -(f + n) / (f - n);
  m[11] = -1.0L;
  m[14] = -2.0L * f * n / (f - n);
}

/* Eq. 4.1.7. */
static long double reference_epsilon(long double n, long double f, long double delta, long double pz) {
  return -2.0L * f * n / (f + n) * (delta / (pz * (pz + delta)));
}

/* k of eq. 4.1.11 as corrected by seed 002. */
static long double reference_k(long double n, long double f, unsigned bits) {
  return (f - n) / (f * n * steps(bits));
}

/* Walker's f(d) (seed 001) in its printed form. */
static long double reference_window_depth(long double n, long double f, long double d) {
  return (f + n) / (2.0L * (f - n)) - f * n / (d * (f - n)) + 0.5L;
}

static double relative_error(double got, long double want) {
  return (double)(fabsl((long double)got - want) / fabsl(want));
}

/* Whether `got` is one of the two floats around `want` (within 1 ulp of the exact value). */
static int within_one_float_ulp(float got, long double want) {
  float nearest = (float)want;
  return got == nearest || got == nextafterf(nearest, INFINITY) || got == nextafterf(nearest, -INFINITY);
}

/* ---- the functions ---- */

static void test_frustum(void) {
  static const double cases[][6] = {
      {-1, 1, -1, 1, 1, 100}, {-0.1, 0.3, -0.2, 0.1, 0.1, 1e4}, {-2, 2, -1.5, 1.5, 0.01, 1e6}};
  size_t c;
  int i;
  float out[16];
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    const double *p = cases[c];
    long double want[16];
    reference_frustum(p[0], p[1], p[2], p[3], p[4], p[5], want);
    CHECK_STATUS(zshift_frustum(p[0], p[1], p[2], p[3], p[4], p[5], out), ZSHIFT_OK);
    for (i = 0; i < 16; i++)
      CHECK(within_one_float_ulp(out[i], want[i]), "frustum case %zu element %d: %.9g vs %.12Lg", c,
            i, (double)out[i], want[i]);
  }
  /* Infinite far plane: element 10 -> -1, element 14 -> -2n (seed 003). */
  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, 0.5, INFINITY, out), ZSHIFT_OK);
  CHECK(out[10] == -1.0f && out[14] == -1.0f && out[11] == -1.0f, "infinite far: m10 %g m14 %g",
        (double)out[10], (double)out[14]);

  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, 1, 100, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_frustum, NAN, 1, -1, 1, 1, 100);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_frustum, -1, 1, -1, 1, 1, NAN);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_frustum, -1, 1, -1, 1, INFINITY, INFINITY);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_frustum, -1, 1, -1, 1, 1, -INFINITY);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_frustum, -INFINITY, 1, -1, 1, 1, 100);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, 1, 1, -1, 1, 1, 100);  /* l == r */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, -1, 1, 2, 2, 1, 100);  /* b == t */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, -1, 1, -1, 1, 0, 100); /* n == 0 */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, -1, 1, -1, 1, -1, 100);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, -1, 1, -1, 1, 5, 5);   /* f == n */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_frustum, -1, 1, -1, 1, 5, 4);   /* f < n */
  /* 2n/(r - l) = 2e40 does not fit a float. */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_OVERFLOW, zshift_frustum, 0, 1e-40, -1, 1, 1, 100);
}

static void test_load_offset_matrix(void) {
  static const double cases[][8] = {/* l r b t n f delta pz */
                                    {-1, 1, -1, 1, 1, 100, 0.01, -50},
                                    {-0.1, 0.1, -0.1, 0.1, 0.1, 1e4, 2.0, -5e3},
                                    {-1, 1, -1, 1, 1, 1e6, -10.0, -1e3}};
  size_t c;
  int i;
  for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    const double *p = cases[c];
    float plain[16], shifted[16];
    long double want[16], offset, moved;
    reference_frustum(p[0], p[1], p[2], p[3], p[4], p[5], want);
    CHECK_STATUS(zshift_frustum(p[0], p[1], p[2], p[3], p[4], p[5], plain), ZSHIFT_OK);
    CHECK_STATUS(zshift_load_offset_matrix(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], shifted),
                 ZSHIFT_OK);
    for (i = 0; i < 16; i++)
      if (i != 10)
        CHECK(shifted[i] == plain[i], "offset case %zu element %d differs from zshift_frustum's", c, i);
    /* Element 10 scaled by 1 + epsilon (eq. 4.1.3): the offset the GPU sees is at least the exact
     * one and at most one float ulp more, in the same direction. */
    offset = want[10] * reference_epsilon(p[4], p[5], p[6], p[7]);
    moved = (long double)shifted[10] - (long double)plain[10];
    CHECK(moved * offset > 0.0L, "offset case %zu: element 10 moved %Lg, expected the sign of %Lg", c,
          moved, offset);
    CHECK(fabsl(moved) >= fabsl(offset) * (1.0L - 1e-12L) &&
              fabsl(moved) <= fabsl(offset) + (long double)(nextafterf(fabsf(shifted[10]), INFINITY) -
                                                            fabsf(shifted[10])),
          "offset case %zu: element 10 moved %Lg for an exact offset %Lg", c, moved, offset);
  }
  CHECK_STATUS(zshift_load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.1, -50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, NAN, -50);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, 0.1, NAN);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, INFINITY, -50);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, 0.1, -0.5);  /* pz > -n */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, 0.1, -200);  /* pz < -f */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_load_offset_matrix, -1, 1, -1, 1, 1, 100, 50, -50);    /* pz + delta == 0 */
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_load_offset_matrix, 1, 1, -1, 1, 1, 100, 0.1, -50);
}

static void test_epsilon(void) {
  double out;
  CHECK_STATUS(zshift_epsilon(0.1, 1000, 0.5, -20, &out), ZSHIFT_OK);
  CHECK(relative_error(out, reference_epsilon(0.1L, 1000, 0.5L, -20)) < 1e-14, "epsilon %.17g", out);
  CHECK(out < 0, "delta > 0 (toward the camera) must give epsilon < 0, got %g", out);
  CHECK_STATUS(zshift_epsilon(1, INFINITY, 0.5, -20, &out), ZSHIFT_OK);
  CHECK(relative_error(out, -2.0L * 0.5L / (-20.0L * -19.5L)) < 1e-14, "epsilon f=inf %.17g", out);
  CHECK_STATUS(zshift_epsilon(1, 100, 0.5, -20, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_epsilon, NAN, 100, 0.5, -20);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_epsilon, 1, 100, NAN, -20);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_epsilon, 1, 100, 0.5, -INFINITY);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_epsilon, 1, 100, 0.5, -0.5);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_epsilon, 1, 100, 30, -20);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_epsilon, 100, 1, 0.5, -20);
}

static void test_min_epsilon(void) {
  double out;
  unsigned bits;
  for (bits = 1; bits <= 32; bits += 7) {
    long double want = 2.0L / steps(bits) * (1000.0L - 0.1L) / (1000.0L + 0.1L);
    CHECK_STATUS(zshift_min_epsilon(0.1, 1000, bits, &out), ZSHIFT_OK);
    CHECK(relative_error(out, want) < 1e-14, "min_epsilon bits %u: %.17g", bits, out);
  }
  CHECK_STATUS(zshift_min_epsilon(0.1, INFINITY, 24, &out), ZSHIFT_OK);
  CHECK(relative_error(out, 2.0L / steps(24)) < 1e-15, "min_epsilon f=inf %.17g", out);
  CHECK_STATUS(zshift_min_epsilon(1, 100, 24, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_epsilon, 1, 100, 0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_epsilon, 1, 100, 33);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_min_epsilon, NAN, 100, 24);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_epsilon, 0, 100, 24);
}

static void test_deltas(void) {
  double toward, away, resolution;
  long double k = reference_k(0.1L, 1000, 16), pz = -300;
  CHECK_STATUS(zshift_min_delta_toward(0.1, 1000, 16, -300, &toward), ZSHIFT_OK);
  CHECK(relative_error(toward, k * pz * pz / (1 - k * pz)) < 1e-13, "min_delta_toward %.17g", toward);
  /* Seeds 000 (with 002) and 001 agree: the minimum shift is Walker's depth step at d = -pz. */
  CHECK_STATUS(zshift_depth_resolution(0.1, 1000, 16, 300, &resolution), ZSHIFT_OK);
  CHECK(relative_error(toward, resolution) < 1e-13, "min_delta_toward %.17g vs depth_resolution %.17g",
        toward, resolution);
  pz = -2;
  CHECK_STATUS(zshift_max_delta_away(0.1, 1000, 16, -2, &away), ZSHIFT_OK);
  CHECK(relative_error(away, -k * pz * pz / (1 + k * pz)) < 1e-12 && away < 0, "max_delta_away %.17g", away);
  /* With 1 bit, k*|pz| >= 1 far from the camera: no shift away can change the stored depth. */
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_UNRESOLVABLE, zshift_max_delta_away, 1, 1e6, 1, -1e5);
  CHECK_STATUS(zshift_min_delta_toward(1, 100, 24, -50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_max_delta_away(1, 100, 24, -50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_delta_toward, 1, 100, 24, -101);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_delta_toward, 1, 100, 24, 50);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_delta_toward, 1, 100, 0, -50);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_min_delta_toward, 1, 100, 24, NAN);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_max_delta_away, 1, 100, 24, -0.5);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_max_delta_away, NAN, 100, 24, -50);
}

static void test_precision(void) {
  double depth, step, before;
  CHECK_STATUS(zshift_window_depth(1, 100, 1, &depth), ZSHIFT_OK);
  CHECK(depth == 0.0, "window depth at the near plane is %.17g, not 0", depth);
  CHECK_STATUS(zshift_window_depth(1, 100, 100, &depth), ZSHIFT_OK);
  CHECK(fabs(depth - 1.0) < 1e-15, "window depth at the far plane is %.17g, not 1", depth);
  CHECK_STATUS(zshift_window_depth(0.1, 1000, 37, &depth), ZSHIFT_OK);
  CHECK(relative_error(depth, reference_window_depth(0.1L, 1000, 37)) < 1e-14, "window depth %.17g", depth);
  /* One depth step back from d lowers the window depth by exactly one quantum (Walker's eq. 3). */
  CHECK_STATUS(zshift_depth_resolution(0.1, 1000, 16, 300, &step), ZSHIFT_OK);
  CHECK_STATUS(zshift_window_depth(0.1, 1000, 300, &depth), ZSHIFT_OK);
  CHECK_STATUS(zshift_window_depth(0.1, 1000, 300 - step, &before), ZSHIFT_OK);
  CHECK(fabs((depth - before) * (double)steps(16) - 1.0) < 1e-9, "one step moves window depth by %.17g quanta",
        (depth - before) * (double)steps(16));
  CHECK_STATUS(zshift_window_depth(1, 100, 50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_depth_resolution(1, 100, 24, 50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_window_depth, 1, 100, 0.5);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_window_depth, 1, 100, 101);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_window_depth, 1, 100, NAN);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_depth_resolution, 1, 100, 33, 50);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_depth_resolution, 1, 100, 24, 0.5);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_depth_resolution, 1, NAN, 24, 50);
}

/* ---- projections for every clip convention, Kooima's median, bias conversions, planning ---- */

/* Runs a call writing `count` doubles on a pattern-filled buffer; it must fail with `expected`
 * and write nothing. */
#define CHECK_ARRAY_ERROR(expected, count, fn, ...)                                           \
  do {                                                                                        \
    double out_[count];                                                                       \
    memset(out_, PATTERN, sizeof out_);                                                       \
    CHECK_STATUS(fn(__VA_ARGS__, out_), expected);                                            \
    CHECK(untouched(out_, sizeof out_), "%s(%s) wrote its output on error", #fn, #__VA_ARGS__); \
  } while (0)

static void check_matrix_within_one_ulp(const float *got, const long double want[16], const char *what) {
  int i;
  for (i = 0; i < 16; i++)
    CHECK(within_one_float_ulp(got[i], want[i]), "%s element %d: %.9g vs %.12Lg", what, i, (double)got[i], want[i]);
}

static void test_projections(void) {
  const ZshiftClip clips[] = {ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_CLIP_ZERO_TO_ONE,
                              ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE};
  const long double n = 0.5L, f = 200.0L;
  long double want[16];
  float out[16], plain[16], shifted[16], gl[16];
  size_t c;
  int i;

  /* gluPerspective(fovy, aspect, n, f): m0 = cot(fovy/2)/aspect, m5 = cot(fovy/2). */
  CHECK_STATUS(zshift_perspective(60.0, 1.5, 0.5, 200.0, out), ZSHIFT_OK);
  reference_frustum(-1, 1, -1, 1, n, f, want);
  want[5] = 1.0L / tanl(30.0L * 3.14159265358979323846264338327950288L / 180.0L);
  want[0] = want[5] / 1.5L;
  check_matrix_within_one_ulp(out, want, "zshift_perspective");
  CHECK_STATUS(zshift_perspective(60.0, 1.5, 0.5, 200.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_perspective, NAN, 1.5, 0.5, 200.0);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_perspective, 180.0, 1.5, 0.5, 200.0);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_perspective, 60.0, 0.0, 0.5, 200.0);

  /* The depth row of each clip convention, as the header states it. */
  for (c = 0; c < 3; c++) {
    reference_frustum(-1, 1, -0.75L, 0.75L, n, f, want);
    if (clips[c].value == ZSHIFT_CLIP_ZERO_TO_ONE.value) {
      want[10] = -f / (f - n);
      want[14] = -f * n / (f - n);
    } else if (clips[c].value == ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE.value) {
      want[10] = n / (f - n);
      want[14] = f * n / (f - n);
    }
    CHECK_STATUS(zshift_projection(-1, 1, -0.75, 0.75, 0.5, 200.0, clips[c], out), ZSHIFT_OK);
    check_matrix_within_one_ulp(out, want, "zshift_projection");
    /* Offset toward the camera: only element 10 (element 14 when reversed) moves. */
    CHECK_STATUS(zshift_offset_projection(-1, 1, -0.75, 0.75, 0.5, 200.0, clips[c], 0.5, -50.0, shifted),
                 ZSHIFT_OK);
    for (i = 0; i < 16; i++) {
      int moving = clips[c].value == ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE.value ? 14 : 10;
      CHECK(i == moving ? shifted[i] != out[i] : shifted[i] == out[i],
            "zshift_offset_projection clip %d element %d (moving element %d)", (int)clips[c].value, i, moving);
    }
  }
  /* Under [-1, 1] the offset matrix is Lengyel's: element 10 moves up by at least |m10 * epsilon|. */
  CHECK_STATUS(zshift_projection(-1, 1, -0.75, 0.75, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, plain), ZSHIFT_OK);
  CHECK_STATUS(zshift_offset_projection(-1, 1, -0.75, 0.75, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50.0,
                                        shifted),
               ZSHIFT_OK);
  CHECK((long double)shifted[10] - plain[10] >=
            fabsl(-(f + n) / (f - n) * reference_epsilon(n, f, 0.5L, -50.0L)) * (1.0L - 1e-12L),
        "zshift_offset_projection moved element 10 by %g", (double)(shifted[10] - plain[10]));
  CHECK_STATUS(zshift_projection(-1, 1, -1, 1, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_projection, -1, 1, -1, 1, 1, 100, clip_value(3));
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_projection, -1, 1, -1, NAN, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE);
  CHECK_STATUS(zshift_offset_projection(-1, 1, -1, 1, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_offset_projection, -1, 1, -1, 1, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NAN, -50);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_offset_projection, -1, 1, -1, 1, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -0.5);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_offset_projection, -1, 1, -1, 1, 1, 100, clip_value(7), 0.5, -50);

  /* zshift_offset_perspective is zshift_offset_projection on gluPerspective's frustum. */
  CHECK_STATUS(zshift_perspective(60.0, 1.5, 0.5, 200.0, gl), ZSHIFT_OK);
  CHECK_STATUS(zshift_offset_perspective(60.0, 1.5, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50.0, out),
               ZSHIFT_OK);
  for (i = 0; i < 16; i++)
    if (i != 10) CHECK(out[i] == gl[i], "zshift_offset_perspective element %d differs from zshift_perspective's", i);
  CHECK(out[10] > gl[10], "zshift_offset_perspective did not move element 10 toward the camera");
  CHECK_STATUS(zshift_offset_perspective(60, 1.5, 0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_offset_perspective, 0.0, 1.5, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50.0);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_offset_perspective, 60.0, NAN, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50.0);

  /* Tweaked infinite projection: m10 = tweak - 1, m14 = (tweak - 2) n. */
  CHECK_STATUS(zshift_tweaked_infinite(-1, 1, -1, 1, 0.5, ZSHIFT_MIN_INFINITE_TWEAK, plain), ZSHIFT_OK);
  reference_frustum(-1, 1, -1, 1, n, 1, want);
  want[10] = (long double)ZSHIFT_MIN_INFINITE_TWEAK - 1.0L;
  want[14] = ((long double)ZSHIFT_MIN_INFINITE_TWEAK - 2.0L) * n;
  check_matrix_within_one_ulp(plain, want, "zshift_tweaked_infinite");
  CHECK(ZSHIFT_MIN_INFINITE_TWEAK == ldexp(1.0, -22), "ZSHIFT_MIN_INFINITE_TWEAK is not 2^-22");
  CHECK_STATUS(zshift_offset_tweaked_infinite(-1, 1, -1, 1, 0.5, ZSHIFT_MIN_INFINITE_TWEAK, 10.0, -1000.0, shifted),
               ZSHIFT_OK);
  for (i = 0; i < 16; i++)
    if (i != 10) CHECK(shifted[i] == plain[i], "zshift_offset_tweaked_infinite element %d moved", i);
  CHECK(shifted[10] != plain[10], "zshift_offset_tweaked_infinite did not move element 10");
  CHECK_STATUS(zshift_tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_tweaked_infinite, -1, 1, -1, 1, 0.5, 1.0);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_tweaked_infinite, -1, 1, -1, 1, 0.5, NAN);
  CHECK_STATUS(zshift_offset_tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0, 1, -10, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_DOMAIN, zshift_offset_tweaked_infinite, -1, 1, -1, 1, 0.5, 0.0, 1.0, -0.25);
  CHECK_MATRIX_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_offset_tweaked_infinite, -1, 1, -1, 1, 0.5, 0.0, NAN, -10.0);
}

static void test_clip_precision(void) {
  const long double n = 0.5L, f = 200.0L, d = 37.0L;
  double out, walker, reference;
  /* Window depth: Walker's under [-1, 1] and [0, 1], n(f - d)/((f - n)d) reversed. */
  CHECK_STATUS(zshift_window_depth(0.5, 200.0, 37.0, &walker), ZSHIFT_OK);
  CHECK_STATUS(zshift_window_depth_clip(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 37.0, &out), ZSHIFT_OK);
  CHECK(out == walker, "window_depth_clip [-1, 1] %.17g vs window_depth %.17g", out, walker);
  CHECK_STATUS(zshift_window_depth_clip(0.5, 200.0, ZSHIFT_CLIP_ZERO_TO_ONE, 37.0, &out), ZSHIFT_OK);
  CHECK(out == walker, "window_depth_clip [0, 1] %.17g vs window_depth %.17g", out, walker);
  CHECK_STATUS(zshift_window_depth_clip(0.5, 200.0, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, 37.0, &out), ZSHIFT_OK);
  CHECK(relative_error(out, n * (f - d) / ((f - n) * d)) < 1e-15, "reversed window depth %.17g", out);
  CHECK_STATUS(zshift_window_depth_clip(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_window_depth_clip, 0.5, 200.0, clip_value(5), 37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_window_depth_clip, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 300.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_window_depth_clip, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NAN);

  /* Depth step: Walker's eq. 3 for UNORM under [-1, 1] (zshift_depth_resolution). */
  CHECK_STATUS(zshift_depth_resolution(0.5, 200.0, 24, 37.0, &reference), ZSHIFT_OK);
  CHECK_STATUS(zshift_depth_step(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, &out),
               ZSHIFT_OK);
  CHECK(relative_error(out, reference) < 1e-15, "depth_step %.17g vs depth_resolution %.17g", out, reference);
  CHECK_STATUS(zshift_depth_step(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_depth_step, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, format_value(9), 37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_depth_step, NAN, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0);

  /* Kooima's median projection (seed 003): window depth d/(d + median). */
  {
    const long double median = 10.0L, r = 1.0L / steps(24), dm = d + median;
    CHECK_STATUS(zshift_median_depth_step(10.0, ZSHIFT_FORMAT_UNORM24, 37.0, &out), ZSHIFT_OK);
    CHECK(relative_error(out, r * dm * dm / (median + r * dm)) < 1e-14, "median_depth_step %.17g", out);
    CHECK_STATUS(zshift_median_ndc_offset(10.0, 0.5, -37.0, &out), ZSHIFT_OK);
    CHECK(relative_error(out, -2.0L * median * 0.5L / (dm * (dm - 0.5L))) < 1e-14, "median_ndc_offset %.17g", out);
  }
  CHECK_STATUS(zshift_median_depth_step(10.0, ZSHIFT_FORMAT_UNORM24, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_median_depth_step, 0.0, ZSHIFT_FORMAT_UNORM24, 37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_median_depth_step, 10.0, ZSHIFT_FORMAT_UNORM24, NAN);
  CHECK_STATUS(zshift_median_ndc_offset(10.0, 0.5, -37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_median_ndc_offset, -1.0, 0.5, -37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_median_ndc_offset, 10.0, 0.5, 1.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_median_ndc_offset, 10.0, NAN, -37.0);

  /* Minimum offsets: seed 002's NDC quantum and eq. 4.1.8 under [-1, 1]. */
  CHECK_STATUS(zshift_min_ndc_offset(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, &out),
               ZSHIFT_OK);
  CHECK(relative_error(out, 2.0L / steps(24)) < 1e-15, "min_ndc_offset %.17g", out);
  CHECK_STATUS(zshift_min_epsilon(0.5, 200.0, 24, &reference), ZSHIFT_OK);
  CHECK_STATUS(zshift_min_epsilon_clip(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, &out),
               ZSHIFT_OK);
  CHECK(relative_error(out, reference) < 1e-15, "min_epsilon_clip %.17g vs min_epsilon %.17g", out, reference);
  CHECK_STATUS(zshift_min_epsilon_clip(0.5, 200.0, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, &out),
               ZSHIFT_OK);
  CHECK(relative_error(out, 1.0L / steps(24) * (f - n) / f) < 1e-15, "min_epsilon_clip [0, 1] %.17g", out);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_UNRESOLVABLE, zshift_min_epsilon_clip, 0.5, INFINITY,
                     ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, ZSHIFT_FORMAT_FLOAT32, 37.0);
  CHECK_STATUS(zshift_min_relative_epsilon(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, &out),
               ZSHIFT_OK);
  CHECK(relative_error(out, 1.0L / steps(24) * d / (f * n / (f - n))) < 1e-14, "min_relative_epsilon %.17g", out);
  CHECK_STATUS(zshift_min_ndc_offset(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_min_epsilon_clip(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_min_relative_epsilon(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_ndc_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, 300.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_min_epsilon_clip, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, format_value(4), 37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_min_relative_epsilon, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, NAN);
}

static void test_bias_and_planning(void) {
  double bias, shift, planes[2], range[3];
  /* A shift toward the camera is a negative bias under [-1, 1]; the inverse gives it back. */
  CHECK_STATUS(zshift_bias_of_shift(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL,
                                    0.25, -37.0, &bias),
               ZSHIFT_OK);
  CHECK(bias < 0, "bias_of_shift toward the camera under [-1, 1] is %g, expected negative", bias);
  CHECK_STATUS(zshift_shift_of_bias(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL,
                                    bias, -37.0, &shift),
               ZSHIFT_OK);
  CHECK(fabs(shift - 0.25) < 1e-9, "shift_of_bias(bias_of_shift(0.25)) = %.17g", shift);
  CHECK_STATUS(zshift_bias_of_shift(0.5, 200.0, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, ZSHIFT_FORMAT_FLOAT32,
                                    ZSHIFT_BIAS_VULKAN, 0.25, -37.0, &bias),
               ZSHIFT_OK);
  CHECK(bias > 0, "bias_of_shift reversed is %g, expected positive", bias);
  CHECK_STATUS(zshift_bias_of_shift(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL, 0.25, -37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_shift_of_bias(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL, -1.0, -37.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_bias_of_shift, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, api_value(3), 0.25, -37.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_DOMAIN, zshift_bias_of_shift, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL, 0.25, -300.0);
  CHECK_SCALAR_ERROR(ZSHIFT_ERR_NOT_FINITE, zshift_shift_of_bias, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL, NAN, -37.0);

  /* Tight planes enclose the scene. */
  CHECK_STATUS(zshift_tight_planes(2.0, 500.0, planes), ZSHIFT_OK);
  CHECK(planes[0] > 0 && planes[0] <= 2.0 && planes[1] >= 500.0, "tight planes [%g, %g] for [2, 500]", planes[0],
        planes[1]);
  CHECK_STATUS(zshift_tight_planes(2.0, 500.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_DOMAIN, 2, zshift_tight_planes, 500.0, 2.0);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_DOMAIN, 2, zshift_tight_planes, 0.0, 2.0);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_NOT_FINITE, 2, zshift_tight_planes, NAN, 2.0);

  /* One offset for a depth range: at least the steps asked for at both ends. */
  CHECK_STATUS(zshift_range_offset(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC,
                                   10.0, 100.0, 2.0, range),
               ZSHIFT_OK);
  {
    /* Two window steps 2q at distance d are the eye shift 2q d^2/(b + 2q d), b = fn/(f - n)
     * (Walker's eq. 3 with the step doubled). */
    const long double q2 = 2.0L / steps(24), b = 200.0L * 0.5L / (200.0L - 0.5L);
    const long double at_lo = q2 * 100.0L / (b + q2 * 10.0L), at_hi = q2 * 10000.0L / (b + q2 * 100.0L);
    /* out[0] is signed: toward the camera is toward NDC -1 under [-1, 1]. */
    CHECK(range[0] < 0 && range[1] >= at_lo * (1 - 1e-12L) && range[2] >= at_hi * (1 - 1e-12L),
          "range_offset %g shifts %.17g at 10 and %.17g at 100 (2 steps: %.17Lg, %.17Lg)", range[0], range[1],
          range[2], at_lo, at_hi);
  }
  CHECK_STATUS(zshift_range_offset(0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 10.0, 100.0, 2.0, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_DOMAIN, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 100.0, 10.0, 2.0);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_DOMAIN, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 10.0, 100.0, 0.5);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_DOMAIN, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, kind_value(9), 10.0, 100.0, 2.0);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_NOT_FINITE, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 10.0, 100.0, NAN);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_NOT_FINITE, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, NAN, 100.0, 2.0);
  CHECK_ARRAY_ERROR(ZSHIFT_ERR_NOT_FINITE, 3, zshift_range_offset, 0.5, 200.0, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 10.0, INFINITY, 2.0);
}

/* ---- the recommendation (zshift_recommend, zshift_recommend_matrix) ---- */

static ZshiftScene sloped_scene(void) {
  ZshiftScene s;
  memset(&s, 0, sizeof s);
  s.l = -0.1;
  s.r = 0.1;
  s.b = -0.075;
  s.t = 0.075;
  s.n = 0.1;
  s.f = 1000;
  s.viewport_width = 256;
  s.viewport_height = 192;
  s.depth_format = 0x81A6; /* GL_DEPTH_COMPONENT24 */
  s.decal_near = 40;
  s.decal_far = 60;
  s.slope = 1.0;
  s.exact_depth = 0;
  s.subpixel_bits = 8;
  return s;
}

static ZshiftRecommendation recommend_ok(const ZshiftScene *scene, const char *what) {
  ZshiftRecommendation r;
  memset(&r, 0, sizeof r);
  CHECK(zshift_recommend(scene, &r) == ZSHIFT_OK, "zshift_recommend(%s) failed", what);
  return r;
}

/* The recommendation's parts must be the sums and conversions its header documents. */
static void check_recommendation_consistent(const ZshiftScene *s, const ZshiftRecommendation *r,
                                            const char *what) {
  long double m10 = (s->f + (long double)s->n) / (s->f - (long double)s->n);
  double eps_of_delta;
  long double window = r->quantum + 2.0L * ((long double)r->transform + r->vertex + r->interpolation + r->snap);
  CHECK(relative_error(r->window_offset, window) < 1e-15, "%s: window_offset %.17g is not q + 2(T+V+I+S)",
        what, r->window_offset);
  CHECK(r->ndc_offset == 2.0 * r->window_offset, "%s: ndc_offset is not 2 * window_offset", what);
  CHECK(r->epsilon < 0 && relative_error(r->epsilon, -(long double)r->ndc_offset / m10) < 1e-14,
        "%s: epsilon %.17g is not -ndc_offset/|m10|", what, r->epsilon);
  CHECK(zshift_epsilon(s->n, s->f, r->delta_at_far, -s->decal_far, &eps_of_delta) == ZSHIFT_OK &&
            relative_error(eps_of_delta, r->epsilon) < 1e-12,
        "%s: delta_at_far %.17g at pz = -decal_far gives epsilon %.17g, not %.17g", what, r->delta_at_far,
        eps_of_delta, r->epsilon);
  CHECK(r->delta_at_far > 0 && r->bleed_gap > 0, "%s: delta_at_far %g, bleed_gap %g", what, r->delta_at_far,
        r->bleed_gap);
}

static void test_recommend(void) {
  ZshiftScene s = sloped_scene(), t;
  ZshiftRecommendation snapped, unsnapped, flat, exact, d16, steeper;
  float plain[16], decal[16];
  long double offset, moved;
  int i;

  CHECK(ZSHIFT_SUBPIXEL_UNSNAPPED == -1, "ZSHIFT_SUBPIXEL_UNSNAPPED is %d", ZSHIFT_SUBPIXEL_UNSNAPPED);
  snapped = recommend_ok(&s, "sloped, 8 subpixel bits");
  check_recommendation_consistent(&s, &snapped, "sloped, 8 subpixel bits");
  CHECK(relative_error(snapped.quantum, 1.0L / steps(24)) < 1e-15, "D24 quantum %.17g", snapped.quantum);
  CHECK(snapped.snap > 0 && snapped.polygon_offset_factor == ldexp(1.0, 1 - 8),
        "snapping with 8 bits: snap %g, glPolygonOffset factor %g (expected 2^-7)", snapped.snap,
        snapped.polygon_offset_factor);

  t = s;
  t.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
  unsnapped = recommend_ok(&t, "unsnapped");
  {
    /* The same through a profile: ZshiftScene.profile wins over subpixel_bits (still 8 in s). */
    ZshiftProfile profile;
    ZshiftRecommendation profiled;
    CHECK_STATUS(zshift_profile_worst_case(&profile), ZSHIFT_OK);
    profile.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
    t = s;
    t.profile = &profile;
    profiled = recommend_ok(&t, "unsnapped through a profile");
    CHECK(profiled.window_offset == unsnapped.window_offset && profiled.snap == 0,
          "profile: offset %.17g, unsnapped scene %.17g", profiled.window_offset, unsnapped.window_offset);
  }
  check_recommendation_consistent(&t, &unsnapped, "unsnapped");
  CHECK(unsnapped.snap == 0 && unsnapped.polygon_offset_factor == 0 && unsnapped.window_offset < snapped.window_offset,
        "unsnapped: snap %g factor %g offset %g (snapped %g)", unsnapped.snap, unsnapped.polygon_offset_factor,
        unsnapped.window_offset, snapped.window_offset);

  t = s;
  t.slope = 3.0;
  steeper = recommend_ok(&t, "slope 3");
  CHECK(steeper.window_offset > snapped.window_offset, "a steeper plane needs a larger offset (%g vs %g)",
        steeper.window_offset, snapped.window_offset);

  t = s;
  t.slope = 0.0;
  flat = recommend_ok(&t, "facing");
  t.exact_depth = 1;
  exact = recommend_ok(&t, "facing, exact depth");
  check_recommendation_consistent(&t, &exact, "facing, exact depth");
  CHECK(flat.snap == 0 && exact.vertex == 0 && exact.interpolation == 0 && exact.window_offset < flat.window_offset,
        "facing plane: snap %g; exact depth: vertex %g interpolation %g", flat.snap, exact.vertex,
        exact.interpolation);

  t = s;
  t.depth_format = 0x81A5; /* GL_DEPTH_COMPONENT16 */
  d16 = recommend_ok(&t, "D16");
  CHECK(relative_error(d16.quantum, 1.0L / steps(16)) < 1e-15 && d16.window_offset > snapped.window_offset,
        "D16 quantum %.17g", d16.quantum);
  t.depth_format = 0x8CAC; /* GL_DEPTH_COMPONENT32F */
  (void)recommend_ok(&t, "D32F");
  t.f = INFINITY;
  (void)recommend_ok(&t, "D32F, infinite far plane");

  /* The matrix: zshift_frustum's, with element 10 moved by at least |m10 * epsilon| toward the
   * camera and by at most one float ulp more. */
  CHECK_STATUS(zshift_recommend_matrix(&s, decal), ZSHIFT_OK);
  CHECK_STATUS(zshift_frustum(s.l, s.r, s.b, s.t, s.n, s.f, plain), ZSHIFT_OK);
  for (i = 0; i < 16; i++)
    if (i != 10) CHECK(decal[i] == plain[i], "recommend_matrix element %d differs from zshift_frustum's", i);
  offset = -(s.f + (long double)s.n) / (s.f - (long double)s.n) * snapped.epsilon;
  moved = (long double)decal[10] - (long double)plain[10];
  CHECK(moved > 0 && moved >= offset * (1.0L - 1e-12L) &&
            moved <= offset + (long double)(nextafterf(fabsf(decal[10]), INFINITY) - fabsf(decal[10])),
        "recommend_matrix moved element 10 by %Lg for an exact offset %Lg", moved, offset);

  /* Errors: NULL pointers, NaN, domain; the output untouched. */
  {
    ZshiftRecommendation out;
    float m[16];
    CHECK_STATUS(zshift_recommend(NULL, &out), ZSHIFT_ERR_NULL_POINTER);
    CHECK_STATUS(zshift_recommend(&s, NULL), ZSHIFT_ERR_NULL_POINTER);
    CHECK_STATUS(zshift_recommend_matrix(NULL, m), ZSHIFT_ERR_NULL_POINTER);
    CHECK_STATUS(zshift_recommend_matrix(&s, NULL), ZSHIFT_ERR_NULL_POINTER);
  }
#define CHECK_SCENE_ERROR(expected, field, value)                                                \
  do {                                                                                           \
    ZshiftRecommendation out_;                                                                   \
    float m_[16];                                                                                \
    t = s;                                                                                       \
    t.field = value;                                                                             \
    memset(&out_, PATTERN, sizeof out_);                                                         \
    memset(m_, PATTERN, sizeof m_);                                                              \
    CHECK_STATUS(zshift_recommend(&t, &out_), expected);                                         \
    CHECK_STATUS(zshift_recommend_matrix(&t, m_), expected);                                     \
    CHECK(untouched(&out_, sizeof out_) && untouched(m_, sizeof m_),                             \
          "zshift_recommend with %s = %s wrote its output on error", #field, #value);            \
  } while (0)
  CHECK_SCENE_ERROR(ZSHIFT_ERR_NOT_FINITE, slope, NAN);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_NOT_FINITE, decal_far, NAN);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_NOT_FINITE, l, NAN);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, slope, -1.0);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, exact_depth, 1);      /* with slope 1 */
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, depth_format, 0x1234);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, viewport_width, 0);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, decal_near, 0.05);     /* nearer than n */
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, decal_near, 70.0);     /* beyond decal_far */
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, decal_far, 2000.0);    /* beyond f */
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, subpixel_bits, -2);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, subpixel_bits, 33);
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, r, -0.1);             /* l == r */
  CHECK_SCENE_ERROR(ZSHIFT_ERR_DOMAIN, n, 0.0);
#undef CHECK_SCENE_ERROR
}

/* ---- the recommendation per clip convention (zshift_recommend_clip, _matrix) ---- */

static void test_recommend_clip(void) {
  ZshiftScene s = sloped_scene(), rev;
  ZshiftRecommendation std_, c, z, r, out;
  float a[16], b[16], plain[16];
  long double moved, ratio;
  int i;

  /* NEG_ONE_TO_ONE is zshift_recommend, matrix included. */
  std_ = recommend_ok(&s, "clip reference");
  CHECK_STATUS(zshift_recommend_clip(&s, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &c), ZSHIFT_OK);
  CHECK(memcmp(&c, &std_, sizeof c) == 0, "recommend_clip(NEG_ONE_TO_ONE) differs from recommend");
  CHECK_STATUS(zshift_recommend_matrix(&s, a), ZSHIFT_OK);
  CHECK_STATUS(zshift_recommend_clip_matrix(&s, ZSHIFT_CLIP_NEG_ONE_TO_ONE, b), ZSHIFT_OK);
  CHECK(memcmp(a, b, sizeof a) == 0, "recommend_clip_matrix(NEG_ONE_TO_ONE) differs from recommend_matrix");

  /* ZERO_TO_ONE: (R1) in window depth = NDC depth, carried by element 10 of zshift_projection's
   * [0,1] matrix, lowered by at least the offset and at most one float ulp more. */
  CHECK_STATUS(zshift_recommend_clip(&s, ZSHIFT_CLIP_ZERO_TO_ONE, &z), ZSHIFT_OK);
  CHECK(relative_error(z.window_offset, z.quantum + 2.0L * ((long double)z.transform + z.vertex +
                                                            z.interpolation + z.snap)) < 1e-15 &&
            z.ndc_offset == z.window_offset && z.epsilon < 0,
        "[0,1]: window_offset %.17g ndc_offset %.17g epsilon %g", z.window_offset, z.ndc_offset, z.epsilon);
  CHECK_STATUS(zshift_recommend_clip_matrix(&s, ZSHIFT_CLIP_ZERO_TO_ONE, a), ZSHIFT_OK);
  CHECK_STATUS(zshift_projection(s.l, s.r, s.b, s.t, s.n, s.f, ZSHIFT_CLIP_ZERO_TO_ONE, plain), ZSHIFT_OK);
  for (i = 0; i < 16; i++)
    if (i != 10) CHECK(a[i] == plain[i], "[0,1] recommend_clip_matrix element %d differs", i);
  moved = (long double)a[10] - (long double)plain[10];
  CHECK(moved >= z.ndc_offset && moved <= z.ndc_offset + (nextafterf(fabsf(plain[10]), INFINITY) - fabsf(plain[10])),
        "[0,1]: element 10 moved by %Lg for an offset %g", moved, z.ndc_offset);

  /* REVERSED, D32F, infinite far: element 10 is 0, element 14 scaled by at least 1 + epsilon. */
  rev = s;
  rev.depth_format = 0x8CAC;
  rev.f = INFINITY;
  CHECK_STATUS(zshift_recommend_clip(&rev, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, &r), ZSHIFT_OK);
  CHECK(r.epsilon > 0 && r.polygon_offset_factor == 0 && r.polygon_offset_units == 0 && r.bleed_gap > 0,
        "reversed: epsilon %g, polygon offset %g %g, gap %g", r.epsilon, r.polygon_offset_factor,
        r.polygon_offset_units, r.bleed_gap);
  /* At decal_far the window offset is epsilon * n / decal_far (window depth n/d). */
  CHECK(relative_error(r.window_offset, (long double)r.epsilon * rev.n / rev.decal_far) < 1e-14,
        "reversed: window_offset %.17g is not epsilon * n / decal_far", r.window_offset);
  CHECK_STATUS(zshift_recommend_clip_matrix(&rev, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, a), ZSHIFT_OK);
  CHECK_STATUS(zshift_projection(rev.l, rev.r, rev.b, rev.t, rev.n, rev.f, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, plain),
               ZSHIFT_OK);
  ratio = (long double)a[14] / (long double)plain[14] - 1.0L;
  CHECK(a[10] == 0.0f && plain[10] == 0.0f && ratio >= r.epsilon && ratio <= r.epsilon + 2.4e-7L,
        "reversed: element 10 %g, element 14 scaled by 1 + %Lg for epsilon %g", a[10], ratio, r.epsilon);

  /* Errors: NULL, an unknown convention; outputs untouched. */
  CHECK_STATUS(zshift_recommend_clip(NULL, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_recommend_clip(&s, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_recommend_clip_matrix(&s, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NULL), ZSHIFT_ERR_NULL_POINTER);
  memset(&out, PATTERN, sizeof out);
  memset(b, PATTERN, sizeof b);
  CHECK_STATUS(zshift_recommend_clip(&s, clip_value(3), &out), ZSHIFT_ERR_DOMAIN);
  CHECK_STATUS(zshift_recommend_clip_matrix(&s, clip_value(-1), b), ZSHIFT_ERR_DOMAIN);
  rev.slope = NAN;
  CHECK_STATUS(zshift_recommend_clip(&rev, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, &out), ZSHIFT_ERR_NOT_FINITE);
  CHECK(untouched(&out, sizeof out) && untouched(b, sizeof b), "recommend_clip wrote its output on error");
}

static void test_status_messages(void) {
  static const ZshiftStatus known[] = {ZSHIFT_OK,          ZSHIFT_ERR_NULL_POINTER, ZSHIFT_ERR_NOT_FINITE,
                                       ZSHIFT_ERR_DOMAIN,  ZSHIFT_ERR_UNRESOLVABLE, ZSHIFT_ERR_OVERFLOW,
                                       ZSHIFT_ERR_INTERNAL, ZSHIFT_ERR_GL};
  static const ZshiftStatus unknown[] = {-1, 8, INT32_MAX, INT32_MIN};
  const char *unknown_text = "unknown zshift status";
  size_t i, j;
  CHECK(ZSHIFT_OK == 0, "ZSHIFT_OK must be 0");
  for (i = 0; i < sizeof known / sizeof known[0]; i++) {
    const char *text = zshift_status_message(known[i]);
    CHECK(text != NULL && text[0] != '\0' && strcmp(text, unknown_text) != 0,
          "status %d has no message of its own", (int)known[i]);
    for (j = 0; j < i; j++)
      CHECK(text != NULL && strcmp(text, zshift_status_message(known[j])) != 0,
            "statuses %d and %d share a message", (int)known[i], (int)known[j]);
  }
  for (i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
    const char *text = zshift_status_message(unknown[i]);
    CHECK(text != NULL && strcmp(text, unknown_text) == 0, "status %d: \"%s\"", (int)unknown[i],
          text ? text : "(null)");
  }
}

static void test_versions(void) {
  const char *version = zshift_version();
  CHECK(version != NULL && strcmp(version, EXPECTED_VERSION) == 0, "zshift_version() is \"%s\", Cargo.toml says \"%s\"",
        version ? version : "(null)", EXPECTED_VERSION);
  CHECK(ZSHIFT_ABI_VERSION == 5, "ZSHIFT_ABI_VERSION is %d; this test was written for 5", ZSHIFT_ABI_VERSION);
}

/* The detail of an error names the input, its value and the rule; it is per thread, replaced by
 * each call, and empty after a success. */
static void expect_detail(const char *what, const char *needle) {
  const char *detail = zshift_last_error();
  CHECK(strstr(detail, needle) != NULL, "%s: zshift_last_error() \"%s\" does not contain \"%s\"", what, detail,
        needle);
}

static void test_last_error(void) {
  float m[16];
  double x;
  ZshiftScene scene;
  ZshiftRecommendation rec;
  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, -1, 100, m), ZSHIFT_ERR_DOMAIN);
  expect_detail("n = -1", "near plane distance n must be greater than 0 (n = -1)");
  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, 1, 100, m), ZSHIFT_OK);
  CHECK(zshift_last_error()[0] == '\0', "a success did not clear the detail");
  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, 1, 0.5, m), ZSHIFT_ERR_DOMAIN);
  expect_detail("f = 0.5", "(f = 0.5)");
  CHECK_STATUS(zshift_frustum(-1, 1, -1, 1, 1, 100, NULL), ZSHIFT_ERR_NULL_POINTER);
  expect_detail("NULL out", "`out` is NULL");
  /* zshift_status_message does not touch the detail. */
  (void)zshift_status_message(ZSHIFT_ERR_DOMAIN);
  expect_detail("after zshift_status_message", "`out` is NULL");
  CHECK_STATUS(zshift_epsilon(1, 100, NAN, -50, &x), ZSHIFT_ERR_NOT_FINITE);
  expect_detail("delta NaN", "delta is NaN or infinite (got NaN)");
  CHECK_STATUS(zshift_epsilon(1, 100, 1, -500, &x), ZSHIFT_ERR_DOMAIN);
  expect_detail("pz = -500", "(Pz = -500)");
  CHECK_STATUS(zshift_min_epsilon(1, 100, 33, &x), ZSHIFT_ERR_DOMAIN);
  expect_detail("bits = 33", "(bits = 33)");
  CHECK_STATUS(zshift_projection(-1, 1, -1, 1, 1, 100, clip_value(7), m), ZSHIFT_ERR_DOMAIN);
  expect_detail("clip 7", "(clip = 7)");
  CHECK_STATUS(zshift_depth_step(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, format_value(0x1902), 50, &x), ZSHIFT_ERR_DOMAIN);
  expect_detail("format GL_DEPTH_COMPONENT", "(format = 0x1902)");
  CHECK_STATUS(zshift_bias_of_shift(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, api_value(9), 0.1, -50, &x),
               ZSHIFT_ERR_DOMAIN);
  expect_detail("api 9", "(api = 9)");
  CHECK_STATUS(zshift_range_offset(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, kind_value(4), 2, 50, 1, &x),
               ZSHIFT_ERR_DOMAIN);
  expect_detail("kind 4", "(kind = 4)");
  CHECK_STATUS(zshift_recommend(NULL, &rec), ZSHIFT_ERR_NULL_POINTER);
  expect_detail("NULL scene", "`scene` is NULL");
  memset(&scene, 0, sizeof scene);
  CHECK_STATUS(zshift_recommend(&scene, &rec), ZSHIFT_ERR_DOMAIN);
  CHECK(strlen(zshift_last_error()) > 10, "an all-zero scene is refused with a detail");
}

/* ---- the front door: the engine's own matrix in, the decal's matrix out ---- */

/* glm::perspective (right-handed, [-1, 1]) as an engine computes it, in float. */
static void engine_perspective(float fovy, float aspect, float n, float f, float m[16]) {
  const float t = (float)tan(fovy / 2.0f);
  int i;
  for (i = 0; i < 16; i++) m[i] = 0.0f;
  m[0] = 1.0f / (aspect * t);
  m[5] = 1.0f / t;
  m[10] = -(f + n) / (f - n);
  m[11] = -1.0f;
  m[14] = -(2.0f * f * n) / (f - n);
}

static int only_element_changed(const float *m, const float *out, int element) {
  int i;
  for (i = 0; i < 16; i++)
    if (i != element && memcmp(&m[i], &out[i], sizeof(float)) != 0) return 0;
  return out[element] != m[element];
}

static long double float_ulp(float x) {
  float a = fabsf(x);
  return (long double)nextafterf(a, INFINITY) - a;
}

static void test_front_door(void) {
  float m[16], rev[16], ortho[16], out[16];
  ZshiftDecal decal;
  ZshiftRecommendation rec;
  const long double delta = 0.25L, d = 37.0L;
  long double seen, want;
  int i;
  engine_perspective(1.0471976f, 1.5f, 0.1f, 1000.0f, m);
  /* Eye shift through element 10: z_ndc = -m10 + m14/d, so the change is m14 delta/(d(d - delta)). */
  CHECK_STATUS(zshift_offset_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.25, 37.0, out), ZSHIFT_OK);
  CHECK(only_element_changed(m, out, 10), "zshift_offset_matrix changed more than element 10");
  seen = -((long double)out[10] - m[10]);
  want = (long double)m[14] * delta / (d * (d - delta));
  CHECK(seen <= want * (1 - 1e-15L) && want - seen <= float_ulp(out[10]) * (1 + 1e-12L),
        "zshift_offset_matrix: NDC change %.20Lg for %.20Lg asked", seen, want);
  /* Reversed Z (glm::perspectiveRH_ZO(fovy, aspect, f, n)): element 14 scaled by 1 + delta/(d - delta). */
  memcpy(rev, m, sizeof rev);
  rev[10] = 0.1f / (1000.0f - 0.1f);
  rev[14] = 1000.0f * 0.1f / (1000.0f - 0.1f);
  CHECK_STATUS(zshift_offset_matrix(rev, ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE, 0.25, 37.0, out), ZSHIFT_OK);
  CHECK(only_element_changed(rev, out, 14), "reversed: more than element 14 changed");
  CHECK((long double)out[14] - rev[14] >= rev[14] * delta / (d - delta) * (1 - 1e-15L),
        "reversed: element 14 moved by %.20Lg", (long double)out[14] - rev[14]);
  /* Orthographic (glOrtho): element 14 moves by m10 * delta. */
  for (i = 0; i < 16; i++) ortho[i] = 0.0f;
  ortho[0] = 0.05f, ortho[5] = 0.1f, ortho[10] = -2.0f / 499.0f, ortho[14] = -501.0f / 499.0f, ortho[15] = 1.0f;
  CHECK_STATUS(zshift_offset_matrix(ortho, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.25, 37.0, out), ZSHIFT_OK);
  CHECK(only_element_changed(ortho, out, 14), "orthographic: more than element 14 changed");
  CHECK((long double)out[14] - ortho[14] <= (long double)ortho[10] * delta * (1 - 1e-15L),
        "orthographic: element 14 moved by %.20Lg", (long double)out[14] - ortho[14]);
  /* The decal matrix from a ZshiftDecal. */
  memset(&decal, 0, sizeof decal);
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("all-zero ZshiftDecal", "viewport_width");
  decal.viewport_width = 1280;
  decal.viewport_height = 720;
  decal.format = ZSHIFT_FORMAT_UNORM24;
  decal.subpixel_bits = 8;
  decal.decal_near = 40.0;
  decal.decal_far = 60.0;
  decal.slope = 1.0;
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_OK);
  CHECK(only_element_changed(m, out, 10) && out[10] > m[10], "zshift_decal_matrix: element 10 %g from %g",
        (double)out[10], (double)m[10]);
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &rec), ZSHIFT_OK);
  CHECK(rec.window_offset > rec.quantum && rec.delta_at_far > 0, "recommend_for_matrix: window offset %g",
        rec.window_offset);
  CHECK_STATUS(zshift_decal_matrix(ortho, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_OK);
  CHECK(only_element_changed(ortho, out, 14), "zshift_decal_matrix (orthographic): more than element 14");
  {
    /* A profile (here the worst case, told it is unsnapped with r = 2) supplies snapping and r;
       subpixel_bits is then ignored. base_reach adds the clipping term; a zeroed profile is
       refused. */
    ZshiftProfile profile, zeroed;
    ZshiftRecommendation profiled, clipped;
    CHECK_STATUS(zshift_profile_worst_case(&profile), ZSHIFT_OK);
    profile.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
    for (i = 0; i < 4; i++) profile.resolvable[i] = 2.0;
    decal.profile = &profile;
    CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &profiled), ZSHIFT_OK);
    CHECK(profiled.snap == 0 && rec.snap > 0 && profiled.window_offset < rec.window_offset,
          "a profile's snapping wins over subpixel_bits: snap %g (without %g)", profiled.snap, rec.snap);
    CHECK(relative_error(profiled.polygon_offset_units, profiled.window_offset / (2 * profiled.quantum)) < 1e-12,
          "units %g are not the offset over r = 2 quanta", profiled.polygon_offset_units);
    decal.base_reach = 1000.0;
    CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &clipped), ZSHIFT_OK);
    CHECK(clipped.clip > 0 && clipped.window_offset > profiled.window_offset, "base_reach: clip term %g",
          clipped.clip);
    decal.base_reach = -1.0;
    CHECK_STATUS(zshift_decal_matrix(ortho, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
    expect_detail("negative base_reach", "base_reach");
    decal.base_reach = 1000.0;
    profile.facing_chain = 99; /* no such chain */
    CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &clipped), ZSHIFT_ERR_DOMAIN);
    expect_detail("facing_chain 99", "facing_chain");
    CHECK(zshift_profile_worst_case(&zeroed) == ZSHIFT_OK && zeroed.facing_chain == -1,
          "the worst-case profile knows no depth chain (facing_chain %d)", (int)zeroed.facing_chain);
    profile.facing_chain = -1;
    profile.line_reach_msaa_wide_whole[1] = -1.0; /* a reach is never negative (NAN: not measured) */
    CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &clipped), ZSHIFT_ERR_DOMAIN);
    expect_detail("negative line_reach_msaa_wide_whole", "line_reach_msaa_wide_whole");
    profile.line_reach_msaa_wide_whole[1] = NAN;
    memset(&zeroed, 0, sizeof zeroed);
    decal.profile = &zeroed;
    CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
    expect_detail("zero-filled profile", "near_clip");
    decal.profile = NULL;
    decal.base_reach = 0.0;
  }
  /* Refusals, each with its detail; outputs untouched. */
  memset(out, PATTERN, sizeof out);
  CHECK_STATUS(zshift_offset_matrix(rev, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.25, 37.0, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("reversed matrix as [-1, 1]", "reversed-Z");
  CHECK_STATUS(zshift_decal_matrix(rev, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  CHECK_STATUS(zshift_offset_matrix(NULL, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.25, 37.0, out), ZSHIFT_ERR_NULL_POINTER);
  expect_detail("NULL m", "`m` is NULL");
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NULL, out), ZSHIFT_ERR_NULL_POINTER);
  expect_detail("NULL decal", "`decal` is NULL");
  CHECK_STATUS(zshift_offset_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 40.0, 37.0, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("d - delta", "d - delta");
  m[2] = 0.5f;
  CHECK_STATUS(zshift_offset_matrix_ndc(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 1e-5, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("oblique", "m[2]");
  m[2] = NAN;
  CHECK_STATUS(zshift_offset_matrix_ndc(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 1e-5, out), ZSHIFT_ERR_NOT_FINITE);
  expect_detail("NaN element", "m[2]");
  CHECK(untouched(out, sizeof out), "a refused front-door call wrote its output");
  CHECK_STATUS(zshift_ortho(-1, 1, -1, 1, 5, 5, ZSHIFT_CLIP_NEG_ONE_TO_ONE, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("ortho f = n", "(f = 5)");
}

/* A decal given by its eye-space corners: the library derives its depths and slope and where it
   lies on the screen. The derived depths and slope are checked against this file's own (the
   recommendation with corners is at most the one from the same depths and slope, which bounds
   every plane of that slope anywhere on the screen); a left-handed matrix with the corners
   mirrored in z gives the same offset; misuse is refused with its detail, outputs untouched. */
static void test_decal_corners(void) {
  float m[16], lh[16], out[16];
  /* A steep square (z = -20 - 2y) below the view axis, 2 units wide, and its mirror in z. */
  const float corners[12] = {-1.0f, -3.0f, -14.0f, 1.0f, -3.0f, -14.0f, 1.0f, -1.0f, -18.0f, -1.0f, -1.0f, -18.0f};
  float mirrored[12];
  ZshiftDecal decal;
  ZshiftRecommendation with, without, left;
  int i;
  engine_perspective(1.0471976f, 1.5f, 0.1f, 1000.0f, m);
  memcpy(lh, m, sizeof lh);
  for (i = 8; i < 12; i++) lh[i] = -m[i];
  for (i = 0; i < 12; i++) mirrored[i] = i % 3 == 2 ? -corners[i] : corners[i];
  memset(&decal, 0, sizeof decal);
  decal.viewport_width = 1280;
  decal.viewport_height = 720;
  decal.format = ZSHIFT_FORMAT_UNORM24;
  decal.subpixel_bits = 8;
  decal.decal_near = 14.0;
  decal.decal_far = 18.0;
  decal.slope = 2.0;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &without), ZSHIFT_OK);
  decal.decal_corners = corners;
  decal.decal_corner_count = 4;
  memset(out, PATTERN, sizeof out);
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("corners with decal_near", "decal_near");
  decal.decal_near = decal.decal_far = decal.slope = 0.0;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &with), ZSHIFT_OK);
  CHECK(with.window_offset <= without.window_offset && with.snap < without.snap && with.interpolation <= without.interpolation,
        "corners: window offset %g (snap %g) against %g (snap %g) from the depths and slope", with.window_offset,
        with.snap, without.window_offset, without.snap);
  /* The same quantum (the derived farthest depth); the vertex term from the decal's own plane
     (its form on eye coordinates) is no larger than the bound over every plane of that slope. */
  CHECK(with.vertex > 0.0 && with.vertex <= without.vertex && with.quantum == without.quantum,
        "corners: the derived depths differ or the vertex term grew (vertex term %g, bound %g)", with.vertex,
        without.vertex);
  decal.decal_corners = mirrored;
  CHECK_STATUS(zshift_recommend_for_matrix(lh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &left), ZSHIFT_OK);
  CHECK(relative_error(left.window_offset, with.window_offset) < 1e-9,
        "left-handed: window offset %g, right-handed %g", left.window_offset, with.window_offset);
  decal.decal_corner_count = 2;
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("two corners", "decal_corner_count");
  decal.decal_corners = NULL;
  decal.decal_corner_count = 4;
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("NULL corners with a count", "decal_corner_count");
  decal.decal_corners = mirrored; /* +z: behind a right-handed eye */
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("corners behind the eye", "wholly behind the near plane");
  expect_detail("corners behind the eye", "left-handed");
  CHECK(untouched(out, sizeof out), "a refused call with corners wrote its output");
}

/* The scene every engine draws: a 2x2 decal on the ground 1.7 below a level camera, 10 ahead,
   through the engine's own matrix, on a packed GL_DEPTH24_STENCIL8 attachment, every pass drawn
   with GL_LEQUAL, the vertices in world space through a view matrix 10^4 from the origin. A
   level camera is answered (the ground contains the view direction; its window plane is
   ordinary); the pipeline fields are checked and refused with the field named, out untouched. */
static void test_engine_scene(void) {
  float m[16], out[16], plain_out[16];
  const float corners[12] = {-1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -9.0f, 1.0f, -1.7f, -11.0f, -1.0f, -1.7f, -11.0f};
  float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1e4f, -1.7f, -1e4f, 1};
  ZshiftDecal decal;
  ZshiftRecommendation strict, equal, far_away, known;
  engine_perspective(1.0471976f, 16.0f / 9.0f, 0.1f, 1000.0f, m);
  memset(&decal, 0, sizeof decal);
  decal.viewport_width = 1920;
  decal.viewport_height = 1080;
  decal.format = ZSHIFT_FORMAT_UNORM24_STENCIL8;
  decal.subpixel_bits = 8;
  decal.decal_corners = corners;
  decal.decal_corner_count = 4;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &strict), ZSHIFT_OK);
  CHECK(strict.window_offset > 0.0 && strict.bleed_gap < 0.09, "level camera: offset %g, gap %g", strict.window_offset,
        strict.bleed_gap);
  /* GL_LEQUAL: one quantum less offset (a tie passes), one more in the gap. */
  decal.depth_func = ZSHIFT_DEPTH_TEST_LEQUAL;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &equal), ZSHIFT_OK);
  CHECK(equal.window_offset < strict.window_offset && equal.quantum == strict.quantum,
        "GL_LEQUAL: offset %g against GL_LESS's %g", equal.window_offset, strict.window_offset);
  /* World space, the camera 10^4 from the origin: the scalar bound, then the matrices. */
  decal.pipeline.world_reach = 1e4;
  decal.pipeline.eye_first = 1;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &far_away), ZSHIFT_OK);
  decal.pipeline.view_matrix = view;
  decal.pipeline.world_box[0] = 9e3;
  decal.pipeline.world_box[2] = 9e3;
  decal.pipeline.world_box[3] = 1.1e4;
  decal.pipeline.world_box[5] = 1.1e4;
  CHECK_STATUS(zshift_recommend_for_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, &known), ZSHIFT_OK);
  CHECK(equal.vertex < far_away.vertex && known.vertex < far_away.vertex,
        "world space: vertex term %g (eye space %g, with the matrices %g)", far_away.vertex, equal.vertex, known.vertex);
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, plain_out), ZSHIFT_OK);
  /* Refusals name the field; out is untouched. */
  memset(out, PATTERN, sizeof out);
  memset(decal.pipeline.world_box, 0, sizeof decal.pipeline.world_box);
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("a view matrix without its box", "world_box");
  decal.pipeline.view_matrix = NULL;
  decal.pipeline.depth_range_near = 0.7;
  decal.pipeline.depth_range_far = 0.5;
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("a reversed depth range", "depth_range_far");
  decal.pipeline.depth_range_near = 0.0;
  decal.pipeline.depth_range_far = 0.0;
  decal.pipeline.world_reach = -1.0;
  CHECK_STATUS(zshift_decal_matrix(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &decal, out), ZSHIFT_ERR_DOMAIN);
  expect_detail("a negative world_reach", "world_reach");
  CHECK(untouched(out, sizeof out), "refused engine scenes wrote their output");
}

/* Edges over their own faces: the matrix method moves only element 10 by the NDC offset it
 * reports; the polygon-offset method's factor is (w + 1)/2 and its D3D bias an integer; the
 * hidden-line gap refuses a separation below it; every error leaves the output untouched and
 * names the field. */
static ZshiftEdges edges_for(void) {
  ZshiftEdges e;
  memset(&e, 0, sizeof e);
  e.viewport_width = 512;
  e.viewport_height = 512;
  e.format = ZSHIFT_FORMAT_UNORM24;
  e.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
  e.depth_near = 10.0;
  e.depth_far = 20.0;
  e.line_width = 1.0;
  e.samples = 1;
  e.face_gradient = 1e-3;
  return e;
}

/* The steepest face of a mesh as drawn: an interleaved buffer (position, normal), a facing
 * triangle, a tilted one and one behind the camera; the tilted one's window gradient computed
 * here by projecting its vertices (long double) and fitting the plane; then passed on. */
static long double window_gradient_c(const float *m, const float *t, int w, int h) {
  long double win[3][3], gx, gy, area;
  int v, r;
  for (v = 0; v < 3; v++) {
    long double c[4];
    for (r = 0; r < 4; r++)
      c[r] = (long double)m[r] * t[6 * v] + (long double)m[4 + r] * t[6 * v + 1] +
             (long double)m[8 + r] * t[6 * v + 2] + m[12 + r];
    win[v][0] = (c[0] / c[3] + 1) / 2 * w;
    win[v][1] = (c[1] / c[3] + 1) / 2 * h;
    win[v][2] = (c[2] / c[3] + 1) / 2;
  }
  area = (win[1][0] - win[0][0]) * (win[2][1] - win[0][1]) - (win[2][0] - win[0][0]) * (win[1][1] - win[0][1]);
  gx = ((win[1][2] - win[0][2]) * (win[2][1] - win[0][1]) - (win[2][2] - win[0][2]) * (win[1][1] - win[0][1])) / area;
  gy = ((win[2][2] - win[0][2]) * (win[1][0] - win[0][0]) - (win[1][2] - win[0][2]) * (win[2][0] - win[0][0])) / area;
  return fabsl(gx) > fabsl(gy) ? fabsl(gx) : fabsl(gy);
}

static void test_steepest_face(void) {
  /* x, y, z, then a normal the call must skip (stride 24 bytes). */
  static const float verts[9][6] = {
      {-1, -1, -10, 0, 0, 1}, {1, -1, -10, 0, 0, 1}, {0, 1, -10, 0, 0, 1},
      {-1, -1, -10, 0, 0, 1}, {1, -1, -14, 0, 0, 1}, {0, 1, -10, 0, 0, 1},
      {-1, -1, 5, 0, 0, 1},   {1, -1, 5, 0, 0, 1},   {0, 1, 6, 0, 0, 1},
  };
  static const uint32_t idx[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  float m[16];
  ZshiftMesh mesh, bad;
  ZshiftSteepestFace s, out, face;
  ZshiftEdges e = edges_for();
  ZshiftEdgeOffset b, by_angle, by_mesh, untouched_offset;
  long double expected;
  engine_perspective(1.0471976f, 1.0f, 1.0f, 1000.0f, m);
  memset(&mesh, 0, sizeof mesh);
  mesh.clip_matrix = m; /* eye-space vertices: the projection is the whole clip matrix */
  mesh.positions = &verts[0][0];
  mesh.vertex_count = 9;
  mesh.position_stride = 24;
  mesh.indices = idx;
  mesh.index_count = 9;
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &s), ZSHIFT_OK);
  expected = window_gradient_c(m, &verts[3][0], 512, 512);
  CHECK(s.triangle == 1 && s.counted == 2 && s.culled == 1 && s.beyond_limit == 0,
        "steepest face: triangle %lld counted %llu culled %llu", (long long)s.triangle,
        (unsigned long long)s.counted, (unsigned long long)s.culled);
  CHECK(fabsl(s.gradient - expected) <= 1e-9L * expected, "steepest face: %.17g, by projection %.17Lg", s.gradient, expected);
  CHECK(s.length >= s.gradient && s.length <= 1.4142136 * s.gradient, "steepest face: length %g of %g", s.length, s.gradient);
  /* Below the tilted face's gradient only the facing one counts, at 0. */
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, s.gradient / 2, &out), ZSHIFT_OK);
  CHECK(out.triangle == 0 && out.gradient == 0.0 && out.beyond_limit == 1, "steepest face under a limit: %g", out.gradient);
  /* Passed on as the face gradient: the worst case's 1-pixel line term is the gradient. */
  e.depth_near = 9.0;
  e.depth_far = 15.0;
  e.face_gradient = s.gradient;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &b), ZSHIFT_OK);
  CHECK(b.face_gradient == s.gradient && b.line_term == s.gradient, "steepest face passed on: line term %g", b.line_term);
  /* The three calls in order (docs/edges.md quotes them). */
  /* 1. The angle's gradient: the limit beyond which faces are grazing (their edges not promised). */
  e.face_angle = 60.0 * 3.14159265358979 / 180.0;
  e.face_gradient = 0.0;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &by_angle), ZSHIFT_OK);
  /* 2. The mesh's steepest face within it. */
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, by_angle.face_gradient, &face),
               ZSHIFT_OK);
  /* 3. The offset for that face: every face within the limit keeps its edges. */
  e.face_angle = 0.0;
  e.face_gradient = face.gradient;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &b), ZSHIFT_OK);
  CHECK(face.triangle == 1 && b.window_offset < by_angle.window_offset,
        "steepest face: the mesh's offset %g, the angle's %g", b.window_offset, by_angle.window_offset);
  /* Or in one call, with the angle as the limit: the same single-sampled offset. */
  e.face_angle = 60.0 * 3.14159265358979 / 180.0;
  e.face_gradient = 0.0;
  CHECK_STATUS(zshift_edge_offset_for_mesh(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, &mesh, ZSHIFT_EDGES_MATRIX, &by_mesh),
               ZSHIFT_OK);
  CHECK(memcmp(&by_mesh, &b, sizeof b) == 0, "zshift_edge_offset_for_mesh differs from the three calls");
  /* Under 4x MSAA the face's gradient length bounds a sample's reach: at most length*(w + 1)/2. */
  e.samples = 4;
  CHECK_STATUS(zshift_edge_offset_for_mesh(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, &mesh, ZSHIFT_EDGES_MATRIX, &by_mesh),
               ZSHIFT_OK);
  CHECK(by_mesh.line_term <= face.length * (1 + 1e-15) && by_mesh.line_term <= face.gradient * by_mesh.line_reach,
        "edges for a mesh under MSAA: line term %g, length %g", by_mesh.line_term, face.length);
  /* Errors name what is wrong and leave the output untouched. */
  memset(&out, PATTERN, sizeof out);
  bad = mesh;
  bad.position_stride = 10;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("steepest face stride", "position_stride");
  bad = mesh;
  bad.vertex_count = 8;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("steepest face index", "indices");
  bad = mesh;
  bad.index_count = 8;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("steepest face index count", "index_count");
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, NAN, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("steepest face limit", "limit");
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0, 512, INFINITY, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("steepest face viewport", "viewport_width");
  bad = mesh;
  bad.positions = NULL;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_NULL_POINTER);
  expect_detail("steepest face positions", "mesh->positions");
  bad = mesh;
  bad.indices = NULL;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_NULL_POINTER);
  bad = mesh;
  bad.clip_matrix = NULL;
  CHECK_STATUS(zshift_steepest_face(&bad, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_steepest_face(NULL, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK(untouched(&out, sizeof out), "zshift_steepest_face wrote its output on error");
  CHECK_STATUS(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, INFINITY, NULL), ZSHIFT_ERR_NULL_POINTER);
  memset(&untouched_offset, PATTERN, sizeof untouched_offset);
  bad = mesh;
  bad.index_count = 8;
  CHECK_STATUS(zshift_edge_offset_for_mesh(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, &bad, ZSHIFT_EDGES_MATRIX, &untouched_offset),
               ZSHIFT_ERR_DOMAIN);
  expect_detail("edges for a mesh: index count", "index_count");
  CHECK_STATUS(zshift_edge_offset_for_mesh(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, NULL, ZSHIFT_EDGES_MATRIX, &untouched_offset),
               ZSHIFT_ERR_NULL_POINTER);
  CHECK(untouched(&untouched_offset, sizeof untouched_offset), "zshift_edge_offset_for_mesh wrote its output on error");
}

static void test_edges(void) {
  float m[16];
  ZshiftEdges e = edges_for();
  ZshiftEdgeOffset a, b, out;
  double planes[2];
  engine_perspective(1.0471976f, 1.0f, 1.0f, 1000.0f, m);
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &b), ZSHIFT_OK);
  CHECK(only_element_changed(m, b.matrix, 10), "zshift_edge_offset: more than element 10 changed");
  CHECK(b.ndc_offset < 0 && (long double)b.matrix[10] - m[10] >= -b.ndc_offset * (1 - 1e-12L),
        "edges: element 10 moved by %.9g for an NDC offset %.9g", (double)(b.matrix[10] - m[10]), b.ndc_offset);
  CHECK(b.line_reach == 1.0 && b.line_term == 1e-3 && b.window_offset > b.line_term, "edges: line term %g", b.line_term);
  CHECK(b.hidden_gap > 0 && b.hidden_gap < 20.0, "edges: gap %g", b.hidden_gap);
  e.line_width = 3.0;
  e.polygon_mode = 1;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_POLYGON_OFFSET, &a), ZSHIFT_OK);
  /* Polygon-mode width 3: (w + 1)/2 plus the 1/8 of a wide outline's quad. */
  CHECK(a.polygon_offset[0] == 2.125 && a.d3d_bias[1] == 2.125 && a.vulkan_bias[1] == 2.125, "edges: factor %g", a.polygon_offset[0]);
  CHECK(a.d3d_bias[0] == (double)(long)a.d3d_bias[0] && a.d3d_bias[0] >= a.polygon_offset[1], "edges: D3D bias %g", a.d3d_bias[0]);
  CHECK(memcmp(a.matrix, m, sizeof m) == 0, "edges: the polygon-offset method changed the matrix");
  /* Refusal below the gap, and planes that answer. */
  e = edges_for();
  e.face_gradient = 1e-9;
  e.format = ZSHIFT_FORMAT_UNORM16;
  engine_perspective(1.0471976f, 1.0f, 0.01f, 100.0f, m);
  e.depth_near = 50.0;
  e.depth_far = 60.0;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &b), ZSHIFT_OK);
  e.hidden_separation = b.hidden_gap / 2;
  memset(&out, PATTERN, sizeof out);
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_UNRESOLVABLE);
  CHECK(untouched(&out, sizeof out), "zshift_edge_offset wrote its output on a refusal");
  expect_detail("edges refusal", "hidden_separation");
  CHECK_STATUS(zshift_edge_planes(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, planes), ZSHIFT_OK);
  CHECK(planes[0] > 40.0 && planes[0] <= 50.0 && planes[1] >= 60.0, "edges: planes %g %g", planes[0], planes[1]);
  /* Bad fields are named; NULLs refused. */
  e = edges_for();
  e.line_width = 0.5;
  memset(&out, PATTERN, sizeof out);
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("edges line_width", "line_width");
  CHECK(untouched(&out, sizeof out), "zshift_edge_offset wrote its output on error");
  e = edges_for();
  e.face_angle = 0.5;
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("edges both slopes", "face_gradient");
  e = edges_for();
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, 7u, &out), ZSHIFT_ERR_DOMAIN);
  expect_detail("edges method", "method");
  CHECK_STATUS(zshift_edge_offset(NULL, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, NULL, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, NULL), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_edge_planes(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, NULL), ZSHIFT_ERR_NULL_POINTER);
  /* The engine's pipeline: world-space vertices far from the origin need more offset than eye
     space; the view matrix with the mesh's box less than world_reach alone; a bad depth range
     is named. A zeroed pipeline (edges_for) is the eye-space default. */
  {
    static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1e4f, 0, 0, 1};
    const double box[6] = {1e4 - 5, -5, -25, 1e4 + 5, 5, -5};
    ZshiftEdgeOffset eye, far_away, known;
    engine_perspective(1.0471976f, 1.0f, 1.0f, 1000.0f, m);
    e = edges_for();
    CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &eye), ZSHIFT_OK);
    e.pipeline.world_reach = 1e4;
    CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &far_away), ZSHIFT_OK);
    e.pipeline.view_matrix = view;
    memcpy(e.pipeline.world_box, box, sizeof box);
    e.pipeline.eye_first = 1;
    CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &known), ZSHIFT_OK);
    CHECK(far_away.window_offset > eye.window_offset && known.window_offset >= eye.window_offset &&
              known.window_offset <= far_away.window_offset,
          "edges in world space: offsets %.9g (eye), %.9g (world_reach), %.9g (view)", eye.window_offset,
          far_away.window_offset, known.window_offset);
    e.pipeline.depth_range_near = 0.75;
    e.pipeline.depth_range_far = 0.25;
    memset(&out, PATTERN, sizeof out);
    CHECK_STATUS(zshift_edge_offset(m, ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &out), ZSHIFT_ERR_DOMAIN);
    expect_detail("edges depth range", "depth_range_far");
    CHECK(untouched(&out, sizeof out), "zshift_edge_offset wrote its output on a bad pipeline");
  }
}

/* ---- shadow bias: a directional light's map (zshift_shadow_bias) ---- */

static ZshiftShadowMap shadow_map(void) {
  ZshiftShadowMap m;
  memset(&m, 0, sizeof m);
  m.light = ZSHIFT_LIGHT_ORTHOGRAPHIC;
  m.l = -8; m.r = 8; m.b = -8; m.t = 8; m.n = 2; m.f = 30;
  m.clip = ZSHIFT_CLIP_NEG_ONE_TO_ONE;
  m.width = 1024; m.height = 1024;
  m.format = ZSHIFT_FORMAT_UNORM24.value;
  m.lookup = ZSHIFT_LOOKUP_PCF;
  m.pcf_size = 3;
  m.limit_angle_deg = 60;
  m.receiver_near = 2; m.receiver_far = 30;
  m.world_reach = 0;
  m.elevation_deg = 30;
  m.profile = NULL;
  return m;
}

/* ---- shadow bias for listed receivers (zshift_shadow_bias_receivers) ---- */

static void test_shadow_bias_receivers(void) {
  ZshiftShadowMap m = shadow_map();
  ZshiftShadowBias out, untouched_out;
  /* A quad facing the light (no footprint) and one tilted: z = -10 + 0.5 x, counter-clockwise
     seen from the light (+z). */
  float corners[] = {-4, -4, -10, 4, -4, -10, 4, 4, -10, -4, 4, -10,
                     -4, -4, -12, 4, -4, -8, 4, 4, -8, -4, 4, -12};
  uint32_t counts[] = {4, 4};
  /* The tilted plane's window depth per texel: 0.5 * texel / (f - n), times a = 1.5 (PCF 3). */
  long double footprint = 1.5L * 0.5L * (16.0L / 1024.0L) / 28.0L;
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, corners, counts, 1, &out), ZSHIFT_OK);
  CHECK(out.footprint < 1e-12, "a facing receiver has no footprint: %.9g", out.footprint);
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, corners, counts, 2, &out), ZSHIFT_OK);
  CHECK(out.footprint >= footprint && relative_error(out.footprint, footprint) < 1e-4, "receiver footprint %.17g vs %.17Lg", out.footprint, footprint);
  CHECK(out.gl_clamp >= out.footprint && out.gl_factor >= 3.0, "clamp %.9g factor %.9g", out.gl_clamp, out.gl_factor);
  /* Errors: NULL arrays, no receiver, a bad corner count, a receiver facing away, untouched output. */
  memset(&untouched_out, PATTERN, sizeof untouched_out);
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, NULL, counts, 1, &untouched_out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, corners, NULL, 1, &untouched_out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, corners, counts, 0, &untouched_out), ZSHIFT_ERR_DOMAIN);
  counts[0] = 2;
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, corners, counts, 1, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "receiver") != NULL, "detail: %s", zshift_last_error());
  counts[0] = 4;
  {
    float away[] = {-4, -4, -10, -4, 4, -10, 4, 4, -10, 4, -4, -10};
    CHECK_STATUS(zshift_shadow_bias_receivers(&m, away, counts, 1, &untouched_out), ZSHIFT_ERR_DOMAIN);
    CHECK(strstr(zshift_last_error(), "faces the light") != NULL, "detail: %s", zshift_last_error());
  }
  CHECK(untouched(&untouched_out, sizeof untouched_out), "zshift_shadow_bias_receivers wrote its output on error");
}

static void test_shadow_bias(void) {
  ZshiftShadowMap m = shadow_map();
  ZshiftShadowBias out, untouched_out;
  long double texel = 16.0L / 1024.0L, a = 1.5L;
  /* The footprint at 60 degrees: a * tan(60) * texel diagonal / (f - n), computed here. */
  long double footprint = a * sqrtl(3.0L) * texel * sqrtl(2.0L) / 28.0L;
  CHECK_STATUS(zshift_shadow_bias(&m, &out), ZSHIFT_OK);
  CHECK(relative_error(out.footprint, footprint) < 1e-12, "shadow footprint %.17g vs %.17Lg", out.footprint, footprint);
  CHECK(out.gl_factor >= 3.0 + 1.0 / 256 && out.gl_factor < (3.0 + 1.0 / 256) * 1.000001, "gl factor %.9g", out.gl_factor);
  CHECK(out.d3d_depth_bias > 0 && out.d3d_depth_bias / 16777215.0 >= out.constant, "D3D DepthBias %d for %.9g", out.d3d_depth_bias, out.constant);
  CHECK(out.webgpu_depth_bias >= out.d3d_depth_bias, "WebGPU %d < D3D %d", out.webgpu_depth_bias, out.d3d_depth_bias);
  CHECK(out.gl_clamp >= out.constant + out.snap + out.footprint && out.d3d_clamp == (float)out.gl_clamp, "clamp %.9g", out.gl_clamp);
  CHECK(out.along_normal > 0 && out.along_normal <= out.along_light && out.peter_panning < out.leak_thickness, "receiver side");
  /* Errors: NULL pointers, a bad field named in the detail, output untouched. */
  CHECK_STATUS(zshift_shadow_bias(NULL, &out), ZSHIFT_ERR_NULL_POINTER);
  CHECK_STATUS(zshift_shadow_bias(&m, NULL), ZSHIFT_ERR_NULL_POINTER);
  memset(&untouched_out, PATTERN, sizeof untouched_out);
  m.limit_angle_deg = 90;
  CHECK_STATUS(zshift_shadow_bias(&m, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "limit_angle_deg") != NULL, "detail: %s", zshift_last_error());
  CHECK(untouched(&untouched_out, sizeof untouched_out), "zshift_shadow_bias wrote its output on error");
  m = shadow_map();
  m.receiver_far = 31;
  CHECK_STATUS(zshift_shadow_bias(&m, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "receiver_far") != NULL, "detail: %s", zshift_last_error());
  m = shadow_map();
  m.lookup = 7;
  CHECK_STATUS(zshift_shadow_bias(&m, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "lookup") != NULL, "detail: %s", zshift_last_error());
  m = shadow_map();
  m.width = 64; m.height = 64; m.pcf_size = 5; m.limit_angle_deg = 89.9;
  /* A clamp that would span the whole depth range: none is set (0), the factor still covers the
     footprint, and no receiver-side offset reaches. */
  CHECK_STATUS(zshift_shadow_bias(&m, &out), ZSHIFT_OK);
  CHECK(out.gl_clamp == 0 && out.d3d_clamp == 0 && out.vk_clamp == 0, "clamp %g", out.gl_clamp);
  CHECK(out.gl_factor >= 5 && isinf(out.along_light), "factor %g, along the light %g", out.gl_factor, out.along_light);
  /* Reversed Z flips the signs. */
  m = shadow_map();
  m.clip = ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE;
  m.format = ZSHIFT_FORMAT_FLOAT32.value;
  m.receiver_far = 28;
  CHECK_STATUS(zshift_shadow_bias(&m, &out), ZSHIFT_OK);
  CHECK(out.gl_factor < 0 && out.gl_units < 0 && out.d3d_depth_bias < 0 && out.vk_clamp < 0, "reversed signs");
}

/* ---- shadow bias with the light's pipeline (ZshiftShadowMap.pipeline) ---- */

static void test_shadow_bias_pipeline(void) {
  /* A light 25 units up the world z axis looking down -z (its view a translation), the scene
     inside the box [-8, 8] x [-8, 8] x [-5, 23] (light depths 2 to 30). */
  static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -25, 1};
  const double box[6] = {-8, -8, -5, 8, 8, 23};
  float ground[] = {-4, -4, -12, 4, -4, -8, 4, 4, -8, -4, 4, -12};
  uint32_t counts[] = {4};
  ZshiftShadowMap m = shadow_map();
  ZshiftShadowBias scalar, exact, untouched_out;
  m.world_reach = 25;
  CHECK_STATUS(zshift_shadow_bias(&m, &scalar), ZSHIFT_OK);
  /* A zeroed pipeline is the behaviour without it; the view and its box are accepted and
     tighten the lookup's (and the caster's) float term. */
  m.pipeline.view_matrix = view;
  memcpy(m.pipeline.world_box, box, sizeof box);
  m.pipeline.eye_first = 1;
  CHECK_STATUS(zshift_shadow_bias(&m, &exact), ZSHIFT_OK);
  CHECK(exact.lookup > 0 && exact.lookup < scalar.lookup, "lookup with the view %.9g vs scalar %.9g", exact.lookup, scalar.lookup);
  CHECK(exact.constant < scalar.constant, "constant with the view %.9g vs scalar %.9g", exact.constant, scalar.constant);
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, ground, counts, 1, &exact), ZSHIFT_OK);
  /* Refusals: a view matrix without its box names world_box; a reversed depth range names
     depth_range_far. */
  memset(&untouched_out, PATTERN, sizeof untouched_out);
  memset(m.pipeline.world_box, 0, sizeof m.pipeline.world_box);
  CHECK_STATUS(zshift_shadow_bias(&m, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "world_box") != NULL, "detail: %s", zshift_last_error());
  CHECK_STATUS(zshift_shadow_bias_receivers(&m, ground, counts, 1, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "world_box") != NULL, "detail: %s", zshift_last_error());
  memcpy(m.pipeline.world_box, box, sizeof box);
  m.pipeline.depth_range_near = 0.75;
  m.pipeline.depth_range_far = 0.25;
  CHECK_STATUS(zshift_shadow_bias(&m, &untouched_out), ZSHIFT_ERR_DOMAIN);
  CHECK(strstr(zshift_last_error(), "depth_range_far") != NULL, "detail: %s", zshift_last_error());
  CHECK(untouched(&untouched_out, sizeof untouched_out), "zshift_shadow_bias wrote its output on error");
  /* A shadow atlas: a tile far from the atlas's corner extrapolates the caster's plane further
     (the caster term grows, the quantum stays); glDepthRange(0.5, 1) doubles a D24 quantum in
     unit window depth and halves the clamp's share of stored depth. */
  {
    ZshiftShadowBias whole, tiled, half;
    m.pipeline.depth_range_near = 0.0;
    m.pipeline.depth_range_far = 0.0;
    CHECK_STATUS(zshift_shadow_bias(&m, &whole), ZSHIFT_OK);
    m.pipeline.viewport_x = 3072;
    m.pipeline.viewport_y = 2048;
    CHECK_STATUS(zshift_shadow_bias(&m, &tiled), ZSHIFT_OK);
    CHECK(tiled.caster > whole.caster && tiled.quantum == whole.quantum,
          "tile: caster %.9g vs %.9g, quantum %.9g vs %.9g", tiled.caster, whole.caster, tiled.quantum, whole.quantum);
    m.pipeline.viewport_x = m.pipeline.viewport_y = 0;
    m.pipeline.depth_range_near = 0.5;
    m.pipeline.depth_range_far = 1.0;
    CHECK_STATUS(zshift_shadow_bias(&m, &half), ZSHIFT_OK);
    CHECK(fabs(half.quantum * 16777215.0 - 2.0) < 1e-9, "quantum under [0.5, 1]: %.9g", half.quantum);
    CHECK(fabs(half.gl_clamp - 0.5 * (half.constant + half.snap + half.footprint)) <= 1e-6 * half.gl_clamp,
          "clamp under [0.5, 1]: %.9g", half.gl_clamp);
  }
}

int main(void) {
  test_edges();
  test_steepest_face();
  test_last_error();
  test_front_door();
  test_decal_corners();
  test_engine_scene();
  test_frustum();
  test_load_offset_matrix();
  test_epsilon();
  test_min_epsilon();
  test_deltas();
  test_precision();
  test_projections();
  test_clip_precision();
  test_bias_and_planning();
  test_recommend();
  test_recommend_clip();
  test_shadow_bias();
  test_shadow_bias_pipeline();
  test_shadow_bias_receivers();
  test_status_messages();
  test_versions();
  if (failures != 0) {
    fprintf(stderr, "abi_test: %d of %d checks failed\n", failures, checks);
    return 1;
  }
  printf("abi_test: all %d checks passed\n", checks);
  return 0;
}
