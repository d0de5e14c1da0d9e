/* The C interface's answers to bad input (a ctest entry; docs/errors.md lists them): each bad
 * option is refused with a message naming the field, a null crane gets error values, and
 * nothing crashes. Exits non-zero on the first answer that is not the expected one. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexstress_crane.h"

static int failures = 0;

/* Creating a crane with `o` must fail with a message containing `expected`. */
static void expect_refusal(const fs_crane_options* o, const char* expected) {
  char error[512];
  fs_crane* c = fs_crane_create(o, error, sizeof error);
  if (c != NULL || strstr(error, expected) == NULL) {
    fprintf(stderr, "expected a refusal with '%s', got %s '%s'\n", expected,
            c != NULL ? "a crane and" : "", error);
    ++failures;
  }
  fs_crane_destroy(c);
}

int main(void) {
  fs_crane_options o;
  const double times[] = {0.0, 1.0, 0.5};
  const double strokes[] = {0.0, 0.05, 5.0};
  const double good_strokes[] = {0.0, 0.05, 0.1};
  char tiny[8];

  fs_crane_default_options(&o);
  o.step_s = 0.0;
  expect_refusal(&o, "fs_crane_options.step_s = 0.000000: must be in (0, 0.05]");
  fs_crane_default_options(&o);
  o.submodel_density = NAN;
  expect_refusal(&o, "fs_crane_options.submodel_density = nan: must be finite and > 0");
  fs_crane_default_options(&o);
  o.cycle_points = 1;
  expect_refusal(
      &o, "fs_crane_options.cycle_points = 1: must be 0 (the synthetic cycle) or at least 2");
  o.cycle_points = 3;
  expect_refusal(&o, "cycle_points = 3 but cycle_time or cycle_stroke is null");
  o.cycle_time = times;
  o.cycle_stroke = strokes;
  expect_refusal(&o, "cycle_stroke[2] = 5.000000 m takes the piston out of the cylinder");
  o.cycle_stroke = good_strokes;
  expect_refusal(&o, "table law: time at row 3 (0.5) does not increase (previous 1)");
  expect_refusal(NULL, "options is null");

  /* A message longer than the buffer is cut and terminated. */
  fs_crane_default_options(&o);
  o.payload_kg = -1.0;
  if (fs_crane_create(&o, tiny, sizeof tiny) != NULL || strlen(tiny) != sizeof tiny - 1) {
    fprintf(stderr, "a short error buffer was not filled and terminated\n");
    ++failures;
  }

  /* A null crane: error values. */
  if (fs_crane_step(NULL) != FS_CRANE_NULL || !isnan(fs_crane_time(NULL)) ||
      fs_crane_num_outputs(NULL) != 0 || fs_crane_output_name(NULL, 0) != NULL ||
      !isnan(fs_crane_damage_per_cycle(NULL)) ||
      strcmp(fs_crane_error(NULL), "fs_crane: null crane") != 0) {
    fprintf(stderr, "a null crane did not give error values\n");
    ++failures;
  }
  fs_crane_destroy(NULL);
  if (failures == 0) printf("the C interface refused every bad input, naming it\n");
  return failures == 0 ? 0 : 1;
}
