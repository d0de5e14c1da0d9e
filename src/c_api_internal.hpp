// The C interface's shared parts (src/c_api_model.cpp, src/c_api_data.cpp): the opaque
// types behind flexstress/flexstress.h and the helpers every entry point uses to check its
// arguments and to turn errors and exceptions into status codes.
#pragma once

#include "flexstress/flexstress.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "flexstress/fatigue/sn_curve.hpp"
#include "flexstress/model/all.hpp"
#include "flexstress/reduction/modal_body_io.hpp"
#include "flexstress/reduction/modal_geometric_stiffness_io.hpp"
#include "flexstress/stress/beam_fibre_stress_modes.hpp"
#include "flexstress/version.hpp"

namespace fsx = flexstress;

struct fs_model_builder {
  fsx::ModelBuilder<double> builder;
  // The modal body data of each flexible body by handle, its name and mode count: rows of
  // stress outputs are made from it (fs_builder_add_beam_fibre_stress), and a geometric
  // stiffness file is checked against it (fs_builder_add_geometric_stiffening).
  struct FlexibleBody {
    int body = -1;
    std::string name;
    int modes = 0;
    std::shared_ptr<const fsx::reduction::ModalBodyData> data;
  };
  std::vector<FlexibleBody> flexible_bodies;
  // Mistakes the C layer finds (a file that cannot be read), reported by finalize before the
  // builder's own.
  fsx::Error first_error;
  bool failed = false;
  std::string error;  // what fs_builder_error returns
};

struct fs_model {
  std::shared_ptr<const fsx::Model<double>> model;
};

struct fs_data {
  std::shared_ptr<const fsx::Model<double>> model;  // keeps the model alive
  fsx::Data<double> data;
  std::string error;
};

namespace flexstress_c_api {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline thread_local std::string t_last_error;

inline int fail(int status, std::string message) {
  try {
    t_last_error = std::move(message);
  } catch (...) {
    t_last_error.clear();  // out of memory: the code still says what happened
  }
  return status;
}

inline int status_of(fsx::ErrorCode code) {
  switch (code) {
    case fsx::ErrorCode::invalid_argument: return FS_ERROR_INVALID_ARGUMENT;
    case fsx::ErrorCode::invalid_mesh: return FS_ERROR_INVALID_MESH;
    case fsx::ErrorCode::degenerate_element: return FS_ERROR_DEGENERATE_ELEMENT;
    case fsx::ErrorCode::singular_matrix: return FS_ERROR_SINGULAR_MATRIX;
    case fsx::ErrorCode::not_converged: return FS_ERROR_NOT_CONVERGED;
    case fsx::ErrorCode::size_mismatch: return FS_ERROR_SIZE_MISMATCH;
    case fsx::ErrorCode::io_error: return FS_ERROR_IO;
    case fsx::ErrorCode::bad_file_format: return FS_ERROR_BAD_FILE_FORMAT;
  }
  return FS_ERROR_INTERNAL;
}

// fail() from inside a catch handler: building the message may itself throw.
inline int fail_noexcept(int status, const char* where, const char* what) noexcept {
  try {
    t_last_error = std::string(where) + ": " + what;
  } catch (...) {
    t_last_error.clear();
  }
  return status;
}

// Runs f, turning any exception into a status (and a message).
template <class F>
inline int guarded(const char* where, F&& f) noexcept {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    return fail_noexcept(FS_ERROR_OUT_OF_MEMORY, where, "out of memory");
  } catch (const std::exception& e) {
    return fail_noexcept(FS_ERROR_INTERNAL, where, e.what());
  } catch (...) {
    return fail_noexcept(FS_ERROR_INTERNAL, where, "unknown exception");
  }
}

// The same for handle-returning functions: the status's message is kept, the handle is
// FS_INVALID_HANDLE.
template <class F>
inline int guarded_handle(const char* where, F&& f) noexcept {
  int handle = FS_INVALID_HANDLE;
  const int s = guarded(where, [&] {
    handle = f();
    return FS_OK;
  });
  return s == FS_OK ? handle : FS_INVALID_HANDLE;
}

inline int null_argument(const char* where) {
  return fail(FS_ERROR_NULL, std::string(where) + ": a required pointer is null");
}

inline int bad_handle(const char* where, const char* what, int handle) {
  return fail(FS_ERROR_INVALID_HANDLE,
              std::string(where) + ": no " + what + " with handle " + std::to_string(handle));
}

inline bool in_range(int handle, std::size_t size) {
  return handle >= 0 && static_cast<std::size_t>(handle) < size;
}

inline fsx::Vec3<double> vec3(const double* p) {
  return fsx::Vec3<double>(p[0], p[1], p[2]);
}
inline void put3(const fsx::Vec3<double>& v, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = v(k);
}

// A mistake the C layer finds while building (a file, a table), kept for finalize; the first
// one counts, as in ModelBuilder, while fs_last_error tells this call's own. Returns
// FS_INVALID_HANDLE.
inline int record(fs_model_builder* b, const fsx::Error& e, const std::string& part) {
  fsx::Error named = e;
  named.message = part + ": " + e.message;
  if (!b->failed) {
    b->failed = true;
    b->first_error = named;
  }
  b->error = b->first_error.what();
  fail(status_of(e.code), named.what());
  return FS_INVALID_HANDLE;
}

inline const fsx::Model<double>* model_of(const fs_model* m) {
  return m ? m->model.get() : nullptr;
}

inline int error_status(fs_data* d, const fsx::Error& e) {
  d->error = e.what();
  return fail(status_of(e.code), d->error);
}

// A C law as a C++ law; the error text names the problem (a bad table).
inline fsx::Result<fsx::MotionLaw<double>> to_law(const fs_motion_law& l) {
  using Law = fsx::MotionLaw<double>;
  switch (l.kind) {
    case FS_LAW_POLYNOMIAL:
      return Law::constant_acceleration(l.coefficients[0], l.coefficients[1], l.coefficients[2]);
    case FS_LAW_TABLE:
    case FS_LAW_REST_TO_REST: {
      if (l.table == nullptr || l.table_rows < 0)
        return fsx::make_error(fsx::ErrorCode::invalid_argument,
                               "table law: null rows or a negative row count");
      std::vector<double> t(static_cast<std::size_t>(l.table_rows)), s(t.size());
      for (std::size_t r = 0; r < t.size(); ++r) {
        t[r] = l.table[2 * r];
        s[r] = l.table[2 * r + 1];
      }
      auto table = fsx::TableLaw<double>::create(t, s,
                                                 l.kind == FS_LAW_TABLE
                                                     ? fsx::TableInterpolation::spline
                                                     : fsx::TableInterpolation::rest_to_rest);
      if (!table) return table.error();
      return Law::from_table(std::move(*table));
    }
    case FS_LAW_CALLBACK: return Law::from_callback(l.callback, l.user);
    case FS_LAW_INPUT: return Law::from_input(fsx::InputId{l.input});
    default: break;
  }
  return fsx::make_error(fsx::ErrorCode::invalid_argument, "unknown law kind ", l.kind);
}

}  // namespace flexstress_c_api
