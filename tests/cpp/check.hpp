// The tests' one assertion: CHECK(cond, printf-style message) counts checks and failures and
// prints each failure with its place; main() reports the counts.
#ifndef ZSHIFT_TESTS_CHECK_HPP
#define ZSHIFT_TESTS_CHECK_HPP

#include <cstdio>

static int checks, failures;

#define CHECK(cond, ...)                                        \
  do {                                                          \
    checks++;                                                   \
    if (!(cond)) {                                              \
      failures++;                                               \
      std::fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
      std::fprintf(stderr, __VA_ARGS__);                        \
      std::fputc('\n', stderr);                                 \
    }                                                           \
  } while (0)

#endif  // ZSHIFT_TESTS_CHECK_HPP
