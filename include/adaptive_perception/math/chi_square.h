#pragma once
// Chi-square quantiles for gating (Boost.Math).
namespace adaptive_perception::math {

/// The p-quantile of the chi-square distribution with `dof` degrees of freedom (p in (0, 1)).
double chiSquareQuantile(double p, int dof);

}  // namespace adaptive_perception::math
