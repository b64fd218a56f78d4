// src/skeleton (this is the folder's main header): the meso-skeleton by Laplacian contraction.
// It owns the contraction and its options, statuses and history; the Laplacian comes from
// src/geometry and the ordering and Cholesky of the normal equations from src/sparse. It may
// include util, optim, mesh, geometry, meshio, io, sparse and itself (not spectral).
//
// Meso-skeleton by Laplacian contraction (Au, Tai, Chu, Cohen-Or & Lee 2008, "Skeleton
// Extraction by Mesh Contraction"; the first stage of Tagliasacchi, Alhashim, Olson & Zhang 2012,
// "Mean Curvature Skeletons"; used by Musialski et al. 2015, section 4, for offset directions).
//
// Each step solves, in least squares, for the #V by 3 positions X':
//     [ W_L L_t ]        [     0     ]
//     [  W_H    ]  X' =  [ W_H X_t   ]
// L_t is the cotangent Laplacian (geometry/cotan_laplacian.h, PSD convention: L_ii >= 0,
// L_ij = -(cot a + cot b)/2) of the current geometry X_t; W_L is a scalar multiplied by s_L after
// every step; W_H = diag(W_H0 sqrt(A_i^0 / A_i^t)) with A_i the one-ring area of vertex i, so
// vertices whose neighbourhood has already collapsed are held in place. The normal equations
//     (W_L^2 L_t^T L_t + W_H^2) X' = W_H^2 X_t
// are symmetric positive definite (W_H > 0); their sparsity pattern (the 2-ring of the mesh) never
// changes, so it is analysed once (fill-reducing ordering, sparse/fill_reducing_ordering.h;
// supernodal structure, sparse/supernodal_cholesky.h) and refactorised numerically every step,
// the three coordinates solved as one 3-column right-hand side.
//
// The contraction runs in a normalised frame (bounding box centred at the origin, diagonal 1) so
// the weights do not depend on the model's units; the result is returned in the input frame.
// Connectivity is unchanged: contracted vertex i corresponds to input vertex i.
//
// Guards for triangles that collapse during contraction: cotangents are computed with |sin|
// floored (CotanOptions::sine_floor = cotan_sine_floor, so |cot| <= 1/floor), and one-ring areas
// are floored at area_ratio_floor times their initial value (so W_H <= W_H0 / sqrt(floor)).
// A failed factorisation or a non-finite solution ends the run with the last good positions.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "geometry/intrinsic_mollification.h"
#include "mesh/mesh.h"
#include "skeleton/coarse_copy.h"

namespace offsetopt {

struct ContractionOptions {
  // W_L0 = initial_laplacian_weight / sqrt(mean face area), measured in the normalised frame.
  // 0.1 reproduces the prototype's 1/(10 sqrt(A)); Au et al. state 1e-3 sqrt(A), which in a
  // diagonal-1 frame is orders of magnitude weaker and needs many more steps.
  double initial_laplacian_weight = 0.1;
  // ... but at least initial_laplacian_weight_per_area / (mean face area). The Laplacian term
  // contracts a feature of size l once W_L * (face area) / l^2 is of order one, so with W_L0
  // proportional to 1/sqrt(A) a finer mesh spends more steps before anything happens (an
  // icosphere of 40k vertices: volume still 0.92 after 3 steps); W_L0 proportional to 1/A
  // makes the step count independent of the resolution. 1e-3 leaves meshes up to a few
  // thousand vertices (face area above 1e-4 of the squared diagonal) on the 1/sqrt(A) rule.
  double initial_laplacian_weight_per_area = 1e-3;
  // s_L: W_L is multiplied by this after every step (Au et al.: 2; the prototype: 3).
  double laplacian_weight_growth = 3.0;
  // W_H0: the initial attraction weight of every vertex to its current position.
  double attraction_weight = 1.0;
  // Meso-skeleton stopping rule: stop after the first step whose enclosed volume is at most this
  // fraction of the input's. Measured on real models (armadillo, camel, elephant, dolphin,
  // fertility, horse, two kittens) and the demo meshes: the volume drops from about 0.2-0.7 to
  // 0.003-0.08 in one step once W_L is strong enough; stopping right after that drop left the
  // fewest vertices on the -n fallback of the offset field (4-12% on the real models), while
  // every further step collapsed thin parts onto curves and pulled their points off the medial
  // axis (17-55% two steps later). 0 disables the rule (full contraction up to max_steps; Au et
  // al. stop a full contraction at 1e-6).
  double stop_volume_ratio = 0.1;
  // Step cap. With the weights above the rule fires after 2-4 steps on every mesh tried
  // (spheres of 2.5k to 160k vertices: 4).
  int max_steps = 8;
  // Guards (see above).
  double cotan_sine_floor = 1e-3;
  // Intrinsic mollification of L_t (Sharp & Crane 2020, section 4.5; see
  // geometry/intrinsic_mollification.h), relative to the current mean edge length: contracted
  // triangles collapse to needles and segments, and mollified weights stay bounded where the sine
  // floor alone lets them grow to 1/floor. 0 leaves only the sine floor.
  double mollify_margin = kDefaultMollifyMargin;
  double area_ratio_floor = 1e-8;
  // Coarse to fine: above coarse_above vertices the contraction runs on a copy decimated to
  // coarse_vertices (skeleton/decimate_mesh.h; its vertices are input vertices), and every other
  // vertex takes the contracted position of the closest point of the coarse surface
  // (barycentric on its face). The skeleton is a low-frequency object: the factorisation of the
  // normal equations (2-ring pattern) grows as n^1.5 in flops (1.3e10 at 113k vertices, 5.2 CPU s
  // for the three steps) and would need about 2 GB at 10^6 vertices. 0 turns it off.
  int coarse_above = 60000;
  int coarse_vertices = 30000;
  // Observer (a progress display): called after each step with an estimate of the fraction done,
  // in [0, 1). It cannot change any result.
  std::function<void(double)> on_progress;
  // Threads for the ordering and the factorisations (1..256); the result is bit for bit the
  // same for any count.
  int threads = 2;

  // Empty when valid, else the first out-of-range field (laplacian_contraction throws it as
  // std::invalid_argument).
  std::string check() const;
};

enum class ContractionStatus {
  volume_ratio_reached,   // stop_volume_ratio met
  step_cap,               // max_steps done
  factorization_failed,   // numerical breakdown; positions are the last good step's
  degenerate_input,       // no faces, zero-size bounding box or zero area: nothing done
};

const char* to_string(ContractionStatus status);

struct ContractionStep {
  double laplacian_weight = 0.0;  // W_L used in this step
  double area_ratio = 1.0;        // surface area after the step / input area
  double volume_ratio = 1.0;      // enclosed (signed) volume after the step / input volume
};

struct ContractionResult {
  Vertices V;  // contracted positions, #V by 3, input frame
  ContractionStatus status = ContractionStatus::degenerate_input;
  int steps = 0;
  double area_ratio = 1.0;
  double volume_ratio = 1.0;
  std::vector<ContractionStep> history;  // one entry per completed step
  // The fill-reducing ordering chosen for the normal equations (sparse/fill_reducing_ordering.h)
  // and its predicted cost: flops = sum of squared column counts of the factor.
  std::string ordering;
  double predicted_factor_flops = 0.0;
  double predicted_factor_nonzeros = 0.0;
  // The vertices of the mesh that was contracted: the input's, or the coarse copy's.
  long long contracted_vertices = 0;
};

ContractionResult laplacian_contraction(const Vertices& V, const Faces& F, const ContractionOptions& options = {});

// The contraction of a coarse copy (skeleton/coarse_copy.h) carried back to its input vertices:
// what laplacian_contraction does above coarse_above vertices, for a caller that shares the copy
// with other stages. Step counts and ratios are the copy's.
ContractionResult laplacian_contraction_of_copy(const CoarseCopy& copy, const ContractionOptions& options = {});

}  // namespace offsetopt
