#pragma once
/// \file Matrix products with the bits of Eigen 3.4's dense product (SSE2, no FMA: the
/// project's flags), formed with less work: over a mostly zero factor's non-zero entries
/// (TimesTransposed), or without the packing Eigen's kernel does for small fixed-size operands
/// (AddTransposedTimes).
///
/// The order of Eigen's matrix-matrix kernel (gebp) is GebpSum's; it was checked against Eigen
/// on 9,000 random shapes up to 320 x 320 x 64, and tests/common/exact_products_test compares on
/// the shapes around every path and on the call shapes. A term with a zero factor is ±0, and
/// adding ±0 to a sum that started at +0 changes no bit (such a sum is never −0), so zero entries
/// may be skipped, as long as the factors are finite (∞·0 is NaN). Larger shapes (Eigen then
/// blocks the product), tiny ones (Eigen's coefficient-wise path, for rows + columns + depth <
/// 20) and non-finite factors go to Eigen's product itself.

#include <Eigen/Core>

namespace formsim::control {

namespace exact_products {

/// Whether Eigen forms an m×n product of depth k with its kernel in the order GebpSum repeats
/// (checked up to these sizes; tiny products take Eigen's coefficient-wise path).
inline bool InGebpOrder(Eigen::Index m, Eigen::Index n, Eigen::Index k) {
  return m <= 320 && n <= 320 && k <= 64 && k + m + n >= 20;
}

/// The entries of an m×n product of depth k that Eigen's kernel sums in two halves: rows
/// [begin, end) (its last pair of rows, when m is not a multiple of four) in columns [0, cols)
/// (whole four-column panels); empty below a depth of 8.
struct HalvedEntries {
  Eigen::Index begin, end, cols;
  bool Contain(Eigen::Index i, Eigen::Index j) const { return i >= begin && i < end && j < cols; }
};
inline HalvedEntries Halved(Eigen::Index m, Eigen::Index n, Eigen::Index k) {
  const Eigen::Index pair = (m / 4) * 4;
  return {pair, k >= 8 ? pair + ((m - pair) / 2) * 2 : pair, (n / 4) * 4};
}

/// Entry (i, j) of an m×n product of depth k, Σₚ term(p), added up in the order of Eigen's
/// kernel: it takes rows four at a time (two SSE2 pairs), then a last pair, then single rows;
/// the last pair's entries in whole four-column panels (`Halved`) add the terms below the
/// depth's multiple of 8 in two sums, the even terms and the odd ones, then the rest in order;
/// every other entry is one sum in order. Every sum starts from +0.
template <class Term>
double GebpSum(Eigen::Index i, Eigen::Index j, Eigen::Index m, Eigen::Index n, Eigen::Index k,
               const Term& term) {
  const Eigen::Index peeled = k & ~Eigen::Index(7);
  double s = 0.0;
  Eigen::Index p = 0;
  if (Halved(m, n, k).Contain(i, j)) {
    double odd = 0.0;
    for (; p < peeled; p += 2) {
      s = s + term(p);
      odd = odd + term(p + 1);
    }
    s = s + odd;
  }
  for (; p < k; ++p) s = s + term(p);
  return s;
}

}  // namespace exact_products

/// a·bᵀ (a: m×k, b: n×k), the bits of Eigen's `a * b.transpose()`; fast when b is mostly zero.
Eigen::MatrixXd TimesTransposed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

/// dst += aᵀ·b (a: k×m, b: k×n, small and fixed-size), the bits of Eigen's
/// `dst.noalias() += a.transpose() * b` for a block `dst` of a dynamic matrix, without the
/// packing Eigen's kernel does for every such product.
template <class Dst, class A, class B>
void AddTransposedTimes(Dst&& dst, const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  const Eigen::Index k = a.rows(), m = a.cols(), n = b.cols();
  // A depth of one at compile time is Eigen's outer product: dst + aᵢbⱼ, no sum from +0.
  if (A::RowsAtCompileTime == 1 || !exact_products::InGebpOrder(m, n, k) || !a.allFinite() ||
      !b.allFinite()) {
    dst.noalias() += a.transpose() * b;
    return;
  }
  // Column by column: the sums from +0 in order, a whole column at once (aᵀ's columns are
  // contiguous), then the entries Eigen sums in two halves, then added to the destination as
  // Eigen's kernel adds them (alpha = 1: dst + 1·s is dst + s).
  const Eigen::Matrix<double, A::ColsAtCompileTime, A::RowsAtCompileTime> at = a.transpose();
  Eigen::Matrix<double, A::ColsAtCompileTime, 1> sum(m);
  const exact_products::HalvedEntries halved = exact_products::Halved(m, n, k);
  for (Eigen::Index j = 0; j < n; ++j) {
    sum.setZero();
    for (Eigen::Index p = 0; p < k; ++p) sum += at.col(p) * b(p, j);
    for (Eigen::Index i = halved.begin; i < halved.end && j < halved.cols; ++i)
      sum(i) = exact_products::GebpSum(i, j, m, n, k,
                                       [&](Eigen::Index p) { return at(i, p) * b(p, j); });
    dst.col(j) += sum;
  }
}

}  // namespace formsim::control
