// EnvelopeCholesky: solves agree with Eigen's dense LLT on block-structured SPD matrices, the
// analysis finds the block order that skips the zero blocks, and bad input is reported.
#include <doctest/doctest.h>

#include <Eigen/Cholesky>
#include <flexstress/core/envelope_cholesky.hpp>

#include "support/random_block_spd.hpp"

namespace test_envelope_cholesky {

using namespace flexstress;
using flexstress::testing::random_block_spd;

namespace {
// The crane-like loop: boom (6 + 10 modes), cylinder, rod; the boom and the cylinder are
// joined only to the ground and to the rod.
BlockPattern crane_pattern() {
  return {{16, 6, 6}, {{0, 2}, {1, 2}}};
}
}  // namespace

TEST_CASE("envelope Cholesky solves a crane-like pattern as Eigen's LLT does, with less work") {
  const BlockPattern pattern = crane_pattern();
  EnvelopeCholesky<double, 28> chol;
  REQUIRE(chol.analyze(pattern));
  // Column j costs len (len + 1) / 2 multiply-adds, len = last[j] - j. Dense: the sum over
  // len = 0..27, 3654. The best orders put the rod between the others, cylinder, rod, boom (the
  // cylinder's columns reach only the rod): len 11..6, then 21..16, then 15..0, that is
  // 251 + 1091 + 680 = 2022 (by hand), or the reverse; the four others fill in to 3654.
  CHECK(chol.factorization_work() == doctest::Approx(2022.0));
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::Matrix<double, 28, 28> a = random_block_spd(pattern, seed);
    REQUIRE(chol.compute(a));
    Eigen::Matrix<double, 28, 1> b = Eigen::Matrix<double, 28, 1>::LinSpaced(-1.0, 2.0);
    Eigen::Matrix<double, 28, 1> x = b;
    chol.solve_in_place(x);
    const Eigen::Matrix<double, 28, 1> reference = a.llt().solve(b);
    CHECK((x - reference).norm() <= 1e-12 * reference.norm());
    CHECK((a * x - b).norm() <= 1e-12 * (a.norm() * x.norm()));
  }
}

TEST_CASE("without analyze() the factorization is dense and still exact") {
  const Eigen::MatrixXd a = random_block_spd({{5, 7}, {{0, 1}}}, 7);
  EnvelopeCholesky<double, Eigen::Dynamic> chol;
  REQUIRE(chol.compute(a));
  CHECK(chol.factorization_work() == doctest::Approx(11.0 * 12.0 * 13.0 / 6.0));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(12);
  chol.solve_in_place(x);
  CHECK((a * x - Eigen::VectorXd::Ones(12)).norm() <= 1e-12 * a.norm() * x.norm());
}

TEST_CASE("odd sizes, single-row blocks and blocks no other touches") {
  // The solves take the columns in pairs, reading L(k + 1, k) even where the envelope holds
  // a stored zero: odd sizes leave a last single column, an uncoupled block has columns whose
  // envelope ends at the diagonal, and a one-row block starts a pair in the middle of another.
  const BlockPattern patterns[] = {{{3, 1, 5}, {{0, 2}}},
                                   {{1, 1, 1, 1, 1}, {{0, 4}, {1, 3}}},
                                   {{7}, {}},
                                   {{2, 4, 1, 3, 5}, {{0, 3}, {3, 4}, {1, 2}}}};
  unsigned seed = 20;
  for (const BlockPattern& pattern : patterns) {
    EnvelopeCholesky<double, Eigen::Dynamic> chol;
    REQUIRE(chol.analyze(pattern));
    const Eigen::MatrixXd a = random_block_spd(pattern, ++seed);
    REQUIRE(chol.compute(a));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), 1.0, -2.0);
    Eigen::VectorXd x = b;
    chol.solve_in_place(x);
    const Eigen::VectorXd reference = a.llt().solve(b);
    CHECK((x - reference).norm() <= 1e-12 * reference.norm());
  }
}

TEST_CASE("a chain of 40 blocks factorizes in its band, in either numbering") {
  // Blocks numbered along the chain, and the same chain numbered from both ends inwards (0, 39,
  // 1, 38, ...), which a dense order would fill: the analysis must recover a banded order.
  for (bool scrambled : {false, true}) {
    BlockPattern pattern;
    const int blocks = 40;
    std::vector<int> label(blocks);
    for (int k = 0; k < blocks; ++k)
      label[k] = scrambled ? (k % 2 ? blocks - 1 - k / 2 : k / 2) : k;
    pattern.block_sizes.assign(blocks, 6);
    for (int k = 0; k + 1 < blocks; ++k) pattern.couplings.push_back({label[k], label[k + 1]});
    EnvelopeCholesky<double, Eigen::Dynamic> chol;
    REQUIRE(chol.analyze(pattern));
    // Banded: a column reaches at most the end of the next block, len <= 11, so at most
    // 240 * 66 multiply-adds, against 240^3 / 6 dense.
    CHECK(chol.factorization_work() <= 240.0 * 66.0);
    const Eigen::MatrixXd a = random_block_spd(pattern, 11);
    REQUIRE(chol.compute(a));
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(240, 0.0, 1.0);
    const Eigen::VectorXd reference = a.llt().solve(x);
    chol.solve_in_place(x);
    CHECK((x - reference).norm() <= 1e-12 * reference.norm());
  }
}

TEST_CASE("float works, and a matrix that is not positive definite is reported") {
  EnvelopeCholesky<float, 28> chol;
  REQUIRE(chol.analyze(crane_pattern()));
  const Eigen::Matrix<float, 28, 28> a = random_block_spd(crane_pattern(), 3).cast<float>();
  REQUIRE(chol.compute(a));
  Eigen::Matrix<float, 28, 1> x = Eigen::Matrix<float, 28, 1>::Ones();
  chol.solve_in_place(x);
  CHECK((a * x - Eigen::Matrix<float, 28, 1>::Ones()).norm() <= 1e-5f * a.norm() * x.norm());

  Eigen::Matrix<float, 28, 28> indefinite = a;
  indefinite(20, 20) = -1.0f;
  CHECK_FALSE(chol.compute(indefinite));
  CHECK_FALSE(chol.ok());
  x.setOnes();
  chol.solve_in_place(x);
  CHECK_FALSE(x.allFinite());  // a caller's finiteness check sees it; no garbage numbers
  REQUIRE(chol.compute(a));
  CHECK(chol.ok());
}

TEST_CASE("an inconsistent pattern is rejected") {
  EnvelopeCholesky<double, 28> chol;
  CHECK_FALSE(chol.analyze({{16, 6, 5}, {}}));        // sizes do not add up to 28
  CHECK_FALSE(chol.analyze({{16, 6, 6}, {{0, 3}}}));  // no block 3
  CHECK_FALSE(chol.analyze({{16, 0, 12}, {}}));       // an empty block
}

}  // namespace test_envelope_cholesky
