#include "control/common/exact_products.hpp"

namespace formsim::control {

Eigen::MatrixXd TimesTransposed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  using Eigen::Index;
  const Index m = a.rows(), n = b.rows(), k = a.cols();
  if (m > 320 || n > 320 || k > 64 || k + m + n < 20 || b.cols() != k || !a.allFinite() ||
      !b.allFinite())
    return a * b.transpose();
  // Column j of the product gains a's column p times b(j, p), p in order: every entry's terms
  // in Eigen's order, and a whole column at once (zero terms of b skipped, zero rows of b left +0).
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(m, n);
  for (Index j = 0; j < n; ++j)
    for (Index p = 0; p < k; ++p) {
      const double bjp = b(j, p);
      if (bjp != 0.0) c.col(j) += a.col(p) * bjp;
    }
  // Eigen's kernel takes rows four at a time (two SSE2 pairs), then a last pair, then single
  // rows. The last pair's entries in whole four-column panels add the terms of the depth's
  // multiples of 8 in two sums, the even terms and the odd ones, then the rest in order.
  const Index peeled = k & ~Index(7);
  if (peeled == 0) return c;
  const Index pair = (m / 4) * 4, pair_end = pair + ((m - pair) / 2) * 2, panels = (n / 4) * 4;
  for (Index i = pair; i < pair_end; ++i)
    for (Index j = 0; j < panels; ++j) {
      double even = 0.0, odd = 0.0;
      for (Index p = 0; p < peeled; p += 2) {
        even = even + a(i, p) * b(j, p);
        odd = odd + a(i, p + 1) * b(j, p + 1);
      }
      double s = even + odd;
      for (Index p = peeled; p < k; ++p) s = s + a(i, p) * b(j, p);
      c(i, j) = s;
    }
  return c;
}

}  // namespace formsim::control
