// The front door from C++ with GLM-built matrices: zshift::offset_matrix() and
// zshift::decal_matrix() change only the element that carries the offset, by at least the
// offset asked and at most one float ulp of that element more, for every projection GLM builds
// (glm::perspective [-1, 1], perspectiveRH_ZO [0, 1], perspectiveLH_ZO, infinitePerspective,
// tweakedInfinitePerspective, a reversed-Z perspectiveRH_ZO(f, n), orthoRH_NO, orthoRH_ZO and a
// reversed orthoRH_ZO). The reference is computed from the matrix's own elements in long double.
//   make -C tests/cpp check
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "zshift.hpp"

#include "check.hpp"

struct Case {
  const char *name;
  glm::mat4 m;
  zshift::Clip clip;
  bool ortho;
};

static long double ulp(float x) {
  float a = std::fabs(x);
  return static_cast<long double>(std::nextafter(a, INFINITY)) - a;
}

// Only `element` differs from `m`, bit for bit; the offset seen is at least `want` (same sign)
// and at most one ulp of the element more.
static void check_offset(const std::string &what, const float *m, const zshift::Matrix &out, int element,
                         long double seen, long double want) {
  for (int i = 0; i < 16; i++)
    if (i != element) CHECK(std::memcmp(&m[i], &out[i], sizeof(float)) == 0, "%s: element %d changed", what.c_str(), i);
  CHECK(out[element] != m[element], "%s: element %d did not move", what.c_str(), element);
  const long double slack = 1e-15L * std::fabs(want);  // the long double reference's own rounding
  CHECK((seen > 0) == (want > 0) && std::fabs(seen) >= std::fabs(want) - slack,
        "%s: offset %.20Lg is less than the %.20Lg asked", what.c_str(), seen, want);
  CHECK(std::fabs(seen) - std::fabs(want) <= ulp(out[element]) + slack,
        "%s: offset %.20Lg exceeds %.20Lg by more than one ulp", what.c_str(), seen, want);
}

int main() {
  using zshift::Clip;
  const float fovy = glm::radians(60.0f), aspect = 16.0f / 9.0f, n = 0.1f, f = 1000.0f;
  const std::vector<Case> cases = {
      {"glm::perspective (RH, [-1, 1])", glm::perspectiveRH_NO(fovy, aspect, n, f), Clip::neg_one_to_one, false},
      {"glm::perspectiveRH_ZO ([0, 1])", glm::perspectiveRH_ZO(fovy, aspect, n, f), Clip::zero_to_one, false},
      {"glm::perspectiveLH_ZO (left-handed, [0, 1])", glm::perspectiveLH_ZO(fovy, aspect, n, f), Clip::zero_to_one,
       false},
      {"glm::infinitePerspective (RH, [-1, 1])", glm::infinitePerspectiveRH(fovy, aspect, n), Clip::neg_one_to_one,
       false},
      {"glm::tweakedInfinitePerspective (2^-22)", glm::tweakedInfinitePerspective(fovy, aspect, n, 2.384185791015625e-7f),
       Clip::neg_one_to_one, false},
      {"glm::perspectiveRH_ZO(f, n) (reversed Z)", glm::perspectiveRH_ZO(fovy, aspect, f, n), Clip::reversed_zero_to_one,
       false},
      {"glm::orthoRH_NO (glOrtho)", glm::orthoRH_NO(-20.0f, 20.0f, -10.0f, 10.0f, 1.0f, 500.0f), Clip::neg_one_to_one,
       true},
      {"glm::orthoRH_ZO ([0, 1])", glm::orthoRH_ZO(-20.0f, 20.0f, -10.0f, 10.0f, 1.0f, 500.0f), Clip::zero_to_one, true},
      {"glm::orthoRH_ZO(.., f, n) (reversed)", glm::orthoRH_ZO(-20.0f, 20.0f, -10.0f, 10.0f, 500.0f, 1.0f),
       Clip::reversed_zero_to_one, true},
  };
  const double shifts[][2] = {{0.01, 50.0}, {1e-4, 0.2}, {2.5, 400.0}, {-0.5, 30.0}};
  for (const Case &c : cases) {
    const float *m = glm::value_ptr(c.m);
    const long double m10 = m[10], m14 = m[14], s = m[11] == 0.0f ? 1.0L : m[11];
    for (const auto &sd : shifts) {
      const long double delta = sd[0], d = sd[1];
      const std::string what = std::string(c.name) + " delta " + std::to_string(sd[0]) + " at " + std::to_string(sd[1]);
      zshift::Matrix out{};
      try {
        out = zshift::offset_matrix(m, c.clip, sd[0], sd[1]);
      } catch (const zshift::Error &e) {
        CHECK(false, "%s threw: %s", what.c_str(), e.what());
        continue;
      }
      if (c.ortho) {
        check_offset(what, m, out, 14, out[14] - m14, m10 * delta);
      } else if (c.clip == Clip::reversed_zero_to_one) {
        check_offset(what, m, out, 14, out[14] - m14, m14 * delta / (d - delta));
      } else {
        check_offset(what, m, out, 10, (out[10] - m10) * s, m14 * delta / (d * (d - delta)));
      }
    }
    // The recommendation from the same matrix: one element, toward the camera.
    const zshift::Decal decal =
        zshift::make_decal(1920, 1080, zshift::Format::float32, zshift::subpixel_unsnapped, 40.0, 60.0, 1.0);
    try {
      const zshift::Matrix dm = zshift::decal_matrix(m, c.clip, decal);
      const int element = (c.ortho || c.clip == Clip::reversed_zero_to_one) ? 14 : 10;
      int changed = 0;
      for (int i = 0; i < 16; i++) changed += std::memcmp(&m[i], &dm[i], sizeof(float)) != 0;
      CHECK(changed == 1 && dm[element] != m[element], "%s: decal_matrix changed %d elements", c.name, changed);
    } catch (const zshift::Error &e) {
      CHECK(false, "%s: decal_matrix threw: %s", c.name, e.what());
    }
  }
  // A convention mismatch is an error whose message says so.
  try {
    zshift::offset_matrix(glm::value_ptr(cases[5].m), Clip::neg_one_to_one, 0.01, 50.0);
    CHECK(false, "a reversed-Z matrix passed as [-1, 1] was accepted");
  } catch (const zshift::Error &e) {
    CHECK(e.status() == zshift::Status::domain && std::strstr(e.what(), "reversed-Z") != nullptr,
          "mismatch threw \"%s\"", e.what());
  }
  if (failures != 0) {
    std::fprintf(stderr, "glm_test: %d of %d checks failed\n", failures, checks);
    return 1;
  }
  std::printf("glm_test: all %d checks passed (GLM %d.%d)\n", checks, GLM_VERSION_MAJOR, GLM_VERSION_MINOR);
  return 0;
}
