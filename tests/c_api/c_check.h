/* The C tests' assertion: reports a failed condition with its line and counts it (main returns
 * non-zero if any failed), so that one run shows every failure. */
#ifndef FLEXSTRESS_TEST_C_CHECK_H
#define FLEXSTRESS_TEST_C_CHECK_H

#include <stdio.h>

static int failures = 0;

#define CHECK(cond)                                                            \
  do {                                                                         \
    if (!(cond)) {                                                             \
      fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                              \
    }                                                                          \
  } while (0)

#endif
