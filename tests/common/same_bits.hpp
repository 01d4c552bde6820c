#pragma once
// Whether two matrices hold the same doubles bit for bit (NaNs and signed zeros included).
#include <Eigen/Core>
#include <cstring>

namespace formsim::testing {

inline bool SameBits(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
  // (An empty matrix may have no storage: memcmp must not see its null pointer.)
  return x.rows() == y.rows() && x.cols() == y.cols() &&
         (x.size() == 0 ||
          std::memcmp(x.data(), y.data(), sizeof(double) * static_cast<std::size_t>(x.size())) == 0);
}

}  // namespace formsim::testing
