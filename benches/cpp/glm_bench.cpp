// C++ side of the zshift benchmarks: GLM's glm::frustum (Debian libglm-dev) beside zshift's C ABI
// called from C++, timed in the same loop shape, and GLM's element 10 for the report's error table.
//
// Built and run by scripts/report (not part of CI):
//   g++ -O2 -std=c++17 -Iinclude benches/cpp/glm_bench.cpp -Ltarget/release -lzshift ...
// Modes:
//   glm_bench time      -> one JSON object: median ns per call of each variant
//   glm_bench m10       -> reads "l r b t n f" lines on stdin, prints GLM's element 10 as
//                          C99 hex floats: float build, double build (one line per input)
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

// Inputs read through volatiles each call, so the compiler cannot fold the builders.
volatile double vl = -0.0577, vr = 0.0577, vb = -0.0414, vt = 0.0414, vn = 0.1, vf = 1000.0;
volatile double vpz = -50.0, vdelta = 0.0;
volatile float sink;

// The seed's LoadOffsetMatrix arithmetic: f, n GLdouble; delta, pz GLfloat (see benches/shared/seed.rs).
float seed_epsilon(double n, double f, float delta, float pz) {
    return -2.0F * f * n * delta / ((f + n) * pz * (pz + delta));
}

template <class F>
double median_ns_per_call(F body) {
    const int batches = 21;
    const long calls = 200000;
    std::vector<double> per_call;
    for (int i = 0; i < batches + 2; ++i) {
        auto t0 = std::chrono::steady_clock::now();
        for (long j = 0; j < calls; ++j) body();
        auto t1 = std::chrono::steady_clock::now();
        if (i >= 2)  // the first two batches warm caches and clocks
            per_call.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / calls);
    }
    std::sort(per_call.begin(), per_call.end());
    return per_call[per_call.size() / 2];
}

int time_all() {
    double n = vn, f = vf, pz = vpz;
    double step = 0.0;
    if (zshift_min_delta_toward(n, f, 24, pz, &step) != ZSHIFT_OK) return 1;
    vdelta = 4.0 * step;  // the same case as benches/cpu.rs

    double glm_plain = median_ns_per_call([] {
        glm::mat4 m = glm::frustum<float>(float(vl), float(vr), float(vb), float(vt), float(vn), float(vf));
        sink = m[2][2] + m[3][2];
    });
    double glm_tweak = median_ns_per_call([] {
        glm::mat4 m = glm::frustum<float>(float(vl), float(vr), float(vb), float(vt), float(vn), float(vf));
        m[2][2] *= 1.0F + seed_epsilon(vn, vf, float(vdelta), float(vpz));
        sink = m[2][2] + m[3][2];
    });
    double glm_double = median_ns_per_call([] {
        glm::dmat4 m = glm::frustum<double>(vl, vr, vb, vt, vn, vf);
        sink = float(m[2][2] + m[3][2]);
    });
    int failures = 0;
    double zs = median_ns_per_call([&failures] {
        float m[16];
        if (zshift_load_offset_matrix(vl, vr, vb, vt, vn, vf, vdelta, vpz, m) != ZSHIFT_OK) ++failures;
        sink = m[10] + m[14];
    });
    double zs_plain = median_ns_per_call([&failures] {
        float m[16];
        if (zshift_frustum(vl, vr, vb, vt, vn, vf, m) != ZSHIFT_OK) ++failures;
        sink = m[10] + m[14];
    });
    if (failures) return 2;
    std::printf(
        "{\"glm_version\": \"%d.%d.%d.%d\", \"glm_frustum_float\": %.3f, "
        "\"glm_frustum_float_seed_tweak\": %.3f, \"glm_frustum_double\": %.3f, "
        "\"zshift_load_offset_matrix_c_abi\": %.3f, \"zshift_frustum_c_abi\": %.3f}\n",
        GLM_VERSION_MAJOR, GLM_VERSION_MINOR, GLM_VERSION_PATCH, GLM_VERSION_REVISION, glm_plain,
        glm_tweak, glm_double, zs, zs_plain);
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
