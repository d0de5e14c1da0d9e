// Opt-in sparse shift-invert eigen solver on Spectra (Debian: libspectra-dev, header-only;
// Yixuan Qiu, https://spectralib.org): the lowest eigenpairs of K x = lambda M x by implicitly
// restarted Lanczos on (K - sigma M)^-1 M (Spectra::SymGEigsShiftSolver, GEigsMode::ShiftInvert;
// Ericsson & Ruhe, Math. Comp. 35 (1980) 1251-1268), for models too large for the dense path.
//
// NOT part of the umbrella header flexstress.hpp, and left out of the -fno-exceptions header
// check (tests/header_check.cmake): Spectra reports failures by throwing. This header catches
// every exception inside solve_eigen_spectra and returns a Result, so callers never see one;
// it still needs a translation unit compiled with exceptions and Spectra on the include path.
//
// Same interface and conventions as solve_eigen (eigen_solver.hpp): ascending eigenvalues,
// mass-normalized vectors (X^T M X = I), Rayleigh-quotient eigenvalues, a Sturm sequence check
// that no eigenvalue below the highest one returned was missed.
#pragma once

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/constraint_transform.hpp"
#include "flexstress/fe/eigen_solver.hpp"

namespace flexstress::fe {

namespace detail {

/// Spectra operator y = (K - sigma M)^-1 x with a sparse LDL^T (Spectra's documented
/// duck-typed OpType: Scalar, rows(), cols(), set_shift(), perform_op()). Both matrices must
/// outlive the operator. set_shift throws when K - sigma M is singular (Spectra's convention).
class SparseLdltShiftInvert {
 public:
  using Scalar = double;
  SparseLdltShiftInvert(const SparseMatrixd& k, const SparseMatrixd& m) : k_(k), m_(m) {}
  Index rows() const { return k_.rows(); }
  Index cols() const { return k_.cols(); }
  void set_shift(const double& sigma) {
    ldlt_.compute(SparseMatrixd(k_ - sigma * m_));
    if (ldlt_.info() != Eigen::Success)
      throw std::invalid_argument("K - sigma M could not be factorized (singular)");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const VectorXd> x(x_in, rows());
    Eigen::Map<VectorXd> y(y_out, rows());
    y.noalias() = ldlt_.solve(x);
  }

 private:
  const SparseMatrixd& k_;
  const SparseMatrixd& m_;
  Eigen::SimplicialLDLT<SparseMatrixd> ldlt_;
};

}  // namespace detail

/// Lowest `options.num_modes` eigenpairs of K x = lambda M x with Spectra's shift-invert
/// Lanczos. Uses options.num_modes, options.shift (< 0: the default small shift of
/// solve_eigen, applied as sigma = -shift so that K - sigma M is positive definite even for
/// free-free models), options.tolerance and options.max_iterations (restarts); options.method
/// and dense_limit are ignored. Preconditions as for solve_eigen: K symmetric positive
/// semi-definite, M symmetric positive semi-definite, K + |sigma| M positive definite.
FLEXSTRESS_PRECOMPUTE
Result<EigenSolution> solve_eigen_spectra(const SparseMatrixd& k, const SparseMatrixd& m,
                                          const EigenOptions& options) {
  const Index n = k.rows();
  if (k.cols() != n || m.rows() != n || m.cols() != n)
    return make_error(ErrorCode::size_mismatch, "Spectra eigen solve: K is ", k.rows(), "x",
                      k.cols(), " but M is ", m.rows(), "x", m.cols());
  const int p = options.num_modes;
  if (p <= 0 || p >= n)
    return make_error(ErrorCode::invalid_argument, "Spectra eigen solve: asked for ", p,
                      " modes of a model with ", n, " DOFs (need 0 < modes < DOFs)");
  const double shift = options.shift >= 0.0 ? options.shift : detail::default_shift(k, m);
  const double sigma = -shift;
  const Index ncv = std::min<Index>(n, std::max<Index>(2 * p + 1, 20));
  try {
    detail::SparseLdltShiftInvert op(k, m);
    Spectra::SparseSymMatProd<double> bop(m);
    Spectra::SymGEigsShiftSolver<detail::SparseLdltShiftInvert, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(op, bop, p, ncv, sigma);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, std::max(options.max_iterations, 1),
                   options.tolerance, Spectra::SortRule::SmallestAlge);
    if (solver.info() != Spectra::CompInfo::Successful)
      return make_error(ErrorCode::not_converged,
                        "Spectra eigen solve: Lanczos did not converge to ", p, " eigenpairs in ",
                        options.max_iterations,
                        " restarts (raise max_iterations or the tolerance)");
    EigenSolution s;
    s.eigenvalues = solver.eigenvalues();
    s.vectors = solver.eigenvectors();
    for (int j = 0; j < p; ++j) {
      s.vectors.col(j) /= std::sqrt(s.vectors.col(j).dot(m * s.vectors.col(j)));
      s.eigenvalues(j) = s.vectors.col(j).dot(k * s.vectors.col(j));  // Rayleigh quotient
    }
    // Sturm check: exactly p eigenvalues below a point just above lambda_p.
    const double lp = s.eigenvalues(p - 1);
    const double mu = lp + std::max(1e-6 * std::abs(lp), shift);
    const Index below = detail::count_eigenvalues_below(k, m, mu);
    if (below >= 0 && below != p)
      return make_error(ErrorCode::not_converged, "Spectra eigen solve: Sturm check found ", below,
                        " eigenvalues below ", mu, " but Lanczos returned ", p,
                        " (a missed or repeated eigenvalue; ask for more modes)");
    return s;
  } catch (const std::exception& e) {
    return make_error(ErrorCode::singular_matrix, "Spectra eigen solve failed: ", e.what(),
                      " (K + |sigma| M must be positive definite, sigma = ", sigma, ")");
  }
}

}  // namespace flexstress::fe
