#pragma once
/// \file Eigen 3.4's LDLT of a dense symmetric matrix (robust Cholesky with diagonal pivoting,
/// the lower triangle), giving exactly its bits, in less time.
///
/// The factorisation is Eigen's `ldlt_inplace<Lower>::unblocked`, step for step: the same
/// pivots, swaps, sums and divisions, mostly by calling the very same Eigen expressions. Only
/// its one O(n³) part, the update of each new column A21 -= A20 · (D A10ᵀ), is our own, and it
/// adds up every row's products in Eigen's order: one running sum per row from +0, column after
/// column (in blocks of 16 columns from 128 on, each block's sum subtracted on its own, as
/// Eigen's matrix-vector kernel does). Two things make it cheaper:
/// - rows in AVX2 lanes of four where the CPU has them (SSE2 pairs otherwise): the lanes are
///   independent rows, so the width changes no bit (no FMA, no reassociation: the file is
///   compiled with -ffp-contract=off);
/// - a column whose multiplier (D A10ᵀ)ⱼ is zero is skipped: its products are ±0, and adding ±0
///   to a running sum that started at +0 changes no bit (such a sum is never −0), as long as the
///   column is finite (∞·0 is NaN): a column with a non-finite entry is never skipped.
/// The solve calls Eigen's own triangular solves on the factor, so it is Eigen's bits too.
/// Tested against Eigen::LDLT bit for bit (factor, transpositions, status, solution) on sizes
/// 0-260, dense and sparse, definite, semi-definite, indefinite and non-finite matrices, on both
/// paths (tests/common/dense_ldlt_test.cpp).

#include <Eigen/Core>
#include <vector>

namespace formsim::control {

/// Which code factors (tests compare them; the bits are the same).
enum class LdltPath {
  kAuto,      ///< AVX2 where the CPU has it, else SSE2 pairs
  kPortable,  ///< SSE2 pairs (or the compiler's vectors off x86)
  kAvx2,      ///< four rows per instruction; kPortable on a CPU without AVX2
  kEigen,     ///< Eigen::LDLT itself (the reference)
};

/// The path of every DenseLdlt built from now on without one (process-wide; tests run whole
/// scenarios on each path).
void SetDefaultLdltPath(LdltPath p);
LdltPath DefaultLdltPath();

/// LDLᵀ = PᵀAP of a symmetric matrix, as Eigen::LDLT<Eigen::MatrixXd> computes it. Its buffers
/// serve every later Compute of the same size.
class DenseLdlt {
 public:
  DenseLdlt() : DenseLdlt(DefaultLdltPath()) {}
  explicit DenseLdlt(LdltPath path) : path_(path) {}

  /// Factors `a` (its lower triangle is read; the matrix is square).
  template <class Derived>
  void Compute(const Eigen::MatrixBase<Derived>& a) {
    m_ = a;
    Factor();
  }

  /// Factors `a`, taking its storage (the caller's matrix is left with this one's last buffer).
  void Compute(Eigen::MatrixXd&& a) {
    m_.swap(a);
    Factor();
  }

  /// Eigen's info() == Success: no pivot was zero with a non-zero column below it.
  bool ok() const { return ok_; }
  /// Eigen's isPositive(): every pivot ≥ 0.
  bool positive() const { return sign_ == Sign::kPositiveSemiDef || sign_ == Sign::kZero; }
  /// A⁻¹b as Eigen's LDLT::solve gives it (pivots of magnitude ≤ DBL_MIN are taken as zero).
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;

  /// The factor as Eigen's matrixLDLT(): L below the diagonal, D on it.
  const Eigen::MatrixXd& matrix() const { return m_; }
  /// The transpositions as Eigen's transpositionsP().
  const Eigen::Transpositions<Eigen::Dynamic, Eigen::Dynamic, int>& transpositions() const {
    return transpositions_;
  }

 private:
  enum class Sign { kPositiveSemiDef, kNegativeSemiDef, kZero, kIndefinite };
  void Factor();
  /// Factor on LdltPath::kEigen: Eigen::LDLT itself.
  void FactorWithEigen();
  // The steps of Factor's column k, in order:
  /// Picks the largest remaining diagonal entry as pivot k and swaps it in (lower triangle).
  void SwapInLargestPivot(Eigen::Index k);
  /// A(k, k) -= A10 (D A10ᵀ) and A21 -= A20 (D A10ᵀ), the O(n³) part (in our kernel).
  void UpdateColumn(Eigen::Index k, bool avx2);
  /// A21 /= A(k, k) when the pivot is valid; whether the column is finite. A zero pivot with a
  /// non-zero column below it clears ok_.
  bool DivideColumn(Eigen::Index k, double akk, bool pivot_is_valid, bool avx2);
  /// Folds pivot `akk` into sign_ (Eigen's isPositive / isNegative).
  void TrackSign(double akk);
  /// The first pivot, the largest diagonal entry, is zero: the whole diagonal is. The factor
  /// stops there (identity transpositions), and fails unless nothing is below the diagonal.
  void FinishZeroDiagonal();

  LdltPath path_;
  Eigen::MatrixXd m_;
  Eigen::Transpositions<Eigen::Dynamic, Eigen::Dynamic, int> transpositions_;
  Eigen::VectorXd temp_;
  std::vector<int> columns_;           // the columns a step's update adds up (multiplier ≠ 0)
  std::vector<int> block_ends_;        // where each of Eigen's column blocks ends in columns_
  std::vector<unsigned char> finite_;  // per column of L: every entry below the diagonal finite
  std::vector<double> diag_;           // the diagonal the pivots are chosen on (A's, swapped)
  std::vector<double> d_;              // D so far (the factor's diagonal), contiguous
  bool ok_ = false;
  Sign sign_ = Sign::kZero;
};

}  // namespace formsim::control
