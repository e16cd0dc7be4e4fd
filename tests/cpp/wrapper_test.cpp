// The C++ wrapper (bindings/cpp/zshift.hpp): every function returns what the C call writes,
// failures throw zshift::Error carrying the C status and its message, and the constexpr parts
// are usable at compile time. Prints each failure and exits nonzero if any check failed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include "zshift.hpp"

// Compile-time checks: these fail the build, not the run.
static_assert(zshift::index(2, 2) == 10, "element 10 is row 2, column 2");
static_assert(zshift::index(2, 3) == 14, "element 14 is row 2, column 3");
static_assert(zshift::to_c(zshift::Status::domain) == ZSHIFT_ERR_DOMAIN, "Status mirrors the header");
static_assert(zshift::abi_version == ZSHIFT_ABI_VERSION, "ABI version mirrors the header");
static_assert(std::is_same_v<zshift::Matrix, std::array<float, 16>>, "Matrix is std::array<float, 16>");
static_assert(std::is_base_of_v<std::runtime_error, zshift::Error>, "Error is a std::runtime_error");
static_assert(zshift::subpixel_unsnapped == ZSHIFT_SUBPIXEL_UNSNAPPED, "unsnapped mirrors the header");

#include "check.hpp"

// The call must throw zshift::Error with `expected` status and the C library's message for it.
template <typename Call>
static void check_throws(const char *what, zshift::Status expected, Call call) {
  try {
    call();
    CHECK(false, "%s did not throw", what);
  } catch (const zshift::Error &e) {
    CHECK(e.status() == expected, "%s threw status %d, expected %d", what, static_cast<int>(e.status()),
          static_cast<int>(expected));
    // what() is the library's detail (input, value, rule), never just the status sentence.
    CHECK(std::strlen(e.what()) > 10 && std::strcmp(e.what(), zshift_status_message(zshift::to_c(expected))) != 0,
          "%s threw \"%s\", not the detail", what, e.what());
  }
}

// [quickstart-cpp]
// The base surface uses the plain projection, the decal the offset zshift recommends for what
// the engine knows about it. Both throw zshift::Error (with the status message) on bad input.
struct Projections {
  zshift::Matrix base, decal;
};

Projections decal_projections(const zshift::Scene &s) {
  return {zshift::frustum(s.l, s.r, s.b, s.t, s.n, s.f), zshift::recommend_matrix(s)};
}

// A decal 40 to 60 units away on a floor tilted by |dz/dx| + |dz/dy| = 1, 1280x720, 24-bit depth:
constexpr zshift::Scene floor_decal =
    zshift::make_scene(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0, 1280, 720, 0x81A6 /* GL_DEPTH_COMPONENT24 */,
                       40.0, 60.0, 1.0, false, 8 /* glGetIntegerv(GL_SUBPIXEL_BITS) */);
// Then: glUniformMatrix4fv(location, 1, GL_FALSE, decal_projections(floor_decal).decal.data());
// [/quickstart-cpp]

static void test_matrices() {
  const double inf = std::numeric_limits<double>::infinity();
  float plain[16], shifted[16];
  Projections p = decal_projections(floor_decal);
  double step;
  zshift_min_delta_toward(0.1, 1000.0, 24, -250.0, &step);
  CHECK(zshift_frustum(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0, plain) == ZSHIFT_OK, "C zshift_frustum failed");
  CHECK(zshift_recommend_matrix(&floor_decal, shifted) == ZSHIFT_OK, "C zshift_recommend_matrix failed");
  CHECK(std::memcmp(p.base.data(), plain, sizeof plain) == 0, "frustum() differs from zshift_frustum");
  CHECK(std::memcmp(p.decal.data(), shifted, sizeof shifted) == 0, "recommend_matrix() differs from the C call");
  CHECK(zshift_load_offset_matrix(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0, 4.0 * step, -250.0, shifted) == ZSHIFT_OK,
        "C zshift_load_offset_matrix failed");
  CHECK(std::memcmp(zshift::load_offset_matrix(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0, 4.0 * step, -250.0).data(),
                    shifted, sizeof shifted) == 0,
        "load_offset_matrix() differs from the C call");
  // delta > 0 moves toward the camera: element 10 (negative) moves up, nothing else moves.
  CHECK(p.decal[zshift::index(2, 2)] > p.base[zshift::index(2, 2)], "the offset did not raise element 10");
  for (std::size_t i = 0; i < 16; i++)
    if (i != 10) CHECK(p.decal[i] == p.base[i], "element %zu moved", i);
  zshift::Matrix infinite = zshift::frustum(-1, 1, -1, 1, 0.5, inf);
  CHECK(infinite[10] == -1.0f && infinite[14] == -1.0f, "infinite far plane: m10 %g m14 %g",
        static_cast<double>(infinite[10]), static_cast<double>(infinite[14]));

  check_throws("frustum(l == r)", zshift::Status::domain, [] { zshift::frustum(1, 1, -1, 1, 1, 100); });
  check_throws("frustum(NaN)", zshift::Status::not_finite, [] { zshift::frustum(std::nan(""), 1, -1, 1, 1, 100); });
  check_throws("frustum(2n/(r-l) > FLT_MAX)", zshift::Status::overflow, [] { zshift::frustum(0, 1e-40, -1, 1, 1, 100); });
  check_throws("load_offset_matrix(pz > -n)", zshift::Status::domain,
               [] { zshift::load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.1, -0.5); });
  check_throws("load_offset_matrix(pz + delta == 0)", zshift::Status::domain,
               [] { zshift::load_offset_matrix(-1, 1, -1, 1, 1, 100, 50, -50); });
}

// Each scalar wrapper returns exactly what its C function writes.
static void test_scalars() {
  double c;
  zshift_epsilon(0.1, 1000, 0.5, -20, &c);
  CHECK(zshift::epsilon(0.1, 1000, 0.5, -20) == c && c < 0, "epsilon");
  zshift_min_epsilon(0.1, 1000, 16, &c);
  CHECK(zshift::min_epsilon(0.1, 1000, 16) == c, "min_epsilon");
  zshift_min_delta_toward(0.1, 1000, 16, -300, &c);
  CHECK(zshift::min_delta_toward(0.1, 1000, 16, -300) == c && c > 0, "min_delta_toward");
  zshift_max_delta_away(0.1, 1000, 16, -2, &c);
  CHECK(zshift::max_delta_away(0.1, 1000, 16, -2) == c && c < 0, "max_delta_away");
  zshift_window_depth(0.1, 1000, 37, &c);
  CHECK(zshift::window_depth(0.1, 1000, 37) == c, "window_depth");
  zshift_depth_resolution(0.1, 1000, 16, 300, &c);
  CHECK(zshift::depth_resolution(0.1, 1000, 16, 300) == c, "depth_resolution");
  // Seeds 000 (with 002) and 001 agree: the minimum shift is Walker's depth step at d = -pz.
  CHECK(std::fabs(zshift::min_delta_toward(1, 1e4, 24, -700) / zshift::depth_resolution(1, 1e4, 24, 700) - 1) < 1e-14,
        "min_delta_toward != depth_resolution");

  check_throws("epsilon(NaN)", zshift::Status::not_finite, [] { zshift::epsilon(1, 100, std::nan(""), -20); });
  check_throws("min_epsilon(bits 0)", zshift::Status::domain, [] { zshift::min_epsilon(1, 100, 0); });
  check_throws("min_delta_toward(pz < -f)", zshift::Status::domain, [] { zshift::min_delta_toward(1, 100, 24, -101); });
  check_throws("max_delta_away(k|pz| >= 1)", zshift::Status::unresolvable,
               [] { zshift::max_delta_away(1, 1e6, 1, -1e5); });
  check_throws("window_depth(d < n)", zshift::Status::domain, [] { zshift::window_depth(1, 100, 0.5); });
  check_throws("depth_resolution(bits 33)", zshift::Status::domain, [] { zshift::depth_resolution(1, 100, 33, 50); });
}

static void test_recommend() {
  static_assert(floor_decal.viewport_width == 1280 && floor_decal.exact_depth == 0u, "make_scene is constexpr");
  ZshiftRecommendation c{};
  CHECK(zshift_recommend(&floor_decal, &c) == ZSHIFT_OK, "C zshift_recommend failed");
  zshift::Recommendation r = zshift::recommend(floor_decal);
  CHECK(std::memcmp(&r, &c, sizeof c) == 0, "recommend() differs from the C call");
  CHECK(r.epsilon < 0 && r.delta_at_far > 0 && r.snap > 0, "recommend(): epsilon %g delta %g snap %g", r.epsilon,
        r.delta_at_far, r.snap);
  zshift::Scene bad = floor_decal;
  bad.decal_near = 70.0;  // beyond decal_far
  check_throws("recommend(decal_near > decal_far)", zshift::Status::domain, [&] { zshift::recommend(bad); });
  check_throws("recommend_matrix(decal_near > decal_far)", zshift::Status::domain,
               [&] { zshift::recommend_matrix(bad); });
  bad = floor_decal;
  bad.slope = std::nan("");
  check_throws("recommend(NaN slope)", zshift::Status::not_finite, [&] { zshift::recommend(bad); });
  // with_corners: the decal's eye-space corners replace decal_near, decal_far and slope (zeroed),
  // and equal the C record's call with the same fields set by hand.
  const float corners[12] = {-1.0f, -3.0f, -14.0f, 1.0f, -3.0f, -14.0f, 1.0f, -1.0f, -18.0f, -1.0f, -1.0f, -18.0f};
  zshift::Scene cornered = zshift::with_corners(floor_decal, corners, 4);
  CHECK(cornered.decal_near == 0.0 && cornered.decal_far == 0.0 && cornered.slope == 0.0 &&
            cornered.decal_corners == corners && cornered.decal_corner_count == 4u,
        "with_corners() did not set the corner fields");
  zshift::Scene by_hand = floor_decal;
  by_hand.decal_near = by_hand.decal_far = by_hand.slope = 0.0;
  by_hand.decal_corners = corners;
  by_hand.decal_corner_count = 4;
  CHECK(zshift_recommend(&by_hand, &c) == ZSHIFT_OK, "C zshift_recommend with corners failed");
  r = zshift::recommend(cornered);
  CHECK(std::memcmp(&r, &c, sizeof c) == 0, "recommend(with_corners()) differs from the C call");
  check_throws("recommend(two corners)", zshift::Status::domain,
               [&] { zshift::recommend(zshift::with_corners(floor_decal, corners, 2)); });
}

// Each wrapper of the clip-convention, median, bias and planning entry points returns exactly
// what its C function writes, and throws on the C function's errors.
static void test_conventions() {
  using zshift::Clip;
  using zshift::Format;
  const ZshiftClip reversed = ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE;
  CHECK(zshift::detail::to_c(Clip::reversed_zero_to_one).value == reversed.value, "Clip mirrors the header");
  CHECK(zshift::detail::to_c(Format::float32).value == ZSHIFT_FORMAT_FLOAT32.value &&
            zshift::detail::to_c(Format::unorm16).value == ZSHIFT_FORMAT_UNORM16.value &&
            zshift::detail::to_c(zshift::DepthTest::greater).value == ZSHIFT_DEPTH_TEST_GREATER.value &&
            zshift::detail::to_c(zshift::BiasApi::vulkan).value == ZSHIFT_BIAS_VULKAN.value &&
            zshift::detail::to_c(zshift::OffsetKind::relative).value == ZSHIFT_OFFSET_RELATIVE.value,
        "the scoped enums mirror the header's constants");
  float c[16];
  double v;
  double planes[2], range[3];

  zshift_perspective(60, 1.5, 0.5, 200, c);
  CHECK(std::memcmp(zshift::perspective(60, 1.5, 0.5, 200).data(), c, sizeof c) == 0, "perspective");
  zshift_projection(-1, 1, -1, 1, 0.5, 200, reversed, c);
  CHECK(std::memcmp(zshift::projection(-1, 1, -1, 1, 0.5, 200, Clip::reversed_zero_to_one).data(), c, sizeof c) == 0,
        "projection");
  zshift_offset_projection(-1, 1, -1, 1, 0.5, 200, reversed, 0.5, -50, c);
  CHECK(std::memcmp(zshift::offset_projection(-1, 1, -1, 1, 0.5, 200, Clip::reversed_zero_to_one, 0.5, -50).data(), c,
                    sizeof c) == 0,
        "offset_projection");
  zshift_offset_perspective(60, 1.5, 0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 0.5, -50, c);
  CHECK(std::memcmp(zshift::offset_perspective(60, 1.5, 0.5, 200, Clip::neg_one_to_one, 0.5, -50).data(), c,
                    sizeof c) == 0,
        "offset_perspective");
  zshift_tweaked_infinite(-1, 1, -1, 1, 0.5, zshift::min_infinite_tweak, c);
  CHECK(std::memcmp(zshift::tweaked_infinite(-1, 1, -1, 1, 0.5, zshift::min_infinite_tweak).data(), c, sizeof c) == 0,
        "tweaked_infinite");
  zshift_offset_tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0, 10, -1000, c);
  CHECK(std::memcmp(zshift::offset_tweaked_infinite(-1, 1, -1, 1, 0.5, 0.0, 10, -1000).data(), c, sizeof c) == 0,
        "offset_tweaked_infinite");

  zshift_median_ndc_offset(10, 0.5, -37, &v);
  CHECK(zshift::median_ndc_offset(10, 0.5, -37) == v, "median_ndc_offset");
  zshift_window_depth_clip(0.5, 200, reversed, 37, &v);
  CHECK(zshift::window_depth_clip(0.5, 200, Clip::reversed_zero_to_one, 37) == v, "window_depth_clip");
  zshift_depth_step(0.5, 200, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_FLOAT32, 37, &v);
  CHECK(zshift::depth_step(0.5, 200, Clip::zero_to_one, Format::float32, 37) == v, "depth_step");
  zshift_median_depth_step(10, ZSHIFT_FORMAT_UNORM24, 37, &v);
  CHECK(zshift::median_depth_step(10, Format::unorm24, 37) == v, "median_depth_step");
  zshift_min_ndc_offset(0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM16, 37, &v);
  CHECK(zshift::min_ndc_offset(0.5, 200, Clip::neg_one_to_one, Format::unorm16, 37) == v, "min_ndc_offset");
  zshift_min_epsilon_clip(0.5, 200, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, 37, &v);
  CHECK(zshift::min_epsilon_clip(0.5, 200, Clip::zero_to_one, Format::unorm24, 37) == v, "min_epsilon_clip");
  zshift_min_relative_epsilon(0.5, 200, reversed, ZSHIFT_FORMAT_FLOAT32, 37, &v);
  CHECK(zshift::min_relative_epsilon(0.5, 200, Clip::reversed_zero_to_one, Format::float32, 37) == v,
        "min_relative_epsilon");
  zshift_bias_of_shift(0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_VULKAN, 0.25, -37, &v);
  CHECK(zshift::bias_of_shift(0.5, 200, Clip::neg_one_to_one, Format::unorm24, zshift::BiasApi::vulkan, 0.25, -37) == v,
        "bias_of_shift");
  zshift_shift_of_bias(0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_OPENGL, -3.0, -37, &v);
  CHECK(zshift::shift_of_bias(0.5, 200, Clip::neg_one_to_one, Format::unorm24, zshift::BiasApi::opengl, -3.0, -37) == v,
        "shift_of_bias");
  zshift_tight_planes(2, 500, planes);
  std::array<double, 2> tight = zshift::tight_planes(2, 500);
  CHECK(tight[0] == planes[0] && tight[1] == planes[1], "tight_planes");
  zshift_range_offset(0.5, 200, ZSHIFT_CLIP_NEG_ONE_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 10, 100, 2, range);
  zshift::RangeOffset ro = zshift::range_offset(0.5, 200, Clip::neg_one_to_one, Format::unorm24,
                                                zshift::OffsetKind::ndc, 10, 100, 2);
  CHECK(ro.offset == range[0] && ro.shift_at_lo == range[1] && ro.shift_at_hi == range[2], "range_offset");

  check_throws("projection(unknown clip)", zshift::Status::domain,
               [] { zshift::projection(-1, 1, -1, 1, 1, 100, static_cast<Clip>(7)); });
  check_throws("perspective(fovy 180)", zshift::Status::domain, [] { zshift::perspective(180, 1, 1, 100); });
  check_throws("tweaked_infinite(tweak 1)", zshift::Status::domain, [] { zshift::tweaked_infinite(-1, 1, -1, 1, 1, 1.0); });
  check_throws("min_epsilon_clip(reversed, f = inf)", zshift::Status::unresolvable, [] {
    zshift::min_epsilon_clip(0.5, std::numeric_limits<double>::infinity(), Clip::reversed_zero_to_one,
                             Format::float32, 37);
  });
  check_throws("tight_planes(nearest > farthest)", zshift::Status::domain, [] { zshift::tight_planes(500, 2); });
  check_throws("range_offset(steps < 1)", zshift::Status::domain, [] {
    zshift::range_offset(0.5, 200, Clip::neg_one_to_one, Format::unorm24, zshift::OffsetKind::ndc, 10, 100, 0.5);
  });
  check_throws("median_ndc_offset(NaN)", zshift::Status::not_finite, [] { zshift::median_ndc_offset(10, std::nan(""), -37); });
}

static void test_messages() {
  CHECK(std::string(zshift::message(zshift::Status::ok)) == zshift_status_message(ZSHIFT_OK), "message(ok)");
  CHECK(zshift::Error(ZSHIFT_ERR_INTERNAL).status() == zshift::Status::internal, "Error keeps its status");
  try {
    zshift::frustum(-1, 1, -1, 1, -1, 100);
    CHECK(false, "frustum(n = -1) did not throw");
  } catch (const zshift::Error &e) {
    CHECK(std::string(e.what()) == "the near plane distance n must be greater than 0 (n = -1)",
          "frustum(n = -1) threw \"%s\"", e.what());
  }
  // version() has C's type: a static const char *, the very pointer the C call returns.
  static_assert(std::is_same_v<decltype(zshift::version()), const char *>, "version() returns const char *");
  CHECK(zshift::version() == zshift_version() && zshift::version()[0] != '\0', "version()");
  CHECK(zshift::status_message(zshift::Status::unresolvable) == zshift_status_message(ZSHIFT_ERR_UNRESOLVABLE),
        "status_message()");
}

// clip_to_frustum() returns what zshift_clip_to_frustum writes: a ground running behind the
// camera, cut inside the frustum.
static void test_clip_to_frustum() {
  const std::vector<zshift::Vertex> ground = {
      {-100.0, -2.0, 100.0}, {100.0, -2.0, 100.0}, {100.0, -2.0, -500.0}, {-100.0, -2.0, -500.0}};
  std::vector<zshift::Vertex> cut = zshift::clip_to_frustum(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, ground);
  double c[3 * 10];
  std::uint32_t count = 0;
  CHECK(zshift_clip_to_frustum(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, ground.data()->data(), 4, c, 10, &count) ==
            ZSHIFT_OK, "C zshift_clip_to_frustum failed");
  CHECK(cut.size() == count && count >= 3 && std::memcmp(cut.data(), c, count * sizeof(zshift::Vertex)) == 0,
        "clip_to_frustum() differs from the C call (%zu vs %u vertices)", cut.size(), static_cast<unsigned>(count));
  for (const zshift::Vertex &v : cut) CHECK(-v[2] > 0.1, "a cut vertex lies behind the near plane (z = %g)", v[2]);
  CHECK(zshift::clip_to_frustum(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}}).empty(),
        "a polygon behind the camera is not cut to nothing");
  check_throws("clip_to_frustum(l == r)", zshift::Status::domain,
               [&] { zshift::clip_to_frustum(1, 1, -1, 1, 1, 10, ground); });
  // Stored in world space 10^4 from the origin: what zshift_clip_to_frustum_stored writes, its
  // nearest vertex further from the camera than the plain cut's.
  ZshiftPipeline stored = {};
  stored.world_reach = 1e4;
  stored.eye_first = 1;
  std::vector<zshift::Vertex> inside = zshift::clip_to_frustum(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, ground, stored);
  CHECK(zshift_clip_to_frustum_stored(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, &stored, ground.data()->data(), 4, c, 10,
                                      &count) == ZSHIFT_OK,
        "C zshift_clip_to_frustum_stored failed");
  CHECK(inside.size() == count && count >= 3 && std::memcmp(inside.data(), c, count * sizeof(zshift::Vertex)) == 0,
        "clip_to_frustum(stored) differs from the C call (%zu vs %u vertices)", inside.size(),
        static_cast<unsigned>(count));
  double plain_nearest = 1e300, stored_nearest = 1e300;
  for (const zshift::Vertex &v : cut) plain_nearest = std::min(plain_nearest, -v[2]);
  for (const zshift::Vertex &v : inside) stored_nearest = std::min(stored_nearest, -v[2]);
  CHECK(stored_nearest > plain_nearest, "the stored cut is not further inside (%g vs %g)", stored_nearest,
        plain_nearest);
  stored.world_reach = -1.0;
  check_throws("clip_to_frustum(world_reach < 0)", zshift::Status::domain,
               [&] { zshift::clip_to_frustum(-0.1, 0.1, -0.1, 0.1, 0.1, 1000.0, ground, stored); });
}

// recommend_clip() and recommend_clip_matrix() return exactly what the C calls write; reversed
// Z with an infinite far plane keeps element 10 at 0 and offsets element 14.
static void test_recommend_clip() {
  using zshift::Clip;
  const ZshiftClip reversed = ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE;
  zshift::Scene s = floor_decal;
  s.f = std::numeric_limits<double>::infinity();
  s.depth_format = 0x8CAC;  // GL_DEPTH_COMPONENT32F
  ZshiftRecommendation c{};
  float m[16];
  CHECK(zshift_recommend_clip(&s, reversed, &c) == ZSHIFT_OK, "C zshift_recommend_clip failed");
  zshift::Recommendation r = zshift::recommend_clip(s, Clip::reversed_zero_to_one);
  CHECK(std::memcmp(&r, &c, sizeof c) == 0 && r.epsilon > 0, "recommend_clip() differs from the C call");
  CHECK(zshift_recommend_clip_matrix(&s, reversed, m) == ZSHIFT_OK, "C zshift_recommend_clip_matrix failed");
  zshift::Matrix decal = zshift::recommend_clip_matrix(s, Clip::reversed_zero_to_one);
  CHECK(std::memcmp(decal.data(), m, sizeof m) == 0, "recommend_clip_matrix() differs from the C call");
  zshift::Matrix plain = zshift::projection(s.l, s.r, s.b, s.t, s.n, s.f, Clip::reversed_zero_to_one);
  CHECK(decal[10] == 0.0f && decal[14] > plain[14], "reversed Z: m10 %g, m14 %g vs %g",
        static_cast<double>(decal[10]), static_cast<double>(decal[14]), static_cast<double>(plain[14]));
  check_throws("recommend_clip(unknown clip)", zshift::Status::domain,
               [&] { zshift::recommend_clip(s, static_cast<Clip>(9)); });
}

// edge_offset() and edge_planes() return what the C calls write; a bad field throws.
static void test_edges() {
  const auto m = zshift::frustum(-0.5, 0.5, -0.5, 0.5, 1.0, 1000.0);
  zshift::Edges e{};
  e.viewport_width = e.viewport_height = 512;
  e.format = ZSHIFT_FORMAT_UNORM24;
  e.subpixel_bits = ZSHIFT_SUBPIXEL_UNSNAPPED;
  e.depth_near = 10.0;
  e.depth_far = 20.0;
  e.line_width = 1.0;
  e.samples = 1;
  e.face_gradient = 1e-3;
  const auto b = zshift::edge_offset(m, zshift::Clip::neg_one_to_one, e, zshift::EdgeMethod::matrix);
  ZshiftEdgeOffset c{};
  CHECK(zshift_edge_offset(m.data(), ZSHIFT_CLIP_NEG_ONE_TO_ONE, &e, ZSHIFT_EDGES_MATRIX, &c) == ZSHIFT_OK, "C call");
  CHECK(std::memcmp(&b, &c, sizeof b) == 0 && b.line_reach == 1.0 && b.matrix[10] > m[10], "edge_offset()");
  const auto a = zshift::edge_offset(m, zshift::Clip::neg_one_to_one, e, zshift::EdgeMethod::polygon_offset);
  CHECK(a.polygon_offset[0] == 1.0 && a.polygon_offset[1] > 0.0, "polygon offset (%g, %g)", a.polygon_offset[0],
        a.polygon_offset[1]);
  const auto planes = zshift::edge_planes(m, zshift::Clip::neg_one_to_one, e, zshift::EdgeMethod::matrix);
  CHECK(planes[0] > 0.0 && planes[0] <= 10.0 && planes[1] >= 20.0, "edge_planes() %g %g", planes[0], planes[1]);
  e.line_width = 0.5;
  check_throws("edge_offset(line_width 0.5)", zshift::Status::domain,
               [&] { zshift::edge_offset(m, zshift::Clip::neg_one_to_one, e, zshift::EdgeMethod::matrix); });
  // The steepest face: what the C call writes; the tilted face is steeper than the facing one;
  // the one-call offset for the mesh pays less than the angle's; an index past the positions
  // throws.
  const std::vector<std::array<float, 3>> positions = {
      {{-1, -1, -10}}, {{1, -1, -10}}, {{0, 1, -10}}, {{-1, -1, -10}}, {{1, -1, -14}}, {{0, 1, -10}}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
  const zshift::Mesh mesh = zshift::make_mesh(m, positions, indices);
  const auto s = zshift::steepest_face(mesh, zshift::Clip::neg_one_to_one, 512, 512);
  ZshiftSteepestFace sc{};
  CHECK(zshift_steepest_face(&mesh, ZSHIFT_CLIP_NEG_ONE_TO_ONE, 512, 512, std::numeric_limits<double>::infinity(),
                             &sc) == ZSHIFT_OK,
        "C call");
  CHECK(std::memcmp(&s, &sc, sizeof s) == 0 && s.triangle == 1 && s.counted == 2 && s.gradient > 0.0,
        "steepest_face() triangle %lld gradient %g", static_cast<long long>(s.triangle), s.gradient);
  e.line_width = 1.0;
  e.face_gradient = 0.0;
  e.face_angle = 1.0471976;
  const auto by_angle = zshift::edge_offset(m, zshift::Clip::neg_one_to_one, e, zshift::EdgeMethod::matrix);
  const auto by_mesh = zshift::edge_offset_for_mesh(m, zshift::Clip::neg_one_to_one, e, mesh, zshift::EdgeMethod::matrix);
  CHECK(by_mesh.window_offset < by_angle.window_offset && by_mesh.face_gradient <= by_angle.face_gradient,
        "edge_offset_for_mesh() %g vs the angle's %g", by_mesh.window_offset, by_angle.window_offset);
  const std::vector<std::uint32_t> past = {0, 1, 6};
  check_throws("steepest_face(index past the positions)", zshift::Status::domain,
               [&] { zshift::steepest_face(zshift::make_mesh(m, positions, past), zshift::Clip::neg_one_to_one, 512, 512); });
}

// One decal over two planes (a mesh decal over terrain): the larger of the two offsets, the
// plane named in a refusal.
static void test_decal_planes() {
  const auto m = zshift::frustum(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0);
  const auto clip = zshift::Clip::neg_one_to_one;
  const std::vector<zshift::Decal> planes = {
      zshift::make_decal(1280, 720, zshift::Format::unorm24, 8, 10.0, 12.0, 1.0),
      zshift::make_decal(1280, 720, zshift::Format::unorm24, 8, 40.0, 45.0, 3.0)};
  const auto a = zshift::decal_matrix(m, clip, planes[0]), b = zshift::decal_matrix(m, clip, planes[1]);
  const auto both = zshift::decal_matrix_planes(m, clip, planes);
  // NDC depth is -m10 + m14/d: the larger offset toward the camera is the larger element 10.
  CHECK(a[10] != b[10] && both == (a[10] > b[10] ? a : b), "decal_matrix_planes() is the larger offset");
  const auto rec = zshift::recommend_for_planes(m.data(), clip, planes.data(), 2);
  CHECK(rec.bleed_gap >= zshift::recommend_for_matrix(m.data(), clip, planes[1]).bleed_gap, "bleed gap");
  auto broken = planes;
  broken[1].decal_far = 2000.0;
  try {
    zshift::decal_matrix_planes(m, clip, broken);
    CHECK(false, "a broken plane was accepted");
  } catch (const zshift::Error &e) {
    CHECK(std::strncmp(e.what(), "plane 1: ", 9) == 0, "the refusal names the plane: %s", e.what());
  }
  check_throws("decal_matrix_planes(no planes)", zshift::Status::null_pointer,
               [&] { zshift::decal_matrix_planes(m.data(), clip, nullptr, 0); });
  // A plane just beyond the near plane, and one whose clipped base asks an offset that would
  // move it past: each answered alone, refused together naming largest_plane.
  auto close = zshift::make_decal(1280, 720, zshift::Format::unorm24, 8, 0.125, 0.13, 0.0);
  int named = 0;
  for (const double reach : {1e4, 1e5, 1e6, 1e7}) {
    auto clipped = zshift::make_decal(1280, 720, zshift::Format::unorm24, 8, 50.0, 51.0, 3.0);
    clipped.base_reach = reach;
    try {
      (void)zshift::decal_matrix(m, clip, close);
      (void)zshift::decal_matrix(m, clip, clipped);
    } catch (const zshift::Error &) {
      continue;
    }
    try {
      (void)zshift::decal_matrix_planes(m, clip, std::vector<zshift::Decal>{close, clipped});
    } catch (const zshift::Error &e) {
      CHECK(e.status() == zshift::Status::unresolvable, "largest_plane refusal status: %s", e.what());
      CHECK(std::strstr(e.what(), "plane 0: ") == e.what(), "names the plane: %s", e.what());
      CHECK(std::strstr(e.what(), "largest_plane = 1") != nullptr, "names largest_plane: %s", e.what());
      ++named;
    }
  }
  CHECK(named > 0, "no base reach made the far plane's offset too large");
}

static void test_shadow_bias() {
  zshift::ShadowMap map{};
  map.light = ZSHIFT_LIGHT_ORTHOGRAPHIC;
  map.l = -8; map.r = 8; map.b = -8; map.t = 8; map.n = 2; map.f = 30;
  map.clip = ZSHIFT_CLIP_NEG_ONE_TO_ONE;
  map.width = 1024; map.height = 1024;
  map.format = 0x81A6;  // GL_DEPTH_COMPONENT24
  map.lookup = ZSHIFT_LOOKUP_NEAREST;
  map.limit_angle_deg = 45;
  map.receiver_near = 2; map.receiver_far = 30;
  map.elevation_deg = 45;
  ZshiftShadowBias c{};
  CHECK(zshift_shadow_bias(&map, &c) == ZSHIFT_OK, "C zshift_shadow_bias failed");
  zshift::ShadowBias b = zshift::shadow_bias(map);
  CHECK(std::memcmp(&b, &c, sizeof c) == 0, "shadow_bias() differs from the C call");
  // Nearest: a = 1/2, footprint 0.5 * tan 45 * texel diagonal / (f - n).
  double footprint = 0.5 * (16.0 / 1024.0) * std::sqrt(2.0) / 28.0;
  CHECK(std::fabs(b.footprint / footprint - 1.0) < 1e-12, "footprint %.17g vs %.17g", b.footprint, footprint);
  CHECK(b.gl_factor >= 1.0 + 1.0 / 256 && b.d3d_depth_bias > 0, "factor %g, DepthBias %d", b.gl_factor, b.d3d_depth_bias);
  zshift::Profile worst = zshift::profile_worst_case();
  zshift::ShadowBias w = zshift::shadow_bias(map, worst);
  CHECK(std::memcmp(&w, &b, sizeof b) == 0, "shadow_bias(map, worst case) differs from the NULL profile");
  map.limit_angle_deg = 90;
  check_throws("shadow_bias(limit 90)", zshift::Status::domain, [&] { zshift::shadow_bias(map); });
  // Listed receivers: a quad tilted as z = -10 + 0.5 x, counter-clockwise seen from the light.
  map.limit_angle_deg = 89.9;
  std::vector<zshift::Receiver> receivers{{{-4, -4, -12}, {4, -4, -8}, {4, 4, -8}, {-4, 4, -12}}};
  zshift::ShadowBias r = zshift::shadow_bias_receivers(map, receivers);
  float flat[] = {-4, -4, -12, 4, -4, -8, 4, 4, -8, -4, 4, -12};
  std::uint32_t counts[] = {4};
  ZshiftShadowBias rc{};
  CHECK(zshift_shadow_bias_receivers(&map, flat, counts, 1, &rc) == ZSHIFT_OK, "C zshift_shadow_bias_receivers failed");
  CHECK(std::memcmp(&r, &rc, sizeof rc) == 0, "shadow_bias_receivers() differs from the C call");
  double own = 0.5 * 0.5 * (16.0 / 1024.0) / 28.0;
  CHECK(r.footprint >= own && r.footprint < own * 1.0001, "receiver footprint %.17g vs %.17g", r.footprint, own);
  std::reverse(receivers[0].begin(), receivers[0].end());
  check_throws("shadow_bias_receivers(facing away)", zshift::Status::domain, [&] { zshift::shadow_bias_receivers(map, receivers); });
  // The light's pipeline (map.pipeline): its view matrix (25 units up z, looking down -z) with the
  // box of the world positions it maps, eye-first; the same record as C, and tighter than the
  // bound from world_reach alone.
  std::reverse(receivers[0].begin(), receivers[0].end());
  map.world_reach = 25;
  zshift::ShadowBias scalar = zshift::shadow_bias_receivers(map, receivers);
  static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -25, 1};
  map.pipeline.view_matrix = view;
  const double box[6] = {-8, -8, -5, 8, 8, 23};
  std::copy(box, box + 6, map.pipeline.world_box);
  map.pipeline.eye_first = 1;
  zshift::ShadowBias viewed = zshift::shadow_bias_receivers(map, receivers);
  CHECK(zshift_shadow_bias_receivers(&map, flat, counts, 1, &rc) == ZSHIFT_OK, "C zshift_shadow_bias_receivers (view) failed");
  CHECK(std::memcmp(&viewed, &rc, sizeof rc) == 0, "shadow_bias_receivers() with the view differs from the C call");
  CHECK(viewed.lookup < scalar.lookup, "lookup with the view %.9g vs scalar %.9g", viewed.lookup, scalar.lookup);
  // A view matrix without its box (all zeros) is refused.
  std::fill(map.pipeline.world_box, map.pipeline.world_box + 6, 0.0);
  check_throws("shadow_bias(view without world_box)", zshift::Status::domain, [&] { zshift::shadow_bias(map); });
}

int main() {
  test_edges();
  test_matrices();
  test_scalars();
  test_recommend();
  test_conventions();
  test_recommend_clip();
  test_messages();
  test_clip_to_frustum();
  test_shadow_bias();
  test_decal_planes();
  if (failures != 0) {
    std::fprintf(stderr, "wrapper_test: %d of %d checks failed\n", failures, checks);
    return 1;
  }
  std::printf("wrapper_test: all %d checks passed (zshift %s)\n", checks, zshift::version());
  return 0;
}
