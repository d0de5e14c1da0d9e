/* The crane from C: one work cycle through flexstress_crane.h, the hot spot and the damage as
 * an engine would read them each step. Also shows what bad options get back. Prints a summary
 * and "key: value" lines (the crane program's keys, for comparison). */
#include <math.h>
#include <stdio.h>

#include "flexstress_crane.h"

int main(void) {
  char error[512];
  fs_crane_options options;
  fs_crane_default_options(&options);

  /* Bad input is refused with a message naming the field. */
  options.payload_kg = -5.0;
  if (fs_crane_create(&options, error, sizeof error) != NULL) {
    fprintf(stderr, "a negative payload was accepted\n");
    return 1;
  }
  printf("refused: %s\n", error);
  fs_crane_default_options(&options);

  fs_crane* crane = fs_crane_create(&options, error, sizeof error);
  if (crane == NULL) {
    fprintf(stderr, "error: %s\n", error);
    return 1;
  }
  const int outputs = fs_crane_num_outputs(crane);
  printf("crane from C: %d stress read-outs at detail D, the first '%s'; cycle of %g s\n", outputs,
         fs_crane_output_name(crane, 0), fs_crane_cycle_end(crane));

  double stresses[256];
  double hot_max = -INFINITY;
  long steps = 0;
  int status;
  while ((status = fs_crane_step(crane)) == FS_CRANE_OK) {
    ++steps;
    const double hot = fs_crane_hot_spot(crane) / 1e6;
    if (hot > hot_max) hot_max = hot;
    if (fs_crane_stresses(crane, stresses, 256) != (outputs < 256 ? outputs : 256)) {
      fprintf(stderr, "fs_crane_stresses copied too few read-outs\n");
      return 1;
    }
    if (steps % 2000 == 0)
      printf("  t %5.2f s  hot spot %7.3f MPa  damage so far %.4e\n", fs_crane_time(crane), hot,
             fs_crane_damage_closed(crane));
  }
  if (status != FS_CRANE_CYCLE_OVER) {
    fprintf(stderr, "error: %s\n", fs_crane_error(crane));
    fs_crane_destroy(crane);
    return 1;
  }
  printf("steps: %ld\n", steps);
  printf("hotspot_max_MPa: %.3f\n", hot_max);
  printf("damage_per_cycle: %.6g\n", fs_crane_damage_per_cycle(crane));
  fs_crane_destroy(crane);

  /* A null crane is an error value, not a crash. */
  if (fs_crane_step(NULL) != FS_CRANE_NULL || !isnan(fs_crane_hot_spot(NULL))) return 1;
  return 0;
}
