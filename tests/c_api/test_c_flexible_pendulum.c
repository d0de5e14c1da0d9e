/* The C interface alone (flexstress/flexstress.h, C99): a flexible pendulum, a beam hinged at
 * one end read from a modal body file, against its full FE model (make_pendulum_files.cpp,
 * the FE kernel without reduction: an independent reference); its swing under gravity; the
 * drivers' laws; outputs, damage meters, a point load and checkpoints; and the answers to
 * mistakes (finalize errors, bad handles, null pointers).
 *
 *   test_c_flexible_pendulum <beam.fsmodal> <beam_reference.txt> */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flexstress/flexstress.h>

#include "c_check.h"

typedef struct reference {
  long root_node, tip_node, num_nodes, next_node;
  double mass, length;
  int num_hz;
  double hz[16];
  double youngs_modulus, iz, half_height;
} reference;

static int read_reference(const char* path, reference* r) {
  FILE* f = fopen(path, "r");
  int ok, i;
  if (!f) return 0;
  ok = fscanf(f, " root_node %ld tip_node %ld num_nodes %ld mass %lf length %lf frequencies %d",
              &r->root_node, &r->tip_node, &r->num_nodes, &r->mass, &r->length, &r->num_hz) == 6;
  ok = ok && r->num_hz > 0 && r->num_hz <= 16;
  for (i = 0; ok && i < r->num_hz; ++i) ok = fscanf(f, "%lf", &r->hz[i]) == 1;
  ok = ok && fscanf(f, " next_node %ld youngs_modulus %lf iz %lf half_height %lf", &r->next_node,
                    &r->youngs_modulus, &r->iz, &r->half_height) == 4;
  fclose(f);
  return ok;
}

typedef struct pendulum {
  fs_model* model;
  int beam, pivot, root, tip, hinge;
} pendulum;

/* The beam hinged about z at its x = 0 node, horizontal, with or without gravity. */
static int build_pendulum(const char* modal_file, const reference* r, int gravity, pendulum* p) {
  const double g[3] = {0.0, -9.81, 0.0};
  fs_model_builder* b = fs_builder_create();
  int status;
  p->beam = fs_builder_add_flexible_body(b, "beam", modal_file, 16);
  p->pivot = fs_builder_add_marker(b, "pivot", FS_GROUND, -1, NULL, NULL);
  p->root = fs_builder_add_marker(b, "root", p->beam, r->root_node, NULL, NULL);
  p->tip = fs_builder_add_marker(b, "tip", p->beam, r->tip_node, NULL, NULL);
  p->hinge = fs_builder_add_joint(b, "hinge", FS_JOINT_REVOLUTE, p->pivot, p->root);
  if (gravity) CHECK(fs_builder_set_gravity(b, g) == FS_OK);
  /* rho 0.9: a little numerical damping of the highest modes, as joints need (step_settings). */
  CHECK(fs_builder_set_integrator(b, 1e-3, 0.9, 30, 0.0) == FS_OK);
  status = fs_builder_finalize(b, &p->model);
  if (status != FS_OK) fprintf(stderr, "finalize: %s\n", fs_builder_error(b));
  fs_builder_destroy(b);
  return status == FS_OK;
}

static void check_frequencies(const char* modal_file, const reference* r) {
  pendulum p;
  fs_data* d;
  double hz[64];
  int count = -1, i;
  if (!build_pendulum(modal_file, r, 0, &p)) {
    ++failures;
    return;
  }
  CHECK(fs_model_num_bodies(p.model) == 1);
  CHECK(fs_model_body_modes(p.model, p.beam) == 16);
  CHECK(fs_model_num_velocities(p.model) == 6 + 16);
  CHECK(fs_model_num_constraints(p.model) == 5);
  CHECK(fs_model_num_markers(p.model) == 3);
  CHECK(fs_model_num_joints(p.model) == 1);
  d = fs_data_create(p.model);
  CHECK(d != NULL);
  CHECK(fs_solve_static_equilibrium(d) == FS_OK);
  CHECK(fs_linearized_frequencies(d, hz, 64, &count) == FS_OK);
  CHECK(count == 6 + 16 - 5);
  /* The free rotation first, then the pinned-free FE model's bending frequencies, from above
   * (Rayleigh-Ritz) and within 0.1 % (16 clamped-root modes; test_model_equilibrium.cpp). */
  CHECK(fabs(hz[0]) < 1e-3);
  for (i = 1; i < r->num_hz && i < count; ++i) {
    const double rel = hz[i] / r->hz[i] - 1.0;
    printf("mode %d: C interface %.6f Hz, FE %.6f Hz (%+.2e)\n", i, hz[i], r->hz[i], rel);
    CHECK(rel > -1e-6 && rel < 1e-3);
  }
  /* A buffer too small: what fits, the count, and a status that says so. */
  CHECK(fs_linearized_frequencies(d, hz, 2, &count) == FS_ERROR_BUFFER_TOO_SMALL);
  CHECK(count == 17 && fabs(hz[0]) < 1e-3);
  fs_data_destroy(d);
  fs_model_destroy(p.model);
}

/* fs_linearize about a state that is not an equilibrium says so: the beam held horizontal,
 * multipliers zero, has a static residual of at least its weight m g (the frame's vertical
 * force); hanging at its equilibrium, round-off. There, the swing is the compound pendulum's,
 * f = sqrt(3 g / (2 L)) / (2 pi) for a slender uniform beam (its section's own inertia and its
 * bending, three orders of magnitude stiffer, shift it by far less than 1 %). */
static void check_static_residual(const char* modal_file, const reference* r) {
  pendulum p;
  fs_data* d;
  double hz[64], before = -1.0, after = -1.0, compound;
  int count = -1;
  if (!build_pendulum(modal_file, r, 1, &p)) {
    ++failures;
    return;
  }
  d = fs_data_create(p.model);
  CHECK(fs_linearize(d, hz, 64, &count, &before) == FS_OK);
  CHECK(before >= 0.999 * r->mass * 9.81);
  CHECK(fs_solve_static_equilibrium(d) == FS_OK);
  CHECK(fs_linearize(d, hz, 64, &count, &after) == FS_OK);
  compound = sqrt(3.0 * 9.81 / (2.0 * r->length)) / (2.0 * 3.14159265358979);
  printf("static residual: %.3e N horizontal, %.3e N hanging; swing %.5f Hz, compound pendulum "
         "%.5f Hz\n",
         before, after, hz[0], compound);
  CHECK(after < 1e-8 * before);
  CHECK(count == 17 && fabs(hz[0] / compound - 1.0) < 1e-2);
  CHECK(fs_linearize(d, hz, 2, &count, NULL) == FS_ERROR_BUFFER_TOO_SMALL);
  CHECK(strstr(fs_last_error(), "fs_linearize") != NULL);
  CHECK(fs_linearize(NULL, hz, 64, &count, &after) == FS_ERROR_NULL);
  CHECK(count == 0 && isnan(after));
  fs_data_destroy(d);
  fs_model_destroy(p.model);
}

static void check_swing(const char* modal_file, const reference* r) {
  pendulum p;
  fs_data* d;
  fs_energy e0, e;
  fs_statistics st;
  double origin[3], axes[9], force[3], moment[3], drift = 0.0, violation = 0.0, bound;
  int i, all_ok = 1;
  if (!build_pendulum(modal_file, r, 1, &p)) {
    ++failures;
    return;
  }
  d = fs_data_create(p.model);
  /* The model may go before its data: the data keeps it. */
  fs_model_destroy(p.model);
  CHECK(fs_initialize(d) == FS_OK);
  CHECK(fs_energy_compute(d, &e0) == FS_OK);
  for (i = 0; i < 500; ++i) {
    const int s = fs_step(d);
    if (s != FS_STEP_OK) {
      fprintf(stderr, "step %d: %s (%s)\n", i, fs_step_status_string(s), fs_data_error(d));
      all_ok = 0;
      break;
    }
    CHECK(fs_energy_compute(d, &e) == FS_OK);
    if (fabs(e.total - e0.total) > drift) drift = fabs(e.total - e0.total);
    if (fs_constraint_violation(d) > violation) violation = fs_constraint_violation(d);
  }
  CHECK(all_ok);
  CHECK(fabs(fs_time(d) - 0.5) < 1e-9);
  /* Energy: the swing turns up to m g L / 2 of potential energy into motion; generalized-alpha
   * at rho = 0.9 damps only the beam's highest modes, barely excited here, so the total stays
   * within 1e-4 of that (measured with clang -O2: 5e-7 of it, 1.6e-5 J). */
  bound = 1e-4 * r->mass * 9.81 * r->length / 2;
  printf("swing: 0.5 s, energy drift %.3e J (bound %.3e J), largest violation %.2e\n", drift, bound,
         violation);
  CHECK(drift < bound);
  CHECK(e.kinetic > 0.1 * r->mass * 9.81 * r->length / 2); /* it swung... */
  CHECK(fs_marker_frame(d, p.tip, origin, axes) == FS_OK);
  CHECK(origin[1] < -0.5);                                     /* ...downwards */
  CHECK(fabs(hypot(origin[0], origin[1]) - r->length) < 0.01); /* a beam of its length */
  CHECK(fabs(axes[8] - 1.0) < 1e-6);                           /* turning about z */
  CHECK(violation < 1e-6);
  CHECK(fs_joint_reaction(d, p.hinge, force, moment) == FS_OK);
  CHECK(isfinite(force[0]) && isfinite(force[1]) && fabs(moment[0]) < 1e-6 * r->mass);
  memset(&st, 0xff, sizeof st); /* a field left unwritten reads -1 (or NaN) */
  CHECK(fs_statistics_get(d, &st) == FS_OK);
  CHECK(st.steps == 500 && st.iterations >= 500 && st.factorizations >= 1);
  /* A smooth swing at 1 ms: no step split, every step converged, the local error estimate
   * under its default tolerance (1e-4 m). */
  CHECK(st.split_steps == 0 && st.substeps == 0 && st.over_budget == 0);
  CHECK(st.largest_error_estimate > 0.0 && st.largest_error_estimate < 1e-4);
  CHECK(st.above_error_tolerance == 0);
  CHECK(st.last_iterations >= 1 && st.last_correction <= 1.0);
  /* The matrix is refactorized before it goes stale: no correction undone; the last step reuses
   * it or factorizes once. */
  CHECK(st.undone_corrections == 0);
  CHECK(st.last_factorizations == 0 || st.last_factorizations == 1);
  printf("statistics: %lld steps, %.2f iterations/step, %lld factorizations, %lld undone\n",
         st.steps, (double)st.iterations / (double)st.steps, st.factorizations,
         st.undone_corrections);
  fs_data_destroy(d);
}

/* A constant push along -y at the tip: its work must show up as kinetic and elastic energy. */
static void push_down(double t, const double* position, const double* velocity, double* force,
                      double* moment, void* user) {
  (void)t, (void)position, (void)velocity, (void)moment;
  force[1] = -*(const double*)user;
}

/* The beam hinged at its root, pushed at its tip by `push` newtons; returns the body. */
static int add_pushed_beam(fs_model_builder* builder, const char* modal_file, const reference* r,
                           const double* push) {
  const int beam = fs_builder_add_flexible_body(builder, "beam", modal_file, 16);
  const int pivot = fs_builder_add_marker(builder, "pivot", FS_GROUND, -1, NULL, NULL);
  const int root = fs_builder_add_marker(builder, "root", beam, r->root_node, NULL, NULL);
  const int tip = fs_builder_add_marker(builder, "tip", beam, r->tip_node, NULL, NULL);
  CHECK(fs_builder_add_joint(builder, "hinge", FS_JOINT_REVOLUTE, pivot, root) >= 0);
  CHECK(fs_builder_add_point_load(builder, "push", tip, push_down, (void*)push) >= 0);
  return beam;
}

/* Outputs, damage meters, a point load and checkpoints in C: the swing without gravity, pushed
 * at the tip, its outputs reading the first two modal coordinates; stopped at 0.2 s, saved,
 * restored into a fresh data and continued, it must match the run that never stopped bit for
 * bit. References: the outputs against the modal coordinates they select; the restored run
 * against the uninterrupted one. */
static void check_outputs_and_checkpoints(const char* modal_file, const reference* r) {
  static const double push = 20.0; /* N */
  double rows[2 * 16] = {0.0}, p[16], a[3], b[3];
  fs_model_builder* builder = fs_builder_create();
  fs_model* m = NULL;
  fs_data *d, *resumed;
  unsigned char* bytes = NULL;
  size_t size = 0, too_small = 0;
  int beam, first, meter, count = 0, i;
  beam = add_pushed_beam(builder, modal_file, r, &push);
  rows[0] = 1.0;      /* output 0: p_0 */
  rows[16 + 1] = 2.0; /* output 1: 2 p_1 */
  first = fs_builder_add_stress_outputs(builder, "modes", beam, rows, 2, 16);
  meter = fs_builder_add_damage_meter(builder, "mode 0", first, 100.0, -1.0, 1.0, 1e3);
  CHECK(first == 0 && meter == 0);
  CHECK(fs_builder_add_stress_outputs(builder, "bad", beam, rows, 2, 15) >= 0);
  CHECK(fs_builder_finalize(builder, &m) == FS_ERROR_SIZE_MISMATCH); /* 15 columns, 16 modes */
  CHECK(strstr(fs_builder_error(builder), "outputs 'bad'") != NULL);
  fs_builder_destroy(builder);
  /* Again without the bad set. */
  builder = fs_builder_create();
  beam = add_pushed_beam(builder, modal_file, r, &push);
  first = fs_builder_add_stress_outputs(builder, "modes", beam, rows, 2, 16);
  meter = fs_builder_add_damage_meter(builder, "mode 0", first, 100.0, -1.0, 1.0, 1e3);
  /* Meters of chosen curves and classes, each at a scale and at half of it (its window halved
   * too: the same classes, every range halved). */
  CHECK(fs_builder_add_damage_meter_curve(builder, "iiw", first, FS_SN_IIW_NORMAL_HAIBACH, 100.0,
                                          -10.0, 10.0, 1e10) == 1);
  CHECK(fs_builder_add_damage_meter_curve(builder, "iiw half", first, FS_SN_IIW_NORMAL_HAIBACH,
                                          100.0, -5.0, 5.0, 5e9) == 2);
  CHECK(fs_builder_add_damage_meter_curve(builder, "shear", first, FS_SN_IIW_SHEAR_HAIBACH, 100.0,
                                          -10.0, 10.0, 1e10) == 3);
  CHECK(fs_builder_add_damage_meter_curve(builder, "shear half", first, FS_SN_IIW_SHEAR_HAIBACH,
                                          100.0, -5.0, 5.0, 5e9) == 4);
  CHECK(fs_builder_add_damage_meter_curve(builder, "en1993", first, FS_SN_EN1993_NORMAL, 100.0,
                                          -10.0, 10.0, 1e10) == 5);
  CHECK(fs_builder_set_integrator(builder, 1e-3, 0.9, 30, 0.0) == FS_OK);
  CHECK(fs_builder_finalize(builder, &m) == FS_OK);
  fs_builder_destroy(builder);
  d = fs_data_create(m);
  resumed = fs_data_create(m);
  CHECK(fs_initialize(d) == FS_OK);
  for (i = 0; i < 400; ++i) {
    CHECK(fs_step(d) == FS_STEP_OK);
    CHECK(fs_evaluate_outputs(d) == FS_STEP_OK);
    if (i == 199) { /* at 0.2 s */
      CHECK(fs_checkpoint_save(d, NULL, 0, &size) == FS_OK && size > 0);
      CHECK(fs_checkpoint_save(d, (unsigned char*)p, sizeof p, &too_small) ==
            FS_ERROR_BUFFER_TOO_SMALL);
      bytes = (unsigned char*)malloc(size);
      CHECK(bytes != NULL && fs_checkpoint_save(d, bytes, size, &size) == FS_OK);
    }
  }
  /* The outputs read the modal coordinates they select. */
  CHECK(fs_modal_coordinates(d, beam, p, 16, &count) == FS_OK && count == 16);
  CHECK(fs_output_value(d, first) == p[0] && fs_output_value(d, first + 1) == 2.0 * p[1]);
  CHECK(fabs(p[0]) > 0.0);                 /* the push bent the beam */
  CHECK(fs_meter_damage(d, meter) >= 0.0); /* finite and not negative */
  /* Ranges of a few MPa are below every knee: Miner damage goes as the range to the power m
   * there (IIW normal stress, Haibach: m = 5; shear: m = 9), and EN 1993-1-9 cuts them off
   * (below about 40 MPa for category 100). */
  printf("meters: IIW %.6g, halved %.6g; shear %.6g, halved %.6g; EN 1993 %.6g\n",
         fs_meter_damage(d, 1), fs_meter_damage(d, 2), fs_meter_damage(d, 3), fs_meter_damage(d, 4),
         fs_meter_damage(d, 5));
  CHECK(fs_meter_damage(d, 1) > 0.0 && fs_meter_damage(d, 3) > 0.0);
  CHECK(fabs(fs_meter_damage(d, 1) / fs_meter_damage(d, 2) / 32.0 - 1.0) < 1e-9);
  CHECK(fabs(fs_meter_damage(d, 3) / fs_meter_damage(d, 4) / 512.0 - 1.0) < 1e-9);
  CHECK(fs_meter_damage(d, 5) == 0.0);
  CHECK(isnan(fs_output_value(d, 7)) && isnan(fs_meter_damage(d, 9)));
  CHECK(fs_meter_refused_samples(d, meter) == 0); /* p_0 stayed within -1..1 */
  CHECK(fs_meter_refused_samples(d, 9) == -1 && fs_meter_refused_samples(NULL, 0) == -1);
  CHECK(isnan(fs_meter_damage(d, 9)) && strstr(fs_last_error(), "no meter with handle 9") != NULL);
  CHECK(isnan(fs_output_value(d, 7)) && strstr(fs_last_error(), "no output with handle 7") != NULL);
  /* Restored at 0.2 s and continued: the same state as the run that never stopped. */
  CHECK(fs_checkpoint_restore(resumed, bytes, size) == FS_OK);
  CHECK(fabs(fs_time(resumed) - 0.2) < 1e-12);
  for (i = 200; i < 400; ++i) {
    CHECK(fs_step(resumed) == FS_STEP_OK);
    CHECK(fs_evaluate_outputs(resumed) == FS_STEP_OK);
  }
  CHECK(fs_body_position(d, beam, a) == FS_OK && fs_body_position(resumed, beam, b) == FS_OK);
  CHECK(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
  CHECK(fs_output_value(d, first) == fs_output_value(resumed, first));
  CHECK(fs_meter_damage(d, meter) == fs_meter_damage(resumed, meter));
  /* A damaged checkpoint is refused and leaves the data as it was. */
  bytes[size / 2] ^= 0x10;
  CHECK(fs_checkpoint_restore(resumed, bytes, size) == FS_ERROR_BAD_FILE_FORMAT);
  CHECK(strstr(fs_last_error(), "checksum") != NULL);
  CHECK(fs_body_position(resumed, beam, b) == FS_OK && a[0] == b[0]);
  printf("outputs and checkpoints: p0 %.3e at 0.4 s, a checkpoint of %lu bytes\n", p[0],
         (unsigned long)size);
  free(bytes);
  fs_data_destroy(resumed);
  fs_data_destroy(d);
  fs_model_destroy(m);
}

/* phi(t) = 0.5 t, written by a callback. */
static void ramp(double t, double out[3], void* user) {
  const double rate = *(const double*)user;
  out[0] = rate * t;
  out[1] = rate;
  out[2] = 0.0;
}

static double angle_z(const fs_data* d, int body) {
  double e[4];
  if (fs_body_orientation(d, body, e) != FS_OK) return NAN;
  return 2.0 * atan2(e[3], e[0]);
}

/* A rigid crank turned by a revolute driver: each kind of law through the interface. */
static void check_drivers(void) {
  const double com[3] = {0.5, 0.0, 0.0}, inertia[9] = {1e-3, 0, 0, 0, 0.1, 0, 0, 0, 0.1};
  const double table[8] = {0.0, 0.0, 0.1, 0.05, 0.2, 0.2, 0.3, 0.3};
  double rate = 0.5, v[3], w[3], x[3];
  fs_model_builder* b = fs_builder_create();
  fs_model* m = NULL;
  fs_data* d;
  fs_motion_law law = fs_law_callback(ramp, &rate);
  int crank, pivot, end, hinge, drive, input, i;
  double effort = 1.0;
  crank = fs_builder_add_rigid_body(b, "crank", 2.0, com, inertia);
  pivot = fs_builder_add_marker(b, "pivot", FS_GROUND, -1, NULL, NULL);
  end = fs_builder_add_marker(b, "crank end", crank, -1, NULL, NULL);
  hinge = fs_builder_add_joint(b, "hinge", FS_JOINT_REVOLUTE, pivot, end);
  drive = fs_builder_add_driver(b, "motor", FS_JOINT_REVOLUTE_DRIVER, pivot, end, &law);
  input = fs_builder_add_input(b, "motor angle");
  CHECK(hinge >= 0 && drive >= 0 && input == 0);
  CHECK(fs_builder_finalize(b, &m) == FS_OK);
  fs_builder_destroy(b);
  CHECK(fs_model_num_inputs(m) == 1 && fs_model_num_constraints(m) == 6);
  d = fs_data_create(m);
  CHECK(fs_initialize(d) == FS_OK);
  for (i = 0; i < 100; ++i) CHECK(fs_step(d) == FS_STEP_OK);
  CHECK(fabs(angle_z(d, crank) - 0.05) < 1e-6); /* callback: 0.5 rad/s for 0.1 s */
  CHECK(fs_body_angular_velocity(d, crank, w) == FS_OK && fabs(w[2] - 0.5) < 1e-4);
  CHECK(fs_body_velocity(d, crank, v) == FS_OK && fabs(v[0]) < 1e-9);
  CHECK(fs_body_position(d, crank, x) == FS_OK && fabs(x[0]) < 1e-9);
  /* The hinge's and the motor's own coordinate: 0.05 rad, turning at 0.5 rad/s. */
  CHECK(fs_joint_coordinate(d, hinge, &x[0], &x[1]) == FS_OK);
  CHECK(fabs(x[0] - 0.05) < 1e-6 && fabs(x[1] - 0.5) < 1e-4);
  CHECK(fs_joint_coordinate(d, drive, &x[0], &x[1]) == FS_OK && fabs(x[0] - 0.05) < 1e-6);
  CHECK(fs_joint_coordinate(d, 7, &x[0], &x[1]) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_body_position(d, crank, x) == FS_OK);
  /* At a constant rate without gravity the motor exerts no moment; the hinge is no driver. */
  CHECK(fs_driver_effort(d, drive, &effort) == FS_OK && fabs(effort) < 1e-6);
  CHECK(fs_driver_effort(d, hinge, &effort) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "joint 'hinge'") != NULL);
  /* A table law (passes through its rows; 0.05 rad at t = 0.1 s, where the ramp is). Its rate
   * differs from the ramp's: a new law is a restart, so initialize again (projects v). */
  law = fs_law_table(table, 4);
  CHECK(fs_set_law(d, drive, &law) == FS_OK);
  CHECK(fs_initialize(d) == FS_OK);
  for (i = 0; i < 100; ++i) CHECK(fs_step(d) == FS_STEP_OK);
  CHECK(fabs(angle_z(d, crank) - 0.2) < 1e-6);
  /* The same rows point to point: at rest at the row (t = 0.2 s; the spline was turning, so
   * initialize again); half way to the next, 0.25 rad at the quintic's peak rate, 1.875 times
   * the segment's mean (0.1 rad in 0.1 s), where the spline through the same rows turns at
   * 1.1 rad/s; at rest again at t = 0.3 s. The step holds the angle to the law; its rate is off
   * by the order of h^2 s''' (3e-3 rad/s half way, 6e-3 at the row: s''' = 30 and 60 times
   * 0.1 / 0.1^3), so the rates are checked to 1e-2 rad/s, which still tells the two laws apart
   * (measured: 2.6e-4 and 5.2e-4 rad/s). */
  law = fs_law_rest_to_rest(table, 4);
  CHECK(fs_set_law(d, drive, &law) == FS_OK);
  CHECK(fs_initialize(d) == FS_OK);
  for (i = 0; i < 50; ++i) CHECK(fs_step(d) == FS_STEP_OK);
  CHECK(fabs(angle_z(d, crank) - 0.25) < 1e-6);
  CHECK(fs_body_angular_velocity(d, crank, w) == FS_OK && fabs(w[2] - 1.875) < 1e-2);
  printf("point to point: %.6g rad/s half way (t = %.3f s), ", w[2], fs_time(d));
  for (i = 0; i < 50; ++i) CHECK(fs_step(d) == FS_STEP_OK);
  CHECK(fabs(angle_z(d, crank) - 0.3) < 1e-6);
  CHECK(fs_body_angular_velocity(d, crank, w) == FS_OK && fabs(w[2]) < 1e-2);
  printf("%.3g rad/s at the row (t = %.3f s)\n", w[2], fs_time(d));
  /* An input law: initialize refuses it until the input is set, then assembles the jump. */
  law = fs_law_input(input);
  CHECK(fs_set_law(d, drive, &law) == FS_OK);
  CHECK(fs_initialize(d) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_data_error(d), "motor angle") != NULL);
  CHECK(fs_set_input(d, input, 0.25, 0.0, 0.0) == FS_OK);
  CHECK(fs_initialize(d) == FS_OK);
  for (i = 0; i < 200; ++i) CHECK(fs_step(d) == FS_STEP_OK);
  CHECK(fabs(angle_z(d, crank) - 0.25) < 1e-6);
  CHECK(fs_set_input(d, input, NAN, 0.0, 0.0) == FS_ERROR_INVALID_ARGUMENT);
  /* A polynomial law; then the driver switched off: the crank turns on freely (no gravity). */
  law = fs_law_polynomial(0.25, 0.0, 0.0);
  CHECK(fs_set_law(d, drive, &law) == FS_OK);
  CHECK(fs_set_joint_active(d, drive, 0) == FS_OK);
  CHECK(fs_step(d) == FS_STEP_OK);
  /* A bad table is an error naming the row, and changes nothing. */
  law = fs_law_table(table, 1);
  CHECK(fs_set_law(d, drive, &law) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_data_error(d), "two rows") != NULL);
  law = fs_law_table(NULL, 3);
  CHECK(fs_set_law(d, drive, &law) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_data_error(d), "null rows") != NULL);
  CHECK(fs_set_law(d, hinge, &law) != FS_OK); /* not a driver */
  fs_data_destroy(d);
  fs_model_destroy(m);
}

static void check_errors(const char* modal_file, const reference* r) {
  fs_model_builder* b = fs_builder_create();
  fs_model* m = NULL;
  fs_data* d;
  char small[8];
  double x[3] = {0.0, 0.0, 0.0};
  const double eye[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double backwards[6] = {0.0, 0.0, 1.0, 0.05, 0.5, 0.1}; /* t: 0, 1, 0.5 */
  fs_motion_law law = fs_law_polynomial(0.0, 0.0, 0.0);
  int beam, pivot, status;
  fs_settings settings;
  /* A marker on a node the body lacks: finalize fails, naming the marker. */
  beam = fs_builder_add_flexible_body(b, "beam", modal_file, 16);
  pivot = fs_builder_add_marker(b, "pivot", FS_GROUND, -1, NULL, NULL);
  CHECK(fs_builder_add_marker(b, "far marker", beam, r->num_nodes + 5, NULL, NULL) >= 0);
  fs_builder_add_joint(b, "hinge", FS_JOINT_REVOLUTE, pivot,
                       fs_builder_add_marker(b, "root", beam, r->root_node, NULL, NULL));
  status = fs_builder_finalize(b, &m);
  printf("expected finalize error: %s\n", fs_builder_error(b));
  CHECK(status == FS_ERROR_INVALID_MESH && m == NULL);
  CHECK(strstr(fs_builder_error(b), "far marker") != NULL);
  CHECK(fs_builder_copy_error(b, small, sizeof small) == strlen(fs_builder_error(b)));
  CHECK(strlen(small) == sizeof small - 1);
  fs_builder_destroy(b);

  /* A file that is not there: the body's handle is invalid and finalize names the body. */
  b = fs_builder_create();
  CHECK(fs_builder_add_flexible_body(b, "ghost", "/nonexistent/ghost.fsmodal", 10) ==
        FS_INVALID_HANDLE);
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_IO && m == NULL);
  CHECK(strstr(fs_builder_error(b), "ghost") != NULL);
  fs_builder_destroy(b);

  /* More modes than the file has; an unknown joint kind; a driver kind without a law. */
  b = fs_builder_create();
  fs_builder_add_flexible_body(b, "greedy", modal_file, 40);
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_SIZE_MISMATCH);
  CHECK(strstr(fs_builder_error(b), "greedy") != NULL);
  fs_builder_destroy(b);
  b = fs_builder_create();
  CHECK(fs_builder_add_joint(b, "odd", 42, 0, 1) == FS_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "odd") != NULL);
  CHECK(fs_builder_add_driver(b, "no law", FS_JOINT_REVOLUTE_DRIVER, 0, 1, NULL) ==
        FS_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "fs_builder_add_driver: a required pointer is null") != NULL);
  /* Neither joint is in the model, so finalize fails too, naming the first: a caller that did
   * not check the handles must not get a model without them. */
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_INVALID_ARGUMENT && m == NULL);
  CHECK(strstr(fs_builder_error(b), "joint 'odd': fs_builder_add_joint: kind 42 is unknown") !=
        NULL);
  fs_builder_destroy(b);

  /* A driver's table whose time goes backwards: finalize names the joint and the row. A step
   * of zero: finalize names the settings. */
  b = fs_builder_create();
  law = fs_law_table(backwards, 3);
  CHECK(fs_builder_add_driver(b, "lift", FS_JOINT_PRISMATIC_DRIVER, 0, 1, &law) ==
        FS_INVALID_HANDLE);
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_INVALID_ARGUMENT && m == NULL);
  CHECK(strstr(fs_builder_error(b), "joint 'lift'") != NULL);
  CHECK(strstr(fs_builder_error(b), "time at row 3 (0.5) does not increase") != NULL);
  fs_builder_destroy(b);
  b = fs_builder_create();
  fs_builder_add_rigid_body(b, "block", 1.0, x, eye);
  CHECK(fs_builder_set_integrator(b, 1e-3, 1.5, 30, 0.0) == FS_OK); /* finalize checks it */
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_INVALID_ARGUMENT && m == NULL);
  CHECK(strstr(fs_builder_error(b), "the spectral radius must be in [0, 1]") != NULL);
  fs_builder_destroy(b);
  /* Values <= 0 (a negative spectral radius) keep the defaults: 1 ms, 0.8, 30 iterations. */
  b = fs_builder_create();
  fs_builder_add_rigid_body(b, "block", 1.0, x, eye);
  CHECK(fs_builder_set_integrator(b, 0.0, -1.0, 0, 0.0) == FS_OK);
  CHECK(fs_builder_finalize(b, &m) == FS_OK);
  d = fs_data_create(m);
  CHECK(fs_settings_get(d, &settings) == FS_OK);
  CHECK(settings.step == 1e-3 && settings.spectral_radius == 0.8 && settings.max_iterations == 30);
  fs_data_destroy(d);
  fs_model_destroy(m);
  m = NULL;
  fs_builder_destroy(b);

  /* Null pointers and handles of nothing: error codes, never a crash. */
  CHECK(fs_builder_add_marker(NULL, "m", FS_GROUND, -1, NULL, NULL) == FS_INVALID_HANDLE);
  CHECK(fs_builder_add_driver(NULL, "d", FS_JOINT_REVOLUTE_DRIVER, 0, 1, &law) ==
        FS_INVALID_HANDLE);
  CHECK(fs_builder_finalize(NULL, &m) == FS_ERROR_NULL);
  CHECK(fs_data_create(NULL) == NULL);
  CHECK(fs_step(NULL) == FS_STEP_ERROR);
  CHECK(fs_initialize(NULL) == FS_ERROR_NULL);
  CHECK(fs_model_num_velocities(NULL) == -1);
  CHECK(isnan(fs_time(NULL)) && isnan(fs_constraint_violation(NULL)));
  CHECK(fs_evaluate_outputs(NULL) == FS_STEP_ERROR);
  CHECK(isnan(fs_output_value(NULL, 0)) && isnan(fs_meter_damage(NULL, 0)));
  CHECK(strcmp(fs_data_error(NULL), "fs_data_error: null data") == 0);
  /* A null builder's error text, cut to the buffer and terminated like any other. */
  CHECK(strcmp(fs_builder_error(NULL), "fs_builder_error: null builder") == 0);
  CHECK(fs_builder_copy_error(NULL, small, sizeof small) == strlen(fs_builder_error(NULL)));
  CHECK(strncmp(small, "fs_buil", sizeof small) == 0);
  fs_data_destroy(NULL);
  fs_model_destroy(NULL);
  fs_builder_destroy(NULL);

  b = fs_builder_create();
  beam = fs_builder_add_rigid_body(b, "block", 1.0, x, eye);
  CHECK(fs_builder_finalize(b, &m) == FS_OK);
  fs_builder_destroy(b);
  d = fs_data_create(m);
  CHECK(fs_body_position(d, 7, x) == FS_ERROR_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "body") != NULL);
  CHECK(fs_body_position(d, FS_GROUND, x) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_body_position(d, beam, NULL) == FS_ERROR_NULL);
  CHECK(fs_marker_frame(d, 0, x, NULL) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_joint_reaction(d, 3, x, x) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_set_joint_active(d, -5, 1) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_set_input(d, 0, 1.0, 0.0, 0.0) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_set_law(d, 0, &law) == FS_ERROR_INVALID_HANDLE);
  CHECK(fs_model_body_modes(m, 3) == -1 && fs_model_body_modes(m, beam) == 0);
  CHECK(fs_set_step_size(d, -1.0) == FS_ERROR_INVALID_ARGUMENT);
  /* Settings: read, checked on write (the message names the field), written back. */
  CHECK(fs_settings_get(d, &settings) == FS_OK);
  CHECK(settings.step == 1e-3 && settings.max_step_halvings == 4);
  CHECK(settings.local_error_tolerance > 0.0 && settings.relative_acceleration_tolerance > 0.0);
  settings.relative_acceleration_tolerance = -1.0;
  CHECK(fs_settings_set(d, &settings) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "relative_acceleration_tolerance") != NULL);
  settings.relative_acceleration_tolerance = 1e-8;
  settings.max_step_halvings = 21;
  CHECK(fs_settings_set(d, &settings) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "max_step_halvings") != NULL);
  settings.max_step_halvings = 0;
  CHECK(settings.newton_error_estimate_fraction == 1.0);
  settings.newton_error_estimate_fraction = 2.0;
  CHECK(fs_settings_set(d, &settings) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "newton_error_estimate_fraction") != NULL);
  settings.newton_error_estimate_fraction = 0.0;
  settings.step = 5e-4;
  CHECK(fs_settings_set(d, &settings) == FS_OK);
  CHECK(fs_settings_get(d, &settings) == FS_OK);
  CHECK(settings.max_step_halvings == 0 && settings.relative_acceleration_tolerance == 1e-8);
  CHECK(settings.newton_error_estimate_fraction == 0.0);
  CHECK(settings.step == 5e-4);
  CHECK(settings.linearized_multipliers == FS_LINEARIZED_MULTIPLIERS_PIECES);
  CHECK(settings.refactorize_pieces == 1 && settings.piece_newton_tolerance_fraction == 0.0);
  settings.linearized_multipliers = 3; /* not one of fs_linearized_multipliers */
  CHECK(fs_settings_set(d, &settings) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "linearized_multipliers") != NULL);
  settings.linearized_multipliers = FS_LINEARIZED_MULTIPLIERS_ALWAYS;
  settings.piece_newton_tolerance_fraction = 2.0;
  CHECK(fs_settings_set(d, &settings) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "piece_newton_tolerance_fraction") != NULL);
  settings.piece_newton_tolerance_fraction = 0.01;
  settings.refactorize_pieces = 0;
  CHECK(fs_settings_set(d, &settings) == FS_OK);
  CHECK(fs_settings_get(d, &settings) == FS_OK);
  CHECK(settings.linearized_multipliers == FS_LINEARIZED_MULTIPLIERS_ALWAYS);
  CHECK(settings.refactorize_pieces == 0 && settings.piece_newton_tolerance_fraction == 0.01);
  CHECK(fs_settings_set(d, NULL) == FS_ERROR_NULL);
  fs_data_destroy(d);
  fs_model_destroy(m);
}

/* The beam held horizontal by a revolute driver at its hinge, under gravity, at rest: the top
 * fibre of its root element carries M c / I with M = m g L / 2 (beam theory). The root stress
 * of 16 Craig-Bampton modes is low by their truncation (docs/model.md): within 1 % (0.36 %). */
static void check_fibre_stress(const char* modal_file, const reference* r) {
  const double g[3] = {0.0, -9.81, 0.0};
  const fs_motion_law hold = fs_law_polynomial(0.0, 0.0, 0.0);
  fs_model_builder* b = fs_builder_create();
  fs_model* m = NULL;
  fs_data* d;
  int beam, pivot, root, top, bottom, status;
  double expected, sigma_top, sigma_bottom, distance = -1.0;
  const double tip_point[3] = {r->length, 0.0, 0.0};
  const double near_next[3] = {r->length / 24.0 + 0.01, 0.01, 0.0};
  beam = fs_builder_add_flexible_body(b, "beam", modal_file, 16);
  pivot = fs_builder_add_marker(b, "pivot", FS_GROUND, -1, NULL, NULL);
  root = fs_builder_add_marker(b, "root", beam, r->root_node, NULL, NULL);
  CHECK(fs_builder_add_joint(b, "hinge", FS_JOINT_REVOLUTE, pivot, root) >= 0);
  CHECK(fs_builder_add_driver(b, "hold", FS_JOINT_REVOLUTE_DRIVER, pivot, root, &hold) >= 0);
  CHECK(fs_builder_set_gravity(b, g) == FS_OK);
  top = fs_builder_add_beam_fibre_stress(b, "root top", beam, r->root_node, r->next_node, NULL,
                                         r->youngs_modulus, 0.0, r->half_height, 0.0);
  bottom = fs_builder_add_beam_fibre_stress(b, "root bottom", beam, r->root_node, r->next_node,
                                            NULL, r->youngs_modulus, 0.0, -r->half_height, 0.0);
  CHECK(top == 0 && bottom == 1);
  status = fs_builder_finalize(b, &m);
  if (status != FS_OK) fprintf(stderr, "finalize: %s\n", fs_builder_error(b));
  CHECK(status == FS_OK);
  fs_builder_destroy(b);
  if (status != FS_OK) return;
  d = fs_data_create(m);
  CHECK(fs_solve_static_equilibrium(d) == FS_OK);
  CHECK(fs_evaluate_outputs(d) == FS_STEP_OK);
  sigma_top = fs_output_value(d, top);
  sigma_bottom = fs_output_value(d, bottom);
  expected = r->mass * 9.81 * r->length / 2.0 * r->half_height / r->iz; /* tension on top */
  printf("root fibre stress %.6g / %.6g MPa, beam theory +-%.6g MPa\n", sigma_top * 1e-6,
         sigma_bottom * 1e-6, expected * 1e-6);
  CHECK(sigma_top > 0.99 * expected && sigma_top < 1.001 * expected);
  /* Their mean is the axial stress: only the weight's component along the bent beam, about
   * rho g times the tip deflection (a few hundred Pa against 15 MPa of bending). */
  CHECK(fabs(sigma_top + sigma_bottom) < 1e-4 * expected);
  fs_data_destroy(d);
  fs_model_destroy(m);

  /* Bad input names what is wrong: a node the file does not have, xi outside [0, 1]. */
  b = fs_builder_create();
  beam = fs_builder_add_flexible_body(b, "beam", modal_file, 16);
  /* Nodes by position: the tip at x = L, the root's neighbour one element (L / 24) along. */
  CHECK(fs_builder_nearest_node(b, beam, tip_point, &distance) == r->tip_node && distance < 1e-12);
  CHECK(fs_builder_nearest_node(b, beam, near_next, &distance) == r->next_node);
  CHECK(fabs(distance - 0.01 * sqrt(2.0)) < 1e-12);
  CHECK(fs_builder_nearest_node(b, FS_GROUND, tip_point, NULL) == -1);
  CHECK(strstr(fs_last_error(), "not a flexible body") != NULL);
  CHECK(fs_builder_nearest_node(b, beam, NULL, NULL) == -1);
  CHECK(fs_builder_add_beam_fibre_stress(b, "far", beam, r->root_node, r->num_nodes + 3, NULL,
                                         r->youngs_modulus, 0.0, 0.0, 0.0) == FS_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "output 'far'") != NULL && strstr(fs_last_error(), "node") != NULL);
  CHECK(fs_builder_finalize(b, &m) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_builder_error(b), "does not exist") != NULL);
  fs_builder_destroy(b);
  b = fs_builder_create();
  beam = fs_builder_add_flexible_body(b, "beam", modal_file, 16);
  CHECK(fs_builder_add_beam_fibre_stress(b, "xi", beam, r->root_node, r->next_node, NULL,
                                         r->youngs_modulus, 1.5, 0.0, 0.0) == FS_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "xi 1.5") != NULL);
  CHECK(fs_builder_add_damage_meter_curve(b, "odd", 0, 9, 100.0, -1.0, 1.0, 1.0) ==
        FS_INVALID_HANDLE);
  CHECK(strstr(fs_last_error(), "unknown S-N curve 9") != NULL); /* this call's reason... */
  CHECK(strstr(fs_builder_error(b), "xi 1.5") != NULL);          /* ...the builder's first */
  CHECK(fs_builder_add_beam_fibre_stress(b, "rigid", FS_GROUND, 0, 1, NULL, 1.0, 0.0, 0.0, 0.0) ==
        FS_INVALID_HANDLE);
  fs_builder_destroy(b);
}

int main(int argc, char** argv) {
  reference r;
  if (argc != 3 || !read_reference(argv[2], &r)) {
    fprintf(stderr, "usage: %s <beam.fsmodal> <beam_reference.txt> (readable)\n", argv[0]);
    return 2;
  }
  printf("flexstress %s (%d)\n", fs_version(), fs_version_number());
  CHECK(fs_version_number() == FLEXSTRESS_VERSION);
  {
    char expected[32];
    snprintf(expected, sizeof expected, "%d.%d.%d", FLEXSTRESS_VERSION_MAJOR,
             FLEXSTRESS_VERSION_MINOR, FLEXSTRESS_VERSION_PATCH);
    CHECK(strcmp(fs_version(), expected) == 0);
  }
  CHECK(strcmp(fs_status_string(FS_ERROR_INVALID_HANDLE), "invalid handle") == 0);
  check_frequencies(argv[1], &r);
  check_static_residual(argv[1], &r);
  check_swing(argv[1], &r);
  check_drivers();
  check_outputs_and_checkpoints(argv[1], &r);
  check_errors(argv[1], &r);
  check_fibre_stress(argv[1], &r);
  if (failures)
    fprintf(stderr, "%d checks failed\n", failures);
  else
    printf("all checks passed\n");
  return failures ? 1 : 0;
}
