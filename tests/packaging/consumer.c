/* A C program built against an installed zshift (scripts/install), through pkg-config and CMake:
 * proves the installed header, library, .pc and CMake package fit together. Prints the version
 * and exits nonzero if a call does not behave. */
#include <stdio.h>
#include <zshift.h>

int main(void) {
  float m[16];
  ZshiftStatus s = zshift_load_offset_matrix(-1, 1, -1, 1, 1, 100, 0.5, -50, m);
  if (s != ZSHIFT_OK) {
    fprintf(stderr, "zshift: %s\n", zshift_status_message(s));
    return 1;
  }
  if (zshift_frustum(1, 1, -1, 1, 1, 100, m) != ZSHIFT_ERR_DOMAIN) {
    fprintf(stderr, "consumer: l == r was not a domain error\n");
    return 1;
  }
  printf("zshift %s, C ABI %d\n", zshift_version(), ZSHIFT_ABI_VERSION);
  return 0;
}
