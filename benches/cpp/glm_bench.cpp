// C++ side of the zshift benchmarks: GLM's glm::frustum (Debian libglm-dev) beside zshift's C ABI
// called from C++, and GLM's element 10 for the report's error table.
//
// Built and run by scripts/report (not part of CI):
//   g++ -O2 -std=c++17 -Iinclude benches/cpp/glm_bench.cpp -Ltarget/release -lzshift ...
// Modes:
//   glm_bench time      -> one JSON object: median ns per call of each variant
//   glm_bench m10       -> reads "l r b t n f" lines on stdin, prints GLM's element 10 as
//                          C99 hex floats: float build, double build (one line per input)
//
// Fairness: every variant leaves its whole 16-float matrix in memory that the compiler must
// assume is read (an empty asm statement with a memory clobber): GLM's in its own glm::mat4,
// ready for glUniformMatrix4fv(.., &m[0][0]), zshift's in the buffer its C ABI writes. Without
// that, GLM's inline builder is reduced to the elements a sink reads.
// Inputs are read through volatiles on every call, so nothing is constant-folded. Batches of
// the variants are interleaved (round robin), so a machine shared with other jobs loads every
// variant alike, and the median batch is reported.
#include <glm/glm.hpp>
#include <glm/ext/matrix_clip_space.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

extern "C" {
#include "zshift.h"
}

namespace {

volatile double vl = -0.0577, vr = 0.0577, vb = -0.0414, vt = 0.0414, vn = 0.1, vf = 1000.0;
volatile double vpz = -50.0, vdelta = 0.0;
volatile double vfovy = 45.0, vaspect = 1.3937;

// Tells the compiler the 16 floats at `p` are read: the matrix must really be stored.
inline void escape(const float* p) { asm volatile("" : : "g"(p) : "memory"); }

// The seed's LoadOffsetMatrix arithmetic: f, n GLdouble; delta, pz GLfloat (see benches/shared/seed.rs).
float seed_epsilon(double n, double f, float delta, float pz) {
    return -2.0F * f * n * delta / ((f + n) * pz * (pz + delta));
}

// Nanoseconds per call of `body` over one batch (the template inlines each builder into its loop).
template <class F>
double batch(F body) {
    const long calls = 20000;
    alignas(64) float out[16];
    auto t0 = std::chrono::steady_clock::now();
    for (long j = 0; j < calls; ++j) {
        body(out);
        escape(out);
    }
    auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / calls;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

int time_all() {
    double n = vn, f = vf, pz = vpz;
    double step = 0.0;
    if (zshift_min_delta_toward(n, f, 24, pz, &step) != ZSHIFT_OK) return 1;
    vdelta = 4.0 * step;  // the same case as benches/cpu.rs

    int failures = 0;
    auto glm_plain = [](float* out) {
        glm::mat4 m = glm::frustum<float>(float(vl), float(vr), float(vb), float(vt), float(vn), float(vf));
        (void)out;
        escape(&m[0][0]);
    };
    auto glm_tweak = [](float* out) {
        glm::mat4 m = glm::frustum<float>(float(vl), float(vr), float(vb), float(vt), float(vn), float(vf));
        m[2][2] *= 1.0F + seed_epsilon(vn, vf, float(vdelta), float(vpz));
        (void)out;
        escape(&m[0][0]);
    };
    auto glm_double = [](float* out) {
        glm::mat4 m(glm::frustum<double>(vl, vr, vb, vt, vn, vf));
        (void)out;
        escape(&m[0][0]);
    };
    auto glm_perspective = [](float* out) {
        glm::mat4 m = glm::perspective<float>(glm::radians(float(vfovy)), float(vaspect), float(vn), float(vf));
        (void)out;
        escape(&m[0][0]);
    };
    auto zs_offset = [&failures](float* out) {
        if (zshift_load_offset_matrix(vl, vr, vb, vt, vn, vf, vdelta, vpz, out) != ZSHIFT_OK) ++failures;
    };
    auto zs_frustum = [&failures](float* out) {
        if (zshift_frustum(vl, vr, vb, vt, vn, vf, out) != ZSHIFT_OK) ++failures;
    };
    auto zs_perspective = [&failures](float* out) {
        if (zshift_perspective(vfovy, vaspect, vn, vf, out) != ZSHIFT_OK) ++failures;
    };
    // The recommendation + matrix of benches/cpu.rs (D24, slope 1, 1920x1080, 8 sub-pixel bits,
    // the decal at -pz, the worst-case profile): a scene record filled per call, as an engine
    // fills one per decal.
    auto zs_recommend = [&failures](float* out) {
        ZshiftScene s;
        std::memset(&s, 0, sizeof s);
        s.l = vl, s.r = vr, s.b = vb, s.t = vt, s.n = vn, s.f = vf;
        s.viewport_width = 1920, s.viewport_height = 1080;
        s.depth_format = 0x81A6;  // GL_DEPTH_COMPONENT24
        s.decal_near = -vpz, s.decal_far = -vpz, s.slope = 1.0;
        s.subpixel_bits = 8;
        if (zshift_recommend_matrix(&s, out) != ZSHIFT_OK) ++failures;
    };
    // The front door on the engine's own matrix (GLM's), the same decal.
    static const glm::mat4 engine = glm::frustum<float>(float(vl), float(vr), float(vb), float(vt),
                                                        float(vn), float(vf));
    auto zs_decal = [&failures](float* out) {
        ZshiftDecal d;
        std::memset(&d, 0, sizeof d);
        d.viewport_width = 1920, d.viewport_height = 1080;
        d.format = ZSHIFT_FORMAT_UNORM24;
        d.subpixel_bits = 8;
        d.decal_near = -vpz, d.decal_far = -vpz, d.slope = 1.0;
        if (zshift_decal_matrix(&engine[0][0], ZSHIFT_CLIP_NEG_ONE_TO_ONE, &d, out) != ZSHIFT_OK)
            ++failures;
    };

    // A mesh decal over 8 terrain planes (slopes 0 to 1.75, the same depths), one call: the
    // front door's cost per plane against zs_decal.
    auto zs_planes = [&failures](float* out) {
        ZshiftDecal d[8];
        std::memset(d, 0, sizeof d);
        for (int i = 0; i < 8; ++i) {
            d[i].viewport_width = 1920, d[i].viewport_height = 1080;
            d[i].format = ZSHIFT_FORMAT_UNORM24;
            d[i].subpixel_bits = 8;
            d[i].decal_near = -vpz, d[i].decal_far = -vpz, d[i].slope = 0.25 * i;
        }
        if (zshift_decal_matrix_planes(&engine[0][0], ZSHIFT_CLIP_NEG_ONE_TO_ONE, d, 8, out) != ZSHIFT_OK)
            ++failures;
    };

    const char* keys[] = {"glm_frustum_float",          "glm_frustum_float_seed_tweak",
                          "glm_frustum_double",         "glm_perspective_float",
                          "zshift_load_offset_matrix_c_abi", "zshift_frustum_c_abi",
                          "zshift_perspective_c_abi", "zshift_recommend_matrix_c_abi",
                          "zshift_decal_matrix_c_abi", "zshift_decal_matrix_planes_8_c_abi"};
    const int variants = 10;
    std::vector<double> ns[variants];
    const int rounds = 61;
    for (int i = 0; i < rounds + 2; ++i) {
        double t[variants] = {batch(glm_plain),       batch(glm_tweak),  batch(glm_double),
                              batch(glm_perspective), batch(zs_offset),  batch(zs_frustum),
                              batch(zs_perspective),  batch(zs_recommend), batch(zs_decal),
                              batch(zs_planes)};
        if (i < 2) continue;  // the first two rounds warm caches and clocks
        for (int k = 0; k < variants; ++k) ns[k].push_back(t[k]);
    }
    if (failures) return 2;
    // Ratios round by round (the two sides a few milliseconds apart, under the same load), then
    // their median: steadier than a ratio of medians on a machine shared with other jobs.
    auto ratio = [&ns](int a, int b) {
        std::vector<double> r;
        for (size_t i = 0; i < ns[a].size(); ++i) r.push_back(ns[a][i] / ns[b][i]);
        return median(r);
    };
    std::printf("{\"glm_version\": \"%d.%d.%d.%d\"", GLM_VERSION_MAJOR, GLM_VERSION_MINOR,
                GLM_VERSION_PATCH, GLM_VERSION_REVISION);
    for (int k = 0; k < variants; ++k) std::printf(", \"%s\": %.3f", keys[k], median(ns[k]));
    std::printf(", \"ratio_frustum_to_glm\": %.3f, \"ratio_offset_to_glm_tweak\": %.3f",
                ratio(5, 0), ratio(4, 1));
    std::printf(", \"ratio_planes_8_to_decal\": %.3f", ratio(9, 8));
    std::printf("}\n");
    return 0;
}

int element10() {
    double l, r, b, t, n, f;
    while (std::scanf("%lf %lf %lf %lf %lf %lf", &l, &r, &b, &t, &n, &f) == 6) {
        glm::mat4 mf = glm::frustum<float>(float(l), float(r), float(b), float(t), float(n), float(f));
        glm::dmat4 md = glm::frustum<double>(l, r, b, t, n, f);
        std::printf("%a %a\n", double(mf[2][2]), md[2][2]);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && std::strcmp(argv[1], "time") == 0) return time_all();
    if (argc == 2 && std::strcmp(argv[1], "m10") == 0) return element10();
    std::fprintf(stderr, "usage: %s time|m10\n", argv[0]);
    return 64;
}
