#include "control/common/dense_ldlt.hpp"

#include <Eigen/Cholesky>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "control/common/cpu_features.hpp"

namespace formsim::control {
namespace {

// One step's column update: col[i] -= Σⱼ a(i, j) t(j) for the rows i of [0, rows), j over
// `js` (ascending), each block of columns summed on its own from +0 and then subtracted
// (Eigen's general_matrix_vector_product: res += alpha c with alpha = -1; c·(−1) is exact, so
// res + (−c) is res − c). Rows go in chunks of 8, 4 and 1 vectors of W rows, then one at a
// time; every row's sum is the same sequence of roundings on every path.
#define FORMSIM_LDLT_CHUNK(V, W, SPLAT, R)           \
  for (; i + (R) * (W) <= rows; i += (R) * (W)) {    \
    V c[R];                                          \
    for (int r = 0; r < (R); ++r) c[r] = SPLAT(0.0); \
    for (int q = first; q < last; ++q) {             \
      const long j = js[q];                          \
      const V tj = SPLAT(t[j]);                      \
      const double* aj = a + j * lda + i;            \
      for (int r = 0; r < (R); ++r) {                \
        V x;                                         \
        std::memcpy(&x, aj + r * (W), sizeof x);     \
        c[r] = c[r] + x * tj;                        \
      }                                              \
    }                                                \
    for (int r = 0; r < (R); ++r) {                  \
      V y;                                           \
      std::memcpy(&y, col + i + r * (W), sizeof y);  \
      y = y - c[r];                                  \
      std::memcpy(col + i + r * (W), &y, sizeof y);  \
    }                                                \
  }

#define FORMSIM_LDLT_KERNEL(NAME, ATTR, V, W, SPLAT)                                 \
  ATTR void NAME(double* col, const double* a, long lda, long rows, const double* t, \
                 const int* js, const int* block_ends, int blocks) {                 \
    int first = 0;                                                                   \
    for (int b = 0; b < blocks; ++b) {                                               \
      const int last = block_ends[b];                                                \
      long i = 0;                                                                    \
      FORMSIM_LDLT_CHUNK(V, W, SPLAT, 8)                                             \
      FORMSIM_LDLT_CHUNK(V, W, SPLAT, 4)                                             \
      FORMSIM_LDLT_CHUNK(V, W, SPLAT, 1)                                             \
      for (; i < rows; ++i) {                                                        \
        double c = 0.0;                                                              \
        for (int q = first; q < last; ++q) c = c + a[js[q] * lda + i] * t[js[q]];    \
        col[i] = col[i] - c;                                                         \
      }                                                                              \
      first = last;                                                                  \
    }                                                                                \
  }

// col[i] /= d for the rows of [0, rows) (Eigen's A21 /= Akk); true when every quotient is
// finite (x − x is 0 for a finite x, NaN otherwise).
#define FORMSIM_LDLT_DIVIDE(NAME, ATTR, V, W, SPLAT)                \
  ATTR bool NAME(double* col, long rows, double d) {                \
    const V dv = SPLAT(d);                                          \
    V bad = SPLAT(0.0);                                             \
    long i = 0;                                                     \
    for (; i + (W) <= rows; i += (W)) {                             \
      V x;                                                          \
      std::memcpy(&x, col + i, sizeof x);                           \
      x = x / dv;                                                   \
      std::memcpy(col + i, &x, sizeof x);                           \
      bad = bad + (x - x);                                          \
    }                                                               \
    bool finite = true;                                             \
    for (int l = 0; l < (W); ++l) finite = finite && bad[l] == 0.0; \
    for (; i < rows; ++i) {                                         \
      col[i] = col[i] / d;                                          \
      finite = finite && std::isfinite(col[i]);                     \
    }                                                               \
    return finite;                                                  \
  }

typedef double V2 __attribute__((vector_size(16)));
#define FORMSIM_SPLAT2(x) (V2{(x), (x)})
FORMSIM_LDLT_KERNEL(UpdatePortable, static, V2, 2, FORMSIM_SPLAT2)
FORMSIM_LDLT_DIVIDE(DividePortable, static, V2, 2, FORMSIM_SPLAT2)

#if defined(__x86_64__) || defined(__i386__)
#define FORMSIM_LDLT_AVX2 1
typedef double V4 __attribute__((vector_size(32)));
#define FORMSIM_SPLAT4(x) (V4{(x), (x), (x), (x)})
FORMSIM_LDLT_KERNEL(UpdateAvx2, __attribute__((target("avx2"))) static, V4, 4, FORMSIM_SPLAT4)
FORMSIM_LDLT_DIVIDE(DivideAvx2, __attribute__((target("avx2"))) static, V4, 4, FORMSIM_SPLAT4)
#endif

#undef FORMSIM_LDLT_KERNEL
#undef FORMSIM_LDLT_CHUNK
#undef FORMSIM_LDLT_DIVIDE

std::atomic<LdltPath> g_default{LdltPath::kAuto};

}  // namespace

void SetDefaultLdltPath(LdltPath p) {
  g_default.store(p, std::memory_order_relaxed);
}
LdltPath DefaultLdltPath() {
  return g_default.load(std::memory_order_relaxed);
}

void DenseLdlt::Factor() {
  using Eigen::Index;
  const Index size = m_.rows();
  transpositions_.resize(size);
  temp_.resize(size);
  sign_ = Sign::kZero;
  ok_ = true;
  if (path_ == LdltPath::kEigen) {
    FactorWithEigen();
    return;
  }
  // The step's kernel: AVX2 only after the CPU check.
  [[maybe_unused]] bool avx2 = false;  // unused where the AVX2 kernel is not compiled (the page)
#ifdef FORMSIM_LDLT_AVX2
  avx2 = path_ != LdltPath::kPortable && CpuHasAvx2();
#endif

  if (size <= 1) {
    transpositions_.setIdentity();
    if (size == 1 && m_(0, 0) > 0.0)
      sign_ = Sign::kPositiveSemiDef;
    else if (size == 1 && m_(0, 0) < 0.0)
      sign_ = Sign::kNegativeSemiDef;
    return;
  }

  finite_.assign(static_cast<std::size_t>(size), 1);
  diag_.resize(static_cast<std::size_t>(size));
  d_.resize(static_cast<std::size_t>(size));
  for (Index i = 0; i < size; ++i) diag_[static_cast<std::size_t>(i)] = m_(i, i);
  columns_.resize(static_cast<std::size_t>(size));
  bool found_zero_pivot = false;
  for (Index k = 0; k < size; ++k) {
    SwapInLargestPivot(k);
    UpdateColumn(k, avx2);
    // As Eigen: only a zero pivot is refused (LDLT reveals no rank), and a zero pivot with a
    // non-zero column below it fails the factorisation.
    const double akk = m_.coeff(k, k);
    const bool pivot_is_valid = std::abs(akk) > 0.0;
    if (k == 0 && !pivot_is_valid) {
      FinishZeroDiagonal();
      return;
    }
    const bool finite = DivideColumn(k, akk, pivot_is_valid, avx2);
    if (found_zero_pivot && pivot_is_valid)
      ok_ = false;
    else if (!pivot_is_valid)
      found_zero_pivot = true;
    TrackSign(akk);
    // Column k of L is final now (later swaps only reorder its entries).
    finite_[static_cast<std::size_t>(k)] = finite ? 1 : 0;
    d_[static_cast<std::size_t>(k)] = akk;
  }
}

void DenseLdlt::FactorWithEigen() {
  const Eigen::LDLT<Eigen::MatrixXd> eigen(m_);
  m_ = eigen.matrixLDLT();
  transpositions_ = eigen.transpositionsP();
  ok_ = eigen.info() == Eigen::Success;
  // Eigen tells the sign through isPositive / isNegative only.
  sign_ = eigen.isPositive() ? (eigen.isNegative() ? Sign::kZero : Sign::kPositiveSemiDef)
                             : (eigen.isNegative() ? Sign::kNegativeSemiDef : Sign::kIndefinite);
}

void DenseLdlt::SwapInLargestPivot(Eigen::Index k) {
  using Eigen::Index;
  const Index size = m_.rows();
  // The largest diagonal entry of the corner (the first of equals) becomes the pivot.
  // (Eigen's maxCoeff on the diagonal's magnitudes, which pivots on the matrix's own diagonal
  // entries; kept in a contiguous copy, swapped with the matrix.)
  Index biggest = k;
  double largest = std::abs(diag_[static_cast<std::size_t>(k)]);
  for (Index i = k + 1; i < size; ++i) {
    const double v = std::abs(diag_[static_cast<std::size_t>(i)]);
    if (v > largest) {
      largest = v;
      biggest = i;
    }
  }
  transpositions_.coeffRef(k) = static_cast<int>(biggest);
  if (k == biggest) return;
  // The transposition, touching only the lower triangle.
  const Index s = size - biggest - 1;
  m_.row(k).head(k).swap(m_.row(biggest).head(k));
  m_.col(k).tail(s).swap(m_.col(biggest).tail(s));
  std::swap(m_.coeffRef(k, k), m_.coeffRef(biggest, biggest));
  std::swap(diag_[static_cast<std::size_t>(k)], diag_[static_cast<std::size_t>(biggest)]);
  for (Index i = k + 1; i < biggest; ++i) {
    const double tmp = m_.coeffRef(i, k);
    m_.coeffRef(i, k) = m_.coeffRef(biggest, i);
    m_.coeffRef(biggest, i) = tmp;
  }
}

void DenseLdlt::UpdateColumn(Eigen::Index k, [[maybe_unused]] bool avx2) {
  using Eigen::Block;
  using Eigen::Dynamic;
  using Eigen::Index;
  using Eigen::MatrixXd;
  if (k == 0) return;
  const Index size = m_.rows();
  const Index rs = size - k - 1;
  Block<MatrixXd, Dynamic, 1> A21(m_, k + 1, k, rs, 1);
  Block<MatrixXd, 1, Dynamic> A10(m_, k, 0, 1, k);
  // Eigen's D·A10ᵀ, from a contiguous copy of D.
  for (Index j = 0; j < k; ++j) temp_(j) = d_[static_cast<std::size_t>(j)] * m_.coeff(k, j);
  m_.coeffRef(k, k) -= (A10 * temp_.head(k)).value();
  if (rs == 1) {
    // One row: Eigen's product falls back to a dot product (a sum from its first term).
    Block<MatrixXd, Dynamic, Dynamic> A20(m_, k + 1, 0, rs, k);
    A21.noalias() -= A20 * temp_.head(k);
    return;
  }
  if (rs <= 1) return;
  // Eigen's matrix-vector kernel takes all columns at once below 128 and blocks of 16
  // from there (while a column is under 32000 bytes; 4 beyond).
  const Index block = k < 128 ? k : (size * Index(sizeof(double)) < 32000 ? 16 : 4);
  block_ends_.clear();
  int n = 0;
  for (Index b = 0; b < k; b += block) {
    const Index end = std::min(b + block, k);
    for (Index j = b; j < end; ++j) {
      columns_[static_cast<std::size_t>(n)] = static_cast<int>(j);
      n += temp_(j) != 0.0 || !finite_[static_cast<std::size_t>(j)];
    }
    block_ends_.push_back(n);
  }
  double* col = &m_.coeffRef(k + 1, k);
  const double* a = &m_.coeffRef(k + 1, 0);
  const int blocks = static_cast<int>(block_ends_.size());
#ifdef FORMSIM_LDLT_AVX2
  if (avx2)
    UpdateAvx2(col, a, m_.outerStride(), rs, temp_.data(), columns_.data(), block_ends_.data(),
               blocks);
  else
#endif
    UpdatePortable(col, a, m_.outerStride(), rs, temp_.data(), columns_.data(), block_ends_.data(),
                   blocks);
}

void DenseLdlt::FinishZeroDiagonal() {
  const Eigen::Index size = m_.rows();
  sign_ = Sign::kZero;
  for (Eigen::Index j = 0; j < size; ++j) {
    transpositions_.coeffRef(j) = static_cast<int>(j);
    ok_ = ok_ && (m_.col(j).tail(size - j - 1).array() == 0.0).all();
  }
}

bool DenseLdlt::DivideColumn(Eigen::Index k, double akk, bool pivot_is_valid,
                             [[maybe_unused]] bool avx2) {
  const Eigen::Index rs = m_.rows() - k - 1;
  if (rs <= 0) return true;
  if (pivot_is_valid) {
#ifdef FORMSIM_LDLT_AVX2
    if (avx2) return DivideAvx2(&m_.coeffRef(k + 1, k), rs, akk);
#endif
    return DividePortable(&m_.coeffRef(k + 1, k), rs, akk);
  }
  const Eigen::Block<Eigen::MatrixXd, Eigen::Dynamic, 1> A21(m_, k + 1, k, rs, 1);
  const bool finite = A21.allFinite();
  ok_ = ok_ && (A21.array() == 0.0).all();
  return finite;
}

void DenseLdlt::TrackSign(double akk) {
  if (sign_ == Sign::kPositiveSemiDef) {
    if (akk < 0.0) sign_ = Sign::kIndefinite;
  } else if (sign_ == Sign::kNegativeSemiDef) {
    if (akk > 0.0) sign_ = Sign::kIndefinite;
  } else if (sign_ == Sign::kZero) {
    if (akk > 0.0)
      sign_ = Sign::kPositiveSemiDef;
    else if (akk < 0.0)
      sign_ = Sign::kNegativeSemiDef;
  }
}

Eigen::VectorXd DenseLdlt::Solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x = transpositions_ * b;
  m_.triangularView<Eigen::UnitLower>().solveInPlace(x);
  const double tolerance = std::numeric_limits<double>::min();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double d = m_(i, i);
    if (std::abs(d) > tolerance)
      x(i) /= d;
    else
      x(i) = 0.0;
  }
  m_.transpose().triangularView<Eigen::UnitUpper>().solveInPlace(x);
  return transpositions_.transpose() * x;
}

}  // namespace formsim::control
