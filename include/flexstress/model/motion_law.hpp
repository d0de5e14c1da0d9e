// Motion laws as values: what a driver prescribes, s(t) with its rate and acceleration. One type
// for every kind, so a model stores laws in a plain array, a Data swaps them at run time and the
// C interface can describe them: a polynomial, a table (a clamped cubic spline), a C-compatible
// callback with user data, or an input set from outside before each step.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

#include "flexstress/dynamics/motion_laws.hpp"
#include "flexstress/model/handles.hpp"

namespace flexstress {

/// A prescribed motion computed by the caller: writes value, rate and acceleration at time t to
/// out[0..2]. Called inside the step: it must not throw, and should not allocate.
using MotionCallback = void (*)(double t, double* out, void* user);

enum class MotionLawKind : std::uint8_t { polynomial, table, callback, input };

template <class Scalar>
struct MotionLaw {
  MotionLawKind kind = MotionLawKind::polynomial;
  PolynomialLaw<Scalar> polynomial{};
  TableLaw<Scalar> table{};
  MotionCallback callback = nullptr;
  void* user = nullptr;
  InputId input{};

  /// s(t) = s0 + v t + a t^2 / 2.
  static MotionLaw constant_acceleration(Scalar s0, Scalar v = Scalar(0), Scalar a = Scalar(0)) {
    MotionLaw law;
    law.polynomial = {s0, v, a};
    return law;
  }
  /// A table law (TableLaw::create checks its rows).
  static MotionLaw from_table(TableLaw<Scalar> t) {
    MotionLaw law;
    law.kind = MotionLawKind::table;
    law.table = std::move(t);
    return law;
  }
  static MotionLaw from_callback(MotionCallback f, void* user_data) {
    MotionLaw law;
    law.kind = MotionLawKind::callback;
    law.callback = f;
    law.user = user_data;
    return law;
  }
  /// The value, rate and acceleration last given to set_input for `id`.
  static MotionLaw from_input(InputId id) {
    MotionLaw law;
    law.kind = MotionLawKind::input;
    law.input = id;
    return law;
  }

  /// Why the law cannot be used, or nullptr.
  const char* check(int num_inputs) const {
    switch (kind) {
      case MotionLawKind::polynomial:
        if (!std::isfinite(double(polynomial.s0)) || !std::isfinite(double(polynomial.v)) ||
            !std::isfinite(double(polynomial.a)))
          return "a polynomial law's coefficients must be finite";
        return nullptr;
      case MotionLawKind::table: return nullptr;  // TableLaw::create checked its rows
      case MotionLawKind::callback:
        return callback == nullptr ? "a callback law needs a function" : nullptr;
      case MotionLawKind::input:
        return input.index < 0 || input.index >= num_inputs ? "an input law names no input of "
                                                              "the model"
                                                            : nullptr;
    }
    return "unknown law kind";
  }

  /// Why steps of size h cannot follow the law, naming its rows, or an empty string (setup
  /// time; see TableLaw::row_too_fast). A prescribed motion that jumps between two close
  /// rows would otherwise end the first step that meets it in a non-finite state.
  std::string check_step(Scalar h) const {
    if (kind != MotionLawKind::table) return std::string();
    const std::size_t row = table.row_too_fast(static_cast<double>(h));
    if (row == 0) return std::string();
    const auto& t = table.times();
    const auto& s = table.values();
    const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
    std::ostringstream out;
    out << "its table changes by " << s[row] - s[row - 1] << " between rows " << row << " and "
        << row + 1 << " (" << t[row] - t[row - 1] << " s apart), faster than steps of "
        << static_cast<double>(h) << " s can follow: more than its whole range (" << *hi - *lo
        << ") within one step";
    return out.str();
  }

  /// s(t); `inputs` holds the current input values (value, rate, acceleration) by InputId.
  MotionValue<Scalar> operator()(Scalar t, const MotionValue<Scalar>* inputs) const {
    switch (kind) {
      case MotionLawKind::polynomial: return polynomial(t);
      case MotionLawKind::table: return table(t);
      case MotionLawKind::callback: {
        double out[3] = {0.0, 0.0, 0.0};
        callback(static_cast<double>(t), out, user);
        return {Scalar(out[0]), Scalar(out[1]), Scalar(out[2])};
      }
      case MotionLawKind::input: return inputs[input.index];
    }
    return {};
  }
};

}  // namespace flexstress
