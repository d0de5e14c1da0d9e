/* The paper's crane from C, through flexstress's general C interface (flexstress.h) alone. The
 * crane program writes the stroke-driven crane as files (`crane --export-c-model DIR`); this
 * program builds the model from them with the builder, puts it in static equilibrium, steps it
 * through the work cycle reading the hot spot at the welded detail D each step, and reads the
 * damage per work cycle from its damage meter. It prints the crane program's "key: value"
 * lines for the figures both report (tests/examples/check_crane.cmake compares them).
 *
 *   crane --export-c-model crane-c && crane_c_demo crane-c
 *
 * DIR holds crane.txt ("key values..." lines: where the parts are, their masses, the damage
 * meter, the integrator), boom.fsmodal (the boom's modal body), detail_d.txt (the detail's
 * stress rows) and cycle.csv (the work cycle: time, stroke); docs/crane.md describes them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flexstress/flexstress.h>

/* ---- the exported files ------------------------------------------------------------------ */

/* crane.txt's values (integers too are read as doubles). */
typedef struct crane_spec {
  double modes, node_a, node_b, b_offset[3], support_a[3], support_c[3];
  double cylinder_mass, cylinder_com[3], cylinder_inertia[9], cylinder_position[3];
  double cylinder_orientation[4], cylinder_c_axes[9];
  double rod_mass, rod_com[3], rod_inertia[9], rod_position[3], rod_orientation[4];
  double gravity[3], initial_length, hot_spot, meter_fat, meter_range[2], meter_scale;
  double step, spectral_radius, max_iterations, tolerance;
} crane_spec;

/* Reads `count` numbers from *text into out, moving *text past them; 0 if there are fewer. */
static int read_numbers(const char** text, double* out, int count) {
  int i;
  for (i = 0; i < count; ++i) {
    char* end;
    out[i] = strtod(*text, &end);
    if (end == *text) return 0;
    *text = end;
  }
  return 1;
}

static int only_space(const char* text) {
  return text[strspn(text, " \t\r\n")] == '\0';
}

static int read_spec(const char* path, crane_spec* c) {
  struct {
    const char* key;
    double* values;
    int count, seen;
  } keys[] = {{"boom_modes", &c->modes, 1, 0},
              {"boom_node_a", &c->node_a, 1, 0},
              {"boom_node_b", &c->node_b, 1, 0},
              {"boom_b_offset", c->b_offset, 3, 0},
              {"support_a", c->support_a, 3, 0},
              {"support_c", c->support_c, 3, 0},
              {"cylinder_mass", &c->cylinder_mass, 1, 0},
              {"cylinder_center_of_mass", c->cylinder_com, 3, 0},
              {"cylinder_inertia", c->cylinder_inertia, 9, 0},
              {"cylinder_position", c->cylinder_position, 3, 0},
              {"cylinder_orientation", c->cylinder_orientation, 4, 0},
              {"cylinder_c_axes", c->cylinder_c_axes, 9, 0},
              {"rod_mass", &c->rod_mass, 1, 0},
              {"rod_center_of_mass", c->rod_com, 3, 0},
              {"rod_inertia", c->rod_inertia, 9, 0},
              {"rod_position", c->rod_position, 3, 0},
              {"rod_orientation", c->rod_orientation, 4, 0},
              {"gravity", c->gravity, 3, 0},
              {"initial_length", &c->initial_length, 1, 0},
              {"hot_spot_output", &c->hot_spot, 1, 0},
              {"meter_fat", &c->meter_fat, 1, 0},
              {"meter_range", c->meter_range, 2, 0},
              {"meter_scale", &c->meter_scale, 1, 0},
              {"step", &c->step, 1, 0},
              {"spectral_radius", &c->spectral_radius, 1, 0},
              {"max_iterations", &c->max_iterations, 1, 0},
              {"tolerance", &c->tolerance, 1, 0}};
  const int num_keys = (int)(sizeof keys / sizeof keys[0]);
  char line[1024], key[64];
  int k, ok = 1, line_number = 0, used;
  FILE* f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "error: cannot open %s\n", path);
    return 0;
  }
  while (ok && fgets(line, sizeof line, f)) {
    const char* values;
    ++line_number;
    if (line[0] == '#' || sscanf(line, "%63s%n", key, &used) != 1) continue;
    for (k = 0; k < num_keys && strcmp(keys[k].key, key) != 0; ++k) continue; /* find it */
    values = line + used;
    if (k == num_keys) {
      fprintf(stderr, "error: %s line %d: unknown key '%s'\n", path, line_number, key);
      ok = 0;
    } else if (!read_numbers(&values, keys[k].values, keys[k].count) || !only_space(values)) {
      fprintf(stderr, "error: %s line %d: '%s' takes %d numbers\n", path, line_number, key,
              keys[k].count);
      ok = 0;
    }
    if (ok) keys[k].seen = 1;
  }
  fclose(f);
  for (k = 0; ok && k < num_keys; ++k)
    if (!keys[k].seen) {
      fprintf(stderr, "error: %s has no '%s'\n", path, keys[k].key);
      ok = 0;
    }
  return ok;
}

/* detail_d.txt: comment lines, "outputs N modes M", then per output M coefficients and its
 * name. Fills *rows (N x M, row-major, malloc'ed) and the name of output `named`. */
static int read_rows(const char* path, int named, double** rows, int* outputs, int* modes,
                     char* name, size_t name_size) {
  char line[4096];
  int i = 0;
  FILE* f = fopen(path, "r");
  *rows = NULL;
  if (!f) {
    fprintf(stderr, "error: cannot open %s\n", path);
    return 0;
  }
  do {
    if (!fgets(line, sizeof line, f)) line[0] = '\0';
  } while (line[0] == '#');
  if (sscanf(line, "outputs %d modes %d", outputs, modes) == 2 && *outputs >= 1 && *modes >= 1 &&
      *modes <= 64)
    *rows = (double*)malloc((size_t)*outputs * (size_t)*modes * sizeof(double));
  for (i = 0; *rows && i < *outputs && fgets(line, sizeof line, f); ++i) {
    const char* text = line;
    if (!read_numbers(&text, *rows + (size_t)i * (size_t)*modes, *modes)) break;
    if (i == named) {
      text += strspn(text, " ");
      snprintf(name, name_size, "%.*s", (int)strcspn(text, "\r\n"), text);
    }
  }
  fclose(f);
  if (*rows && i == *outputs) return 1;
  fprintf(stderr, "error: %s: expected 'outputs N modes M', then N rows of M numbers and a name\n",
          path);
  free(*rows);
  *rows = NULL;
  return 0;
}

/* cycle.csv: "time,stroke" rows (a header line allowed). Returns them as the driver's table
 * (t0, s0, t1, s1, ...; malloc'ed) with s = initial_length + stroke, the cylinder's length. */
static double* read_cycle(const char* path, double initial_length, int* num_rows) {
  char line[256];
  double *table = NULL, t, stroke;
  int capacity = 0, ok = 1;
  FILE* f = fopen(path, "r");
  *num_rows = 0;
  if (!f) {
    fprintf(stderr, "error: cannot open %s\n", path);
    return NULL;
  }
  while (ok && fgets(line, sizeof line, f)) {
    if (sscanf(line, "%lf,%lf", &t, &stroke) != 2) {
      if (*num_rows == 0 && strpbrk(line, "0123456789") == NULL) continue; /* the header */
      fprintf(stderr, "error: %s: expected 'time,stroke', got '%s'\n", path, line);
      ok = 0;
    } else if (*num_rows == capacity) {
      double* grown;
      capacity = capacity ? 2 * capacity : 64;
      grown = (double*)realloc(table, 2 * (size_t)capacity * sizeof(double));
      if (grown) table = grown;
      ok = grown != NULL;
    }
    if (ok) {
      table[2 * *num_rows] = t;
      table[2 * *num_rows + 1] = initial_length + stroke;
      ++*num_rows;
    }
  }
  fclose(f);
  if (ok && *num_rows < 2) fprintf(stderr, "error: %s: needs at least two rows\n", path);
  if (ok && *num_rows >= 2) return table;
  free(table);
  return NULL;
}

/* DIR/name, in a buffer the next call reuses. */
static const char* file_in(const char* dir, const char* name) {
  static char path[4096];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  return path;
}

/* ---- the model --------------------------------------------------------------------------- */

/* What the run reads: the first stress output (the others follow it) and the damage meter. */
typedef struct crane_handles {
  int boom, first_output, meter;
} crane_handles;

/* Builds the crane: the builder records any mistake and fs_builder_finalize reports the first,
 * naming the part, so the calls before it need no checks of their own. */
static fs_model* build_crane(const char* boom_file, const crane_spec* c, const double* rows,
                             int outputs, int columns, const double* cycle, int cycle_rows,
                             crane_handles* h) {
  fs_model_builder* b = fs_builder_create();
  fs_model* model = NULL;
  fs_motion_law stroke;
  int cylinder, rod, a_support, a_boom, c_support, c_cylinder, b_boom, b_rod, cylinder_axis,
      rod_axis;
  if (!b) return NULL;
  /* Bodies, in the order the step's matrices follow: the flexible boom from its modal body file
   * (its frame at the origin), then the cylinder and its rod, rigid, their frames with z along
   * C -> B and origins at C and B. */
  h->boom = fs_builder_add_flexible_body(b, "boom", boom_file, (int)c->modes);
  cylinder = fs_builder_add_rigid_body(b, "cylinder", c->cylinder_mass, c->cylinder_com,
                                       c->cylinder_inertia);
  rod = fs_builder_add_rigid_body(b, "rod", c->rod_mass, c->rod_com, c->rod_inertia);
  fs_builder_set_initial_pose(b, cylinder, c->cylinder_position, c->cylinder_orientation);
  fs_builder_set_initial_pose(b, rod, c->rod_position, c->rod_orientation);

  /* Markers: frames on the bodies that joints hold together (NULL axes: the body's own). The
   * boom's sit on its FE nodes; B hangs below its node by a rigid offset. */
  a_support = fs_builder_add_marker(b, "A on support", FS_GROUND, -1, c->support_a, NULL);
  a_boom = fs_builder_add_marker(b, "A on boom", h->boom, (long)c->node_a, NULL, NULL);
  c_support = fs_builder_add_marker(b, "C on support", FS_GROUND, -1, c->support_c, NULL);
  c_cylinder = fs_builder_add_marker(b, "C on cylinder", cylinder, -1, NULL, c->cylinder_c_axes);
  b_boom = fs_builder_add_marker(b, "B on boom", h->boom, (long)c->node_b, c->b_offset, NULL);
  b_rod = fs_builder_add_marker(b, "B on rod", rod, -1, NULL, NULL);
  cylinder_axis = fs_builder_add_marker(b, "cylinder axis", cylinder, -1, NULL, NULL);
  rod_axis = fs_builder_add_marker(b, "rod axis", rod, -1, NULL, NULL);

  /* Joints. A: the boom hinged on the support, about z. C: the cylinder on the support, a
   * universal joint (z and the in-plane cross axis, so that the closed loop A-B-C is not
   * over-constrained). B: the rod on the boom, spherical. The rod slides in the cylinder. */
  fs_builder_add_joint(b, "A", FS_JOINT_REVOLUTE, a_support, a_boom);
  fs_builder_add_joint(b, "C", FS_JOINT_UNIVERSAL, c_support, c_cylinder);
  fs_builder_add_joint(b, "B", FS_JOINT_SPHERICAL, b_boom, b_rod);
  fs_builder_add_joint(b, "slide", FS_JOINT_PRISMATIC, cylinder_axis, rod_axis);
  /* The stroke drives the rod's origin along the cylinder's z: the cylinder's length over time,
   * a clamped cubic spline through the cycle's rows (copied: the table may go after this). */
  stroke = fs_law_table(cycle, cycle_rows);
  fs_builder_add_driver(b, "stroke", FS_JOINT_PRISMATIC_DRIVER, cylinder_axis, rod_axis, &stroke);

  /* Detail D's stresses, linear in the boom's modal coordinates (finalize checks that the rows
   * have a column per mode), and a damage meter on the hot spot: streaming rainflow on the
   * scaled stress (crane.txt: 1e-6, Pa to MPa, over +-400 MPa), Miner damage by the IIW curve
   * of the FAT class (100). */
  h->first_output = fs_builder_add_stress_outputs(b, "detail D", h->boom, rows, outputs, columns);
  h->meter = fs_builder_add_damage_meter(b, "hot spot (MPa)", h->first_output + (int)c->hot_spot,
                                         c->meter_fat, c->meter_range[0], c->meter_range[1],
                                         c->meter_scale);
  fs_builder_set_gravity(b, c->gravity);
  fs_builder_set_integrator(b, c->step, c->spectral_radius, (int)c->max_iterations, c->tolerance);

  if (fs_builder_finalize(b, &model) != FS_OK)
    fprintf(stderr, "error: the crane does not build: %s\n", fs_builder_error(b));
  for (int i = 0; i < fs_model_warning_count(model); ++i)
    fprintf(stderr, "warning: %s\n", fs_model_warning(model, i));
  fs_builder_destroy(b); /* the model does not need it */
  return model;
}

/* ---- the work cycle ---------------------------------------------------------------------- */

/* Steps the cycle; prints progress and the figures. Returns 0 if every step succeeded. */
static int run_cycle(const fs_model* model, const crane_spec* c, const crane_handles* h,
                     double t_first, double t_last) {
  const long steps = (long)ceil((t_last - t_first) / c->step);
  double hot_max = -HUGE_VAL;
  long i;
  int status = FS_STEP_OK;
  fs_statistics statistics;
  fs_data* d = fs_data_create(model);
  if (!d) return 1;
  /* The crane starts at rest: static equilibrium under gravity at the cycle's first stroke,
   * then consistent initial conditions (the accelerations the first step starts from). */
  if (fs_solve_static_equilibrium(d) != FS_OK || fs_initialize(d) != FS_OK) {
    fprintf(stderr, "error: the crane does not start: %s\n", fs_data_error(d));
    fs_data_destroy(d);
    return 1;
  }
  for (i = 0; i < steps; ++i) {
    double hot;
    status = fs_step(d);
    /* The outputs once per step: the stresses, and the meter counts the hot spot's cycles. */
    if (status == FS_STEP_OK) status = fs_evaluate_outputs(d);
    if (status != FS_STEP_OK) {
      fprintf(stderr, "error: step %ld at t = %g s: %s: %s\n", i, fs_time(d),
              fs_step_status_string(status), fs_data_error(d));
      break;
    }
    hot = fs_output_value(d, h->first_output + (int)c->hot_spot) / 1e6; /* Pa to MPa */
    if (hot > hot_max) hot_max = hot;
    if ((i + 1) % 2000 == 0)
      printf("  t %5.2f s  hot spot %7.3f MPa  damage so far %.4e\n", fs_time(d), hot,
             fs_meter_damage(d, h->meter));
  }
  if (status == FS_STEP_OK) {
    fs_statistics_get(d, &statistics);
    printf("  %.2f Newton iterations per step\n",
           (double)statistics.iterations / (double)statistics.steps);
    printf("steps: %ld\n", i);
    printf("hotspot_max_MPa: %.3f\n", hot_max);
    /* The meter's damage with its open cycles closed as a repeating history: per work cycle. */
    printf("damage_per_cycle: %.6g\n", fs_meter_damage(d, h->meter));
  }
  fs_data_destroy(d);
  return status == FS_STEP_OK ? 0 : 1;
}

int main(int argc, char** argv) {
  char hot_name[128] = "";
  crane_spec spec;
  double *rows = NULL, *cycle = NULL;
  int outputs = 0, modes = 0, cycle_rows = 0, result = 1, ok;
  crane_handles handles;
  fs_model* model = NULL;
  if (argc != 2) {
    fprintf(stderr, "usage: %s DIR (the files of `crane --export-c-model DIR`)\n", argv[0]);
    return 2;
  }
  ok = read_spec(file_in(argv[1], "crane.txt"), &spec) &&
       read_rows(file_in(argv[1], "detail_d.txt"), (int)spec.hot_spot, &rows, &outputs, &modes,
                 hot_name, sizeof hot_name) &&
       (cycle = read_cycle(file_in(argv[1], "cycle.csv"), spec.initial_length, &cycle_rows));
  if (ok)
    model = build_crane(file_in(argv[1], "boom.fsmodal"), &spec, rows, outputs, modes, cycle,
                        cycle_rows, &handles);
  if (model) {
    const double t_first = cycle[0], t_last = cycle[2 * cycle_rows - 2];
    printf(
        "crane from C (flexstress %s): a boom of %d modes, %d stress outputs at detail D, "
        "the hot spot '%s'; a cycle of %g s\n",
        fs_version(), fs_model_body_modes(model, handles.boom), outputs, hot_name,
        t_last - t_first);
    result = run_cycle(model, &spec, &handles, t_first, t_last);
  }
  fs_model_destroy(model);
  free(cycle);
  free(rows);
  return result;
}
