// Eigen's eigensolvers for dense matrices, compiled once (in stability.cpp) for the core and the
// kit's tests: each is among the costliest templates to compile, several seconds of GCC in every
// file that names one (issue 27: critical_steps.cpp compiles in 10.5 s at -O2 instead of 17.0).
// The same solvers with the same options; only where they are compiled moves.
#pragma once

#include <Eigen/Eigenvalues>

namespace springlab::solvers {

using SymmetricEigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>;
using GeneralEigen = Eigen::EigenSolver<Eigen::MatrixXd>;

/// The eigenvalues (ascending) of the symmetric matrix `m` and, when `vectors`, its eigenvectors.
SymmetricEigen symmetric_eigen(const Eigen::MatrixXd& m, bool vectors = true);

/// The eigenvalues of the square matrix `m` and, when `vectors`, its eigenvectors.
GeneralEigen general_eigen(const Eigen::MatrixXd& m, bool vectors = true);

}  // namespace springlab::solvers
