#include "adaptive_perception/math/chi_square.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <stdexcept>
#include <string>

namespace adaptive_perception::math {

double chiSquareQuantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0) || dof < 1)
    throw std::invalid_argument("chiSquareQuantile: p = " + std::to_string(p) + ", dof = " +
                                std::to_string(dof) + " (allowed: 0 < p < 1, dof >= 1)");
  return boost::math::quantile(boost::math::chi_squared(dof), p);
}

}  // namespace adaptive_perception::math
