/* Compile-fail test: passing an argument of one kind where another kind goes must not compile,
 * in C (not merely warn) and in C++. Built by `make -C tests/c compile-fail` once per CASE:
 * CASE 0 is the correct call and must compile; every other CASE must be rejected by the compiler
 * with no warning flags at all. The same file is compiled as C and as C++ (the wrapper's scoped
 * enums for cases 100 and up). */
#include "zshift.h"

#if defined(__cplusplus) && CASE >= 100
#include "zshift.hpp"
#endif

int main(void) {
  double out = 0.0;
  float m[16];
  (void)m;
#if CASE == 0
  /* The correct calls. */
  zshift_depth_step(1.0, 100.0, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, 50.0, &out);
  zshift_projection(-1, 1, -1, 1, 1, 100, ZSHIFT_CLIP_NEG_ONE_TO_ONE, m);
  zshift_bias_of_shift(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_BIAS_VULKAN, 0.1, -50, &out);
  zshift_range_offset(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_OFFSET_NDC, 2, 50, 1, &out);
#elif CASE == 1
  /* clip and format swapped */
  zshift_depth_step(1.0, 100.0, ZSHIFT_FORMAT_UNORM24, ZSHIFT_CLIP_ZERO_TO_ONE, 50.0, &out);
#elif CASE == 2
  /* a bare integer where a clip convention goes */
  zshift_projection(-1, 1, -1, 1, 1, 100, 1, m);
#elif CASE == 3
  /* a depth format where the bias API goes */
  zshift_bias_of_shift(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_FORMAT_UNORM24, 0.1, -50, &out);
#elif CASE == 4
  /* a clip convention where the offset kind goes */
  zshift_range_offset(1, 100, ZSHIFT_CLIP_ZERO_TO_ONE, ZSHIFT_FORMAT_UNORM24, ZSHIFT_CLIP_ZERO_TO_ONE, 2, 50, 1, &out);
#elif CASE == 5
  /* a GL enum integer where a depth format goes (convert with `ZshiftFormat f = { value };`) */
  zshift_depth_step(1.0, 100.0, ZSHIFT_CLIP_ZERO_TO_ONE, 0x81A6, 50.0, &out);
#elif CASE == 100
  /* C++ wrapper: scoped enums swapped */
  out = zshift::depth_step(1.0, 100.0, zshift::Format::unorm24, zshift::Clip::zero_to_one, 50.0);
#elif CASE == 101
  /* C++ wrapper: a bare integer where a Clip goes */
  out = zshift::window_depth_clip(1.0, 100.0, 1, 50.0);
#endif
  return out > 1e300;
}
