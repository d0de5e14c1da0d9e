// Cholesky factorization of a symmetric positive definite matrix with block structure, stored
// and factorized within its envelope (profile), for the small systems a real-time step solves.
//
// The implicit integrator's iteration matrix S = M b' + ... + alpha B^T B is made of body blocks
// (each body's mass matrix, dense) coupled only where a joint joins two bodies. In a good block
// order the fill of the factor stays inside the envelope: column j of L is nonzero from the
// diagonal down to a last row last[j], and last[] never decreases (Jennings 1966; George & Liu,
// Computer Solution of Large Sparse Positive Definite Systems, 1981, ch. 4). analyze() picks the
// block order that minimizes the work (all orders for up to six blocks, else the natural order,
// its reverse and reverse Cuthill-McKee orders from every block), so a crane-like loop skips the
// zero boom-cylinder block and a 40-bar chain factorizes in O(n b^2) instead of O(n^3).
//
// Beyond the zeros it skips, it is written for short vectors: every inner loop is an axpy over
// contiguous memory (the factorization right-looking by columns; the back substitution reads a
// transposed copy of the factor, so it is an axpy too instead of a dot product, whose sum is a
// serial chain), the substitutions take two columns per pass, and the diagonal is stored
// inverted (a division per row costs its latency). The crane's 28 x 28 matrix (g++ -O3, SSE2,
// bench/bench_linear_algebra.cpp): solve 256 ns against 694 ns for Eigen::LLT, factorization
// 1.0 to 1.1 us against 1.5 to 1.9 us (docs/performance.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace flexstress {

/// Symmetric block pattern: the sizes of the diagonal blocks and the pairs of blocks that may
/// hold nonzeros off the diagonal (each pair once, either order). Everything else must be zero.
struct BlockPattern {
  std::vector<int> block_sizes;
  std::vector<std::pair<int, int>> couplings;
};

template <class Scalar, int N>
class EnvelopeCholesky {
 public:
  using Matrix = Eigen::Matrix<Scalar, N, N>;
  using Vector = Eigen::Matrix<Scalar, N, 1>;
  using Index = Eigen::Matrix<int, N, 1>;

  /// Without analyze(), compute() treats the matrix as dense (one block).
  EnvelopeCholesky() = default;

  /// Records the pattern and chooses the block order (setup: allocates when N is Dynamic).
  /// Returns false (and keeps the previous analysis) for an inconsistent pattern.
  bool analyze(const BlockPattern& pattern) {
    const int blocks = static_cast<int>(pattern.block_sizes.size());
    int n = 0;
    for (int size : pattern.block_sizes) {
      if (size <= 0) return false;
      n += size;
    }
    if (blocks == 0 || (N != Eigen::Dynamic && n != N)) return false;
    std::vector<std::vector<int>> adjacent(static_cast<std::size_t>(blocks));
    for (const auto& [a, b] : pattern.couplings) {
      if (a < 0 || b < 0 || a >= blocks || b >= blocks) return false;
      if (a == b) continue;
      adjacent[static_cast<std::size_t>(a)].push_back(b);
      adjacent[static_cast<std::size_t>(b)].push_back(a);
    }
    std::vector<int> best(static_cast<std::size_t>(blocks));
    std::iota(best.begin(), best.end(), 0);
    double best_work = work(pattern.block_sizes, adjacent, best);
    const auto consider = [&](const std::vector<int>& order) {
      const double w = work(pattern.block_sizes, adjacent, order);
      if (w < best_work) {
        best_work = w;
        best = order;
      }
    };
    if (blocks <= 6) {
      std::vector<int> order = best;
      while (std::next_permutation(order.begin(), order.end())) consider(order);
    } else {
      std::vector<int> order(best.rbegin(), best.rend());
      consider(order);
      for (int start = 0; start < blocks; ++start) consider(reverse_cuthill_mckee(adjacent, start));
    }
    resize(n);
    // Scalar positions in the chosen order, and the structural last row of each column.
    std::vector<int> block_start(static_cast<std::size_t>(blocks));
    for (int pos = 0, offset = 0; pos < blocks; ++pos) {
      block_start[static_cast<std::size_t>(best[static_cast<std::size_t>(pos)])] = offset;
      offset += pattern.block_sizes[static_cast<std::size_t>(best[static_cast<std::size_t>(pos)])];
    }
    identity_ = true;
    std::vector<int> original_start(static_cast<std::size_t>(blocks));
    std::partial_sum(pattern.block_sizes.begin(), pattern.block_sizes.end() - 1,
                     original_start.begin() + 1);
    for (int b = 0; b < blocks; ++b) {
      const auto ub = static_cast<std::size_t>(b);
      int last_row = block_start[ub] + pattern.block_sizes[ub] - 1;
      for (int c : adjacent[ub]) {
        const auto uc = static_cast<std::size_t>(c);
        last_row = std::max(last_row, block_start[uc] + pattern.block_sizes[uc] - 1);
      }
      for (int k = 0; k < pattern.block_sizes[ub]; ++k) {
        perm_(block_start[ub] + k) = original_start[ub] + k;
        last_(block_start[ub] + k) = last_row;
        identity_ = identity_ && block_start[ub] == original_start[ub];
      }
    }
    close_envelope();
    analyzed_ = true;
    return true;
  }

  /// Factorizes a (symmetric: both triangles hold the matrix; entries outside the analyzed
  /// pattern must be zero). Returns false if a is not numerically positive definite; solves
  /// then give NaN, so a caller's finiteness check catches it. Never allocates once analyze()
  /// has run (without it, the first call sizes a dynamic factor for a dense pattern).
  bool compute(const Matrix& a) {
    if (!analyzed_ || size() != a.rows()) resize_dense(static_cast<int>(a.rows()));
    const int n = size();
    for (int j = 0; j < n; ++j) {
      const int pj = perm_(j);
      Scalar* column = &l_(0, j);
      for (int i = j; i <= last_(j); ++i) column[i] = a(perm_(i), pj);
    }
    ok_ = true;
    for (int k = 0; k < n; ++k) {
      Scalar* ck = &l_(0, k);
      const Scalar d = ck[k];
      if (!(d > Scalar(0)) || !std::isfinite(d)) {
        ok_ = false;
        inverse_diagonal_.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
        return false;
      }
      const Scalar root = std::sqrt(d);
      const Scalar inverse = Scalar(1) / root;
      ck[k] = root;
      inverse_diagonal_(k) = inverse;
      const int last = last_(k);
      for (int i = k + 1; i <= last; ++i) ck[i] *= inverse;
      for (int j = k + 1; j <= last; ++j)  // column j -= L(j, k) * column k, rows j..last
        subtract_scaled(&l_(j, j), &ck[j], ck[j], last - j + 1);
    }
    // Row k of L (columns first[k]..k) as column k of u_, for the back substitution.
    for (int j = 0; j < n; ++j)
      for (int i = j; i <= last_(j); ++i) u_(j, i) = l_(i, j);
    return true;
  }

  /// x <- A^-1 x with the last factorization. Never allocates.
  template <class Derived>
  void solve_in_place(Eigen::MatrixBase<Derived>& x) {
    const int n = size();
    Scalar* y = work_.data();
    if (identity_) {
      for (int i = 0; i < n; ++i) y[i] = x(i);
    } else {
      for (int i = 0; i < n; ++i) y[i] = x(perm_(i));
    }
    // Two columns at a time: each unknown waits for the one before it (a multiply and a
    // subtraction), and pairing them halves the number of dependent passes over the vector.
    // Entries outside the envelope are stored zeros, so L(k+1, k) may be read unconditionally.
    const Scalar* d = inverse_diagonal_.data();
    int k = 0;
    for (; k + 1 < n; k += 2) {  // L z = y, by columns
      const Scalar* c0 = &l_(0, k);
      const Scalar* c1 = &l_(0, k + 1);
      const Scalar y0 = y[k] * d[k];
      const Scalar y1 = (y[k + 1] - y0 * c0[k + 1]) * d[k + 1];
      y[k] = y0;
      y[k + 1] = y1;
      const int split = std::max(last_(k), k + 1);  // rows after it: column k + 1 only
      subtract_scaled(y + k + 2, c0 + k + 2, y0, c1 + k + 2, y1, split - k - 1);
      subtract_scaled(y + split + 1, c1 + split + 1, y1, last_(k + 1) - split);
    }
    if (k < n) {
      y[k] *= d[k];
      subtract_scaled(y + k + 1, &l_(0, k) + k + 1, y[k], last_(k) - k);
    }
    for (k = n - 1; k > 0; k -= 2) {  // L^T w = z, by columns of L^T (rows of L)
      const Scalar* u0 = &u_(0, k);
      const Scalar* u1 = &u_(0, k - 1);
      const Scalar y0 = y[k] * d[k];
      const Scalar y1 = (y[k - 1] - y0 * u0[k - 1]) * d[k - 1];
      y[k] = y0;
      y[k - 1] = y1;
      const int split = std::min(first_(k), k - 1);  // rows before it: column k - 1 only
      subtract_scaled(y + split, u0 + split, y0, u1 + split, y1, k - 1 - split);
      subtract_scaled(y + first_(k - 1), u1 + first_(k - 1), y1, split - first_(k - 1));
    }
    if (k == 0) y[0] *= d[0];
    if (identity_) {
      for (int i = 0; i < n; ++i) x(i) = y[i];
    } else {
      for (int i = 0; i < n; ++i) x(perm_(i)) = y[i];
    }
  }

  int size() const { return static_cast<int>(perm_.size()); }
  /// False after a factorization that met a non-positive pivot.
  bool ok() const { return ok_; }
  /// Multiply-adds of one factorization in the analyzed envelope (n^3/6 for a dense one).
  double factorization_work() const {
    double w = 0;
    for (int k = 0; k < size(); ++k) {
      const double len = last_(k) - k;
      w += len * (len + 1) / 2;
    }
    return w;
  }
  /// Position of each row of the factor in the original matrix.
  const Index& permutation() const { return perm_; }

 private:
  /// y[0..n) -= f x[0..n). The ranges never overlap (columns of the factor, or the work
  /// vector); saying so lets the compiler vectorize without a runtime overlap check, which
  /// costs more than these short loops.
  static void subtract_scaled(Scalar* __restrict y, const Scalar* __restrict x, Scalar f, int n) {
    for (int i = 0; i < n; ++i) y[i] -= f * x[i];
  }
  /// y[0..n) -= f0 x0[0..n) + f1 x1[0..n).
  static void subtract_scaled(Scalar* __restrict y, const Scalar* __restrict x0, Scalar f0,
                              const Scalar* __restrict x1, Scalar f1, int n) {
    for (int i = 0; i < n; ++i) y[i] -= f0 * x0[i] + f1 * x1[i];
  }

  void resize(int n) {
    l_.setZero(n, n);
    u_.setZero(n, n);
    inverse_diagonal_.setZero(n);
    work_.setZero(n);
    perm_.resize(n);
    last_.resize(n);
    first_.resize(n);
  }
  void resize_dense(int n) {
    resize(n);
    for (int i = 0; i < n; ++i) {
      perm_(i) = i;
      last_(i) = n - 1;
    }
    identity_ = true;
    close_envelope();
    analyzed_ = true;
  }
  /// Fill: column k updates columns k+1..last[k] down to last[k], so last[] becomes a running
  /// maximum; first[k] is the first column whose envelope reaches row k.
  void close_envelope() {
    const int n = size();
    for (int j = 1; j < n; ++j) last_(j) = std::max(last_(j), last_(j - 1));
    for (int j = 0; j < n; ++j) last_(j) = std::max(last_(j), j);
    for (int k = 0, j = 0; k < n; ++k) {
      while (last_(j) < k) ++j;
      first_(k) = j;
    }
  }
  static double work(const std::vector<int>& sizes, const std::vector<std::vector<int>>& adjacent,
                     const std::vector<int>& order) {
    const std::size_t blocks = sizes.size();
    std::vector<int> start(blocks), end(blocks);
    for (std::size_t pos = 0, offset = 0; pos < blocks; ++pos) {
      const auto b = static_cast<std::size_t>(order[pos]);
      start[b] = static_cast<int>(offset);
      offset += static_cast<std::size_t>(sizes[b]);
      end[b] = static_cast<int>(offset) - 1;
    }
    double w = 0;
    int running = -1;
    for (std::size_t pos = 0; pos < blocks; ++pos) {
      const auto b = static_cast<std::size_t>(order[pos]);
      int last = end[b];
      for (int c : adjacent[b]) last = std::max(last, end[static_cast<std::size_t>(c)]);
      running = std::max(running, last);
      for (int j = start[b]; j <= end[b]; ++j) {
        const double len = running - j;
        w += len * (len + 1) / 2;
      }
    }
    return w;
  }
  /// Breadth-first from start, neighbours by increasing degree, then reversed (George & Liu,
  /// ch. 4.3); blocks not reached (separate components) follow in the same way.
  static std::vector<int> reverse_cuthill_mckee(const std::vector<std::vector<int>>& adjacent,
                                                int start) {
    const int blocks = static_cast<int>(adjacent.size());
    std::vector<int> order;
    std::vector<char> seen(static_cast<std::size_t>(blocks), 0);
    for (int root = start, tried = 0; tried < blocks; root = (root + 1) % blocks, ++tried) {
      if (seen[static_cast<std::size_t>(root)]) continue;
      seen[static_cast<std::size_t>(root)] = 1;
      order.push_back(root);
      for (std::size_t head = order.size() - 1; head < order.size(); ++head) {
        std::vector<int> next;
        for (int c : adjacent[static_cast<std::size_t>(order[head])])
          if (!seen[static_cast<std::size_t>(c)]) {
            seen[static_cast<std::size_t>(c)] = 1;
            next.push_back(c);
          }
        std::sort(next.begin(), next.end(), [&](int a, int b) {
          return adjacent[static_cast<std::size_t>(a)].size() <
                 adjacent[static_cast<std::size_t>(b)].size();
        });
        order.insert(order.end(), next.begin(), next.end());
      }
    }
    std::reverse(order.begin(), order.end());
    return order;
  }

  Matrix l_, u_;  ///< the factor (column j: rows j..last[j]) and its transpose
  Vector inverse_diagonal_, work_;
  Index perm_, last_, first_;
  bool identity_ = true, ok_ = false, analyzed_ = false;
};

}  // namespace flexstress
