// Eigen's symmetric eigensolver, compiled once for the core (in stability.cpp): its templates are
// among the costliest of the core's to compile, and two files need it. Without its own copy,
// critical_steps.cpp compiles in 10.5 s of GCC at -O2 instead of 17.0 (issue 27). Private to the
// core.
#pragma once

#include <Eigen/Eigenvalues>

namespace springlab::internal {

using SymmetricEigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;

/// The eigenvalues (ascending) of the symmetric matrix `m` and, when `vectors`, its eigenvectors.
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& m, bool vectors = true);

}  // namespace springlab::internal
