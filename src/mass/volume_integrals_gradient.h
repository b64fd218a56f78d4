// Analytic derivative of the ten raw volume integrals (mass/volume_integrals.h) with respect to
// every vertex coordinate, the origin held fixed. Per triangle, with D = a·(b×c), S = a+b+c and
// u_a = a + S (likewise for b, c):
//   ∂D/∂a = b×c, ∂D/∂b = c×a, ∂D/∂c = a×b,
//   ∂(D S_i/24)/∂a = (b×c) S_i/24 + D e_i/24,
//   ∂(D G_ij/120)/∂a = (b×c) G_ij/120 + D (e_i u_a,j + e_j u_a,i)/120,  G_ij = Σ v_i v_j + S_i S_j.
// O(#F) per call. What an optimiser needs is the vector-Jacobian product Jᵀw for the weights
// w = ∂f/∂(integrals), accumulated into a #V by 3 gradient (same layout as Mesh::V).
#pragma once
#include <Eigen/Core>

#include "mass/volume_integrals.h"

namespace offsetopt {

// gradient += Jᵀ w, where J = ∂ volume_integrals(mesh, origin).values / ∂ mesh.V and `gradient`
// is #V by 3 (row i: the derivative with respect to vertex i's x, y, z). `gradient` must already
// have mesh.V's shape.
void accumulate_volume_integrals_gradient(const Mesh& mesh, const Eigen::Vector3d& origin, const Vector10d& weights,
                                          Vertices& gradient);

// The dense 10 by 3#V Jacobian; column 3i + c is vertex i's coordinate c (c = 0, 1, 2 for
// x, y, z). For tests and small meshes.
Eigen::MatrixXd volume_integrals_jacobian(const Mesh& mesh, const Eigen::Vector3d& origin);

// The 10 by #V derivative of the integrals along one direction per vertex: column i is
// ∂ values / ∂ x_i · directions.row(i). What moving vertex i along its offset direction does to
// every integral at once, in one pass over the faces (the optimiser's ∂P/∂δ).
Eigen::Matrix<double, 10, Eigen::Dynamic> volume_integrals_directional_jacobian(const Mesh& mesh,
                                                                                const Eigen::Vector3d& origin,
                                                                                const Vertices& directions);

// Both at once for the surface with vertices V and faces F, in one pass over the faces (the
// optimiser's evaluation, without building a Mesh): `integrals` gets exactly what
// volume_integrals({V, F}, origin).values returns (same compensated sums, same order) and
// `jacobian` (resized to jacobian_rows by #V) the first jacobian_rows rows of what
// volume_integrals_directional_jacobian returns, bit for bit. jacobian_rows is 1 (the volume),
// 4 (and the first moments) or 10 (other values: the largest of these not above it, at least 1):
// a goal that needs no second moments skips their derivatives. integral_count < 10 sums only the
// first max(integral_count, jacobian rows) integrals (rounded up to 1, 4 or 10 like the rows),
// each bit for bit as above, and sets the others to NaN: an optimiser's inner evaluations, whose
// goal reads no more than those, skip the rest. jacobian_is_zero: the caller promises `jacobian`
// already has its shape and holds +0 everywhere (an optimiser that clears the columns as it reads
// them), so it is not cleared again; the result is the same.
void volume_integrals_and_directional_jacobian(const Vertices& V, const Faces& F, const Eigen::Vector3d& origin,
                                               const Vertices& directions, Vector10d& integrals,
                                               Eigen::MatrixXd& jacobian, int jacobian_rows = 10,
                                               int integral_count = 10, bool jacobian_is_zero = false);

}  // namespace offsetopt
