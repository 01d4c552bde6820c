// TimesTransposed against Eigen's product, bit for bit, on the shapes the sliding window's
// re-anchoring forms (a dense n×k factor times a k×n one with few non-zero rows, k = 2 per moved
// landmark) and on random shapes around every path of Eigen's kernel: row counts around its
// 4- and 2-row blocks, column counts around its 4-column panels, depths around its 8-term
// peeling, zeros of both signs, and the fallbacks (large and tiny products, non-finite factors).
#include "control/common/exact_products.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "tests/common/same_bits.hpp"

namespace formsim::control {
namespace {

using Eigen::MatrixXd;
using formsim::testing::SameBits;

// Entries: a quarter zeros (half of them −0), the rest spanning seven decades; `zero_rows` of
// the rows all zero.
MatrixXd Random(int rows, int cols, double zero_rows, std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) {
    const bool zero = u(rng) < zero_rows;
    for (int j = 0; j < cols; ++j) {
      const double r = u(rng);
      m(i, j) = zero || r < 0.25 ? (r < 0.125 ? -0.0 : 0.0)
                                 : n01(rng) * std::pow(10.0, std::floor(7.0 * u(rng)) - 3.0);
    }
  }
  return m;
}

TEST(TimesTransposed, EveryShapeGetsEigensBits) {
  std::mt19937_64 rng(3);
  int checked = 0;
  for (int k : {1, 2, 3, 7, 8, 9, 15, 16, 17, 23, 31, 40, 64, 65})
    for (int m : {1, 2, 3, 5, 6, 7, 11, 12, 13, 40, 151, 320, 321})
      for (int n : {1, 3, 4, 5, 8, 9, 17, 64, 150}) {
        const MatrixXd a = Random(m, k, 0.3, rng), b = Random(n, k, 0.6, rng);
        EXPECT_TRUE(SameBits(TimesTransposed(a, b), a * b.transpose()))
            << m << "x" << k << " times (" << n << "x" << k << ")^T";
        ++checked;
      }
  EXPECT_EQ(checked, 14 * 13 * 9);
}

TEST(TimesTransposed, TheReanchoringShapesGetEigensBits) {
  std::mt19937_64 rng(5);
  for (int moves : {1, 2, 3, 4, 5, 9, 13, 17, 22, 32})
    for (int n : {22, 64, 154, 230}) {
      const int k = 2 * moves;
      const MatrixXd hu = Random(n, k, 0.0, rng), d = Random(n, k, 0.8, rng);
      const MatrixXd uhu = Random(k, k, 0.0, rng);
      const std::string what = std::to_string(n) + " unknowns, " + std::to_string(moves) + " moves";
      EXPECT_TRUE(SameBits(TimesTransposed(hu, d), hu * d.transpose())) << what;
      const MatrixXd du = TimesTransposed(d, uhu.transpose());
      EXPECT_TRUE(SameBits(du, d * uhu)) << what;
      EXPECT_TRUE(SameBits(TimesTransposed(du, d), d * uhu * d.transpose())) << what;
    }
}

TEST(TimesTransposed, NonFiniteFactorsGetEigensBits) {
  std::mt19937_64 rng(9);
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {inf, -inf, std::nan("")}) {
    MatrixXd a = Random(30, 4, 0.3, rng), b = Random(40, 4, 0.6, rng);
    a(3, 1) = bad;  // ∞·0 = NaN where b's row is zero: those entries must not stay +0
    EXPECT_TRUE(SameBits(TimesTransposed(a, b), a * b.transpose())) << bad;
  }
}

// dst += aᵀb into a block of a dynamic matrix holding other values, against Eigen's own.
template <int K, int M, int N>
void ExpectAddTransposedTimesBits(std::mt19937_64& rng, bool bottom_rows = false) {
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix<double, K, M> a = Random(K, M, 0.1, rng);
    const Eigen::Matrix<double, K, N> b = Random(K, N, 0.1, rng);
    const MatrixXd start = Random(M + 7, N + 5, 0.0, rng);
    MatrixXd want = start, got = start;
    if (bottom_rows && K > 2) {
      // The odometry factor's planar rows: a fixed-size block of its Jacobians.
      want.block(3, 2, M, N).noalias() +=
          a.template bottomRows<2>().transpose() * b.template bottomRows<2>();
      AddTransposedTimes(got.block(3, 2, M, N), a.template bottomRows<2>(),
                         b.template bottomRows<2>());
    } else {
      want.block(3, 2, M, N).noalias() += a.transpose() * b;
      AddTransposedTimes(got.block(3, 2, M, N), a, b);
    }
    EXPECT_TRUE(SameBits(got, want)) << K << "x" << M << " and " << K << "x" << N;
  }
}

TEST(AddTransposedTimes, TheWindowsFactorShapesGetEigensBits) {
  std::mt19937_64 rng(21);
  ExpectAddTransposedTimesBits<8, 10, 10>(rng);        // IMU: Jiᵀ Ji, Jiᵀ Jj (depth 8: halves)
  ExpectAddTransposedTimesBits<5, 10, 10>(rng);        // odometry
  ExpectAddTransposedTimesBits<5, 10, 10>(rng, true);  // its planar rows
  ExpectAddTransposedTimesBits<1, 10, 10>(rng);        // one-row factors
  ExpectAddTransposedTimesBits<9, 6, 13>(rng);         // halves in a 2-row tail, 13 columns
  ExpectAddTransposedTimesBits<16, 11, 9>(rng);        // two rounds of 8
  ExpectAddTransposedTimesBits<2, 3, 4>(rng);          // tiny: Eigen's coefficient-wise path
}

}  // namespace
}  // namespace formsim::control
