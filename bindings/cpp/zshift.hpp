// zshift.hpp: a header-only C++17 wrapper over the zshift C ABI (include/zshift.h).
//
// Matrices come back as `zshift::Matrix` (std::array<float, 16>, column-major, what glLoadMatrixf
// and glUniformMatrix4fv(loc, 1, GL_FALSE, m.data()) take); scalars as double. A failing call
// throws `zshift::Error`, which carries the C status and its message; nothing else throws.
//
// Conventions, as in the C header: OpenGL right-handed eye space looking down -z, NDC depth
// [-1, 1], window depth [0, 1]; n, f, d are positive distances (f may be +infinity where a
// function says so), pz is an eye-space z (negative in front of the camera); delta > 0 moves
// geometry toward the camera and gives epsilon < 0. Equation numbers (4.1.x) refer to Lengyel's
// offset matrix; the depth step is Walker's depth resolution.
//
// Link with the zshift library (pkg-config zshift, or CMake's zshift::zshift).
#ifndef ZSHIFT_HPP
#define ZSHIFT_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "zshift.h"

static_assert(ZSHIFT_ABI_VERSION == 5, "zshift.hpp wraps version 5 of the zshift C ABI");

namespace zshift {

/// A 4x4 matrix, column-major: element 10 is row 2, column 2.
using Matrix = std::array<float, 16>;

/// The index in a Matrix of the element at `row`, `column` (0-based): column * 4 + row.
/// `index(2, 2)` is 10, the element that carries the depth offset.
constexpr std::size_t index(std::size_t row, std::size_t column) noexcept { return column * 4 + row; }

/// The C ABI version this wrapper was written for (ZSHIFT_ABI_VERSION).
inline constexpr int abi_version = ZSHIFT_ABI_VERSION;

/// The outcome of a C call, as a scoped enum with the header's values.
enum class Status : std::int32_t {
  ok = ZSHIFT_OK,
  null_pointer = ZSHIFT_ERR_NULL_POINTER,
  not_finite = ZSHIFT_ERR_NOT_FINITE,
  domain = ZSHIFT_ERR_DOMAIN,
  unresolvable = ZSHIFT_ERR_UNRESOLVABLE,
  overflow = ZSHIFT_ERR_OVERFLOW,
  internal = ZSHIFT_ERR_INTERNAL,
  gl = ZSHIFT_ERR_GL,
};

/// The C status code of a Status.
constexpr ZshiftStatus to_c(Status status) noexcept { return static_cast<ZshiftStatus>(status); }

/// The library's sentence for a status (never null; unknown codes get "unknown zshift status").
inline const char *message(Status status) noexcept { return zshift_status_message(to_c(status)); }

/// zshift_status_message under its C name: the same sentence as message().
inline const char *status_message(Status status) noexcept { return message(status); }

/// A zshift call failed. `status()` says how; `what()` says which input, its value and why (the
/// library's zshift_last_error() detail, such as "the near plane distance n must be greater than
/// 0 (n = -1)"), or the status's message where there is no detail.
class Error : public std::runtime_error {
 public:
  /// An error for `status`, with the detail the failing call left on this thread.
  explicit Error(ZshiftStatus status) : Error(status, zshift_last_error()) {}

  /// An error for `status` with the given detail (the status's message if it is empty).
  Error(ZshiftStatus status, const char *detail)
      : std::runtime_error(detail != nullptr && detail[0] != '\0' ? detail : zshift_status_message(status)),
        status_(static_cast<Status>(status)) {}

  /// How the call failed (never Status::ok).
  Status status() const noexcept { return status_; }

 private:
  Status status_;
};

namespace detail {
inline void check(ZshiftStatus status) {
  if (status != ZSHIFT_OK) throw Error(status);
}

template <typename Call>
Matrix matrix(Call call) {
  Matrix m{};
  check(call(m.data()));
  return m;
}

template <typename Call>
double scalar(Call call) {
  double value = 0.0;
  check(call(&value));
  return value;
}
}  // namespace detail

/// The glFrustum(l, r, b, t, n, f) matrix (seed 000, eq. 4.1.1), each element the float nearest
/// the exact value. `f` may be +infinity (element 10 is -1, element 14 is -2n).
/// Throws Error: Status::not_finite for NaN or a stray infinity; Status::domain if l == r,
/// b == t, n <= 0 or f <= n; Status::overflow if an element does not fit a float.
inline Matrix frustum(double l, double r, double b, double t, double n, double f) {
  return detail::matrix([&](float *out) { return zshift_frustum(l, r, b, t, n, f, out); });
}

/// The drop-in for the seed's LoadOffsetMatrix: frustum() with element 10 scaled by
/// 1 + epsilon(n, f, delta, pz) (eq. 4.1.3 and 4.1.7) and rounded away from the plain element,
/// so the offset is never lost to float rounding. Every other element equals frustum()'s.
/// Throws Error: as frustum(); Status::not_finite for a NaN or infinite delta or pz;
/// Status::domain if pz is outside [-f, -n] or pz + delta >= 0.
inline Matrix load_offset_matrix(double l, double r, double b, double t, double n, double f,
                                 double delta, double pz) {
  return detail::matrix(
      [&](float *out) { return zshift_load_offset_matrix(l, r, b, t, n, f, delta, pz, out); });
}

/// Epsilon for an eye-space shift delta at eye depth pz (eq. 4.1.7):
/// -(2fn/(f+n)) * delta / (pz * (pz + delta)). Throws Error: Status::not_finite,
/// Status::domain (bad planes, pz outside [-f, -n], pz + delta >= 0), Status::overflow.
inline double epsilon(double n, double f, double delta, double pz) {
  return detail::scalar([&](double *out) { return zshift_epsilon(n, f, delta, pz, out); });
}

/// The smallest |epsilon| that moves depth by one step of a `bits`-bit buffer:
/// 2/(2^bits - 1) * (f - n)/(f + n) (eq. 4.1.8 as corrected by seed 002).
/// Throws Error: Status::not_finite, Status::domain (bad planes, bits outside 1..=32).
inline double min_epsilon(double n, double f, std::uint32_t bits) {
  return detail::scalar([&](double *out) { return zshift_min_epsilon(n, f, bits, out); });
}

/// The smallest shift toward the camera that changes the stored depth at pz:
/// k*pz^2/(1 - k*pz), eq. 4.1.9 with seed 002's k = (f - n)/(f*n*(2^bits - 1)).
/// Throws Error: Status::not_finite, Status::domain (bad planes, pz outside [-f, -n], bits).
inline double min_delta_toward(double n, double f, std::uint32_t bits, double pz) {
  return detail::scalar([&](double *out) { return zshift_min_delta_toward(n, f, bits, pz, out); });
}

/// The largest (least negative) shift away from the camera that still changes the stored depth
/// at pz: -k*pz^2/(1 + k*pz), eq. 4.1.10 with the corrected k.
/// Throws Error: as min_delta_toward(); Status::unresolvable if k*|pz| >= 1; Status::overflow.
inline double max_delta_away(double n, double f, std::uint32_t bits, double pz) {
  return detail::scalar([&](double *out) { return zshift_max_delta_away(n, f, bits, pz, out); });
}

/// The window depth in [0, 1] of a point at eye distance d (Walker's f(d), seed 001).
/// Throws Error: Status::not_finite, Status::domain (bad planes, d outside [n, f]).
inline double window_depth(double n, double f, double d) {
  return detail::scalar([&](double *out) { return zshift_window_depth(n, f, d, out); });
}

/// The exact depth step at eye distance d: q*d^2/(b + q*d), q = 1/(2^bits - 1),
/// b = fn/(f - n) (Walker's eq. 3, seed 001). Throws Error: Status::not_finite, Status::domain.
inline double depth_resolution(double n, double f, std::uint32_t bits, double d) {
  return detail::scalar([&](double *out) { return zshift_depth_resolution(n, f, bits, d, out); });
}

/// What a scene knows about one decal and the surface under it (the C `ZshiftScene`): the base's
/// glFrustum, the viewport, the depth attachment's GL internal format, the decal's nearest and
/// farthest eye distance, its plane's eye-space slope |dz/dx| + |dz/dy|, whether base and decal
/// share one float z (`exact_depth`), and GL_SUBPIXEL_BITS (or `subpixel_unsnapped`).
using Scene = ZshiftScene;

/// The recommended offset in every form an engine may apply it (the C `ZshiftRecommendation`).
using Recommendation = ZshiftRecommendation;

/// `subpixel_bits` for a rasterizer that sets depth up from unsnapped positions (Mesa llvmpipe).
inline constexpr std::int32_t subpixel_unsnapped = ZSHIFT_SUBPIXEL_UNSNAPPED;

/// A Scene from its fields, in declaration order; usable in constant expressions. depth_func,
/// base_reach, profile and the pipeline fields take their documented defaults (0: the
/// convention's strict test, a base inside the frustum; nullptr: the worst-case profile with
/// subpixel_bits; the viewport at the framebuffer's origin, glDepthRange(0, 1), eye-space
/// vertices); set them on the result, or pass a probed Profile to recommend(scene, profile).
constexpr Scene make_scene(double l, double r, double b, double t, double n, double f,
                           std::uint32_t viewport_width, std::uint32_t viewport_height,
                           std::uint32_t depth_format, double decal_near, double decal_far,
                           double slope, bool exact_depth, std::int32_t subpixel_bits) noexcept {
  return Scene{l, r, b, t, n, f, viewport_width, viewport_height, depth_format, decal_near,
               decal_far, slope, exact_depth ? 1u : 0u, subpixel_bits, ZshiftDepthTest{0u}, 0.0, nullptr,
               nullptr, 0u, ZshiftPipeline{0u, 0u, 0.0, 0.0, 0.0, 0u, nullptr, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}}};
}

/// The smallest offset zshift's error model of a real rasterizer guarantees ends z-fighting
/// for `scene` (quantum, f32 rounding of transform, vertices and interpolation, sub-pixel
/// snapping; seeds 000, 002, 004), with its bleed gap and glPolygonOffset equivalent.
/// Throws Error: Status::not_finite; Status::domain (bad frustum, zero viewport, unknown
/// depth_format, decal depths outside [n, f] or decreasing, negative slope, exact_depth with a
/// slope, subpixel_bits < -1 or > 32); Status::overflow.
inline Recommendation recommend(const Scene &scene) {
  Recommendation out{};
  detail::check(zshift_recommend(&scene, &out));
  return out;
}

/// The decal's projection for the recommended offset: frustum() of the scene with element 10
/// scaled by 1 + recommend(scene).epsilon, rounded outward. Throws Error: as recommend().
inline Matrix recommend_matrix(const Scene &scene) {
  return detail::matrix([&](float *out) { return zshift_recommend_matrix(&scene, out); });
}

// ---- Every clip convention, Kooima's median projection, depth bias, planning ----

/// NDC depth convention (ZSHIFT_CLIP_*): OpenGL's [-1, 1]; [0, 1] (glClipControl ZERO_TO_ONE,
/// Direct3D, Vulkan); reversed [0, 1] (near 1, far 0, GL_GREATER; for float depth).
enum class Clip : std::int32_t {
  neg_one_to_one = 0,        // ZSHIFT_CLIP_NEG_ONE_TO_ONE
  zero_to_one = 1,           // ZSHIFT_CLIP_ZERO_TO_ONE
  reversed_zero_to_one = 2,  // ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE
};

/// Depth attachment format (ZSHIFT_FORMAT_*): 16-, 24-, 32-bit unsigned normalized, 32-bit float.
enum class Format : std::uint32_t {
  unorm16 = 0x81A5,  // GL_DEPTH_COMPONENT16
  unorm24 = 0x81A6,  // GL_DEPTH_COMPONENT24
  unorm32 = 0x81A7,  // GL_DEPTH_COMPONENT32
  float32 = 0x8CAC,  // GL_DEPTH_COMPONENT32F
};

/// The depth test of a pass (ZSHIFT_DEPTH_TEST_*), by its GL enum.
enum class DepthTest : std::uint32_t {
  less = 0x0201,     // GL_LESS
  lequal = 0x0203,   // GL_LEQUAL
  greater = 0x0204,  // GL_GREATER
  gequal = 0x0206,   // GL_GEQUAL
};

/// Whose constant depth bias (ZSHIFT_BIAS_*): glPolygonOffset units, Direct3D DepthBias, Vulkan
/// depthBiasConstantFactor.
enum class BiasApi : std::int32_t {
  opengl = 0,    // ZSHIFT_BIAS_OPENGL
  direct3d = 1,  // ZSHIFT_BIAS_DIRECT3D
  vulkan = 2,    // ZSHIFT_BIAS_VULKAN
};

/// What range_offset() returns (ZSHIFT_OFFSET_*): a signed NDC offset for element 10, or a
/// relative epsilon for element 14 (reversed Z with float depth).
enum class OffsetKind : std::int32_t {
  ndc = 0,       // ZSHIFT_OFFSET_NDC
  relative = 1,  // ZSHIFT_OFFSET_RELATIVE
};

namespace detail {
// The C argument types of the scoped enums (the C constants are `static const` structs, so the
// enums above restate their values; tests/cpp checks that they agree).
inline ZshiftClip to_c(Clip v) noexcept { ZshiftClip c; c.value = static_cast<std::int32_t>(v); return c; }
inline ZshiftFormat to_c(Format v) noexcept { ZshiftFormat c; c.value = static_cast<std::uint32_t>(v); return c; }
inline ZshiftDepthTest to_c(DepthTest v) noexcept { ZshiftDepthTest c; c.value = static_cast<std::uint32_t>(v); return c; }
inline ZshiftBiasApi to_c(BiasApi v) noexcept { ZshiftBiasApi c; c.value = static_cast<std::int32_t>(v); return c; }
inline ZshiftOffsetKind to_c(OffsetKind v) noexcept { ZshiftOffsetKind c; c.value = static_cast<std::int32_t>(v); return c; }
}  // namespace detail

/// The smallest tweak for tweaked_infinite() that keeps far geometry inside the clip volume in
/// float arithmetic: 2^-22 (Lengyel, GDC 2007).
inline constexpr double min_infinite_tweak = ZSHIFT_MIN_INFINITE_TWEAK;

/// gluPerspective(fovy, aspect, n, f), fovy in degrees, NDC depth [-1, 1], f may be +infinity.
/// Throws Error: Status::not_finite; Status::domain unless 0 < fovy < 180, aspect > 0, 0 < n < f.
inline Matrix perspective(double fovy, double aspect, double n, double f) {
  return detail::matrix([&](float *out) { return zshift_perspective(fovy, aspect, n, f, out); });
}

/// glFrustum's x/y rows with the depth row of `clip` (zshift_projection).
/// Throws Error: as frustum(); Status::domain for an unknown clip.
inline Matrix projection(double l, double r, double b, double t, double n, double f, Clip clip) {
  return detail::matrix([&](float *out) {
    return zshift_projection(l, r, b, t, n, f, detail::to_c(clip), out);
  });
}

/// projection() with geometry at `pz` moved toward the camera by `delta`: a constant NDC offset
/// through element 10 ([-1, 1], [0, 1]; seed 000 eq. 4.1.3-4.1.7 generalised) or element 14
/// scaled (reversed), rounded outward. Throws Error: as projection(); Status::domain if pz is
/// outside [-f, -n] or the shifted point leaves [n, f].
inline Matrix offset_projection(double l, double r, double b, double t, double n, double f, Clip clip,
                                double delta, double pz) {
  return detail::matrix([&](float *out) {
    return zshift_offset_projection(l, r, b, t, n, f, detail::to_c(clip), delta, pz, out);
  });
}

/// offset_projection() for gluPerspective parameters. Throws Error: as both.
inline Matrix offset_perspective(double fovy, double aspect, double n, double f, Clip clip, double delta,
                                 double pz) {
  return detail::matrix([&](float *out) {
    return zshift_offset_perspective(fovy, aspect, n, f, detail::to_c(clip), delta, pz, out);
  });
}

/// The tweaked infinite projection: m10 = tweak - 1, m14 = (tweak - 2) n, NDC [-1, 1].
/// Throws Error: as frustum(); Status::domain unless 0 <= tweak < 1.
inline Matrix tweaked_infinite(double l, double r, double b, double t, double n, double tweak) {
  return detail::matrix([&](float *out) { return zshift_tweaked_infinite(l, r, b, t, n, tweak, out); });
}

/// tweaked_infinite() with geometry at `pz` moved toward the camera by `delta` (element 10,
/// rounded outward). Throws Error: as tweaked_infinite(); Status::domain if pz or pz + delta > -n.
inline Matrix offset_tweaked_infinite(double l, double r, double b, double t, double n, double tweak,
                                      double delta, double pz) {
  return detail::matrix(
      [&](float *out) { return zshift_offset_tweaked_infinite(l, r, b, t, n, tweak, delta, pz, out); });
}

/// The `ndc_offset` uniform of bindings/glsl/ftransform_mdp.glsl (Kooima's median projection,
/// seed 003) that moves geometry at `pz` toward the camera by `delta`.
/// Throws Error: Status::not_finite; Status::domain unless median > 0, pz <= 0, pz + delta <= 0.
inline double median_ndc_offset(double median, double delta, double pz) {
  return detail::scalar([&](double *out) { return zshift_median_ndc_offset(median, delta, pz, out); });
}

/// The window depth at eye distance d under `clip` (Walker's f(d), seed 001; reversed
/// n(f - d)/((f - n)d)). Throws Error: Status::not_finite, Status::domain.
inline double window_depth_clip(double n, double f, Clip clip, double d) {
  return detail::scalar(
      [&](double *out) { return zshift_window_depth_clip(n, f, detail::to_c(clip), d, out); });
}

/// The exact depth step at eye distance d under `clip` and `format` (Walker's eq. 3 for every
/// convention). Throws Error: Status::not_finite, Status::domain.
inline double depth_step(double n, double f, Clip clip, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_depth_step(n, f, detail::to_c(clip), detail::to_c(format), d, out);
  });
}

/// The depth step at eye distance d (>= 0) under Kooima's median projection (seed 003).
/// Throws Error: Status::not_finite, Status::domain.
inline double median_depth_step(double median, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_median_depth_step(median, detail::to_c(format), d, out);
  });
}

/// The smallest constant NDC offset (a magnitude) that changes the stored depth at d (seed 002's
/// quantum 2/(2^m - 1) for UNORM under [-1, 1]). Throws Error: as depth_step().
inline double min_ndc_offset(double n, double f, Clip clip, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_min_ndc_offset(n, f, detail::to_c(clip), detail::to_c(format), d, out);
  });
}

/// The smallest |epsilon| for element 10's scaling that changes the stored depth at d under
/// `clip` and `format` (eq. 4.1.8 as corrected by seed 002 under [-1, 1]). Throws Error: as
/// depth_step(); Status::unresolvable for reversed Z with f = +infinity.
inline double min_epsilon_clip(double n, double f, Clip clip, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_min_epsilon_clip(n, f, detail::to_c(clip), detail::to_c(format), d,
                                   out);
  });
}

/// The smallest relative epsilon (element 14 scaled by 1 + epsilon) that changes the stored depth
/// at d. Throws Error: as depth_step().
inline double min_relative_epsilon(double n, double f, Clip clip, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_min_relative_epsilon(n, f, detail::to_c(clip), detail::to_c(format), d,
                                       out);
  });
}

/// The constant depth bias of `api` equivalent to moving geometry at pz toward the camera by
/// delta (negative under [-1, 1] and [0, 1]). Throws Error: Status::not_finite, Status::domain.
inline double bias_of_shift(double n, double f, Clip clip, Format format, BiasApi api, double delta, double pz) {
  return detail::scalar([&](double *out) {
    return zshift_bias_of_shift(n, f, detail::to_c(clip), detail::to_c(format),
                                detail::to_c(api), delta, pz, out);
  });
}

/// The eye-space shift toward the camera a constant `bias` of `api` makes at pz (the inverse of
/// bias_of_shift()). Throws Error: as bias_of_shift(); Status::unresolvable.
inline double shift_of_bias(double n, double f, Clip clip, Format format, BiasApi api, double bias, double pz) {
  return detail::scalar([&](double *out) {
    return zshift_shift_of_bias(n, f, detail::to_c(clip), detail::to_c(format),
                                detail::to_c(api), bias, pz, out);
  });
}

/// The tightest clip planes {n, f} for a scene between eye distances `nearest` and `farthest`
/// (f may be +infinity). Throws Error: Status::not_finite; Status::domain unless
/// 0 < nearest <= farthest.
inline std::array<double, 2> tight_planes(double nearest, double farthest) {
  std::array<double, 2> planes{};
  detail::check(zshift_tight_planes(nearest, farthest, planes.data()));
  return planes;
}

/// range_offset()'s result: the offset, and the eye-space shifts it makes at lo and at hi.
struct RangeOffset {
  double offset, shift_at_lo, shift_at_hi;
};

/// The smallest single offset that moves stored depth by at least `steps` steps at every
/// distance in [lo, hi]; multiply `offset` by k for the k-th stacked decal layer.
/// Throws Error: Status::not_finite, Status::domain, Status::unresolvable.
inline RangeOffset range_offset(double n, double f, Clip clip, Format format, OffsetKind kind, double lo,
                                double hi, double steps) {
  std::array<double, 3> out{};
  detail::check(zshift_range_offset(n, f, detail::to_c(clip), detail::to_c(format),
                                    detail::to_c(kind), lo, hi, steps, out.data()));
  return {out[0], out[1], out[2]};
}

/// recommend() for a scene drawn under `clip` (zshift_recommend_clip): Clip::neg_one_to_one is
/// recommend(); Clip::zero_to_one (glClipControl GL_ZERO_TO_ONE, GL_LESS) a constant NDC offset
/// through element 10 (`epsilon` < 0, Lengyel's element-10 form); Clip::reversed_zero_to_one
/// (GL_GREATER, clear depth 0) a relative `epsilon` > 0 for element 14, `window_offset` its value
/// at decal_far, no glPolygonOffset equivalent (0, 0). Throws Error: as recommend();
/// Status::domain for an unknown clip.
inline Recommendation recommend_clip(const Scene &scene, Clip clip) {
  Recommendation out{};
  detail::check(zshift_recommend_clip(&scene, detail::to_c(clip), &out));
  return out;
}

/// The decal's projection for recommend_clip()'s offset: projection() under `clip` with element
/// 10 lowered ([-1, 1], [0, 1]) or element 14 scaled by 1 + epsilon (reversed), rounded outward.
/// Throws Error: as recommend_clip().
inline Matrix recommend_clip_matrix(const Scene &scene, Clip clip) {
  return detail::matrix(
      [&](float *out) { return zshift_recommend_clip_matrix(&scene, detail::to_c(clip), out); });
}

// ---- The front door: the engine's own matrix in, the decal's matrix out ----

/// What the engine knows about a decal besides its matrix (the C `ZshiftDecal`). Fill every
/// field; make_decal() names them in order.
using Decal = ZshiftDecal;

/// A Decal: viewport, depth format, GL_SUBPIXEL_BITS (or subpixel_unsnapped), the decal's
/// nearest and farthest eye distance, its plane's slope |dz/dx| + |dz/dy|, and whether every
/// corner of base and decal has the same float eye z.
inline Decal make_decal(std::uint32_t viewport_width, std::uint32_t viewport_height, Format format,
                        std::int32_t subpixel_bits, double decal_near, double decal_far, double slope,
                        bool exact_depth = false) noexcept {
  Decal d{};
  d.viewport_width = viewport_width;
  d.viewport_height = viewport_height;
  d.format = detail::to_c(format);
  d.subpixel_bits = subpixel_bits;
  d.decal_near = decal_near;
  d.decal_far = decal_far;
  d.slope = slope;
  d.exact_depth = exact_depth ? 1u : 0u;
  return d;
}

/// `scene` described by the decal's eye-space corners (`count` of them, 3 floats each, kept
/// alive by the caller until the call that uses the scene returns) instead of decal_near,
/// decal_far and slope, which become 0: the library derives them and the decal's place on the
/// screen, which makes the offset far tighter on sloped planes.
inline Scene with_corners(Scene scene, const float *corners, std::uint32_t count) noexcept {
  scene.decal_near = scene.decal_far = scene.slope = 0.0;
  scene.decal_corners = corners;
  scene.decal_corner_count = count;
  return scene;
}

/// `decal` described by its eye-space corners, as with_corners(Scene, ...); projected through
/// the matrix passed with it (perspective only). A decal under the camera may reach behind it,
/// and one may run on beyond the far plane: the part drawn counts.
inline Decal with_corners(Decal decal, const float *corners, std::uint32_t count) noexcept {
  decal.decal_near = decal.decal_far = decal.slope = 0.0;
  decal.decal_corners = corners;
  decal.decal_corner_count = count;
  return decal;
}

/// The decal's matrix: the engine's own projection `m` (16 floats, column-major, e.g.
/// glm::value_ptr(P)) with the recommended offset for `decal` in its own offset element, every
/// other element bit-identical (zshift_decal_matrix). Throws Error (what() names the element or
/// field): a matrix that is not a perspective or orthographic projection, a convention mismatch
/// (a reversed-Z matrix with Clip::neg_one_to_one), a bad decal.
inline Matrix decal_matrix(const float *m, Clip clip, const Decal &decal) {
  return detail::matrix([&](float *out) { return zshift_decal_matrix(m, detail::to_c(clip), &decal, out); });
}
/// decal_matrix() of a Matrix.
inline Matrix decal_matrix(const Matrix &m, Clip clip, const Decal &decal) {
  return decal_matrix(m.data(), clip, decal);
}

/// The recommendation behind decal_matrix() (zshift_recommend_for_matrix). Throws Error: as
/// decal_matrix().
inline Recommendation recommend_for_matrix(const float *m, Clip clip, const Decal &decal) {
  Recommendation out{};
  detail::check(zshift_recommend_for_matrix(m, detail::to_c(clip), &decal, &out));
  return out;
}

/// The matrix of one decal on several planes, drawn in one pass (zshift_decal_matrix_planes): a
/// mesh decal over terrain, cut from its triangles, one Decal per plane (each its own corners,
/// base_reach and pipeline.world_box; the rest shared). The largest of the planes' offsets.
/// Throws Error: as decal_matrix(), what() beginning "plane i: " for a plane's refusal;
/// Status::unresolvable naming largest_plane where the largest offset would move plane i past the
/// near plane though its own fits: draw each piece with its own decal_matrix(), or leave out the
/// piece of plane largest_plane.
inline Matrix decal_matrix_planes(const float *m, Clip clip, const Decal *decals, std::uint32_t count) {
  return detail::matrix(
      [&](float *out) { return zshift_decal_matrix_planes(m, detail::to_c(clip), decals, count, out); });
}
/// decal_matrix_planes() of a Matrix and a vector of planes.
/// (More than 65536 planes are refused, as the C call refuses them.)
inline Matrix decal_matrix_planes(const Matrix &m, Clip clip, const std::vector<Decal> &decals) {
  const auto count = decals.size() > 65536 ? std::uint32_t{65537} : static_cast<std::uint32_t>(decals.size());
  return decal_matrix_planes(m.data(), clip, decals.data(), count);
}

/// The recommendation behind decal_matrix_planes() (zshift_recommend_for_planes): the plane with
/// the largest offset, with bleed_gap the largest of every plane's at that offset. Throws Error:
/// as decal_matrix_planes().
inline Recommendation recommend_for_planes(const float *m, Clip clip, const Decal *decals, std::uint32_t count) {
  Recommendation out{};
  detail::check(zshift_recommend_for_planes(m, detail::to_c(clip), decals, count, &out));
  return out;
}

/// The engine's own projection `m` with geometry at eye distance `d` moved toward the camera by
/// `delta` (zshift_offset_matrix): element 10 (perspective [-1, 1], [0, 1]), 14 (perspective
/// reversed, relative; orthographic, constant), rounded outward; every other element
/// bit-identical. Throws Error: as decal_matrix(); d <= 0 or d - delta <= 0 (perspective).
inline Matrix offset_matrix(const float *m, Clip clip, double delta, double d) {
  return detail::matrix([&](float *out) { return zshift_offset_matrix(m, detail::to_c(clip), delta, d, out); });
}
/// offset_matrix() of a Matrix.
inline Matrix offset_matrix(const Matrix &m, Clip clip, double delta, double d) {
  return offset_matrix(m.data(), clip, delta, d);
}

/// The engine's own projection `m` with NDC depth moved toward the camera by `ndc`
/// (zshift_offset_matrix_ndc). Throws Error: as decal_matrix().
inline Matrix offset_matrix_ndc(const float *m, Clip clip, double ndc) {
  return detail::matrix([&](float *out) { return zshift_offset_matrix_ndc(m, detail::to_c(clip), ndc, out); });
}
/// offset_matrix_ndc() of a Matrix.
inline Matrix offset_matrix_ndc(const Matrix &m, Clip clip, double ndc) {
  return offset_matrix_ndc(m.data(), clip, ndc);
}

/// glOrtho(l, r, b, t, n, f) with the depth row of `clip` (zshift_ortho).
inline Matrix ortho(double l, double r, double b, double t, double n, double f, Clip clip) {
  return detail::matrix([&](float *out) { return zshift_ortho(l, r, b, t, n, f, detail::to_c(clip), out); });
}

/// ortho() with every point moved toward the camera by `delta` (element 14, rounded outward).
inline Matrix offset_ortho(double l, double r, double b, double t, double n, double f, Clip clip, double delta) {
  return detail::matrix(
      [&](float *out) { return zshift_offset_ortho(l, r, b, t, n, f, detail::to_c(clip), delta, out); });
}

/// The exact depth step of an orthographic projection at eye distance d: r * (f - n).
inline double ortho_depth_step(double n, double f, Clip clip, Format format, double d) {
  return detail::scalar([&](double *out) {
    return zshift_ortho_depth_step(n, f, detail::to_c(clip), detail::to_c(format), d, out);
  });
}

/// The detail of the last failed zshift call on this thread ("" after a success): which
/// input, its value and why. zshift::Error::what() already carries it.
inline std::string last_error() { return zshift_last_error(); }

/// The library version, such as "0.1.0": a static string, as zshift_version() returns it.
inline const char *version() noexcept { return zshift_version(); }

/// An eye-space vertex (x, y, z), for clip_to_frustum().
using Vertex = std::array<double, 3>;

namespace detail {
/// The checks and buffers both cuts share: `call` is the C cut of `polygon` into a buffer of
/// capacity count + 6 (the header: always enough).
template <typename Call>
std::vector<Vertex> cut(const std::vector<Vertex> &polygon, Call call) {
  static_assert(sizeof(Vertex) == 3 * sizeof(double), "Vertex is three packed doubles");
  if (polygon.size() > 65536) throw Error(ZSHIFT_ERR_DOMAIN, "the polygon must have at most 65536 vertices");
  const std::uint32_t count = static_cast<std::uint32_t>(polygon.size());
  const std::uint32_t capacity = count + 6;
  std::vector<Vertex> out(capacity);
  std::uint32_t written = 0;
  check(call(polygon.empty() ? nullptr : polygon.data()->data(), count, out.data()->data(), capacity, &written));
  out.resize(written);
  return out;
}
}  // namespace detail

/// Cuts a convex base polygon (eye-space vertices in order around it) to the view frustum of
/// glFrustum(l, r, b, t, n, f), in double and slightly inside, so that the rasterizer clips
/// nothing of it (zshift_clip_to_frustum): draw the result as a triangle fan and pass
/// base_reach = 0. Empty when nothing is inside. Throws Error: Status::not_finite,
/// Status::domain (a bad frustum, more than 65536 vertices).
inline std::vector<Vertex> clip_to_frustum(double l, double r, double b, double t, double n, double f,
                                           const std::vector<Vertex> &polygon) {
  return detail::cut(polygon, [&](const double *in, std::uint32_t count, double *out, std::uint32_t capacity,
                                  std::uint32_t *written) {
    return zshift_clip_to_frustum(l, r, b, t, n, f, in, count, out, capacity, written);
  });
}

/// clip_to_frustum() for a polygon the engine stores as `stored` says (world space through a
/// float view matrix: its world_reach, eye_first, and view_matrix with world_box, as a
/// ZshiftScene's pipeline; zshift_clip_to_frustum_stored): the cut lies further inside by the
/// largest error that storage and the float transform can give a vertex, which is relative to
/// the world coordinates, not to the vertex's distance from the camera (cut only 2^-16 inside, a
/// vertex close to the camera can land outside, and a rasterizer that clips at the sides cuts a
/// sliver off its triangle). Camera-relative rendering needs none of it. Throws Error as
/// clip_to_frustum(), and Status::domain for a pipeline field out of range.
inline std::vector<Vertex> clip_to_frustum(double l, double r, double b, double t, double n, double f,
                                           const std::vector<Vertex> &polygon, const ZshiftPipeline &stored) {
  return detail::cut(polygon, [&](const double *in, std::uint32_t count, double *out, std::uint32_t capacity,
                                  std::uint32_t *written) {
    return zshift_clip_to_frustum_stored(l, r, b, t, n, f, &stored, in, count, out, capacity, written);
  });
}

// ---------------------------------------------------------------------------------------------
// The rasterizer probe (zshift_probe): measures the current GL context's profile through a
// function loader. Added by the probe's owner; keep this block separate.
// ---------------------------------------------------------------------------------------------

/// What a rasterizer does that the offset model needs (the C ZshiftProfile; its fields are
/// documented in zshift.h). Get one from probe() or profile_worst_case().
using Profile = ZshiftProfile;

/// Profile::near_clip values.
enum class NearClip : std::int32_t {
  clipped_f32 = ZSHIFT_NEAR_CLIP_CLIPPED_F32,
  plane_preserving = ZSHIFT_NEAR_CLIP_PLANE_PRESERVING,
};

/// The worst-case profile: the recommendation's default assumptions (measured == 0).
inline Profile profile_worst_case() {
  Profile out{};
  detail::check(zshift_profile_worst_case(&out));
  return out;
}

/// Measures the rasterizer of the OpenGL context current on this thread (zshift_probe): call it
/// once after creating the context. `loader(name, user)` returns the entry point `name` or NULL.
/// Every GL state the probe touches is restored. Throws Error: Status::gl with what failed in
/// zshift's message (a missing entry point, no context or one older than 3.2, a pending GL
/// error, a refused depth format), Status::null_pointer for a null loader.
inline Profile probe(ZshiftGlLoader loader, void *user = nullptr) {
  Profile out{};
  detail::check(zshift_probe(loader, user, &out));
  return out;
}

/// probe() with any callable taking the entry point's name, such as
/// `[](const char *name) { return eglGetProcAddress(name); }` or glfwGetProcAddress: its result
/// (a function pointer, or NULL) is converted to ZshiftGlProc.
template <typename GetProc>
Profile probe_with(GetProc &&get_proc) {
  ZshiftGlLoader trampoline = [](const char *name, void *user) -> ZshiftGlProc {
    auto &get = *static_cast<std::remove_reference_t<GetProc> *>(user);
    return reinterpret_cast<ZshiftGlProc>(get(name));
  };
  return probe(trampoline, static_cast<void *>(&get_proc));
}

/// recommend() with the rasterizer's profile (from probe(), once per context): the profile
/// supplies every rasterizer fact, its snapping included (scene.subpixel_bits is then ignored).
inline Recommendation recommend(Scene scene, const Profile &profile) {
  scene.profile = &profile;
  return recommend(scene);
}

/// recommend_clip() with the rasterizer's profile, as recommend(scene, profile).
inline Recommendation recommend_clip(Scene scene, Clip clip, const Profile &profile) {
  scene.profile = &profile;
  return recommend_clip(scene, clip);
}

/// recommend_clip_matrix() with the rasterizer's profile, as recommend(scene, profile).
inline Matrix recommend_clip_matrix(Scene scene, Clip clip, const Profile &profile) {
  scene.profile = &profile;
  return recommend_clip_matrix(scene, clip);
}

/// decal_matrix() with the rasterizer's profile (Decal::profile; decal.subpixel_bits is then
/// ignored) and the base's reach (Decal::base_reach, 0 when it lies inside the frustum).
inline Matrix decal_matrix(const float *m, Clip clip, Decal decal, const Profile &profile) {
  decal.profile = &profile;
  return decal_matrix(m, clip, decal);
}

/// recommend_for_matrix() with the rasterizer's profile, as decal_matrix(m, clip, decal, profile).
inline Recommendation recommend_for_matrix(const float *m, Clip clip, Decal decal, const Profile &profile) {
  decal.profile = &profile;
  return recommend_for_matrix(m, clip, decal);
}

// ---- Edges over their own faces (zshift_edge_offset, docs/edges.md) ----

/// What an engine knows about a mesh whose edges it draws over its faces (ZshiftEdges).
using Edges = ZshiftEdges;
/// The offset for the edges by one method (ZshiftEdgeOffset).
using EdgeOffset = ZshiftEdgeOffset;

/// Which way edges are kept in front of their faces.
enum class EdgeMethod : std::uint32_t {
  /// Faces pushed back with glPolygonOffset (D3D/Vulkan depth bias), edges unoffset.
  polygon_offset = ZSHIFT_EDGES_POLYGON_OFFSET,
  /// Edges pulled forward through the projection matrix (the one offset that moves GL_LINES).
  matrix = ZSHIFT_EDGES_MATRIX,
};

/// The offset that keeps a mesh's edges in front of its own faces, with the hidden-line gap it
/// costs (zshift_edge_offset). Throws Error: a bad field (what() names it), an orthographic
/// `m`, Status::unresolvable where the gap exceeds hidden_separation (see edge_planes()).
inline EdgeOffset edge_offset(const float *m, Clip clip, const Edges &edges, EdgeMethod method) {
  EdgeOffset out{};
  detail::check(zshift_edge_offset(m, detail::to_c(clip), &edges, static_cast<std::uint32_t>(method), &out));
  return out;
}
/// edge_offset() of a Matrix.
inline EdgeOffset edge_offset(const Matrix &m, Clip clip, const Edges &edges, EdgeMethod method) {
  return edge_offset(m.data(), clip, edges, method);
}

/// Near and far planes with which edge_offset() answers (zshift_edge_planes). Throws Error: as
/// edge_offset(); Status::unresolvable when even the tightest planes do not.
inline std::array<double, 2> edge_planes(const float *m, Clip clip, const Edges &edges, EdgeMethod method) {
  std::array<double, 2> out{};
  detail::check(zshift_edge_planes(m, detail::to_c(clip), &edges, static_cast<std::uint32_t>(method), out.data()));
  return out;
}
/// edge_planes() of a Matrix.
inline std::array<double, 2> edge_planes(const Matrix &m, Clip clip, const Edges &edges, EdgeMethod method) {
  return edge_planes(m.data(), clip, edges, method);
}

/// A mesh as the engine draws it (ZshiftMesh): clip matrix, positions and stride, indices.
using Mesh = ZshiftMesh;
/// A mesh's steepest face as drawn (ZshiftSteepestFace): `gradient` is what Edges::face_gradient
/// takes (face_angle 0) for this mesh, matrix and viewport; `length` bounds multisampled lines.
using SteepestFace = ZshiftSteepestFace;

/// A Mesh over packed positions and an index vector (which must outlive it), drawn through
/// `clip_matrix` (projection * view * model, which must outlive it too).
inline Mesh make_mesh(const Matrix &clip_matrix, const std::vector<std::array<float, 3>> &positions,
                      const std::vector<std::uint32_t> &indices) {
  Mesh mesh{};
  mesh.clip_matrix = clip_matrix.data();
  mesh.positions = positions.empty() ? nullptr : positions[0].data();
  mesh.vertex_count = positions.size();
  mesh.position_stride = sizeof(positions[0]);
  mesh.indices = indices.empty() ? nullptr : indices.data();
  mesh.index_count = indices.size();
  return mesh;
}

/// The steepest face of a mesh as drawn (zshift_steepest_face): the largest window-depth gradient
/// max(|dz/dx|, |dz/dy|) of its triangles (and the largest length) in a `width` x `height`
/// viewport, leaving out triangles that draw nothing and those steeper than `limit` (the
/// face_gradient a face_angle gives, or infinity). Throws Error naming a bad input (an index
/// past the positions, a NaN position, a zero viewport).
inline SteepestFace steepest_face(const Mesh &mesh, Clip clip, std::uint32_t width, std::uint32_t height,
                                  double limit = std::numeric_limits<double>::infinity()) {
  SteepestFace out{};
  detail::check(zshift_steepest_face(&mesh, detail::to_c(clip), width, height, limit, &out));
  return out;
}

/// edge_offset() paying for the mesh's own steepest faces within the limit that `edges`'
/// face_angle (or face_gradient) sets (zshift_edge_offset_for_mesh). Throws as edge_offset() and
/// steepest_face().
inline EdgeOffset edge_offset_for_mesh(const float *m, Clip clip, const Edges &edges, const Mesh &mesh,
                                       EdgeMethod method) {
  EdgeOffset out{};
  detail::check(zshift_edge_offset_for_mesh(m, detail::to_c(clip), &edges, &mesh,
                                            static_cast<std::uint32_t>(method), &out));
  return out;
}
/// edge_offset_for_mesh() of a Matrix.
inline EdgeOffset edge_offset_for_mesh(const Matrix &m, Clip clip, const Edges &edges, const Mesh &mesh,
                                       EdgeMethod method) {
  return edge_offset_for_mesh(m.data(), clip, edges, mesh, method);
}

/// What an engine knows about one shadow map (ZshiftShadowMap): the light's projection
/// (ZSHIFT_LIGHT_*, l..f), clip, map size and format, the lookup (ZSHIFT_LOOKUP_*), the limit
/// angle, the receivers' light-space depths, world_reach, elevation, profile (NULL: worst case),
/// and pipeline (zeroed: not given; its view_matrix with world_box, and eye_first, are the light's
/// view as the caster and lookup shaders apply it — Python's view_matrix, world_box, eye_first).
using ShadowMap = ZshiftShadowMap;
/// The shadow bias in every API's units, its receiver-side alternatives and cost
/// (ZshiftShadowBias).
using ShadowBias = ZshiftShadowBias;

/// The smallest caster-side shadow bias keeping every receiver within the limit angle free of
/// acne (zshift_shadow_bias; docs/shadows.md). Throws Error: a bad field (the detail names it),
/// Status::unresolvable with the remedy when no bias is acne-free at that angle.
inline ShadowBias shadow_bias(const ShadowMap &map) {
  ShadowBias out{};
  detail::check(zshift_shadow_bias(&map, &out));
  return out;
}

/// shadow_bias() with the rasterizer's profile (from probe()).
inline ShadowBias shadow_bias(ShadowMap map, const Profile &profile) {
  map.profile = &profile;
  return shadow_bias(map);
}

/// One receiver of shadow_bias_receivers(): a planar polygon's corners in the light's view space
/// (a spot light at the origin, looking down -z), counter-clockwise seen from its lit front.
using Receiver = std::vector<std::array<float, 3>>;

/// shadow_bias() for the receivers an engine lists (zshift_shadow_bias_receivers;
/// docs/shadows.md): the bias follows from each receiver's own plane, at any angle short of
/// edge-on; receivers facing away by more than map.limit_angle_deg everywhere are skipped;
/// map.receiver_near/far are not used (keep them inside [n, f]). Throws Error as shadow_bias().
inline ShadowBias shadow_bias_receivers(const ShadowMap &map, const std::vector<Receiver> &receivers) {
  std::vector<float> corners;
  std::vector<std::uint32_t> counts;
  for (const Receiver &r : receivers) {
    counts.push_back(static_cast<std::uint32_t>(r.size()));
    for (const auto &c : r) corners.insert(corners.end(), c.begin(), c.end());
  }
  ShadowBias out{};
  detail::check(zshift_shadow_bias_receivers(&map, corners.data(), counts.data(), static_cast<std::uint32_t>(counts.size()), &out));
  return out;
}

}  // namespace zshift

#endif  // ZSHIFT_HPP
