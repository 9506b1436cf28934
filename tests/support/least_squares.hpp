// The least-squares fit the probes of a student's function share (probes.cpp, spring_lists.cpp):
// Eigen's QR solver compiled once, in least_squares.cpp, for every size of fit (issue 27: each
// matrix type it is instantiated for costs seconds of compiling).
#pragma once

#include <Eigen/Core>

namespace springlab::testing {

/// The x minimising |a x - y| (Eigen's Householder QR with column pivoting); the caller checks
/// the residual when an exact fit is what it looks for.
Eigen::VectorXd least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& y);

}  // namespace springlab::testing
