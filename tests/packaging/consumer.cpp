// A C++ program built against an installed zshift through CMake's zshift::zshift_static.
#include <cstdio>
#include <zshift.hpp>

int main() {
  try {
    zshift::frustum(1, 1, -1, 1, 1, 100);
    std::fprintf(stderr, "consumer: l == r did not throw\n");
    return 1;
  } catch (const zshift::Error &e) {
    if (e.status() != zshift::Status::domain) return 1;
  }
  zshift::Matrix m = zshift::load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.5, -50);
  std::printf("zshift %s (C++), element 10 = %.9g\n", zshift::version(), static_cast<double>(m[10]));
  return 0;
}
