// DenseLdlt against Eigen::LDLT, bit for bit: the factor, the transpositions, the status and
// the solution, on every path, for matrices that reach each of Eigen's branches (pivot swaps,
// zero pivots, the one-row dot product, the 16-column blocks from 128 columns on) and each of
// ours (skipped zero columns, non-finite columns never skipped). A changed rounding anywhere in
// the column update fails the dense cases; skipping a column with an infinite entry fails the
// non-finite ones.
#include "control/common/dense_ldlt.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "control/common/cpu_features.hpp"
#include "tests/common/same_bits.hpp"

namespace formsim::control {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using formsim::testing::SameBits;

std::vector<LdltPath> Paths() {
  std::vector<LdltPath> p{LdltPath::kAuto, LdltPath::kPortable, LdltPath::kEigen};
  if (CpuHasAvx2()) p.push_back(LdltPath::kAvx2);
  return p;
}

// Compares every path with Eigen.
void ExpectEigensBits(const MatrixXd& a, const std::string& what) {
  const Eigen::LDLT<MatrixXd> eigen(a);
  std::mt19937_64 rng(a.rows());
  std::normal_distribution<double> n01;
  VectorXd b(a.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = n01(rng);
  const VectorXd x = eigen.solve(b);
  for (LdltPath path : Paths()) {
    DenseLdlt ldlt(path);
    ldlt.Compute(a);
    SCOPED_TRACE(what + ", path " + std::to_string(static_cast<int>(path)));
    EXPECT_TRUE(SameBits(ldlt.matrix(), eigen.matrixLDLT()));
    EXPECT_EQ(ldlt.transpositions().indices(), eigen.transpositionsP().indices());
    EXPECT_EQ(ldlt.ok(), eigen.info() == Eigen::Success);
    EXPECT_EQ(ldlt.positive(), eigen.isPositive());
    EXPECT_TRUE(SameBits(ldlt.Solve(b), x));
  }
}

MatrixXd Random(int rows, int cols, std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = n01(rng);
  return m;
}

// Positive definite with information spanning many decades (as a sliding window's is).
MatrixXd Definite(int n, std::mt19937_64& rng) {
  const MatrixXd b = Random(n, n, rng);
  MatrixXd a = b * b.transpose();
  std::uniform_real_distribution<double> decades(-4.0, 6.0);
  for (int i = 0; i < n; ++i) {
    const double s = std::pow(10.0, decades(rng));
    a.row(i) *= s;
    a.col(i) *= s;
  }
  return a;
}

// A window's shape: banded frame blocks, landmark columns touching a few frames, the rest zero.
MatrixXd Sparse(int n, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, n - 1);
  MatrixXd j = MatrixXd::Zero(2 * n, n);
  for (int r = 0; r < 2 * n; ++r) {
    const int c = r % n;
    for (int k = c; k < std::min(n, c + 3); ++k) j(r, k) = std::ldexp(pick(rng) - n / 2, -3);
    if (r % 5 == 0) j(r, pick(rng)) = 1.5;
  }
  MatrixXd a = j.transpose() * j;
  a.diagonal().array() += 1e-9;
  return a;
}

TEST(DenseLdlt, DefiniteMatricesOfEverySizeGetEigensBits) {
  std::mt19937_64 rng(7);
  for (int n = 0; n <= 40; ++n) ExpectEigensBits(Definite(n, rng), "definite " + std::to_string(n));
  for (int n : {63, 64, 65, 127, 128, 129, 130, 143, 144, 145, 200, 260})
    ExpectEigensBits(Definite(n, rng), "definite " + std::to_string(n));
}

TEST(DenseLdlt, SparseMatricesSkipZeroColumnsWithEigensBits) {
  std::mt19937_64 rng(11);
  for (int n : {17, 33, 90, 131, 170, 233}) {
    const MatrixXd a = Sparse(n, rng);
    ExpectEigensBits(a, "sparse " + std::to_string(n));
    // The case reaches the skip: some step's multipliers are zero.
    const Eigen::LDLT<MatrixXd> eigen(a);
    const MatrixXd& f = eigen.matrixLDLT();
    int zeros = 0;
    for (int k = 1; k < n; ++k)
      for (int j = 0; j < k; ++j) zeros += f(k, j) == 0.0;
    EXPECT_GT(zeros, n) << n;
  }
}

TEST(DenseLdlt, SemiDefiniteIndefiniteAndZeroMatricesGetEigensBits) {
  std::mt19937_64 rng(13);
  for (int n : {2, 3, 9, 40, 150}) {
    const MatrixXd b = Random(n, std::max(1, n / 3), rng);
    ExpectEigensBits(b * b.transpose(), "rank-deficient " + std::to_string(n));
    const MatrixXd c = Random(n, n, rng);
    ExpectEigensBits(c + c.transpose(), "indefinite " + std::to_string(n));
    ExpectEigensBits(MatrixXd::Zero(n, n), "zero " + std::to_string(n));
    MatrixXd d = Definite(n, rng);
    d.row(n / 2).setZero();
    d.col(n / 2).setZero();
    ExpectEigensBits(d, "a zero row and column " + std::to_string(n));
    ExpectEigensBits(-Definite(n, rng), "negative definite " + std::to_string(n));
    MatrixXd p = Definite(n, rng);
    p.diagonal().setZero();  // zero pivots with non-zero columns: Eigen's NumericalIssue
    ExpectEigensBits(p, "zero diagonal " + std::to_string(n));
    MatrixXd z = Sparse(n, rng);  // its zeros, every other one negative
    for (int c = 0; c < n; ++c)
      for (int r = c; r < n; ++r)
        if (z(r, c) == 0.0 && (r + c) % 2 == 0) z(r, c) = z(c, r) = -0.0;
    ExpectEigensBits(z, "negative zeros " + std::to_string(n));
  }
}

TEST(DenseLdlt, NonFiniteEntriesGetEigensBits) {
  std::mt19937_64 rng(17);
  const double inf = std::numeric_limits<double>::infinity();
  for (int n : {4, 20, 140}) {
    for (double bad : {inf, -inf, std::nan("")}) {
      MatrixXd a = Sparse(n, rng);
      a(n - 1, 1) = a(1, n - 1) = bad;
      ExpectEigensBits(a, "non-finite " + std::to_string(n));
    }
    // Overflow inside the factorisation: pivots of 1e-300 under entries of 1e300.
    MatrixXd o = Sparse(n, rng);
    o(0, 0) = 1e-300;
    o.col(0).tail(n - 1) *= 1e300;
    o.row(0).tail(n - 1) *= 1e300;
    ExpectEigensBits(o, "overflow " + std::to_string(n));
  }
}

}  // namespace
}  // namespace formsim::control
