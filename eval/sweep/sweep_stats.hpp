// Statistics over the seeds of a sweep (aggregate.csv, paired.csv): mean, sample standard
// deviation and the two-sided 95 % confidence interval of the mean by Student's t,
//   mean ± t_{0.975, n-1} · s / sqrt(n).
// The t quantile is computed, not looked up: the regularized incomplete beta function
// (continued fraction, Numerical Recipes 3rd ed. §6.4) gives the t CDF, which bisection
// inverts. A figure that cannot be computed (std and interval for n < 2) is absent.
#pragma once

#include <optional>
#include <vector>

namespace lifelong::eval {

struct SampleStats {
  int n = 0;
  std::optional<double> mean;       ///< n >= 1
  std::optional<double> std;        ///< sample standard deviation (n - 1); n >= 2
  std::optional<double> ci95_low;   ///< n >= 2
  std::optional<double> ci95_high;  ///< n >= 2
};

/// Regularized incomplete beta function I_x(a, b), a, b > 0, x in [0, 1].
double RegularizedIncompleteBeta(double a, double b, double x);

/// CDF of Student's t distribution with `dof` > 0 degrees of freedom at t.
double StudentTCdf(double t, double dof);

/// The t with StudentTCdf(t, dof) == p, for p in (0, 1); accurate to ~1e-12 relative.
double StudentTQuantile(double p, double dof);

/// Mean, std and the 95 % t interval of `values`.
SampleStats ComputeStats(const std::vector<double>& values);

}  // namespace lifelong::eval
