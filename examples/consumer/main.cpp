// The C++ side of examples/consumer (see main.c): zshift.hpp throws zshift::Error on bad input.
#include <cstdio>
#include <zshift.hpp>

int main() {
  zshift::Matrix proj = zshift::frustum(-0.1, 0.1, -0.075, 0.075, 0.1, 1000.0);
  // viewport, depth format, GL_SUBPIXEL_BITS, nearest and farthest eye distance, slope, exact depth:
  zshift::Decal decal = zshift::make_decal(800, 600, zshift::Format::unorm24, 8, 50.0, 50.0, 0.0, false);
  try {
    zshift::Matrix m = zshift::decal_matrix(proj, zshift::Clip::neg_one_to_one, decal);
    std::printf("zshift %s (C++): element 10 %.9g -> %.9g\n", zshift::version(), static_cast<double>(proj[10]),
                static_cast<double>(m[10]));
    return m[10] > proj[10] ? 0 : 1;
  } catch (const zshift::Error &e) {
    std::fprintf(stderr, "zshift: %s\n", e.what());
    return 1;
  }
}
