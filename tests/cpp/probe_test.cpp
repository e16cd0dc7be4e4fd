// The probe through the C++ wrapper (bindings/cpp/zshift.hpp): a headless EGL context (Mesa
// llvmpipe), zshift::probe_with(eglGetProcAddress), the profile's llvmpipe figures, and
// zshift::Error with Status::gl for a loader that finds nothing. Fails, never skips, without a
// context.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "zshift.hpp"

namespace {

int failures = 0;

void expect(bool ok, const char *what) {
  if (!ok) {
    std::fprintf(stderr, "FAIL: %s\n", what);
    ++failures;
  }
}

// A 3.3 core context on Mesa's surfaceless platform, current on this thread (no surface: the
// probe draws into its own framebuffer).
bool make_context() {
  const EGLAttrib none[] = {EGL_NONE};
  EGLDisplay display = eglGetPlatformDisplay(0x31DD /* EGL_PLATFORM_SURFACELESS_MESA */, EGL_DEFAULT_DISPLAY, none);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API)) {
    std::fprintf(stderr, "no EGL surfaceless display (EGL error 0x%x)\n", static_cast<unsigned>(eglGetError()));
    return false;
  }
  const EGLint core[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, static_cast<EGLConfig>(nullptr), EGL_NO_CONTEXT, core);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    std::fprintf(stderr, "no 3.3 core context (EGL error 0x%x)\n", static_cast<unsigned>(eglGetError()));
    return false;
  }
  return true;
}

}  // namespace

int main() {
  if (!make_context()) return 1;
  zshift::Profile p = zshift::probe_with([](const char *name) { return eglGetProcAddress(name); });
  std::printf("probe: %.1f ms, subpixel_bits %d, r D16 %.3f D24 %.3f D32F %.3f, near_clip %d\n",
              p.probe_seconds * 1e3, p.subpixel_bits, p.resolvable[0], p.resolvable[1], p.resolvable[3],
              p.near_clip);
  expect(p.measured == 1, "a probed profile says measured");
  expect(p.subpixel_bits == zshift::subpixel_unsnapped, "llvmpipe sets depth up from unsnapped positions");
  // lp_state_setup.c: units * 2 * mrd on UNORM, 2^(e - 23) on float depth.
  expect(std::fabs(p.resolvable[1] - 2.0) < 0.01 && std::fabs(p.resolvable[3] - 1.0) < 0.01, "llvmpipe's r");
  expect(p.near_clip == static_cast<std::int32_t>(zshift::NearClip::clipped_f32), "llvmpipe clips in float");

  zshift::Profile worst = zshift::profile_worst_case();
  expect(worst.measured == 0 && worst.subpixel_bits == 8 && worst.resolvable[0] == 1.0, "worst case");

  // The probed profile in the recommendation: unsnapped (no snap term, though the scene says 8
  // bits), and the polygon-offset units counted in llvmpipe's r = 2 quanta.
  zshift::Scene scene = zshift::make_scene(-0.1, 0.1, -0.075, 0.075, 0.1, 1000, 256, 192, 0x81A6, 40, 60, 1.0,
                                           false, 8);
  zshift::Recommendation plain = zshift::recommend(scene), probed = zshift::recommend(scene, p);
  expect(plain.snap > 0 && probed.snap == 0 && probed.window_offset < plain.window_offset,
         "a probed profile's snapping wins over subpixel_bits");
  expect(std::fabs(probed.polygon_offset_units * 2 * probed.quantum / probed.window_offset - 1) < 1e-12,
         "units in r = 2 quanta");
  zshift::Decal decal = zshift::make_decal(256, 192, zshift::Format::unorm24, 8, 40, 60, 1.0);
  decal.base_reach = 1000;
  float m[16] = {};
  m[0] = 1.0f, m[5] = 4.0f / 3, m[10] = -1.0002f, m[11] = -1, m[14] = -0.20002f;
  zshift::Recommendation clipped = zshift::recommend_for_matrix(m, zshift::Clip::neg_one_to_one, decal, p);
  expect(clipped.snap == 0 && clipped.clip > 0, "the front door takes the profile and the base's reach");

  bool threw = false;
  try {
    zshift::probe_with([](const char *) { return static_cast<void (*)(void)>(nullptr); });
  } catch (const zshift::Error &e) {
    threw = e.status() == zshift::Status::gl;
  }
  expect(threw, "a loader that finds nothing throws Status::gl");
  if (failures == 0) std::printf("probe_test: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
