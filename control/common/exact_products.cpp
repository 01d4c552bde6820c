#include "control/common/exact_products.hpp"

namespace formsim::control {

Eigen::MatrixXd TimesTransposed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  using Eigen::Index;
  const Index m = a.rows(), n = b.rows(), k = a.cols();
  if (!exact_products::InGebpOrder(m, n, k) || b.cols() != k || !a.allFinite() || !b.allFinite())
    return a * b.transpose();
  // Column j of the product gains a's column p times b(j, p), p in order: every entry's terms
  // in order from +0, a whole column at once (zero terms of b skipped, zero rows of b left +0).
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(m, n);
  for (Index j = 0; j < n; ++j)
    for (Index p = 0; p < k; ++p) {
      const double bjp = b(j, p);
      if (bjp != 0.0) c.col(j) += a.col(p) * bjp;
    }
  // The entries Eigen sums in two halves, again in its order.
  const exact_products::HalvedEntries halved = exact_products::Halved(m, n, k);
  for (Index i = halved.begin; i < halved.end; ++i)
    for (Index j = 0; j < halved.cols; ++j)
      c(i, j) = exact_products::GebpSum(i, j, m, n, k, [&](Index p) { return a(i, p) * b(j, p); });
  return c;
}

}  // namespace formsim::control
