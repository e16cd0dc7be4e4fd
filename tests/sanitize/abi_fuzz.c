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
 * buffer; the header promises they work (src/ffi.rs stores with write_unaligned / byte copies).
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
    double l, r, b, t, n, f, delta, pz, d;
    uint32_t bits;
    int32_t status;
};

/* X(name, element type, element count, arguments before the output pointer) */
#define ZSHIFT_WRITERS(X)                                                                      \
    X(zshift_frustum, float, 16, in->l, in->r, in->b, in->t, in->n, in->f)                    \
    X(zshift_load_offset_matrix, float, 16, in->l, in->r, in->b, in->t, in->n, in->f,         \
      in->delta, in->pz)                                                                       \
    X(zshift_epsilon, double, 1, in->n, in->f, in->delta, in->pz)                              \
    X(zshift_min_epsilon, double, 1, in->n, in->f, in->bits)                                   \
    X(zshift_min_delta_toward, double, 1, in->n, in->f, in->bits, in->pz)                      \
    X(zshift_max_delta_away, double, 1, in->n, in->f, in->bits, in->pz)                        \
    X(zshift_window_depth, double, 1, in->n, in->f, in->d)                                     \
    X(zshift_depth_resolution, double, 1, in->n, in->f, in->bits, in->d)

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
    ZshiftStatus (*call)(const struct inputs *in, unsigned char *out);
};

#define WRAP_WRITER(name, type, count, ...)                                                    \
    static ZshiftStatus call_##name(const struct inputs *in, unsigned char *out) {             \
        return name(__VA_ARGS__, (type *)(void *)out);                                         \
    }
ZSHIFT_WRITERS(WRAP_WRITER)

#define LIST_WRITER(name, type, count, ...) {#name, ELEM_OF_##type, sizeof(type), count, call_##name},
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
            if (!isfinite(x)) fail(w->name, in, "NaN or infinity in an OK result", s);
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

static void check_all(const struct inputs *in) {
    for (size_t i = 0; i < NWRITERS; i++) {
        for (size_t misalign = 0; misalign < 8; misalign++) check_writer(&WRITERS[i], in, misalign);
        check_null(&WRITERS[i], in);
    }
    for (size_t i = 0; i < NTEXTS; i++) check_text(&TEXTS[i], in);
}

static const struct inputs VALID = {-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0, 0.01, -50.0, 50.0, 24, 0};

static double *field(struct inputs *in, int k) {
    double *fields[] = {&in->l, &in->r, &in->b, &in->t, &in->n, &in->f, &in->delta, &in->pz, &in->d};
    return fields[k];
}
enum { NFIELDS = 9 };

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

int main(int argc, char **argv) {
    long random_cases = argc > 1 ? atol(argv[1]) : 2000;
    const double edges[] = {0.0,     -0.0,     1.0,  -1.0,   DBL_MIN, -DBL_MIN, 5e-324,
                            DBL_MAX, -DBL_MAX, INFINITY, -INFINITY, NAN, 1e300, -1e-300};
    const uint32_t edge_bits[] = {0, 1, 16, 24, 32, 33, UINT32_MAX};
    const int32_t edge_status[] = {-1, 0, 1, 2, 3, 4, 5, 6, 7, INT32_MIN, INT32_MAX};
    long cases = 0;

    check_all(&VALID), cases++;
    for (int k = 0; k < NFIELDS; k++)
        for (size_t e = 0; e < sizeof edges / sizeof edges[0]; e++) {
            struct inputs in = VALID;
            *field(&in, k) = edges[e];
            check_all(&in), cases++;
        }
    for (size_t e = 0; e < sizeof edge_bits / sizeof edge_bits[0]; e++) {
        struct inputs in = VALID;
        in.bits = edge_bits[e];
        check_all(&in), cases++;
    }
    for (size_t e = 0; e < sizeof edge_status / sizeof edge_status[0]; e++) {
        struct inputs in = VALID;
        in.status = edge_status[e];
        check_all(&in), cases++;
    }
    /* Plausible frusta over many decades, one in eight with a field set to an edge value. */
    for (long c = 0; c < random_cases; c++) {
        struct inputs in;
        in.n = decades(-30, 30);
        in.f = next_u64() % 8 == 0 ? INFINITY : in.n * decades(0, 12);
        double far = isfinite(in.f) ? in.f : in.n * 1e12;
        in.d = in.n + unit() * (far - in.n);
        in.pz = -(in.n + unit() * (far - in.n));
        in.delta = (next_u64() % 4 == 0 ? -1 : 1) * -in.pz * decades(-16, 0);
        in.l = -in.n * decades(-3, 3), in.r = in.n * decades(-3, 3);
        in.b = -in.n * decades(-3, 3), in.t = in.n * decades(-3, 3);
        in.bits = 1 + (uint32_t)(next_u64() % 32);
        in.status = (int32_t)(next_u64() % 9) - 1;
        if (next_u64() % 8 == 0) *field(&in, (int)(next_u64() % NFIELDS)) = edges[next_u64() % (sizeof edges / sizeof edges[0])];
        check_all(&in), cases++;
    }
    printf("abi_fuzz: %zu functions, %ld input sets, %ld calls (%ld OK, %ld errors, %ld NULL/text), %ld failures\n",
           NWRITERS + NTEXTS, cases, calls, oks, errors, calls - oks - errors, failures);
    return failures ? 1 : 0;
}
