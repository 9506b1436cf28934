// Eigen's symmetric eigensolver, compiled once for the core (in stability.cpp): its templates are
// the costliest of the core's to compile (about 8 s of GCC at -O2 in each file that instantiates
// them, several times that under the sanitizers), and two files need it. Private to the core.
#pragma once

#include <Eigen/Eigenvalues>

namespace springlab::internal {

using SymmetricEigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;

/// The eigenvalues (ascending) of the symmetric matrix `m` and, when `vectors`, its eigenvectors.
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& m, bool vectors = true);

}  // namespace springlab::internal
