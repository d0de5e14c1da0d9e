/* The paper's crane, compiled, behind a C interface: for engines written in C, or in any
 * language that calls C (C#, Python's ctypes, Rust, Lua...). Create a crane, step it at its
 * fixed time step, read the stresses at welded detail D and the fatigue damage, destroy it.
 *
 *   fs_crane_options o;
 *   fs_crane_default_options(&o);
 *   char error[256];
 *   fs_crane* c = fs_crane_create(&o, error, sizeof error);
 *   if (!c) { fprintf(stderr, "%s\n", error); return 1; }
 *   while (fs_crane_step(c) == FS_CRANE_OK) draw(fs_crane_hot_spot(c));
 *   printf("%g\n", fs_crane_damage_per_cycle(c));
 *   fs_crane_destroy(c);
 *
 * Every function is safe to call with a null crane (it returns an error value). A crane is used
 * by one thread at a time; separate cranes may run in parallel. Stresses are in Pa. */
#ifndef FLEXSTRESS_CRANE_H
#define FLEXSTRESS_CRANE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fs_crane fs_crane;

typedef struct fs_crane_options {
  double payload_kg;       /* added mass at x = 2.5 m on the boom (default 100) */
  double step_s;           /* fixed time step, (0, 0.05] s (default 0.001) */
  double submodel_density; /* sub-model mesh density, > 0 (default 1: 1792 bricks) */
  /* The work cycle: cycle_points rows of time (s, increasing) and stroke (m, the cylinder's
   * extension from the start). cycle_points = 0 (default) takes the synthetic cycle of
   * docs/crane.md. The arrays are copied; they need not outlive fs_crane_create. */
  const double* cycle_time;
  const double* cycle_stroke;
  int cycle_points;
} fs_crane_options;

/* What fs_crane_step returns. */
enum {
  FS_CRANE_OK = 0,         /* stepped; the read-outs are this step's */
  FS_CRANE_CYCLE_OVER = 1, /* the work cycle is over; nothing was done */
  FS_CRANE_FAILED =
      -1,            /* the step failed; fs_crane_error says why, the state is the last good one */
  FS_CRANE_NULL = -2 /* the crane pointer was null */
};

void fs_crane_default_options(fs_crane_options* options);

/* Builds a crane (precomputation, static equilibrium: about a second). Returns null if the
 * options are bad or the build fails, with the reason in `error` (if not null; truncated to
 * error_size, always terminated). */
fs_crane* fs_crane_create(const fs_crane_options* options, char* error, size_t error_size);
void fs_crane_destroy(fs_crane* crane);

/* One fixed step. Allocates nothing. */
int fs_crane_step(fs_crane* crane);
double fs_crane_time(const fs_crane* crane);      /* s; NaN for a null crane */
double fs_crane_cycle_end(const fs_crane* crane); /* s; NaN for a null crane */

/* The stress read-outs at detail D: the hot spots, the paper's strain gauges, the nominal
 * stress, the hot spot along the weld toe. */
int fs_crane_num_outputs(const fs_crane* crane);
const char* fs_crane_output_name(const fs_crane* crane, int index); /* null if out of range */
/* Copies min(capacity, count) read-outs (Pa) into `out`; returns how many it copied. */
int fs_crane_stresses(const fs_crane* crane, double* out, int capacity);
double fs_crane_hot_spot(const fs_crane* crane); /* IIW hot spot at the toe's centre, Pa */

/* Miner damage (IIW FAT 100 hot-spot curve): of the rainflow cycles closed so far, and with
 * the open residue closed as a repeating cycle (the damage per work cycle once it is over). */
double fs_crane_damage_closed(const fs_crane* crane);
double fs_crane_damage_per_cycle(const fs_crane* crane);

/* Why the last step failed; "" if none. */
const char* fs_crane_error(const fs_crane* crane);

#ifdef __cplusplus
}
#endif

#endif /* FLEXSTRESS_CRANE_H */
