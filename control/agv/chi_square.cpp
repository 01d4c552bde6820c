#include "control/agv/chi_square.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace formsim::control::agv {
namespace {

// Regularised lower incomplete gamma P(a, x): power series below a + 1, Lentz continued
// fraction for Q = 1 - P above (Numerical Recipes §6.2).
double GammaP(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return sum * std::exp(log_prefactor);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-15) break;
  }
  return 1.0 - std::exp(log_prefactor) * h;
}

}  // namespace

double ChiSquareCdf(double x, int dof) {
  if (dof < 1) throw std::invalid_argument("chi-square needs dof >= 1");
  return GammaP(0.5 * dof, 0.5 * x);
}

double ChiSquareQuantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("chi-square quantile needs p in (0, 1)");
  double lo = 0.0, hi = dof + 10.0;
  while (ChiSquareCdf(hi, dof) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-10 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace formsim::control::agv
