#pragma once
/// \file Chi-square distribution helpers for innovation gating.

namespace formsim::control::agv {

/// P(X ≤ x) for X ~ χ²(dof), dof ≥ 1 (regularised lower incomplete gamma P(dof/2, x/2)).
double ChiSquareCdf(double x, int dof);
/// The x with ChiSquareCdf(x, dof) = p, for p in (0, 1) (bisection to 1e-10 relative).
/// Example: ChiSquareQuantile(0.99, 3) ≈ 11.345.
double ChiSquareQuantile(double p, int dof);

}  // namespace formsim::control::agv
