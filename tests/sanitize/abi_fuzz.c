/* Calls every exported zshift_* function from C with edge inputs, under AddressSanitizer and
 * UndefinedBehaviorSanitizer (scripts/sanitize builds and runs it against the static library).
 *
 * For each function and input: the output is placed at every misalignment 0..7 inside a
 * sentinel-filled buffer with guard bytes, and once more as NULL. A failure is a status outside
 * the header's codes, ZSHIFT_ERR_INTERNAL (a caught panic), a NaN or infinity in an OK result,
 * a byte written outside the output, any byte written on an error, NULL not refused, or a
 * sanitizer report (the build makes every report fatal).
 *
 * Misaligned float and double pointers are what a C caller gets from a packed struct or a byte
 * buffer; the header promises they work (src/ffi/ stores with write_unaligned / byte copies).
 * Forming one is implementation-defined territory in ISO C but well defined on every ABI zshift
 * targets; this driver never dereferences one itself (it reads the bytes back with memcpy).
 *
 * Adding an exported function is one line in ZSHIFT_WRITERS or ZSHIFT_TEXTS below.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "zshift.h"

struct inputs {
    double l, r, b, t, n, f, delta, pz, d, fovy, aspect, tweak, median, bias, nearest, farthest,
        lo, hi, steps;
    uint32_t bits;
    int32_t status;
    ZshiftClip clip;
    ZshiftFormat format;
    ZshiftBiasApi api;
    ZshiftOffsetKind kind;
    ZshiftScene scene;
    float matrix[16]; /* the engine's own projection, for the front door */
    ZshiftDecal decal;
    double ndc;
};

#define REC_DOUBLES (sizeof(ZshiftRecommendation) / sizeof(double))

/* X(name, element type, element count, element that may be +INFINITY or -1, arguments before
 * the output pointer) */
#define ZSHIFT_WRITERS(X)                                                                      \
    X(zshift_frustum, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f)                \
    X(zshift_load_offset_matrix, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f,     \
      in->delta, in->pz)                                                                       \
    X(zshift_epsilon, double, 1, -1, in->n, in->f, in->delta, in->pz)                          \
    X(zshift_min_epsilon, double, 1, -1, in->n, in->f, in->bits)                               \
    X(zshift_min_delta_toward, double, 1, -1, in->n, in->f, in->bits, in->pz)                  \
    X(zshift_max_delta_away, double, 1, -1, in->n, in->f, in->bits, in->pz)                    \
    X(zshift_window_depth, double, 1, -1, in->n, in->f, in->d)                                 \
    X(zshift_depth_resolution, double, 1, -1, in->n, in->f, in->bits, in->d)                   \
    X(zshift_perspective, float, 16, -1, in->fovy, in->aspect, in->n, in->f)                   \
    X(zshift_projection, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f, in->clip)   \
    X(zshift_offset_projection, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f,      \
      in->clip, in->delta, in->pz)                                                             \
    X(zshift_offset_perspective, float, 16, -1, in->fovy, in->aspect, in->n, in->f, in->clip, \
      in->delta, in->pz)                                                                       \
    X(zshift_tweaked_infinite, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->tweak)   \
    X(zshift_offset_tweaked_infinite, float, 16, -1, in->l, in->r, in->b, in->t, in->n,       \
      in->tweak, in->delta, in->pz)                                                            \
    X(zshift_median_ndc_offset, double, 1, -1, in->median, in->delta, in->pz)                  \
    X(zshift_window_depth_clip, double, 1, -1, in->n, in->f, in->clip, in->d)                  \
    X(zshift_depth_step, double, 1, -1, in->n, in->f, in->clip, in->format, in->d)             \
    X(zshift_median_depth_step, double, 1, -1, in->median, in->format, in->d)                  \
    X(zshift_min_ndc_offset, double, 1, -1, in->n, in->f, in->clip, in->format, in->d)         \
    X(zshift_min_epsilon_clip, double, 1, -1, in->n, in->f, in->clip, in->format, in->d)       \
    X(zshift_min_relative_epsilon, double, 1, -1, in->n, in->f, in->clip, in->format, in->d)   \
    X(zshift_bias_of_shift, double, 1, -1, in->n, in->f, in->clip, in->format, in->api,        \
      in->delta, in->pz)                                                                       \
    X(zshift_shift_of_bias, double, 1, -1, in->n, in->f, in->clip, in->format, in->api,        \
      in->bias, in->pz)                                                                        \
    X(zshift_tight_planes, double, 2, 1, in->nearest, in->farthest)                            \
    X(zshift_range_offset, double, 3, -1, in->n, in->f, in->clip, in->format, in->kind,        \
      in->lo, in->hi, in->steps)                                                               \
    X(zshift_recommend, double, REC_DOUBLES, -1, &in->scene)                                   \
    X(zshift_recommend_matrix, float, 16, -1, &in->scene)                                   \
    X(zshift_recommend_clip, double, REC_DOUBLES, -1, &in->scene, in->clip)                    \
    X(zshift_recommend_clip_matrix, float, 16, -1, &in->scene, in->clip)                      \
    X(zshift_offset_matrix, float, 16, -1, in->matrix, in->clip, in->delta, in->d)            \
    X(zshift_offset_matrix_ndc, float, 16, -1, in->matrix, in->clip, in->ndc)                 \
    X(zshift_decal_matrix, float, 16, -1, in->matrix, in->clip, &in->decal)                   \
    X(zshift_recommend_for_matrix, double, REC_DOUBLES, -1, in->matrix, in->clip, &in->decal) \
    X(zshift_ortho, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f, in->clip)        \
    X(zshift_offset_ortho, float, 16, -1, in->l, in->r, in->b, in->t, in->n, in->f, in->clip, \
      in->delta)                                                                               \
    X(zshift_ortho_depth_step, double, 1, -1, in->n, in->f, in->clip, in->format, in->d)

/* X(name, arguments) for functions that return a static C string */
#define ZSHIFT_TEXTS(X)                                                                        \
    X(zshift_status_message, in->status)                                                       \
    X(zshift_version, )

enum elem { ELEM_FLOAT, ELEM_DOUBLE };
#define ELEM_OF_float ELEM_FLOAT
#define ELEM_OF_double ELEM_DOUBLE

struct writer {
    const char *name;
    enum elem elem;
    size_t size, count;
    long inf_ok;
    ZshiftStatus (*call)(const struct inputs *in, unsigned char *out);
};

/* void * converts to the parameter's type (float *, double *, ZshiftRecommendation *). */
#define WRAP_WRITER(name, type, count, inf_ok, ...)                                            \
    static ZshiftStatus call_##name(const struct inputs *in, unsigned char *out) {             \
        return name(__VA_ARGS__, (void *)out);                                                 \
    }
ZSHIFT_WRITERS(WRAP_WRITER)

#define LIST_WRITER(name, type, count, inf_ok, ...)                                            \
    {#name, ELEM_OF_##type, sizeof(type), count, inf_ok, call_##name},
static const struct writer WRITERS[] = {ZSHIFT_WRITERS(LIST_WRITER)};

struct text {
    const char *name;
    const char *(*call)(const struct inputs *in);
};

#define WRAP_TEXT(name, ...)                                                                   \
    static const char *text_##name(const struct inputs *in) {                                  \
        (void)in;                                                                              \
        return name(__VA_ARGS__);                                                              \
    }
ZSHIFT_TEXTS(WRAP_TEXT)

#define LIST_TEXT(name, ...) {#name, text_##name},
static const struct text TEXTS[] = {ZSHIFT_TEXTS(LIST_TEXT)};

#define NWRITERS (sizeof WRITERS / sizeof WRITERS[0])
#define NTEXTS (sizeof TEXTS / sizeof TEXTS[0])

enum { SENTINEL = 0xA5, GUARD = 16, MAX_OUT = 16 * 8 };

static long calls, oks, errors, failures;

static void fail(const char *name, const struct inputs *in, const char *what, int status) {
    failures++;
    fprintf(stderr,
            "FAIL %s: %s (status %d) l=%a r=%a b=%a t=%a n=%a f=%a delta=%a pz=%a d=%a bits=%u\n",
            name, what, status, in->l, in->r, in->b, in->t, in->n, in->f, in->delta, in->pz,
            in->d, in->bits);
}

static void check_writer(const struct writer *w, const struct inputs *in, size_t misalign) {
    /* Heap allocation of exactly guard + output + guard: ASan sees any write past it. */
    size_t bytes = w->size * w->count, total = GUARD + misalign + bytes + GUARD;
    unsigned char *buf = malloc(total);
    if (!buf) abort();
    memset(buf, SENTINEL, total);
    unsigned char *out = buf + GUARD + misalign;
    ZshiftStatus s = w->call(in, out);
    calls++;
    if (s < ZSHIFT_OK || s > ZSHIFT_ERR_OVERFLOW) fail(w->name, in, "status outside the header's codes or INTERNAL", s);
    for (size_t k = 0; k < total; k++) {
        int inside = buf + k >= out && buf + k < out + bytes;
        if (buf[k] != SENTINEL && (!inside || s != ZSHIFT_OK)) {
            fail(w->name, in, inside ? "output written on error" : "byte written outside the output", s);
            break;
        }
    }
    if (s == ZSHIFT_OK) {
        oks++;
        for (size_t k = 0; k < w->count; k++) {
            double x;
            if (w->elem == ELEM_FLOAT) {
                float v;
                memcpy(&v, out + k * sizeof v, sizeof v);
                x = v;
            } else {
                memcpy(&x, out + k * sizeof x, sizeof x);
            }
            int inf_ok = (long)k == w->inf_ok && x == INFINITY; /* documented +INFINITY */
            if (!isfinite(x) && !inf_ok) fail(w->name, in, "NaN or infinity in an OK result", s);
        }
    } else {
        errors++;
    }
    free(buf);
}

static void check_null(const struct writer *w, const struct inputs *in) {
    ZshiftStatus s = w->call(in, NULL);
    calls++;
    if (s != ZSHIFT_ERR_NULL_POINTER) fail(w->name, in, "NULL output not refused", s);
}

static void check_text(const struct text *t, const struct inputs *in) {
    const char *p = t->call(in);
    calls++;
    if (!p) {
        fail(t->name, in, "returned NULL", 0);
        return;
    }
    /* strlen reads up to the NUL: ASan catches a missing terminator in a global. */
    if (strlen(p) == 0) fail(t->name, in, "returned an empty string", 0);
}

/* A NULL scene is refused like a NULL output, and the output is left alone. */
static void check_null_scene(const struct inputs *in) {
    ZshiftRecommendation rec;
    float m[16];
    memset(&rec, SENTINEL, sizeof rec);
    memset(m, SENTINEL, sizeof m);
    unsigned char want[sizeof rec > sizeof m ? sizeof rec : sizeof m];
    memset(want, SENTINEL, sizeof want);
    calls += 2;
    if (zshift_recommend(NULL, &rec) != ZSHIFT_ERR_NULL_POINTER || memcmp(&rec, want, sizeof rec))
        fail("zshift_recommend", in, "NULL scene not refused cleanly", 0);
    if (zshift_recommend_matrix(NULL, m) != ZSHIFT_ERR_NULL_POINTER || memcmp(m, want, sizeof m))
        fail("zshift_recommend_matrix", in, "NULL scene not refused cleanly", 0);
}

static void check_all(const struct inputs *in) {
    for (size_t i = 0; i < NWRITERS; i++) {
        for (size_t misalign = 0; misalign < 8; misalign++) check_writer(&WRITERS[i], in, misalign);
        check_null(&WRITERS[i], in);
    }
    for (size_t i = 0; i < NTEXTS; i++) check_text(&TEXTS[i], in);
}

static const struct inputs VALID = {
    .l = -0.1, .r = 0.1, .b = -0.075, .t = 0.075, .n = 0.1, .f = 1000.0, .delta = 0.01,
    .pz = -50.0, .d = 50.0, .fovy = 60.0, .aspect = 4.0 / 3.0, .tweak = 1e-6, .median = 10.0,
    .bias = -2.0, .nearest = 0.5, .farthest = 800.0, .lo = 10.0, .hi = 100.0, .steps = 1.0,
    .bits = 24, .status = 0, .clip = {0}, .format = {0x81A6 /* UNORM24 */}, .api = {0}, .kind = {0},
    .scene = {.l = -0.1, .r = 0.1, .b = -0.075, .t = 0.075, .n = 0.1, .f = 1000.0,
              .viewport_width = 1920, .viewport_height = 1080, .depth_format = 0x81A6,
              .decal_near = 49.0, .decal_far = 51.0, .slope = 0.5, .exact_depth = 0,
              .subpixel_bits = 8},
    /* glFrustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000) */
    .matrix = {1.0f, 0, 0, 0, 0, 1.3333334f, 0, 0, 0, 0, -1.0002f, -1.0f, 0, 0, -0.20002f, 0},
    .decal = {.viewport_width = 1920, .viewport_height = 1080, .format = {0x81A6}, .subpixel_bits = 8,
              .decal_near = 49.0, .decal_far = 51.0, .slope = 0.5, .exact_depth = 0},
    .ndc = 1e-5};

/* Every double input, the scene's included, by index. */
static double *field(struct inputs *in, int k) {
    double *fields[] = {&in->l, &in->r, &in->b, &in->t, &in->n, &in->f, &in->delta, &in->pz,
                        &in->d, &in->fovy, &in->aspect, &in->tweak, &in->median, &in->bias,
                        &in->nearest, &in->farthest, &in->lo, &in->hi, &in->steps, &in->scene.l,
                        &in->scene.r, &in->scene.b, &in->scene.t, &in->scene.n, &in->scene.f,
                        &in->scene.decal_near, &in->scene.decal_far, &in->scene.slope};
    return fields[k];
}
enum { NFIELDS = 28 };

/* Every integer input, by index, through a uint32_t view (int32_t fields take the same bits). */
static uint32_t *int_field(struct inputs *in, int k) {
    uint32_t *fields[] = {&in->bits, (uint32_t *)&in->status, (uint32_t *)&in->clip.value,
                          &in->format.value, (uint32_t *)&in->api.value, (uint32_t *)&in->kind.value,
                          &in->scene.viewport_width, &in->scene.viewport_height,
                          &in->scene.depth_format, &in->scene.exact_depth,
                          (uint32_t *)&in->scene.subpixel_bits};
    return fields[k];
}
enum { NINTS = 11 };

/* Deterministic xorshift, so a failure repeats. */
static uint64_t rng_state = 0x9e3779b97f4a7c15u;
static uint64_t next_u64(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}
static double unit(void) { return (double)(next_u64() >> 11) / 9007199254740992.0; }
static double decades(double lo, double hi) { return pow(10.0, lo + unit() * (hi - lo)); }
static double sign(void) { return next_u64() % 2 ? 1.0 : -1.0; }

/* The scene may lie anywhere relative to the output: it is read before anything is written.
 * The recommendation is written over the scene itself and must equal the separate answer. */
static void check_overlap(const struct inputs *in) {
    ZshiftRecommendation want;
    ZshiftStatus s = zshift_recommend(&in->scene, &want);
    for (size_t shift = 0; shift < 16; shift++) {
        size_t size = sizeof(ZshiftScene) > sizeof want ? sizeof(ZshiftScene) : sizeof want;
        unsigned char *buf = malloc(size + shift + 1);
        if (!buf) abort();
        memcpy(buf + 1, &in->scene, sizeof in->scene); /* misaligned scene */
        ZshiftStatus t = zshift_recommend((void *)(buf + 1), (void *)(buf + 1 + shift));
        calls++;
        if (t != s || (s == ZSHIFT_OK && memcmp(buf + 1 + shift, &want, sizeof want) != 0))
            fail("zshift_recommend", in, "output overlapping the scene differs", t);
        free(buf);
    }
}

int main(int argc, char **argv) {
    long random_cases = argc > 1 ? atol(argv[1]) : 2000;
    const double edges[] = {0.0,     -0.0,     1.0,      -1.0,      DBL_MIN, -DBL_MIN, 5e-324,
                            DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN,     1e300,    -1e-300};
    const uint32_t edge_ints[] = {0, 1, 2, 3, 4, 24, 32, 33, 0x81A5, 0x8CAC, UINT32_MAX, 0x80000000u};
    const size_t nedges = sizeof edges / sizeof edges[0], nints = sizeof edge_ints / sizeof edge_ints[0];
    long cases = 0;

    check_all(&VALID), cases++;
    check_overlap(&VALID);
    check_null_scene(&VALID);
    for (int k = 0; k < NFIELDS; k++)
        for (size_t e = 0; e < nedges; e++) {
            struct inputs in = VALID;
            *field(&in, k) = edges[e];
            check_all(&in), cases++;
        }
    for (int k = 0; k < NINTS; k++)
        for (size_t e = 0; e < nints; e++) {
            struct inputs in = VALID;
            *int_field(&in, k) = edge_ints[e];
            check_all(&in), cases++;
        }
    /* Plausible inputs over many decades, some with fields set to edge values. */
    for (long c = 0; c < random_cases; c++) {
        struct inputs in = VALID;
        in.n = decades(-12, 12);
        in.f = next_u64() % 8 == 0 ? INFINITY : in.n * decades(0.0001, 10);
        double far = isfinite(in.f) ? in.f : in.n * 1e12;
        in.d = in.n + unit() * (far - in.n);
        in.pz = -(in.n + unit() * (far - in.n));
        in.delta = (next_u64() % 4 == 0 ? -1 : 1) * -in.pz * decades(-16, 0);
        in.l = -in.n * decades(-3, 3), in.r = in.n * decades(-3, 3);
        in.b = -in.n * decades(-3, 3), in.t = in.n * decades(-3, 3);
        in.fovy = 180 * unit(), in.aspect = decades(-3, 3);
        in.tweak = next_u64() % 2 ? unit() : 2.4e-7 * decades(0, 4);
        in.median = decades(-6, 6), in.bias = sign() * decades(-3, 6);
        in.nearest = in.n, in.farthest = in.n * decades(0, 10);
        double a = in.n + unit() * (far - in.n), b = in.n + unit() * (far - in.n);
        in.lo = a < b ? a : b, in.hi = a < b ? b : a;
        in.steps = 1 + (double)(next_u64() % 8);
        in.bits = 1 + (uint32_t)(next_u64() % 32);
        in.status = (int32_t)(next_u64() % 9) - 1;
        const uint32_t formats[] = {0x81A5, 0x81A6, 0x81A7, 0x8CAC};
        in.clip.value = (int32_t)(next_u64() % 3), in.format.value = formats[next_u64() % 4];
        in.api.value = (int32_t)(next_u64() % 3), in.kind.value = (int32_t)(next_u64() % 2);
        in.scene = (ZshiftScene){.l = in.l, .r = in.r, .b = in.b, .t = in.t, .n = in.n, .f = in.f,
                                 .viewport_width = 1 + (uint32_t)(next_u64() % 4096),
                                 .viewport_height = 1 + (uint32_t)(next_u64() % 4096),
                                 .depth_format = formats[next_u64() % 4],
                                 .decal_near = in.lo, .decal_far = in.hi,
                                 .slope = next_u64() % 3 ? decades(-3, 1) : 0.0,
                                 .exact_depth = 0,
                                 .subpixel_bits = (int32_t)(next_u64() % 14) - 1};
        /* The engine's matrix: the random frustum's, perspective or orthographic, sometimes with one
         * element set to an edge value; the decal: the scene's. */
        if (next_u64() % 2) {
            (void)zshift_projection(in.l, in.r, in.b, in.t, in.n, in.f, in.clip, in.matrix);
        } else {
            (void)zshift_ortho(in.l, in.r, in.b, in.t, in.n, in.f, in.clip, in.matrix);
        }
        if (next_u64() % 8 == 0) in.matrix[next_u64() % 16] = (float)edges[next_u64() % nedges];
        in.decal = (ZshiftDecal){.viewport_width = in.scene.viewport_width,
                                 .viewport_height = in.scene.viewport_height,
                                 .format = {in.scene.depth_format},
                                 .subpixel_bits = in.scene.subpixel_bits,
                                 .decal_near = in.lo, .decal_far = in.hi, .slope = in.scene.slope,
                                 .exact_depth = 0};
        in.ndc = sign() * decades(-9, -1);
        if (next_u64() % 4 == 0) *field(&in, (int)(next_u64() % NFIELDS)) = edges[next_u64() % nedges];
        if (next_u64() % 8 == 0) *int_field(&in, (int)(next_u64() % NINTS)) = edge_ints[next_u64() % nints];
        check_all(&in), cases++;
        if (c % 16 == 0) check_overlap(&in);
    }
    printf("abi_fuzz: %zu functions, %ld input sets, %ld calls (%ld OK, %ld errors, %ld NULL/text/overlap), "
           "%ld failures\n",
           NWRITERS + NTEXTS, cases, calls, oks, errors, calls - oks - errors, failures);
    return failures ? 1 : 0;
}
