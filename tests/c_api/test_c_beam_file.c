/* A flexible body made from C alone (fs_save_beam_modal_body): a steel cantilever, 1 m of a
 * solid 40 x 20 mm section, 20 elements, clamped at x = 0 by a fixed joint to the ground. Its
 * linearized frequencies against Euler-Bernoulli's cantilever, f = (beta L)^2 / (2 pi L^2)
 * sqrt(E I / (rho A)), beta L = 1.875104 and 4.694091 (Blevins, Formulas for Natural Frequency
 * and Mode Shape, table 8-1), in both bending planes. The FE beam carries its section's rotary
 * inertia, which the formula leaves out: it lowers the frequencies by about (beta r)^2 / 2,
 * r^2 = I / A, at most 2.3e-4 for the first modes and 1.5e-3 for the second here, so they are
 * checked to 1e-3 and 3e-3.
 *
 *   test_c_beam_file <output dir>  (writes <dir>/cantilever.fsmodal) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <flexstress/flexstress.h>

#include "c_check.h"

static const double pi = 3.14159265358979323846;

static fs_beam_body steel_cantilever(const double* root) {
  fs_beam_body beam;
  memset(&beam, 0, sizeof beam);
  beam.length = 1.0;
  beam.elements = 20;
  beam.youngs_modulus = 210e9;
  beam.poissons_ratio = 0.3;
  beam.density = 7850.0;
  beam.area = 0.04 * 0.02;
  beam.iz = 0.02 * 0.04 * 0.04 * 0.04 / 12.0; /* 40 mm along the section's y */
  beam.iy = 0.04 * 0.02 * 0.02 * 0.02 / 12.0;
  beam.torsion_constant = 0.229 * 0.04 * 0.02 * 0.02 * 0.02; /* a 2:1 rectangle (Roark) */
  beam.interface_at = root;
  beam.interface_count = 1;
  beam.fixed_interface_modes = 6;
  return beam;
}

static double cantilever_hz(double beta_l, double i) {
  return beta_l * beta_l / (2.0 * pi) * sqrt(210e9 * i / (7850.0 * 0.04 * 0.02));
}

static void check_frequencies(const char* path) {
  const double root_at = 0.0, origin[3] = {0, 0, 0};
  fs_beam_body beam = steel_cantilever(&root_at);
  fs_model_builder* b;
  fs_model* m = NULL;
  fs_data* d;
  double hz[16], expected[4];
  int body, ground, root, count = -1, k;
  long root_node;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_OK);
  b = fs_builder_create();
  body = fs_builder_add_flexible_body(b, "cantilever", path, 6); /* the whole basis */
  root_node = fs_builder_nearest_node(b, body, origin, NULL);
  CHECK(root_node == 0);
  ground = fs_builder_add_marker(b, "wall", FS_GROUND, -1, NULL, NULL);
  root = fs_builder_add_marker(b, "root", body, root_node, NULL, NULL);
  CHECK(fs_builder_add_joint(b, "clamp", FS_JOINT_FIXED, ground, root) >= 0);
  CHECK(fs_builder_finalize(b, &m) == FS_OK);
  fs_builder_destroy(b);
  if (!m) {
    ++failures;
    return;
  }
  CHECK(fs_model_body_modes(m, body) == 6);
  CHECK(fs_model_warning_count(m) == 0);
  d = fs_data_create(m);
  CHECK(fs_linearized_frequencies(d, hz, 16, &count) == FS_OK);
  CHECK(count == 6);
  /* Ascending: first bending about the weak axis (iy), then the strong (iz = 4 iy), then the
   * second modes. */
  expected[0] = cantilever_hz(1.875104, beam.iy);
  expected[1] = cantilever_hz(1.875104, beam.iz);
  expected[2] = cantilever_hz(4.694091, beam.iy);
  expected[3] = cantilever_hz(4.694091, beam.iz);
  for (k = 0; k < 4 && k < count; ++k) {
    const double rel = hz[k] / expected[k] - 1.0;
    printf("mode %d: %.5f Hz, Euler-Bernoulli %.5f Hz (%+.2e)\n", k + 1, hz[k], expected[k], rel);
    CHECK(fabs(rel) < (k < 2 ? 1e-3 : 3e-3));
  }
  fs_data_destroy(d);
  fs_model_destroy(m);
}

static void check_errors(const char* path) {
  const double root_at = 0.0, off_beam = 2.0, twice[2] = {0.5, 0.5};
  fs_beam_body beam = steel_cantilever(&root_at);
  CHECK(fs_save_beam_modal_body(NULL, path) == FS_ERROR_NULL);
  CHECK(fs_save_beam_modal_body(&beam, NULL) == FS_ERROR_NULL);
  beam.length = -1.0;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  printf("expected: %s\n", fs_last_error());
  CHECK(strstr(fs_last_error(), "length -1") != NULL);
  beam = steel_cantilever(&off_beam);
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  printf("expected: %s\n", fs_last_error());
  CHECK(strstr(fs_last_error(), "interface position 0 (2 m) is outside the beam [0, 1]") != NULL);
  beam = steel_cantilever(twice);
  beam.interface_count = 2;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  printf("expected: %s\n", fs_last_error());
  CHECK(strstr(fs_last_error(), "interface position 1 (0.5 m) falls on the node") != NULL);
  beam = steel_cantilever(&root_at);
  beam.area = 0.0;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  printf("expected: %s\n", fs_last_error());
  CHECK(strstr(fs_last_error(), "section area") != NULL);
  beam = steel_cantilever(&root_at);
  beam.orientation[0] = 2.0; /* the section's y along the beam */
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "lies along the beam's x") != NULL);
  beam = steel_cantilever(&root_at);
  beam.damping_ratio = 1.0;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(fs_last_error(), "damping_ratio 1 must be in [0, 1)") != NULL);
  beam = steel_cantilever(&root_at);
  CHECK(fs_save_beam_modal_body(&beam, "/nonexistent/dir/beam.fsmodal") == FS_ERROR_IO);
  printf("expected: %s\n", fs_last_error());
}

/* An interface position a micrometre off a node (0.5 m; elements of 50 mm) is that node: no
 * sliver of an element, which would be about 1e9 times stiffer in bending than its neighbours. */
static void check_snapping(const char* path) {
  const double at[2] = {0.0, 0.500001}, point[3] = {0.500001, 0.0, 0.0};
  fs_beam_body beam = steel_cantilever(at);
  fs_model_builder* b;
  double distance = -1.0;
  int body;
  beam.interface_count = 2;
  CHECK(fs_save_beam_modal_body(&beam, path) == FS_OK);
  b = fs_builder_create();
  body = fs_builder_add_flexible_body(b, "cantilever", path, 6 + 6);
  CHECK(fs_builder_nearest_node(b, body, point, &distance) == 10);
  CHECK(fabs(distance - 1e-6) < 1e-9);
  fs_builder_destroy(b);
}

/* Keeping 8 of the 12 modes of a beam with two interface nodes loses flexibility at them (the
 * static constraint modes are among the highest): finalize succeeds with a warning that names
 * the body (Model::warnings; tests/model/test_model_warnings.cpp checks what it warns of). */
static void check_warnings(const char* path) {
  const int counts[2] = {12, 8};
  int k;
  for (k = 0; k < 2; ++k) {
    fs_model_builder* b = fs_builder_create();
    fs_model* m = NULL;
    fs_builder_add_flexible_body(b, "cantilever", path, counts[k]);
    CHECK(fs_builder_finalize(b, &m) == FS_OK);
    fs_builder_destroy(b);
    if (!m) {
      ++failures;
      continue;
    }
    CHECK(fs_model_warning_count(m) == (k == 0 ? 0 : 1));
    if (k == 1 && fs_model_warning(m, 0)) {
      printf("warning: %s\n", fs_model_warning(m, 0));
      CHECK(strstr(fs_model_warning(m, 0), "body 'cantilever': its lowest 8 of") != NULL);
    }
    CHECK(fs_model_warning(m, fs_model_warning_count(m)) == NULL);
    fs_model_destroy(m);
  }
  CHECK(fs_model_warning_count(NULL) == -1);
}

int main(int argc, char** argv) {
  char path[4096];
  if (argc != 2 || strlen(argv[1]) > sizeof path - 32) {
    fprintf(stderr, "usage: %s <output dir>\n", argv[0]);
    return 2;
  }
  snprintf(path, sizeof path, "%s/cantilever.fsmodal", argv[1]);
  check_frequencies(path);
  check_snapping(path);
  check_warnings(path);
  check_errors(path);
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
