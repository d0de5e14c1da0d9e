/* flexstress's runtime model behind a C interface (C99, and C++): for programs written in C
 * or in any language that calls C. Build a model with a builder, finalize it, make a data for
 * it, then initialize and step; read bodies, markers, joints and energies by handle.
 *
 *   fs_model_builder* b = fs_builder_create();
 *   int beam = fs_builder_add_flexible_body(b, "beam", "beam.fsmodal", 16);
 *   int pivot = fs_builder_add_marker(b, "pivot", FS_GROUND, -1, NULL, NULL);
 *   int root = fs_builder_add_marker(b, "root", beam, 0, NULL, NULL);
 *   fs_builder_add_joint(b, "hinge", FS_JOINT_REVOLUTE, pivot, root);
 *   fs_model* m = NULL;
 *   if (fs_builder_finalize(b, &m) != FS_OK) puts(fs_builder_error(b));
 *   fs_data* d = fs_data_create(m);
 *   fs_initialize(d);
 *   while (fs_step(d) == FS_STEP_OK) ...
 *   fs_data_destroy(d); fs_model_destroy(m); fs_builder_destroy(b);
 *
 * Errors. Functions return an fs_status (FS_OK = 0), a handle (>= 0; FS_INVALID_HANDLE on
 * failure) or a pointer (NULL on failure). Builder mistakes (a node the body lacks, a bad law)
 * are recorded with the part's name and returned by fs_builder_finalize; read the text with
 * fs_builder_error. Failures of a data (initialize, equilibrium, a step) are read with
 * fs_data_error; any failing call also sets fs_last_error (per thread). A null or foreign
 * handle is an error code, never a crash; no C++ exception crosses this interface.
 *
 * Threads. A finalized fs_model is immutable: any number of threads may share it, each with its
 * own fs_data. An fs_model_builder and an fs_data are not thread-safe: use each from one
 * thread at a time. A data keeps its model alive (destroying the model first is allowed).
 *
 * Units are SI. Frames: positions global; 3x3 matrices are 9 doubles, column-major (columns:
 * axes); orientations are Euler parameters (e0, e1, e2, e3), scalar first. */
#ifndef FLEXSTRESS_H
#define FLEXSTRESS_H

#include <stddef.h>
#include "flexstress/version.hpp"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fs_model_builder fs_model_builder;
typedef struct fs_model fs_model;
typedef struct fs_data fs_data;

typedef enum fs_status {
  FS_OK = 0,
  FS_ERROR_NULL = 1,           /* a required pointer argument was null */
  FS_ERROR_INVALID_HANDLE = 2, /* a body, marker, joint or input handle is not of the model */
  FS_ERROR_INVALID_ARGUMENT = 3,
  FS_ERROR_INVALID_MESH = 4, /* e.g. a marker on a node the body lacks */
  FS_ERROR_DEGENERATE_ELEMENT = 5,
  FS_ERROR_SINGULAR_MATRIX = 6,
  FS_ERROR_NOT_CONVERGED = 7,
  FS_ERROR_SIZE_MISMATCH = 8, /* e.g. more modes asked than the data has */
  FS_ERROR_IO = 9,
  FS_ERROR_BAD_FILE_FORMAT = 10,
  FS_ERROR_BUFFER_TOO_SMALL = 11, /* a result was truncated to the caller's buffer */
  FS_ERROR_OUT_OF_MEMORY = 12,
  FS_ERROR_INTERNAL = 13 /* an unexpected C++ exception, caught */
} fs_status;

/* What fs_step returns (flexstress::StepStatus); after a failure the state is the last good
 * one and fs_data_error says why. */
typedef enum fs_step_status {
  FS_STEP_OK = 0,
  FS_STEP_NEWTON_NOT_CONVERGED = 1,
  FS_STEP_CONSTRAINT_VIOLATION = 2,
  FS_STEP_NON_FINITE_STATE = 3,
  FS_STEP_ABOVE_STABILITY_LIMIT = 4,
  FS_STEP_INVALID_INPUT = 5,
  FS_STEP_CAPACITY_EXCEEDED = 6,
  FS_STEP_TOO_LARGE = 7,      /* the corrector diverged: the step is too large for the motion */
  FS_STEP_BUDGET_REACHED = 8, /* kept at the Newton budget (accept_at_iteration_limit) */
  FS_STEP_ERROR = -1          /* null or foreign data, or an internal error */
} fs_step_status;

typedef enum fs_joint_kind {
  FS_JOINT_SPHERICAL = 0,        /* 3 equations: origins coincide */
  FS_JOINT_REVOLUTE = 1,         /* 5: turns about the common z axis */
  FS_JOINT_UNIVERSAL = 2,        /* 4 */
  FS_JOINT_CYLINDRICAL = 3,      /* 4: turns about and slides along z */
  FS_JOINT_PRISMATIC = 4,        /* 5: slides along z */
  FS_JOINT_FIXED = 5,            /* 6 */
  FS_JOINT_DISTANCE = 6,         /* 1: fs_builder_add_distance */
  FS_JOINT_PRISMATIC_DRIVER = 7, /* 1: (r_j - r_i) . z_i = s(t); fs_builder_add_driver */
  FS_JOINT_REVOLUTE_DRIVER = 8   /* 1: angle x_i -> x_j about z_i = s(t); fs_builder_add_driver */
} fs_joint_kind;

#define FS_GROUND (-1)         /* the ground body (fixed); its markers take node -1 */
#define FS_INVALID_HANDLE (-2) /* what a handle-returning function returns on failure */

/* A prescribed motion s(t): value, rate and acceleration written to out[0..2]. Called inside
 * the step, from the thread stepping the data: it must not longjmp out, and should be fast. */
typedef void (*fs_motion_callback)(double t, double out[3], void* user);

typedef enum fs_law_kind {
  FS_LAW_POLYNOMIAL = 0, /* s = c[0] + c[1] t + c[2] t^2 / 2 */
  FS_LAW_TABLE = 1,      /* clamped cubic spline through rows (t, s), t increasing */
  FS_LAW_CALLBACK = 2,
  FS_LAW_INPUT = 3, /* set by fs_set_input before each step, for the step's end (t + step) */
  FS_LAW_REST_TO_REST = 4 /* rows (t, s): stops at every row, the quintic between two (0.3) */
} fs_law_kind;

/* A motion law; make one with the fs_law_* functions. Tables are copied when the law is used
 * (fs_builder_add_driver, fs_set_law): the rows need not outlive that call. */
typedef struct fs_motion_law {
  int kind; /* fs_law_kind */
  double coefficients[3];
  const double* table; /* rows x 2 doubles: t0, s0, t1, s1, ... */
  int table_rows;
  fs_motion_callback callback;
  void* user;
  int input;
} fs_motion_law;

fs_motion_law fs_law_polynomial(double s0, double v, double a);
/* A clamped cubic spline through (t, s) rows, at rest at the first and last and held outside;
 * two rows (t0, s0), (t1, s1) make the smooth step s0 + (s1 - s0)(3u^2 - 2u^3),
 * u = (t - t0) / (t1 - t0). */
fs_motion_law fs_law_table(const double* rows, int num_rows);
/* Point to point through (t, s) rows: the motion stops at every row and between two follows
 * s_i + (s_i+1 - s_i)(10u^3 - 15u^4 + 6u^5), whose rate and acceleration vanish at both rows (no
 * jump in acceleration at a start or stop, unlike the spline's; no overshoot between rows). */
fs_motion_law fs_law_rest_to_rest(const double* rows, int num_rows);
fs_motion_law fs_law_callback(fs_motion_callback callback, void* user);
fs_motion_law fs_law_input(int input);

/* ---- version ----------------------------------------------------------------------------- */
/* The library's version; FLEXSTRESS_VERSION (flexstress/version.hpp) is the header's. Structures
 * such as fs_settings may grow between minor versions: a program built against another
 * version's header must be rebuilt (check fs_version_number() == FLEXSTRESS_VERSION). */
const char* fs_version(void); /* "0.3.0" */
int fs_version_number(void);  /* major * 10000 + minor * 100 + patch */
/* The message of this thread's last failing call, or "" if none failed (a successful call
 * leaves it as it was). The text is valid until the next fs_ call of this thread: copy it before
 * calling another, also within one expression (C does not order a call's arguments). */
const char* fs_last_error(void);
const char* fs_status_string(int status);
const char* fs_step_status_string(int step_status);

/* ---- builder ----------------------------------------------------------------------------- */
fs_model_builder* fs_builder_create(void); /* NULL only if out of memory */
void fs_builder_destroy(fs_model_builder* b);

/* Return the handle (>= 0), or FS_INVALID_HANDLE when the call's own arguments are wrong (a
 * null builder or name, an unknown kind, a bad law, a node the modal body file lacks; what
 * fs_last_error then says). Mistakes only the whole model shows (a marker on a node its body
 * lacks, a joint between two markers of one body, a handle that is not the model's) still
 * return a handle. Either way fs_builder_finalize fails with the first mistake, naming it. */
int fs_builder_add_rigid_body(fs_model_builder* b, const char* name, double mass,
                              const double center_of_mass[3], const double inertia_about_com[9]);
/* A flexible body from a modal body file (flexstress/reduction/modal_body_io.hpp), keeping its
 * lowest `modes` modes (10 and 16 run kernels compiled for that count). A file that cannot be
 * read gives FS_INVALID_HANDLE, and finalize then fails with the file's error. */
int fs_builder_add_flexible_body(fs_model_builder* b, const char* name, const char* path,
                                 int modes);

/* A straight uniform beam as a modal body file (0.3): along the body's x from 0 to length, in
 * `elements` equal Euler-Bernoulli elements, nodes added at the interface positions (where
 * joints attach, or at the node within a thousandth of an element of one;
 * fs_builder_nearest_node finds a node by position), reduced by Craig-Bampton
 * with six-DOF interface nodes there and fixed_interface_modes fixed-interface modes:
 * 6 (interface_count - 1) + fixed_interface_modes modes in all. Keep all of them in
 * fs_builder_add_flexible_body (docs/reduction.md, "Keeping fewer modes than the basis"). */
typedef struct fs_beam_body {
  double length; /* m */
  int elements;
  double youngs_modulus, poissons_ratio, density; /* Pa, -, kg/m^3 */
  /* The section: m^2, and m^4 about its local y and z axes (iz resists bending in the x-y
   * plane), St. Venant torsion constant (m^4). */
  double area, iy, iz, torsion_constant;
  double orientation[3]; /* the section's local y in the body frame; zeros: the body's y */
  const double* interface_at; /* distances from x = 0 (m), interface_count of them */
  int interface_count;
  int fixed_interface_modes;
  double damping_ratio; /* modal damping of every mode */
} fs_beam_body;
/* Reduces the beam and saves it at path. Errors name the field (a length, a section property,
 * an interface position off the beam) or the file. */
int fs_save_beam_modal_body(const fs_beam_body* beam, const char* path);
int fs_builder_set_damping_ratio(fs_model_builder* b, int body, double zeta);
/* Geometric stiffening of a flexible body by its own inertial and gravity loads (what a
 * fast-spinning blade needs: without it, a blade spinning faster than its lowest in-plane
 * frequency bends away), from a geometric stiffness file saved for the body's modal body file
 * (flexstress/reduction/modal_geometric_stiffness_io.hpp). Returns FS_OK, or the file's error
 * (FS_ERROR_IO, FS_ERROR_BAD_FILE_FORMAT: also a file saved for another body), which finalize
 * then reports; a rigid body is an error at finalize. */
int fs_builder_add_geometric_stiffening(fs_model_builder* b, int body, const char* path);
/* Where a body's frame starts; orientation may be NULL (identity). */
int fs_builder_set_initial_pose(fs_model_builder* b, int body, const double position[3],
                                const double orientation[4]);
/* A marker on `body` (FS_GROUND for the ground) at `node` (-1: the body frame), with a rigid
 * offset (NULL: zero) and axes (NULL: identity; columns: the marker's axes in the body frame). */
int fs_builder_add_marker(fs_model_builder* b, const char* name, int body, long node,
                          const double offset[3], const double axes[9]);
/* A joint between markers i and j on different bodies; not the drivers or distance. */
int fs_builder_add_joint(fs_model_builder* b, const char* name, int kind, int marker_i,
                         int marker_j);
int fs_builder_add_distance(fs_model_builder* b, const char* name, int marker_i, int marker_j,
                            double length);
/* kind: FS_JOINT_PRISMATIC_DRIVER or FS_JOINT_REVOLUTE_DRIVER. */
int fs_builder_add_driver(fs_model_builder* b, const char* name, int kind, int marker_i,
                          int marker_j, const fs_motion_law* law);
/* Tension f = stiffness (L - rest_length) + damping L_dot + preload between marker origins. */
int fs_builder_add_spring_damper(fs_model_builder* b, const char* name, int marker_i, int marker_j,
                                 double stiffness, double damping, double rest_length,
                                 double preload);
/* A force and moment at a marker on a body, computed each evaluation by the callback from the
 * time and the marker's global position and velocity; it writes force[3] and moment[3]
 * (global, zeroed before the call). Called from the thread stepping the data, inside the
 * step: it must not block or longjmp. */
typedef void (*fs_point_load_callback)(double t, const double* position, const double* velocity,
                                       double* force, double* moment, void* user);
int fs_builder_add_point_load(fs_model_builder* b, const char* name, int marker,
                              fs_point_load_callback callback, void* user);
/* Stress outputs of a flexible body: y = F p with F given row-major (num_outputs x the body's
 * modes, e.g. a sub-model's fused rows). Returns the first output's handle; the others follow
 * it. */
int fs_builder_add_stress_outputs(fs_model_builder* b, const char* name, int body,
                                  const double* rows, int num_outputs, int num_modes);
/* The node of a flexible body's modal body file nearest to `point` (body frame, m), for markers
 * and fibre stresses; its distance in *distance if not NULL. -1 (fs_last_error says why) for a
 * body that is not flexible or a null point. */
long fs_builder_nearest_node(const fs_model_builder* b, int body, const double point[3],
                             double* distance);
/* A beam's axial stress as one output of a flexible body: sigma_xx at the fibre (y, z) of the
 * section (m, along its local y and z axes) at xi (0 at node_a, 1 at node_b) of the
 * Euler-Bernoulli beam between two nodes of the body's modal body file, E (u' - y v'' - z w'')
 * from their mode shapes (displacements and rotations). orientation: the section's local y axis
 * in the body frame (NULL: the body frame's y, or its z for a beam along y). node_a and node_b must be the
 * two nodes of one beam element: the file does not record elements, and between other nodes the
 * result is the stress of a single cubic through them, not the beam's. Errors name the node (one
 * the file does not have, or without rotations) or the value (xi outside [0, 1], E not
 * positive). Returns the output's handle. */
int fs_builder_add_beam_fibre_stress(fs_model_builder* b, const char* name, int body, long node_a,
                                     long node_b, const double orientation[3],
                                     double youngs_modulus, double xi, double y, double z);
/* A damage meter on an output: streaming rainflow on 128 classes over [lower, upper] of
 * scale * output (e.g. 1e-6 for Pa to MPa), damage by the IIW curve of class fat (MPa at 2e6
 * cycles, slope 3, Haibach slope 5 beyond the knee at 1e7). Ranges count at their classes'
 * centres: fit the window to the stress history (a window ten times too wide rounds a range to
 * a few classes, and damage goes with the range to the power 3 to 5; docs/fatigue.md). */
int fs_builder_add_damage_meter(fs_model_builder* b, const char* name, int output, double fat,
                                double lower, double upper, double scale);
/* S-N curves of a damage meter (category: MPa at 2e6 cycles). */
typedef enum fs_sn_curve {
  FS_SN_IIW_NORMAL_HAIBACH = 0,  /* IIW normal stress: m = 3 to 1e7 cycles, then m = 5 */
  FS_SN_IIW_NORMAL_SLOPE_22 = 1, /* IIW normal stress: m = 3 to 1e7 cycles, then m = 22 */
  FS_SN_IIW_SHEAR_HAIBACH = 2,   /* IIW shear stress: m = 5 to 1e8 cycles, then m = 9 */
  FS_SN_IIW_SHEAR_SLOPE_22 = 3,  /* IIW shear stress: m = 5 to 1e8 cycles, then m = 22 */
  FS_SN_EN1993_NORMAL = 4,       /* EN 1993-1-9: m = 3 to 5e6, m = 5 to 1e8, cut-off below */
  FS_SN_EN1993_SHEAR = 5         /* EN 1993-1-9: m = 5 to 1e8, cut-off below */
} fs_sn_curve;
/* A damage meter as fs_builder_add_damage_meter (128 classes over [lower, upper] of
 * scale * output) with the S-N curve chosen (fs_sn_curve) for its category. */
int fs_builder_add_damage_meter_curve(fs_model_builder* b, const char* name, int output, int curve,
                                      double category, double lower, double upper, double scale);
int fs_builder_add_input(fs_model_builder* b, const char* name);
int fs_builder_set_gravity(fs_model_builder* b, const double gravity[3]);
/* Integrator settings every data starts with: step (s; default 1e-3), spectral radius at
 * infinity in [0, 1] (1: no numerical damping; default 0.8), Newton iterations per step
 * (default 30), and an absolute Newton tolerance (an acceleration, m/s^2) in place of the
 * default: the larger of 1e-5 and 1e-6 of the larger of |gravity| and the largest acceleration
 * at fs_initialize. A step, iteration count or tolerance <= 0, or a negative spectral radius,
 * keeps that default. */
int fs_builder_set_integrator(fs_model_builder* b, double step, double spectral_radius,
                              int max_iterations, double tolerance);

/* Checks and builds the model into *model (NULL on failure). The error names the first part
 * that is wrong. The builder stays usable (and must still be destroyed). */
int fs_builder_finalize(fs_model_builder* b, fs_model** model);
/* The builder's last error ("" if none); valid until the next call on that builder. */
const char* fs_builder_error(const fs_model_builder* b);
/* Copies it (terminated, truncated to size); returns its full length. */
size_t fs_builder_copy_error(const fs_model_builder* b, char* buffer, size_t size);

/* ---- model ------------------------------------------------------------------------------- */
void fs_model_destroy(fs_model* m);
/* Sizes; -1 for a null model (or a bad body for fs_model_body_modes). */
int fs_model_num_velocities(const fs_model* m);
int fs_model_num_constraints(const fs_model* m);
int fs_model_num_bodies(const fs_model* m);
int fs_model_num_markers(const fs_model* m);
int fs_model_num_joints(const fs_model* m);
int fs_model_num_inputs(const fs_model* m);
int fs_model_body_modes(const fs_model* m, int body);
/* What finalize found legal but likely wrong (0.4): a sentence each naming the part (a flexible
 * body keeping too few of its basis's modes to take a joint's static load). The count (-1 for
 * a null model), and warning `index` (NULL if there is none such), valid while the model is. */
int fs_model_warning_count(const fs_model* m);
const char* fs_model_warning(const fs_model* m, int index);

/* ---- data -------------------------------------------------------------------------------- */
fs_data* fs_data_create(const fs_model* m); /* at the initial poses, at rest; NULL on failure */
void fs_data_destroy(fs_data* d);
int fs_data_reset(fs_data* d);
/* Why the last initialize, equilibrium or step failed; "" if none. Valid until the next call
 * on that data. */
const char* fs_data_error(const fs_data* d);

/* Consistent initial conditions (assembles the joints, projects velocities). */
int fs_initialize(fs_data* d);
/* Moves the data to static equilibrium (velocities zero) at its time. */
int fs_solve_static_equilibrium(fs_data* d);
/* One step; returns an fs_step_status. Allocates nothing. Initializes the data first if it
 * was not (or a runtime change asks for it), as fs_initialize would. */
int fs_step(fs_data* d);
int fs_set_step_size(fs_data* d, double step);

/* A data's integrator settings (flexstress::ImplicitSettings, whose comments say what each
 * does): read them with fs_settings_get, change fields, write them back with fs_settings_set,
 * which checks them (FS_ERROR_INVALID_ARGUMENT with a message naming the field) and keeps the
 * state; the next step uses them. */
typedef struct fs_settings {
  double step;                            /* s */
  double spectral_radius;                 /* at infinity, in [0, 1]; 1: no numerical damping */
  int max_iterations;                     /* Newton iterations per step (or piece) */
  int accept_at_iteration_limit;          /* 1: a step at the limit is kept (a real-time budget) */
  double acceleration_tolerance;          /* absolute part of the Newton tolerance, m/s^2 */
  double relative_acceleration_tolerance; /* times the acceleration scale */
  double local_error_tolerance;           /* m, rad; 0: no local error control */
  int max_step_halvings;                  /* a failing step is retried in down to 2^-n pieces */
  double velocity_drift_limit;            /* projects drifting velocities; 0: never */
  int project_velocities;                 /* 1: after every step */
  double newton_error_estimate_fraction;  /* in [0, 1]: stop on the estimated error; 0: off */
  int keep_stalled_steps; /* 1 (default): a step whose Newton stalled at the limit within the
                           * joints' tolerance (a singular configuration) is kept */
  int linearized_multipliers; /* an fs_linearized_multipliers: where each correction also
                               * updates the multipliers on the linearized constraints */
  int refactorize_pieces;     /* 1 (default): a split step's pieces factorize at every correction */
  double piece_newton_tolerance_fraction; /* in [0, 1]: a piece's corrections stop at this
                                           * fraction of local_error_tolerance; 0 (default): off */
} fs_settings;
typedef enum fs_linearized_multipliers {
  FS_LINEARIZED_MULTIPLIERS_OFF = 0,
  FS_LINEARIZED_MULTIPLIERS_PIECES = 1, /* default: in the pieces of a split step */
  FS_LINEARIZED_MULTIPLIERS_ALWAYS = 2
} fs_linearized_multipliers;
int fs_settings_get(const fs_data* d, fs_settings* out);
int fs_settings_set(fs_data* d, const fs_settings* settings);
double fs_time(const fs_data* d); /* s; NaN for a null data */

/* Runtime changes: an input's value for the next steps, a joint switched on or off (the next
 * step restarts from the state, projecting it), a driver's law (if its value or rate differs
 * from the old law's at the current time, call fs_initialize before stepping). */
/* An input's value, rate and acceleration for the end of the next step (fs_time + step; before
 * fs_initialize, for fs_time). Within a step split in pieces it follows the quintic through its
 * values, rates and accelerations at the step's two ends. */
int fs_set_input(fs_data* d, int input, double value, double rate, double acceleration);
int fs_set_joint_active(fs_data* d, int joint, int active);
int fs_set_law(fs_data* d, int joint, const fs_motion_law* law);
/* Moves the joint's marker j onto marker i (origin and axes) in this data, so that switching
 * the joint on holds the bodies where they are. */
int fs_anchor_joint(fs_data* d, int joint);
/* A body's velocity: its frame's linear velocity (global) and angular velocity (body axes). */
int fs_set_body_velocity(fs_data* d, int body, const double velocity[3],
                         const double omega_body[3]);

/* ---- checkpoints ------------------------------------------------------------------------- */
/* The whole data as bytes (state, joint switches, anchors, laws, inputs, integrator history,
 * outputs and meters) with a description of its model. With buffer NULL only *size is set;
 * FS_ERROR_BUFFER_TOO_SMALL if capacity is short (then *size says what is needed). */
int fs_checkpoint_save(const fs_data* d, unsigned char* buffer, size_t capacity, size_t* size);
/* Restores a checkpoint into d (a data of the same model: the error names the part that
 * differs otherwise). A restored run continues bit for bit; on error d is unchanged. */
int fs_checkpoint_restore(fs_data* d, const unsigned char* buffer, size_t size);

/* ---- read-outs --------------------------------------------------------------------------- */
int fs_body_position(const fs_data* d, int body, double position[3]);
int fs_body_orientation(const fs_data* d, int body, double euler_parameters[4]);
int fs_body_velocity(const fs_data* d, int body, double velocity[3]);
int fs_body_angular_velocity(const fs_data* d, int body, double omega_body[3]);
/* A marker's frame at the current state: origin (global) and axes (columns, global). */
int fs_marker_frame(const fs_data* d, int marker, double origin[3], double axes[9]);
/* Force and moment the joint applies to marker j's body, at marker j's origin, in marker i's
 * axes. Valid after fs_initialize, a step or an equilibrium. */
int fs_joint_reaction(const fs_data* d, int joint, double force[3], double moment[3]);
/* What a driver exerts along its coordinate: the force (prismatic, N) pushing marker j along
 * marker i's +z, or the moment (revolute, N m) turning it about that axis.
 * FS_ERROR_INVALID_ARGUMENT for a joint that is not a driver. */
int fs_driver_effort(const fs_data* d, int joint, double* effort);
/* A revolute joint's (or revolute driver's) angle from x_i to x_j about z_i, in (-pi, pi], or a
 * prismatic joint's (or prismatic driver's) stroke along z_i (m), and its rate, from the joint's
 * markers as they are. FS_ERROR_INVALID_ARGUMENT for other kinds (no single coordinate). */
int fs_joint_coordinate(const fs_data* d, int joint, double* value, double* rate);

typedef struct fs_energy {
  double kinetic, gravity, elastic, springs, total;
} fs_energy;
int fs_energy_compute(fs_data* d, fs_energy* out);
double fs_constraint_violation(const fs_data* d); /* largest |Phi|; NaN for a null data */

typedef struct fs_statistics {
  long long steps, iterations, factorizations;
  long long over_budget;       /* steps kept at the iteration limit */
  long long drift_projections; /* steps whose drifting velocities were projected */
  long long split_steps;       /* steps retried in pieces, and the pieces they took */
  long long substeps;
  double largest_error_estimate;   /* the largest local error estimate of a step (m, rad) */
  long long above_error_tolerance; /* smallest pieces kept above the local error tolerance */
  int last_iterations;
  double last_correction; /* the last step's final correction over its tolerance (<= 1: met) */
  long long stalled_steps; /* of over_budget, kept with Newton stalled (keep_stalled_steps) */
  /* Corrections undone because the residual rose (the reused matrix had gone stale); a step
   * whose budget ends on one keeps the state before it (0.3) */
  long long undone_corrections;
  int last_factorizations; /* factorizations of the last step (0.3) */
} fs_statistics;
int fs_statistics_get(const fs_data* d, fs_statistics* out);

/* A flexible body's modal coordinates: min(capacity, modes) of them to p, the count to *count
 * (if not NULL); FS_ERROR_BUFFER_TOO_SMALL if some did not fit. */
int fs_modal_coordinates(const fs_data* d, int body, double* p, int capacity, int* count);
/* Evaluates every output of the data at its state and feeds the damage meters (once per
 * step). Returns an fs_step_status. Allocates nothing. */
int fs_evaluate_outputs(fs_data* d);
double fs_output_value(const fs_data* d, int output); /* NaN for a bad handle */
/* Damage so far of a meter, its open cycles closed as a repeating history. NaN if bad. */
double fs_meter_damage(const fs_data* d, int meter);
/* Samples a meter refused so far (outside its class window, or not finite), which its damage
 * leaves out: above zero, the window is too narrow for the run. -1 if bad. */
long long fs_meter_refused_samples(const fs_data* d, int meter);

/* Natural frequencies (Hz, ascending) of small vibrations about the data's state, which must be
 * an equilibrium (fs_solve_static_equilibrium). Writes min(capacity, count) of them to hz and
 * the full count to *count (if not NULL); FS_ERROR_BUFFER_TOO_SMALL if some did not fit. */
int fs_linearized_frequencies(fs_data* d, double* hz, int capacity, int* count);
/* The same, and (if static_residual is not NULL) how far the state is from the equilibrium it
 * is linearized about: the largest entry of -Q + B^T lambda there (N, N m and modal forces), 0
 * to round-off after fs_solve_static_equilibrium. On an error before the linearization, *count
 * is 0 and *static_residual NaN. */
int fs_linearize(fs_data* d, double* hz, int capacity, int* count, double* static_residual);

#ifdef __cplusplus
}
#endif

#endif /* FLEXSTRESS_H */
