#include "optim/bounded_simplex.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/LU>

#include "optim/paired_pricing.h"

namespace offsetopt {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kCandidatesPerPass = 64;
constexpr int kPricingWindow = 1024;  // columns priced per window, at least (an eighth of them when more)

// A breakpoint of the dual ratio test: θ, −|α|, column, taken in lexicographic order (the same
// comparisons as on an array of the three, fewer instructions).
struct Breakpoint {
  double theta, minus_alpha;
  int column;
  bool earlier(const Breakpoint& o) const {
    if (theta < o.theta) return true;
    if (o.theta < theta) return false;
    if (minus_alpha < o.minus_alpha) return true;
    if (o.minus_alpha < minus_alpha) return false;
    return column < o.column;
  }
};

// The breakpoints that surely hold the entering one, moved to the front; their count. The ratio
// test takes breakpoints in increasing θ while `worst` less their |α|·range stays positive; those
// whose θ has a binary exponent at most the one where that sum surely passes `worst` (summed by
// exponent, with room for its rounding) come before all others in the test's order, so it takes
// the same ones in the same order from a heap of these alone (most steps flip a tenth of the
// breakpoints or fewer). All of them (breaks.size(), the order untouched) when the sum does not
// surely pass or a θ is not finite. `weight` is scratch.
std::size_t entering_prefix(std::vector<Breakpoint>& breaks, double worst, const std::vector<double>& lo, const std::vector<double>& hi,
                            std::vector<double>& weight) {
  const auto exponent = [](double theta) {
    std::uint64_t bits;
    std::memcpy(&bits, &theta, sizeof bits);
    return static_cast<int>((bits >> 52) & 0x7FF);  // θ >= 0 (or −0): the order of the exponents is θ's
  };
  weight.assign(2048, 0.0);
  for (const Breakpoint& b : breaks) {
    const int e = exponent(b.theta);
    if (e == 0x7FF) return breaks.size();
    weight[static_cast<std::size_t>(e)] -= b.minus_alpha * (hi[static_cast<std::size_t>(b.column)] - lo[static_cast<std::size_t>(b.column)]);
  }
  double total = 0.0;
  int last = -1;
  for (int e = 0; e < 0x7FF && last < 0; ++e) {
    total += weight[static_cast<std::size_t>(e)];
    if (total - worst > 1e-8 * (total + worst)) last = e;
  }
  if (last < 0) return breaks.size();
  const auto end = std::partition(breaks.begin(), breaks.end(), [&](const Breakpoint& b) { return exponent(b.theta) <= last; });
  return static_cast<std::size_t>(end - breaks.begin());
}

// The simplex state over n structural columns, m slacks and m artificials (index n + i and
// n + m + i for row i).
class Simplex {
 public:
  Simplex(const LinearProgram& lp, const BoundedSimplexOptions& o) : lp_(lp), o_(o) {
    n_ = static_cast<int>(lp.A.cols());
    m_ = static_cast<int>(lp.A.rows());
    const int total = n_ + 2 * m_;
    lo_.assign(static_cast<std::size_t>(total), 0.0);
    hi_.assign(static_cast<std::size_t>(total), 0.0);
    value_.assign(static_cast<std::size_t>(total), 0.0);
    cost_.assign(static_cast<std::size_t>(total), 0.0);
    position_.assign(static_cast<std::size_t>(total), -1);
    sigma_.assign(static_cast<std::size_t>(m_), 1.0);
    for (int j = 0; j < n_; ++j) {
      lo_[j] = lp.lower(j);
      hi_[j] = lp.upper(j);
    }
    for (int i = 0; i < m_; ++i) {
      const RowSense s = lp.sense[static_cast<std::size_t>(i)];
      lo_[n_ + i] = s == RowSense::greater_equal ? -kInf : 0.0;
      hi_[n_ + i] = s == RowSense::less_equal ? kInf : 0.0;
    }
  }

  // The dual method, then the primal phase 2 from its basis; false when the dual method gave up
  // (r keeps its iteration counts).
  bool solve_from_dual(LpResult& r, const std::vector<std::int8_t>* start, const std::vector<int>* start_basis) {
    if (!solve_dual(r, start, start_basis)) return false;
    r.phase1_iterations = r.iterations;
    if (!refactor()) return false;
    const LpStatus s = run(r);
    if (s != LpStatus::optimal) return false;
    r.y = duals();
    finish(r, s, "");
    return true;
  }

  LpResult solve(const std::vector<std::int8_t>* start) {
    LpResult r;
    for (int j = 0; j < n_; ++j) {
      const bool up = start && (*start)[static_cast<std::size_t>(j)] == 1 && std::isfinite(hi_[j]);
      value_[j] = up ? hi_[j] : std::isfinite(lo_[j]) ? lo_[j] : std::isfinite(hi_[j]) ? hi_[j] : 0.0;
    }
    // Slack basic where the start satisfies the row, else an artificial takes up the residual.
    Eigen::VectorXd residual = lp_.b;
    for (int j = 0; j < n_; ++j)
      if (value_[j] != 0.0) residual -= value_[j] * lp_.A.col(j);
    basis_.assign(static_cast<std::size_t>(m_), -1);
    bool phase1 = false;
    for (int i = 0; i < m_; ++i) {
      const int s = n_ + i, a = n_ + m_ + i;
      const double clipped = std::min(std::max(residual(i), lo_[s]), hi_[s]);
      if (clipped == residual(i)) {
        set_basic(i, s);
        value_[s] = residual(i);
      } else {
        value_[s] = clipped;
        sigma_[i] = residual(i) > clipped ? 1.0 : -1.0;
        hi_[a] = kInf;
        cost_[a] = -1.0;
        value_[a] = std::fabs(residual(i) - clipped);
        set_basic(i, a);
        phase1 = true;
      }
    }
    if (!refactor()) return finish(r, LpStatus::numerical, "singular starting basis");
    if (phase1) {
      const LpStatus s = run(r);
      r.phase1_iterations = r.iterations;
      if (s != LpStatus::optimal) return finish(r, s == LpStatus::unbounded ? LpStatus::numerical : s, "phase 1 did not end");
      double artificial = 0.0;
      for (int i = 0; i < m_; ++i) artificial += value_[n_ + m_ + i];
      if (artificial > o_.feasibility_tolerance * std::max(1, m_)) {
        r.y = duals();
        return finish(r, LpStatus::infeasible, "the rows admit no point in the box", false);
      }
    }
    for (int i = 0; i < m_; ++i) {  // artificials stay at 0 (basic ones leave when they block)
      hi_[n_ + m_ + i] = 0.0;
      cost_[n_ + m_ + i] = 0.0;
    }
    for (int j = 0; j < n_; ++j) cost_[j] = lp_.c(j);
    if (!refactor()) return finish(r, LpStatus::numerical, "singular basis after phase 1");
    const LpStatus s = run(r);
    r.y = duals();
    return finish(r, s, s == LpStatus::optimal ? "" : s == LpStatus::unbounded ? "the objective is unbounded" : "stopped early");
  }

 private:
  void set_basic(int row, int var) {
    basis_[static_cast<std::size_t>(row)] = var;
    position_[static_cast<std::size_t>(var)] = row;
  }

  // Column `var` of [A I diag(σ)] times v (v of length m).
  double column_dot(int var, const Eigen::VectorXd& v) const {
    if (var < n_) return lp_.A.col(var).dot(v);
    if (var < n_ + m_) return v(var - n_);
    return sigma_[static_cast<std::size_t>(var - n_ - m_)] * v(var - n_ - m_);
  }
  Eigen::VectorXd binv_column(int var) const {
    if (var < n_) return binv_ * lp_.A.col(var);
    if (var < n_ + m_) return binv_.col(var - n_);
    return sigma_[static_cast<std::size_t>(var - n_ - m_)] * binv_.col(var - n_ - m_);
  }
  Eigen::VectorXd duals() const {
    Eigen::VectorXd cb(m_);
    for (int i = 0; i < m_; ++i) cb(i) = cost_[static_cast<std::size_t>(basis_[static_cast<std::size_t>(i)])];
    return binv_.transpose() * cb;
  }

  // B⁻¹ from scratch and the basic values from the nonbasic ones.
  bool refactor() {
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(m_, m_);
    for (int i = 0; i < m_; ++i) {
      const int var = basis_[static_cast<std::size_t>(i)];
      if (var < n_) B.col(i) = lp_.A.col(var);
      else if (var < n_ + m_) B(var - n_, i) = 1.0;
      else B(var - n_ - m_, i) = sigma_[static_cast<std::size_t>(var - n_ - m_)];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(B);
    if (m_ > 0 && !lu.isInvertible()) return false;
    binv_ = m_ > 0 ? Eigen::MatrixXd(lu.inverse()) : Eigen::MatrixXd(0, 0);
    Eigen::VectorXd rhs = lp_.b;
    for (int var = 0; var < n_ + 2 * m_; ++var) {
      if (position_[static_cast<std::size_t>(var)] >= 0 || value_[var] == 0.0) continue;
      if (var < n_) rhs -= value_[var] * lp_.A.col(var);
      else if (var < n_ + m_) rhs(var - n_) -= value_[var];
      else rhs(var - n_ - m_) -= sigma_[static_cast<std::size_t>(var - n_ - m_)] * value_[var];
    }
    const Eigen::VectorXd xb = binv_ * rhs;
    for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] = xb(i);
    pivots_since_refactor_ = 0;
    flips_since_refactor_ = 0;
    return xb.allFinite();
  }

  // The simplex loop on the current costs: optimal, unbounded, iteration_cap or numerical.
  LpStatus run(LpResult& r) {
    const double tol = o_.optimality_tolerance;
    int degenerate_run = 0;
    bool bland = false;
    std::vector<std::pair<double, int>> candidates;
    const int total = n_ + 2 * m_;
    // Partial pricing: a pass prices windows of columns, from where the last one stopped, until
    // one holds candidates; optimality needs a whole cycle without any. Bland's rule prices from
    // the first column.
    const int window = std::max(kPricingWindow, total / 8);
    Eigen::VectorXd priced;
    for (;;) {
      const Eigen::VectorXd y = duals();
      ++r.pricing_passes;
      candidates.clear();
      if (bland) window_start_ = 0;
      for (int scanned = 0; scanned < total && candidates.empty();) {
        const int begin = window_start_, end = bland ? total : std::min(total, begin + window);
        const int structural_end = std::min(end, n_);
        if (structural_end > begin) priced.noalias() = lp_.A.middleCols(begin, structural_end - begin).transpose() * y;
        for (int var = begin; var < end; ++var) {
          if (position_[static_cast<std::size_t>(var)] >= 0 || lo_[var] == hi_[var]) continue;
          const double d = cost_[var] - (var < n_ ? priced(var - begin) : column_dot(var, y));
          const bool up = d > tol && value_[var] < hi_[var], down = d < -tol && value_[var] > lo_[var];
          if (!up && !down) continue;
          candidates.emplace_back(std::fabs(d) * (up ? 1.0 : -1.0), var);
          if (bland) break;  // the lowest attractive index
        }
        scanned += end - begin;
        window_start_ = end == total ? 0 : end;
        if (bland) break;
      }
      if (candidates.empty()) {
        // Confirm on a fresh factorisation before claiming optimality.
        if (pivots_since_refactor_ == 0 && flips_since_refactor_ == 0) return LpStatus::optimal;
        if (!refactor()) return LpStatus::numerical;
        continue;
      }
      // The best few in order (a full sort of thousands of candidates per pass costs more than
      // the pass); when they all flip, the next pass brings the rest.
      const auto first = [](const std::pair<double, int>& a, const std::pair<double, int>& b) {
        const double fa = std::fabs(a.first), fb = std::fabs(b.first);
        return fa != fb ? fa > fb : a.second < b.second;
      };
      const std::size_t keep = std::min<std::size_t>(candidates.size(), kCandidatesPerPass);
      std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep), candidates.end(), first);
      candidates.resize(keep);
      // After a pivot the duals change, but only the remaining candidates are priced again (m
      // each, not a pass over every column): a pass then serves many pivots, which matters when
      // most steps are pivots (a few rows, many columns entering and leaving between 0 and 1).
      Eigen::VectorXd y_now = y;
      bool duals_moved = false;
      for (auto& [signed_d, var] : candidates) {
        if (duals_moved) {
          if (position_[static_cast<std::size_t>(var)] >= 0) continue;
          const double d = cost_[var] - column_dot(var, y_now);
          const bool up = d > tol && value_[var] < hi_[var], down = d < -tol && value_[var] > lo_[var];
          if (!up && !down) continue;
          signed_d = std::fabs(d) * (up ? 1.0 : -1.0);
        }
        if (r.iterations >= o_.max_iterations) return LpStatus::iteration_cap;
        ++r.iterations;
        const double dir = signed_d > 0.0 ? 1.0 : -1.0;
        const Eigen::VectorXd alpha = binv_column(var);
        int leave = -1;
        const double theta_basis = ratio_test(alpha, dir, bland, leave);
        const double flip = hi_[var] - lo_[var];
        if (leave < 0 && !std::isfinite(flip)) return LpStatus::unbounded;
        if (leave < 0 || flip <= theta_basis) {
          // Bound flip: the duals stay, so the next candidate needs no new pricing.
          for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] -= dir * flip * alpha(i);
          value_[var] = dir > 0.0 ? hi_[var] : lo_[var];
          ++flips_since_refactor_;
          continue;
        }
        const double theta = theta_basis;
        const bool degenerate = theta * std::fabs(signed_d) <= 1e-14;
        degenerate_run = degenerate ? degenerate_run + 1 : 0;
        const bool was_bland = bland;
        bland = degenerate_run >= o_.degenerate_before_bland;
        pivot(var, leave, alpha, dir, theta);
        if (pivots_since_refactor_ >= o_.refactor_every && !refactor()) return LpStatus::numerical;
        if (bland || was_bland) break;  // Bland's rule prices every column again
        y_now = duals();
        duals_moved = true;
      }
    }
  }

  // The dual simplex with bound flips, from the slack basis: every column starts at the bound its
  // cost favours (`start` breaks ties), so the basis is dual feasible, and each step lets the most
  // infeasible basic variable leave, flipping every column whose reduced cost changes sign before
  // the entering one's (Maros 2003; Koberstein 2005, "bound flipping ratio test"): one pass over
  // the columns moves many of them, where the primal method pivots about once per column.
  // Infinite bounds are replaced by ±kArtificialBound while it runs. It ends primal feasible and
  // hands over to the primal method's phase 2 (which confirms optimality on a fresh
  // factorisation), or returns false: infeasible, stalled, or stopped on an artificial bound.
  bool solve_dual(LpResult& r, const std::vector<std::int8_t>* start, const std::vector<int>* start_basis) {
    constexpr double kArtificialBound = 1e3;
    // The variables with an infinite bound (few: a margin column, the slacks) and their own bounds.
    struct Replaced {
      int var;
      double lo, hi;
    };
    std::vector<Replaced> replaced;
    const auto restore = [&] {
      for (const Replaced& b : replaced) {
        lo_[b.var] = b.lo;
        hi_[b.var] = b.hi;
      }
    };
    for (int var = 0; var < n_ + m_; ++var) {
      if (std::isfinite(lo_[var]) && std::isfinite(hi_[var])) continue;
      replaced.push_back({var, lo_[var], hi_[var]});
      if (!std::isfinite(lo_[var])) lo_[var] = -kArtificialBound;
      if (!std::isfinite(hi_[var])) hi_[var] = kArtificialBound;
    }
    const double dtol = o_.optimality_tolerance, ftol = o_.feasibility_tolerance, ptol = o_.pivot_tolerance;
    for (int j = 0; j < n_; ++j) {
      cost_[j] = lp_.c(j);
      const bool up = cost_[j] > dtol || (cost_[j] >= -dtol && start && (*start)[static_cast<std::size_t>(j)] == 1);
      value_[j] = up ? hi_[j] : lo_[j];
    }
    // The given basis when it is one (m distinct columns or slacks whose matrix is regular), else
    // the slack basis. Nonbasic slacks rest at 0, a bound of every row's slack.
    bool started = false;
    if (start_basis && static_cast<int>(start_basis->size()) == m_) {
      std::vector<char> seen(static_cast<std::size_t>(n_ + m_), 0);
      bool valid = true;
      for (int var : *start_basis) {
        valid = valid && var >= 0 && var < n_ + m_ && !seen[static_cast<std::size_t>(var)];
        if (valid) seen[static_cast<std::size_t>(var)] = 1;
      }
      if (valid) {
        // refactor() sets the basic values only: those are the ones to put back if it fails.
        std::vector<double> placed(static_cast<std::size_t>(m_));
        for (int i = 0; i < m_; ++i) placed[static_cast<std::size_t>(i)] = value_[(*start_basis)[static_cast<std::size_t>(i)]];
        basis_.assign(static_cast<std::size_t>(m_), -1);
        for (int i = 0; i < m_; ++i) set_basic(i, (*start_basis)[static_cast<std::size_t>(i)]);
        started = refactor();
        if (!started) {
          for (int i = 0; i < m_; ++i) {
            const int var = (*start_basis)[static_cast<std::size_t>(i)];
            position_[static_cast<std::size_t>(var)] = -1;
            value_[var] = placed[static_cast<std::size_t>(i)];
          }
        }
      }
    }
    if (!started) {
      basis_.assign(static_cast<std::size_t>(m_), -1);
      for (int i = 0; i < m_; ++i) set_basic(i, n_ + i);
      if (!refactor()) {
        restore();
        return false;
      }
    } else {
      // Dual feasible first: every nonbasic variable on the bound its reduced cost favours (the
      // loop below does this only when some row is violated; a basis that is already primal
      // feasible would otherwise go to the primal method as it is).
      const Eigen::VectorXd y = duals();
      const Eigen::VectorXd priced_y = lp_.A.transpose() * y;
      bool moved_any = false;
      for (int var = 0; var < n_ + m_; ++var) {
        if (position_[static_cast<std::size_t>(var)] >= 0 || lo_[var] == hi_[var]) continue;
        const double d = cost_[var] - (var < n_ ? priced_y(var) : y(var - n_));
        const double to = d > dtol ? hi_[var] : d < -dtol ? lo_[var] : value_[var];
        if (to == value_[var]) continue;
        value_[var] = to;
        moved_any = true;
      }
      if (moved_any && !refactor()) {
        restore();
        return false;
      }
    }
    const int max_pivots = 20 * m_ + 200;
    int pivots = 0;
    std::vector<std::pair<double, int>> flips;   // (|α|, column) of the pass's breakpoints
    std::vector<Breakpoint> breaks;
    std::vector<double> weight_by_exponent;
    Eigen::MatrixXd yr(m_, 2);
    Eigen::MatrixXd priced;
    std::optional<PairedPricing> paired;  // packed at the first dual step (else Eigen's own product)
    const bool pairs_priced = PairedPricing::eligible(m_, n_);
    for (;;) {
      if (r.iterations >= o_.max_iterations || pivots >= max_pivots) break;
      // The leaving row: the largest bound violation among the basic variables.
      int row = -1;
      double worst = ftol;
      for (int i = 0; i < m_; ++i) {
        const int var = basis_[static_cast<std::size_t>(i)];
        const double v = value_[var], off = std::max(lo_[var] - v, v - hi_[var]);
        if (off > worst) {
          worst = off;
          row = i;
        }
      }
      if (row < 0) {
        if (pivots_since_refactor_ == 0 && flips_since_refactor_ == 0) {
          // Feasible: no column may rest on an artificial bound.
          for (const Replaced& b : replaced)
            if (position_[static_cast<std::size_t>(b.var)] < 0 &&
                ((value_[b.var] == lo_[b.var] && !std::isfinite(b.lo)) || (value_[b.var] == hi_[b.var] && !std::isfinite(b.hi)))) {
              restore();
              return false;
            }
          restore();
          return true;
        }
        if (!refactor()) break;
        continue;
      }
      const int leaving = basis_[static_cast<std::size_t>(row)];
      const bool below = value_[leaving] < lo_[leaving];
      const double sigma = below ? -1.0 : 1.0;
      yr.col(0) = duals();
      yr.col(1) = binv_.row(row).transpose();
      if (pairs_priced && !paired) paired.emplace(lp_.A);
      if (paired) {
        paired->price(yr, priced);  // Aᵀ[y r], the product's bits
      } else {
        priced.noalias() = lp_.A.transpose() * yr;
      }
      // Breakpoints: a column at its lower bound (reduced cost d ≤ 0) turns when σα > 0, one at
      // its upper bound when σα < 0; θ = |d| / |α|. Columns whose cost has the wrong sign
      // (rounding) are put on the right bound first.
      breaks.clear();
      Eigen::VectorXd moved = Eigen::VectorXd::Zero(m_);
      int corrected = 0;
      for (int var = 0; var < n_ + m_; ++var) {
        if (position_[static_cast<std::size_t>(var)] >= 0 || lo_[var] == hi_[var]) continue;
        const double d = cost_[var] - (var < n_ ? priced(var, 0) : yr(var - n_, 0));
        const double a = var < n_ ? priced(var, 1) : yr(var - n_, 1);
        const bool at_lower = value_[var] == lo_[var];
        if ((at_lower && d > dtol) || (!at_lower && d < -dtol)) {
          const double to = at_lower ? hi_[var] : lo_[var];
          if (var < n_) moved += (to - value_[var]) * lp_.A.col(var);
          else moved(var - n_) += to - value_[var];
          value_[var] = to;
          ++corrected;
          continue;
        }
        const double s = sigma * a;
        if (at_lower ? s > ptol : s < -ptol) breaks.push_back({std::max(at_lower ? -d : d, 0.0) / std::fabs(s), -std::fabs(s), var});
      }
      if (corrected > 0) {
        const Eigen::VectorXd shift = binv_ * moved;
        for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] -= shift(i);
        flips_since_refactor_ += corrected;
        r.iterations += corrected;
        continue;
      }
      if (breaks.empty()) break;  // no column can restore the row: infeasible (the primal method proves it)
      // In increasing θ (ties: the larger |α|, then the lower index), flip while the violation left
      // stays positive; the column where it would not enters.
      const auto later = [](const Breakpoint& a, const Breakpoint& b) { return b.earlier(a); };
      const std::size_t prefix = entering_prefix(breaks, worst, lo_, hi_, weight_by_exponent);
      std::size_t heap_begin = 0, heap_end = prefix;  // the heap: breaks[heap_begin, heap_end)
      bool rest_left = prefix < breaks.size();
      std::make_heap(breaks.begin(), breaks.begin() + static_cast<std::ptrdiff_t>(prefix), later);
      double slope = worst;
      int enter = -1;
      moved.setZero();
      int flipped = 0;
      for (;;) {
        if (heap_end == heap_begin) {
          if (!rest_left) break;
          rest_left = false;  // (not expected) the others, all later in the order
          heap_begin = prefix;
          heap_end = breaks.size();
          std::make_heap(breaks.begin() + static_cast<std::ptrdiff_t>(heap_begin), breaks.end(), later);
        }
        std::pop_heap(breaks.begin() + static_cast<std::ptrdiff_t>(heap_begin), breaks.begin() + static_cast<std::ptrdiff_t>(heap_end),
                      later);
        const Breakpoint b = breaks[--heap_end];
        const int var = b.column;
        const double range = hi_[var] - lo_[var], next = slope + b.minus_alpha * range;
        if (next <= 0.0) {
          enter = var;
          break;
        }
        slope = next;
        const double to = value_[var] == lo_[var] ? hi_[var] : lo_[var];
        if (var < n_) moved += (to - value_[var]) * lp_.A.col(var);
        else moved(var - n_) += to - value_[var];
        value_[var] = to;
        ++flipped;
      }
      if (flipped > 0) {
        const Eigen::VectorXd shift = binv_ * moved;
        for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] -= shift(i);
        flips_since_refactor_ += flipped;
        r.iterations += flipped;
      }
      if (enter < 0) break;  // every breakpoint flipped and the row still violated: infeasible
      const Eigen::VectorXd alpha = binv_column(enter);
      if (std::fabs(alpha(row)) <= ptol) break;
      const double target = below ? lo_[leaving] : hi_[leaving];
      const double step = (value_[leaving] - target) / alpha(row);
      for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] -= step * alpha(i);
      value_[enter] += step;
      value_[leaving] = target;
      exchange(enter, row, alpha);
      ++pivots;
      ++r.iterations;
      ++r.pricing_passes;
      if (pivots_since_refactor_ >= o_.refactor_every && !refactor()) break;
    }
    restore();
    return false;
  }

  // Harris's two-pass ratio test; returns the step and the leaving row (−1: nothing blocks).
  double ratio_test(const Eigen::VectorXd& alpha, double dir, bool bland, int& leave) const {
    const double ftol = o_.feasibility_tolerance, ptol = o_.pivot_tolerance;
    auto room = [&](int i, double rate, double slack_tol) {
      const int var = basis_[static_cast<std::size_t>(i)];
      if (rate < 0.0) return std::isfinite(lo_[var]) ? (value_[var] - lo_[var] + slack_tol) / -rate : kInf;
      return std::isfinite(hi_[var]) ? (hi_[var] - value_[var] + slack_tol) / rate : kInf;
    };
    double bound = kInf;
    for (int i = 0; i < m_; ++i) {
      const double rate = -dir * alpha(i);
      if (std::fabs(rate) <= ptol) continue;
      bound = std::min(bound, room(i, rate, ftol));
    }
    leave = -1;
    if (!std::isfinite(bound)) return kInf;
    double best_rate = 0.0, step = kInf;
    for (int i = 0; i < m_; ++i) {
      const double rate = -dir * alpha(i);
      if (std::fabs(rate) <= ptol) continue;
      const double t = room(i, rate, 0.0);
      if (t > bound) continue;
      const int var = basis_[static_cast<std::size_t>(i)];
      const bool better = leave < 0 || (bland ? var < basis_[static_cast<std::size_t>(leave)]
                                              : std::fabs(rate) > best_rate ||
                                                    (std::fabs(rate) == best_rate && var < basis_[static_cast<std::size_t>(leave)]));
      if (better) {
        leave = i;
        best_rate = std::fabs(rate);
        step = std::max(t, 0.0);
      }
    }
    return step;
  }

  void pivot(int enter, int row, const Eigen::VectorXd& alpha, double dir, double theta) {
    for (int i = 0; i < m_; ++i) value_[basis_[static_cast<std::size_t>(i)]] -= dir * theta * alpha(i);
    value_[enter] += dir * theta;
    const int leaving = basis_[static_cast<std::size_t>(row)];
    // The leaving column rests on the bound it reached.
    value_[leaving] = -dir * alpha(row) < 0.0 ? lo_[leaving] : hi_[leaving];
    exchange(enter, row, alpha);
  }

  // The basis exchange and B⁻¹'s rank-one update; values are the caller's.
  void exchange(int enter, int row, const Eigen::VectorXd& alpha) {
    const int leaving = basis_[static_cast<std::size_t>(row)];
    position_[static_cast<std::size_t>(leaving)] = -1;
    set_basic(row, enter);
    const double p = alpha(row);
    binv_.row(row) /= p;
    for (int i = 0; i < m_; ++i)
      if (i != row && alpha(i) != 0.0) binv_.row(i) -= alpha(i) * binv_.row(row);
    ++pivots_since_refactor_;
  }

  LpResult& finish(LpResult& r, LpStatus status, const std::string& message, bool set_y = true) {
    r.status = status;
    r.message = message;
    r.x.resize(n_);
    for (int j = 0; j < n_; ++j) r.x(j) = value_[j];
    r.objective = lp_.c.size() == n_ ? lp_.c.dot(r.x) : 0.0;
    if (set_y && r.y.size() != m_) r.y = binv_.rows() == m_ ? duals() : Eigen::VectorXd::Zero(m_);
    r.basis.clear();
    if (status == LpStatus::optimal) r.basis = basis_;
    return r;
  }

  const LinearProgram& lp_;
  const BoundedSimplexOptions& o_;
  int n_ = 0, m_ = 0;
  std::vector<double> lo_, hi_, value_, cost_, sigma_;
  std::vector<int> position_, basis_;
  Eigen::MatrixXd binv_;
  int pivots_since_refactor_ = 0, flips_since_refactor_ = 0;
  int window_start_ = 0;
};

// A's entries all finite: x · 0 is 0 for a finite x and NaN for an infinite or NaN one, and NaN
// stays in the sum (allFinite() compares A − A with itself, a temporary of A's size).
bool all_finite(const Eigen::MatrixXd& A) { return (A.array() * 0.0).sum() == 0.0; }

}  // namespace

const char* to_string(LpStatus status) {
  switch (status) {
    case LpStatus::optimal: return "optimal";
    case LpStatus::infeasible: return "infeasible";
    case LpStatus::unbounded: return "unbounded";
    case LpStatus::iteration_cap: return "iteration_cap";
    case LpStatus::numerical: return "numerical";
  }
  return "numerical";
}

std::string BoundedSimplexOptions::check() const {
  if (max_iterations < 1) return "the iteration cap must be >= 1";
  if (refactor_every < 1) return "refactor_every must be >= 1";
  if (!(feasibility_tolerance > 0.0 && feasibility_tolerance < 1e-2)) return "the feasibility tolerance must be in (0, 1e-2)";
  if (!(optimality_tolerance > 0.0 && optimality_tolerance < 1e-2)) return "the optimality tolerance must be in (0, 1e-2)";
  if (!(pivot_tolerance > 0.0 && pivot_tolerance < 1e-2)) return "the pivot tolerance must be in (0, 1e-2)";
  if (degenerate_before_bland < 1) return "degenerate_before_bland must be >= 1";
  return "";
}

LpResult bounded_simplex(const LinearProgram& lp, const BoundedSimplexOptions& options, const std::vector<std::int8_t>* start,
                         const std::vector<int>* start_basis) {
  LpResult r;
  const Eigen::Index m = lp.A.rows(), n = lp.A.cols();
  std::string problem = options.check();
  if (problem.empty() && (lp.b.size() != m || static_cast<Eigen::Index>(lp.sense.size()) != m || lp.c.size() != n ||
                          lp.lower.size() != n || lp.upper.size() != n || (start && static_cast<Eigen::Index>(start->size()) != n)))
    problem = "the sizes of A, b, sense, c, lower, upper (and start) disagree";
  for (Eigen::Index j = 0; problem.empty() && j < n; ++j)
    if (!(lp.lower(j) <= lp.upper(j)) || lp.lower(j) == kInf || lp.upper(j) == -kInf) problem = "a column has empty bounds";
  if (problem.empty() && (!all_finite(lp.A) || !lp.b.allFinite() || !lp.c.allFinite())) problem = "A, b and c must be finite";
  if (!problem.empty()) {
    r.status = LpStatus::numerical;
    r.message = problem;
    r.x = Eigen::VectorXd::Zero(n);
    r.y = Eigen::VectorXd::Zero(m);
    return r;
  }
  if (options.dual) {
    LpResult dual;
    Simplex first(lp, options);
    if (first.solve_from_dual(dual, start, start_basis)) return dual;
    // Given up: the primal method from the start, with what is left of the iteration cap.
    BoundedSimplexOptions rest = options;
    rest.max_iterations = std::max(1, options.max_iterations - dual.iterations);
    Simplex simplex(lp, rest);
    LpResult primal = simplex.solve(start);
    primal.iterations += dual.iterations;
    primal.pricing_passes += dual.pricing_passes;
    return primal;
  }
  Simplex simplex(lp, options);
  return simplex.solve(start);
}

double farkas_gap(const LinearProgram& lp, const Eigen::VectorXd& y) {
  const Eigen::Index m = lp.A.rows();
  for (Eigen::Index i = 0; i < m; ++i) {
    const RowSense s = lp.sense[static_cast<std::size_t>(i)];
    if ((s == RowSense::less_equal && y(i) < 0.0) || (s == RowSense::greater_equal && y(i) > 0.0)) return -kInf;
  }
  const Eigen::VectorXd w = lp.A.transpose() * y;
  double gap = -lp.b.dot(y);
  for (Eigen::Index j = 0; j < w.size(); ++j) {
    if (w(j) == 0.0) continue;
    const double bound = w(j) > 0.0 ? lp.lower(j) : lp.upper(j);
    if (!std::isfinite(bound)) return -kInf;
    gap += w(j) * bound;
  }
  return gap;
}

}  // namespace offsetopt
