// Lowest eigenpairs of K x = lambda M x (K, M symmetric, K positive semi-definite, M positive
// semi-definite, K + sigma M positive definite for sigma > 0).
//
// Two paths, same answer:
//  - dense: the shifted pencil (M, K + sigma M) with Eigen's generalized self-adjoint solver,
//    mu = 1 / (lambda + sigma); robust for free-free structures (K singular) and massless DOFs
//    (lambda = infinity, dropped). O(n^3): models up to a few thousand DOFs.
//  - subspace iteration with shift (Bathe, Finite Element Procedures, sec. 11.6): one sparse
//    LDL^T of K - sigma M, q = max(2p, p + 8) iteration vectors, Rayleigh-Ritz on each pass, and
//    a Sturm sequence check (the count of negative pivots of K - mu M) that no eigenvalue below
//    the highest wanted one was missed. No exceptions; for very large models the opt-in Spectra
//    path (eigen_solver_spectra.hpp) is an alternative.
// Eigenvectors are mass-normalized: X^T M X = I, X^T K X = diag(lambda).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "flexstress/core/precompute.hpp"
#include "flexstress/core/status.hpp"
#include "flexstress/fe/constraint_transform.hpp"

namespace flexstress::fe {

enum class EigenMethod : unsigned char { automatic, dense, subspace_iteration };

struct EigenOptions {
  int num_modes = 6;
  EigenMethod method = EigenMethod::automatic;
  /// Models with at most this many DOFs use the dense path under `automatic`.
  Index dense_limit = 1500;
  /// Shift sigma; < 0 picks 1e-8 tr(K) / tr(M) (small against any elastic eigenvalue, large
  /// enough to make K + sigma M definite for free-free structures).
  double shift = -1.0;
  double tolerance = 1e-10;  ///< subspace iteration: relative change of the eigenvalues
  int max_iterations = 200;
};

struct EigenSolution {
  VectorXd eigenvalues;  ///< lambda = omega^2, ascending
  MatrixXd vectors;      ///< columns, mass-normalized

  /// Natural frequencies in Hz (negative round-off eigenvalues give 0).
  VectorXd frequencies_hz() const {
    VectorXd f(eigenvalues.size());
    for (Index i = 0; i < f.size(); ++i)
      f(i) = std::sqrt(std::max(eigenvalues(i), 0.0)) / (2.0 * 3.14159265358979323846);
    return f;
  }
};

namespace detail {

inline double default_shift(const SparseMatrixd& k, const SparseMatrixd& m) {
  const double tk = k.diagonal().sum(), tm = m.diagonal().sum();
  return tm > 0.0 ? 1e-8 * tk / tm : 1e-8 * tk;
}

FLEXSTRESS_PRECOMPUTE
Result<EigenSolution> eigen_dense(const SparseMatrixd& k, const SparseMatrixd& m, int p,
                                  double sigma) {
  const MatrixXd kd(k), md(m);
  const MatrixXd b = kd + sigma * md;
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(md, b, Eigen::ComputeEigenvectors);
  if (es.info() != Eigen::Success)
    return make_error(ErrorCode::singular_matrix,
                      "eigen solve: K + sigma M is not positive definite (a mechanism with no "
                      "mass, or a negative stiffness)");
  // mu ascending -> lambda descending; take the largest mu.
  const Index n = kd.rows();
  std::vector<Index> order;
  for (Index i = n - 1; i >= 0 && static_cast<int>(order.size()) < p; --i)
    if (es.eigenvalues()(i) > 0.0) order.push_back(i);
  if (static_cast<int>(order.size()) < p)
    return make_error(ErrorCode::size_mismatch, "eigen solve: asked for ", p,
                      " modes but the model has only ", order.size(),
                      " with finite frequency (DOFs: ", n, ")");
  EigenSolution s;
  s.eigenvalues.resize(p);
  s.vectors.resize(n, p);
  for (int j = 0; j < p; ++j) {
    const Index i = order[static_cast<std::size_t>(j)];
    const VectorXd x = es.eigenvectors().col(i);
    s.vectors.col(j) = x / std::sqrt(x.dot(md * x));
    // Rayleigh quotient: second-order accurate in the vector, more accurate than 1/mu - sigma
    // when K + sigma M is ill-conditioned.
    s.eigenvalues(j) = s.vectors.col(j).dot(kd * s.vectors.col(j));
  }
  return s;
}

/// Number of eigenvalues below mu (Sturm sequence: negative pivots of K - mu M).
FLEXSTRESS_PRECOMPUTE
Index count_eigenvalues_below(const SparseMatrixd& k, const SparseMatrixd& m, double mu) {
  Eigen::SimplicialLDLT<SparseMatrixd> f(SparseMatrixd(k - mu * m));
  if (f.info() != Eigen::Success) return -1;
  return static_cast<Index>((f.vectorD().array() < 0.0).count());
}

FLEXSTRESS_PRECOMPUTE
Result<EigenSolution> eigen_subspace(const SparseMatrixd& k, const SparseMatrixd& m,
                                     const EigenOptions& opt, double sigma) {
  const Index n = k.rows();
  const int p = opt.num_modes;
  const Index q = std::min<Index>(n, std::max<Index>(2 * p, p + 8));
  Eigen::SimplicialLDLT<SparseMatrixd> f(SparseMatrixd(k + sigma * m));
  if (f.info() != Eigen::Success || (f.vectorD().array() <= 0.0).any())
    return make_error(ErrorCode::singular_matrix,
                      "eigen solve: K + sigma M is not positive definite (a mechanism with no "
                      "mass, or a negative stiffness)");
  // Start: M-weighted unit vectors at the DOFs with the largest m_ii / k_ii (Bathe), plus
  // pseudo-random vectors with a fixed seed (deterministic results).
  MatrixXd x = MatrixXd::Zero(n, q);
  const VectorXd md = m.diagonal(), kd = k.diagonal();
  x.col(0) = md;
  std::vector<Index> idx(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) idx[static_cast<std::size_t>(i)] = i;
  auto ratio = [&](Index i) { return kd(i) > 0.0 ? md(i) / kd(i) : md(i) * 1e30; };
  std::sort(idx.begin(), idx.end(), [&](Index a, Index b) { return ratio(a) > ratio(b); });
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (Index j = 1; j < q; ++j) {
    if (j < q / 2) {
      x(idx[static_cast<std::size_t>(j - 1)], j) = 1.0;
    } else {
      for (Index i = 0; i < n; ++i) x(i, j) = uni(rng);
    }
  }
  VectorXd lambda_old = VectorXd::Constant(q, std::numeric_limits<double>::infinity());
  for (int it = 0; it < opt.max_iterations; ++it) {
    const MatrixXd y = m * x;
    const MatrixXd xbar = f.solve(y);
    const MatrixXd ks = xbar.transpose() * y;           // X^T (K + sigma M) X
    const MatrixXd ms = xbar.transpose() * (m * xbar);  // X^T M X
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(
        0.5 * (ks + ks.transpose()), 0.5 * (ms + ms.transpose()), Eigen::ComputeEigenvectors);
    if (es.info() != Eigen::Success)
      return make_error(ErrorCode::not_converged,
                        "eigen solve: subspace iteration lost rank (too few independent "
                        "vectors; the model may have fewer modes than requested)");
    x = xbar * es.eigenvectors();
    const VectorXd lambda = es.eigenvalues();
    bool converged = true;
    for (int j = 0; j < p; ++j)
      if (std::abs(lambda(j) - lambda_old(j)) > opt.tolerance * std::abs(lambda(j)))
        converged = false;
    lambda_old = lambda;
    if (converged) {
      EigenSolution s;
      s.eigenvalues = lambda.head(p).array() - sigma;
      s.vectors = x.leftCols(p);
      for (int j = 0; j < p; ++j) {
        s.vectors.col(j) /= std::sqrt(s.vectors.col(j).dot(m * s.vectors.col(j)));
        s.eigenvalues(j) = s.vectors.col(j).dot(k * s.vectors.col(j));  // Rayleigh quotient
      }
      // Sturm check: exactly p eigenvalues below a point between lambda_p and lambda_{p+1}.
      const double lp = s.eigenvalues(p - 1);
      const double next = q > p ? lambda(p) - sigma : lp * 1.1;
      const double mu = lp + 0.5 * (next - lp);
      const Index below = count_eigenvalues_below(k, m, mu);
      if (below >= 0 && below != p)
        return make_error(ErrorCode::not_converged, "eigen solve: Sturm check found ", below,
                          " eigenvalues below ", mu, " but subspace iteration converged to ", p,
                          "; increase num_modes or use the dense solver");
      return s;
    }
  }
  return make_error(ErrorCode::not_converged,
                    "eigen solve: subspace iteration did not converge in ", opt.max_iterations,
                    " iterations");
}

}  // namespace detail

/// Lowest `options.num_modes` eigenpairs of K x = lambda M x.
FLEXSTRESS_PRECOMPUTE
Result<EigenSolution> solve_eigen(const SparseMatrixd& k, const SparseMatrixd& m,
                                  const EigenOptions& options)
#if FLEXSTRESS_PRECOMPUTE_BODIES
{
  const Index n = k.rows();
  if (k.cols() != n || m.rows() != n || m.cols() != n)
    return make_error(ErrorCode::size_mismatch, "eigen solve: K is ", k.rows(), "x", k.cols(),
                      " but M is ", m.rows(), "x", m.cols());
  if (options.num_modes <= 0)
    return make_error(ErrorCode::invalid_argument, "eigen solve: asked for ", options.num_modes,
                      " modes");
  if (options.num_modes > n)
    return make_error(ErrorCode::size_mismatch, "eigen solve: asked for ", options.num_modes,
                      " modes but the model has only ", n, " DOFs");
  const double sigma = options.shift >= 0.0 ? options.shift : detail::default_shift(k, m);
  const bool dense = options.method == EigenMethod::dense ||
                     (options.method == EigenMethod::automatic && n <= options.dense_limit);
  if (dense) return detail::eigen_dense(k, m, options.num_modes, sigma);
  return detail::eigen_subspace(k, m, options, sigma);
}
#else
    ;
#endif

}  // namespace flexstress::fe

// This header's precompute entry points (core/precompute.hpp).
#define FLEXSTRESS_PRECOMPUTE_FE_EIGEN_SOLVER(X)   \
  X(4, Result<fe::EigenSolution>, fe::solve_eigen, \
    (const fe::SparseMatrixd&, const fe::SparseMatrixd&, const fe::EigenOptions&))
namespace flexstress {
FLEXSTRESS_PRECOMPUTE_EXTERN(FLEXSTRESS_PRECOMPUTE_FE_EIGEN_SOLVER)
}  // namespace flexstress
