#include "spectral/manifold_harmonics.h"

#include "geometry/lumped_mass.h"

namespace offsetopt {

const char* to_string(BasisKind kind) { return kind == BasisKind::laplacian ? "laplacian" : "mass"; }

bool parse_basis_kind(const std::string& text, BasisKind& kind) {
  if (text == "laplacian") {
    kind = BasisKind::laplacian;
    return true;
  }
  if (text == "mass") {
    kind = BasisKind::mass;
    return true;
  }
  return false;
}

std::string ManifoldHarmonicsOptions::check() const {
  if (std::string problem = cotan.check(); !problem.empty()) return problem;
  return lanczos.check();
}

LanczosResult manifold_harmonics(const Mesh& mesh, int k, const ManifoldHarmonicsOptions& options) {
  if (std::string problem = options.check(); !problem.empty()) {
    LanczosResult result;
    result.status = LanczosStatus::invalid_input;
    result.message = problem;
    return result;
  }
  const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F, options.cotan);
  const Eigen::VectorXd mass = options.kind == BasisKind::mass ? lumped_mass(mesh.V, mesh.F) : Eigen::VectorXd();
  return lanczos_eigensolver(L, mass, k, options.lanczos, &mesh.V);
}

}  // namespace offsetopt
