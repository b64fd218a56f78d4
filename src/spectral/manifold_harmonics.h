// src/spectral (this is the folder's main header): the manifold-harmonic basis. It owns the
// eigensolver (block shift-invert Lanczos, its operator's block solves and panel kernels) and the
// basis files; the operators it diagonalises come from src/geometry (cotan Laplacian, lumped
// mass) and the factorisation of L + sM from src/sparse. It may include util, optim, mesh,
// geometry, meshio, io, sparse and itself.
//
// Manifold-harmonic basis of a mesh (Musialski et al. 2015 section 5.1; Vallet & Lévy 2008): the
// k eigenvectors of the cotan Laplacian with the smallest eigenvalues, Γk (#V by k), used as the
// reduced coordinates of the offsets (δ = Γk α).
//  - BasisKind::laplacian: L γ = λ γ, as in the paper; columns have ‖γ‖₂ = 1.
//  - BasisKind::mass: L γ = λ M γ with the lumped mass M; columns have γᵀMγ = 1. This is the
//    discretisation that converges to the Laplace–Beltrami eigenfunctions under refinement
//    (λ ≈ l(l+1)/R² on a sphere of radius R), independent of how densely a region is sampled.
// Assembly by geometry/cotan_laplacian.h and geometry/lumped_mass.h, eigenpairs by
// spectral/lanczos_eigensolver.h (nested dissection on the vertex positions competing with
// minimum degree for the factorisation's ordering).
#pragma once
#include <string>

#include "geometry/cotan_laplacian.h"
#include "mesh/mesh.h"
#include "spectral/lanczos_eigensolver.h"

namespace offsetopt {

enum class BasisKind { laplacian, mass };

const char* to_string(BasisKind kind);  // "laplacian" or "mass"
// Parses "laplacian" or "mass"; false for anything else.
bool parse_basis_kind(const std::string& text, BasisKind& kind);

struct ManifoldHarmonicsOptions {
  BasisKind kind = BasisKind::mass;
  CotanOptions cotan;
  LanczosOptions lanczos;
  std::string check() const;
};

// Eigenpairs of the mesh (1 <= k < #V); see LanczosResult for the fields and status.
LanczosResult manifold_harmonics(const Mesh& mesh, int k, const ManifoldHarmonicsOptions& options = {});

}  // namespace offsetopt
