#include "least_squares.hpp"

#include <Eigen/QR>

namespace springlab::testing {

Eigen::VectorXd least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  return a.colPivHouseholderQr().solve(y);
}

}  // namespace springlab::testing
