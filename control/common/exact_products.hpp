#pragma once
/// \file Matrix products with mostly zero factors, with the bits of Eigen 3.4's dense product
/// (SSE2, no FMA: the project's flags).
///
/// Eigen's matrix-matrix kernel (gebp) adds each entry's terms in order, one running sum from +0
/// per entry, except in its last pair of rows (when the row count is not a multiple of four),
/// whose entries in whole four-column panels sum the terms below the largest multiple of 8 of the
/// depth as two sums, the even and the odd terms, before the rest. TimesTransposed repeats that
/// (checked against Eigen on 9,000 random shapes up to 320 x 320 x 64; tests/common/
/// exact_products_test compares on the shapes around every path). A term with a zero factor is
/// ±0, and adding ±0 to such a sum changes no bit (it is never −0), so zero entries of b are
/// skipped and its zero rows give +0 columns, as long as the factors are finite (∞·0 is NaN).
/// Larger shapes (Eigen then blocks the product), tiny products (Eigen's coefficient-wise path,
/// for rows + columns + depth < 20) and non-finite factors go to Eigen's product itself.

#include <Eigen/Core>

namespace formsim::control {

/// a·bᵀ (a: m×k, b: n×k), the bits of Eigen's `a * b.transpose()`; fast when b is mostly zero.
Eigen::MatrixXd TimesTransposed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace formsim::control
