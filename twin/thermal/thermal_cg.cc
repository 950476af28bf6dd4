// The linear solver of one multirate level's backward-Euler system: conjugate gradients preconditioned by one
// multigrid V-cycle for large stiff systems, else by symmetric Gauss-Seidel (Eisenstat's implementation) or, for
// systems too large to solve on one thread, the diagonal (docs/THERMAL.md, "Discretisation").
#include <algorithm>
#include <array>
#include <cmath>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

constexpr int kMaxIterations = 2000;
// Systems of at least this many cells are preconditioned by multigrid, smaller ones by their diagonal.
constexpr std::size_t kMultigridCells = 512;
// ... and stiff: conduction (the sum of the face conductances) at least this many times the storage and losses
// (the rest of the diagonal), summed over the system. Milder systems converge in a few diagonally preconditioned
// iterations, each a fraction of a V-cycle's cost (at 30, aluminium's 1 s and micro steps took 24 of them a solve,
// about 7 and 17 V-cycles now; docs/THERMAL.md, "Benchmark").
constexpr double kMultigridStiffness = 10.0;

double Sum(const std::vector<double>& partial) {
  double total = 0.0;
  for (double v : partial) total += v;
  return total;
}

// Conjugate gradients on the level's system from the scratch's x and r = b - A x, preconditioned by one multigrid
// V-cycle (`multigrid`) or the diagonal, until every Jacobi correction |r_i / A_ii| is below the tolerance. Each
// iteration takes one stencil product: p = z + beta p and A p = A z + beta (A p)_old in one pass. Returns the
// iterations. With `same_faces` the cells are those of the last solve, whose grid coordinates L.ijk still holds.
// With `fixed` > 0, exactly that many iterations (a run following choices), unless the search direction vanishes.
int Iterate(ThermalState& s, LevelSystem& L, bool multigrid, bool same_faces, int fixed) {
  LevelScratch& w = L.scratch;
  const PaddedStencil& a = w.stencil;
  const std::size_t n = L.cells.size();
  double* x = w.x.data();
  double* p = w.p.data();
  double* r = w.r.data();
  double* z = w.z.data();
  double* ap = w.ap.data();
  const double* inv = w.inverse_diagonal.data();
  const double* stop = w.stop.data();
  if (multigrid && !(same_faces && L.ijk.size() == n)) {
    L.ijk.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      L.ijk[i] = s.cell_ijk[static_cast<std::size_t>(L.cells[i])];
    }
  }
  if (multigrid && same_faces && w.multigrid_faces) {
    L.multigrid.SetDiagonal(a);  // a nonlinear round: only the capacity's terms of the diagonal changed
  } else if (multigrid) {
    L.multigrid.Setup(a, L.ijk);
    w.multigrid_faces = true;
  }
  // z = B r; returns r.z.
  auto precondition = [&]() {
    if (multigrid) L.multigrid.Apply(w.r, w.z);
    ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
      double rz = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        if (!multigrid) z[i] = r[i] * inv[i];
        rz += r[i] * z[i];
      }
      w.part_a[c] = rz;
    });
    return Sum(w.part_a);
  };
  const double tolerance = s.settings.solver_tolerance_c;
  double rz = precondition();
  double beta = 0.0;
  int iterations = 0;
  const int most_iterations = fixed > 0 ? fixed : kMaxIterations;
  while (iterations < most_iterations) {
    const bool first = iterations == 0;
    ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
      double pap = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        const double az = a.Row(z, i);
        p[i] = first ? z[i] : z[i] + beta * p[i];
        ap[i] = first ? az : az + beta * ap[i];
        pap += p[i] * ap[i];
      }
      w.part_a[c] = pap;
    });
    const double pap = Sum(w.part_a);
    if (!(pap > 0.0)) break;  // the residual is zero already (only a followed count can ask for more)
    const double alpha = rz / pap;
    // x and r; with the diagonal preconditioner z = r / A_ii and r.z in the same pass.
    ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
      double most = 0.0, rz_part = 0.0;
      for (std::size_t i = begin; i < end; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * ap[i];
        const double correction = r[i] * inv[i];
        most = std::max(most, std::abs(r[i] * stop[i]));
        if (!multigrid) {
          z[i] = correction;
          rz_part += r[i] * correction;
        }
      }
      w.part_max[c] = most;
      w.part_a[c] = rz_part;
    });
    ++iterations;
    if (fixed <= 0 && *std::max_element(w.part_max.begin(), w.part_max.end()) <= tolerance) break;
    const double rz_new = multigrid ? precondition() : Sum(w.part_a);
    beta = rz_new / rz;
    rz = rz_new;
  }
  return iterations;
}

// The plane i + j + k of active cell c's grid coordinates.
int Plane(const ThermalState& s, int c) {
  const std::array<int, 3>& g = s.cell_ijk[static_cast<std::size_t>(c)];
  return g[0] + g[1] + g[2];
}

// The symmetric Gauss-Seidel preconditioner's system from the level's (StencilSystem L): the cells sorted by their
// plane i + j + k, and per position the lower faces (-x, -y, -z) and the upper ones (+x, +y, +z). A cell's lower
// neighbours lie in the plane before its own and its upper ones in the plane after it, so every lower neighbour comes
// earlier, every upper one later, and the order inside a plane changes nothing: the triangular solves are those of
// the grid's lexicographic order, but the cells of one plane do not wait for each other (a wavefront). With
// `same_faces` (and this structure built for the level's last solve) only the diagonal is copied again.
void OrderSymmetricGaussSeidel(const ThermalState& s, LevelSystem& L, bool same_faces) {
  LevelScratch& w = L.scratch;
  const std::size_t n = L.cells.size();
  if (!same_faces || !w.sgs_faces) {
    // Counting sort by plane.
    int low = Plane(s, L.cells[0]), high = low;
    for (int c : L.cells) {
      low = std::min(low, Plane(s, c));
      high = std::max(high, Plane(s, c));
    }
    std::vector<int>& start = w.sgs_start;
    start.assign(static_cast<std::size_t>(high - low) + 2, 0);
    for (int c : L.cells) ++start[static_cast<std::size_t>(Plane(s, c) - low) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    w.order.resize(n);
    std::vector<int>& at = w.sgs_at;  // the position of each local index
    at.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = start[static_cast<std::size_t>(Plane(s, L.cells[i]) - low)]++;
      w.order[static_cast<std::size_t>(k)] = static_cast<int>(i);
      at[i] = k;
    }
    w.lower.resize(n);
    w.upper.resize(n);
    w.lower_g.resize(n);
    w.upper_g.resize(n);
    const int pad = static_cast<int>(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = static_cast<std::size_t>(w.order[k]);
      for (int e = 0; e < 3; ++e) {
        const int j_low = L.neighbour[i][2 * e], j_up = L.neighbour[i][2 * e + 1];
        w.lower[k][e] = j_low >= 0 ? at[static_cast<std::size_t>(j_low)] : pad;
        w.lower_g[k][e] = j_low >= 0 ? L.conductance[i][2 * e] : 0.0;
        w.upper[k][e] = j_up >= 0 ? at[static_cast<std::size_t>(j_up)] : pad;
        w.upper_g[k][e] = j_up >= 0 ? L.conductance[i][2 * e + 1] : 0.0;
      }
    }
    w.sgs_faces = true;
  }
  w.sgs_diagonal.resize(n);
  w.sgs_inverse.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    w.sgs_diagonal[k] = L.diagonal[static_cast<std::size_t>(w.order[k])];
    w.sgs_inverse[k] = 1.0 / w.sgs_diagonal[k];
  }
}

// Runs `iterate(fixed)` unless the first guess already meets the tolerance (`worst`: its largest Jacobi correction),
// with the iteration count a choice (SolverChoices): a run following choices takes the recorded count, so that its
// result is a continuous function of the system. Returns the iterations.
template <typename Run>
int ChooseIterations(ThermalState& s, double worst, const Run& iterate) {
  const bool following = FollowingChoices(s);
  const int fixed = following ? ChooseCount(s, 0) : 0;
  int iterations = 0;
  if (fixed > 0 || (!following && worst > s.settings.solver_tolerance_c)) iterations = iterate(fixed);
  if (!following) ChooseCount(s, iterations);
  return iterations;
}

// The transformed system's first residual r^ = K^-1 r (a forward solve) and z = D r^ (the Jacobi preconditioner of
// B is D^-1), in the scratch's vectors of `n` cells; returns r^.z.
double TransformResidual(LevelScratch& w, std::size_t n) {
  double* rh = w.sgs_rh.data();
  double rz = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::array<int, 3>& lo = w.lower[k];
    const std::array<double, 3>& g = w.lower_g[k];
    rh[k] = (w.sgs_r[k] + g[0] * rh[lo[0]] + g[1] * rh[lo[1]] + g[2] * rh[lo[2]]) * w.sgs_inverse[k];
    w.sgs_z[k] = w.sgs_diagonal[k] * rh[k];
    rz += rh[k] * w.sgs_z[k];
  }
  return rz;
}

// Conjugate gradients preconditioned by symmetric Gauss-Seidel, M = (D - E) D^-1 (D - E^T) with A = D - E - E^T (E:
// the faces to lower cells, OrderSymmetricGaussSeidel), by Eisenstat's trick (Eisenstat 1981, SIAM J. Sci. Stat.
// Comput. 2, 1-4; Saad 2003, "Iterative Methods for Sparse Linear Systems", sec. 9.2.2): with K = D - E, CG
// preconditioned by D^-1 on B = K^-1 A K^-T, whose product B p = t + K^-1 (p - D t), t = K^-T p, takes one backward
// and one forward triangular solve, together one stencil product. The iterate x = K^-T y moves by alpha t; the true
// residual r = K r^ by -alpha (p - E t), E t summed in the forward solve. Works on the scratch's wavefront-ordered
// vectors (w.sgs_x the iterate, w.sgs_r its residual) of `n` cells; stops as Iterate does, when every Jacobi
// correction |r_i / A_ii| is below `tolerance`, or after `fixed` iterations (> 0). Returns the iterations.
int IterateSymmetricGaussSeidel(LevelScratch& w, std::size_t n, double tolerance, int fixed) {
  const std::array<int, 3>* lower = w.lower.data();
  const std::array<int, 3>* upper = w.upper.data();
  const std::array<double, 3>* lower_g = w.lower_g.data();
  const std::array<double, 3>* upper_g = w.upper_g.data();
  const double* d = w.sgs_diagonal.data();
  const double* inv = w.sgs_inverse.data();
  double* x = w.sgs_x.data();
  double* r = w.sgs_r.data();
  double* t = w.sgs_t.data();
  double* sv = w.sgs_s.data();
  double* rh = w.sgs_rh.data();
  double* z = w.sgs_z.data();
  double* p = w.sgs_p.data();
  double* q = w.sgs_q.data();
  double* et = w.sgs_et.data();
  const double* stop = w.sgs_stop.data();
  double rz = TransformResidual(w, n);
  double beta = 0.0;
  int done = 0;
  const int most = fixed > 0 ? fixed : kMaxIterations;
  while (done < most) {
    // p = z + beta p and t = K^-T p (backward).
    const bool first = done == 0;
    for (std::size_t k = n; k-- > 0;) {
      p[k] = first ? z[k] : z[k] + beta * p[k];
      const std::array<int, 3>& up = upper[k];
      const std::array<double, 3>& g = upper_g[k];
      t[k] = (p[k] + g[0] * t[up[0]] + g[1] * t[up[1]] + g[2] * t[up[2]]) * inv[k];
    }
    // s = K^-1 (p - D t) (forward), q = B p = t + s, and E t. The sums run in two accumulators (even and odd
    // positions): one chain of additions would make each cell wait for the last.
    auto forward = [&](std::size_t k) {
      const std::array<int, 3>& lo = lower[k];
      const std::array<double, 3>& g = lower_g[k];
      et[k] = g[0] * t[lo[0]] + g[1] * t[lo[1]] + g[2] * t[lo[2]];
      sv[k] = (p[k] - d[k] * t[k] + g[0] * sv[lo[0]] + g[1] * sv[lo[1]] + g[2] * sv[lo[2]]) * inv[k];
      q[k] = t[k] + sv[k];
      return p[k] * q[k];
    };
    double pq_even = 0.0, pq_odd = 0.0;
    std::size_t k = 0;
    for (; k + 1 < n; k += 2) {
      pq_even += forward(k);
      pq_odd += forward(k + 1);
    }
    if (k < n) pq_even += forward(k);
    const double pq = pq_even + pq_odd;
    if (!(pq > 0.0)) break;  // the residual is zero already (only a followed count can ask for more)
    const double alpha = rz / pq;
    // x, r^ and r; z = D r^ and r^.z.
    auto update = [&](std::size_t k, double* largest, double* rz_sum) {
      x[k] += alpha * t[k];
      rh[k] -= alpha * q[k];
      r[k] -= alpha * (p[k] - et[k]);
      *largest = std::max(*largest, std::abs(r[k] * stop[k]));
      z[k] = d[k] * rh[k];
      *rz_sum += rh[k] * z[k];
    };
    double largest_even = 0.0, largest_odd = 0.0, rz_even = 0.0, rz_odd = 0.0;
    for (k = 0; k + 1 < n; k += 2) {
      update(k, &largest_even, &rz_even);
      update(k + 1, &largest_odd, &rz_odd);
    }
    if (k < n) update(k, &largest_even, &rz_even);
    ++done;
    if (fixed <= 0 && std::max(largest_even, largest_odd) <= tolerance) break;
    const double rz_new = rz_even + rz_odd;
    beta = rz_new / rz;
    rz = rz_new;
  }
  return done;
}

// Solves the level's system into L.t_new from `guess` by IterateSymmetricGaussSeidel: the wavefront order and its
// faces (OrderSymmetricGaussSeidel), the first guess and its residual in that order, the iterations (a choice,
// ChooseIterations), the solution back in the level's order. Serial: for systems under kParallelCells, which
// ForChunks runs on the calling thread anyway. Returns the iterations.
int SolveSymmetricGaussSeidel(ThermalState& s, LevelSystem& L, const std::vector<double>& guess, bool same_faces,
                              int deepest_tested) {
  LevelScratch& w = L.scratch;
  const std::size_t n = L.cells.size();
  OrderSymmetricGaussSeidel(s, L, same_faces);
  // Vectors read through a face hold n + 1 values, the last the zero slot; every other value is written before it
  // is read.
  for (std::vector<double>* v : {&w.sgs_x, &w.sgs_t, &w.sgs_s, &w.sgs_rh}) {
    v->resize(n + 1);
    (*v)[n] = 0.0;
  }
  for (std::vector<double>* v : {&w.sgs_r, &w.sgs_z, &w.sgs_p, &w.sgs_q, &w.sgs_et}) v->resize(n);
  const int* order = w.order.data();
  double* x = w.sgs_x.data();
  w.sgs_stop.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int c = L.cells[static_cast<std::size_t>(order[k])];
    x[k] = guess[c];
    w.sgs_stop[k] = s.depth[c] <= deepest_tested ? w.sgs_inverse[k] : 0.0;
  }
  // The first residual and its largest Jacobi correction.
  double worst = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::array<int, 3>& lo = w.lower[k];
    const std::array<int, 3>& up = w.upper[k];
    const std::array<double, 3>& gl = w.lower_g[k];
    const std::array<double, 3>& gu = w.upper_g[k];
    double& r = w.sgs_r[k];
    r = L.rhs[static_cast<std::size_t>(order[k])] - w.sgs_diagonal[k] * x[k] +
        (gl[0] * x[lo[0]] + gl[1] * x[lo[1]] + gl[2] * x[lo[2]]) +
        (gu[0] * x[up[0]] + gu[1] * x[up[1]] + gu[2] * x[up[2]]);
    worst = std::max(worst, std::abs(r * w.sgs_stop[k]));
  }
  const int iterations = ChooseIterations(s, worst, [&](int fixed) {
    return IterateSymmetricGaussSeidel(w, n, s.settings.solver_tolerance_c, fixed);
  });
  for (std::size_t k = 0; k < n; ++k) L.t_new[static_cast<std::size_t>(order[k])] = x[k];
  return iterations;
}

}  // namespace

// Solves the level's system by preconditioned conjugate gradients from `guess` (degC by active cell), until every
// Jacobi correction |r_i / A_ii| (the temperature correction a Jacobi sweep would make) is below the tolerance.
// Stiff systems of kMultigridCells cells or more are preconditioned by one additive-correction multigrid V-cycle
// (thermal_multigrid.h), the others by symmetric Gauss-Seidel (under kParallelCells cells) or the diagonal. With
// `same_faces` the system differs from the one last solved only in its diagonal and right-hand side (a nonlinear
// round), so only the diagonal is copied. Returns the iterations.
int SolveLevel(ThermalState& s, LevelSystem& L, const std::vector<double>& guess, bool same_faces,
               int deepest_tested) {
  const std::size_t n = L.cells.size();
  if (n == 0) return 0;
  LevelScratch& w = L.scratch;
  if (!same_faces) {
    w.stencil_faces = w.multigrid_faces = w.sgs_faces = false;
    L.ijk.clear();  // other cells: their grid coordinates are found again if the multigrid is taken
  }
  const std::size_t chunks = Chunks(n);
  w.part_a.resize(chunks);
  w.part_b.resize(chunks);
  w.part_max.resize(chunks);
  // The stiffness: conduction (the faces inside the system) over storage and losses, summed.
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
    double conduction = 0.0, rest = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      double faces = 0.0;
      for (int f = 0; f < 6; ++f) faces += L.neighbour[i][f] >= 0 ? L.conductance[i][f] : 0.0;
      conduction += faces;
      rest += L.diagonal[i] - faces;
    }
    w.part_a[c] = conduction;
    w.part_b[c] = rest;
  });
  // The preconditioner is a choice (SolverChoices), as is the iteration count (ChooseIterations).
  const bool multigrid = ChooseCount(s, n >= kMultigridCells && Sum(w.part_a) >= kMultigridStiffness *
                                                                                    Sum(w.part_b)) != 0;
  if (!multigrid && n < kParallelCells) return SolveSymmetricGaussSeidel(s, L, guess, same_faces, deepest_tested);
  const PaddedStencil& a = w.stencil;
  if (!w.stencil_faces) {
    w.stencil.Assign(L);
    w.stencil_faces = true;
  } else {
    std::copy(L.diagonal.begin(), L.diagonal.end(), w.stencil.diagonal.begin());
  }
  // x, z and p are multiplied by the matrix: n + 1 values, the last the zero slot.
  w.x.resize(n + 1);
  w.z.resize(n + 1);
  w.p.resize(n + 1);
  w.x[n] = w.z[n] = w.p[n] = 0.0;
  w.r.resize(n);
  w.ap.resize(n);
  w.inverse_diagonal.resize(n);
  w.stop.resize(n);
  double* x = w.x.data();
  double* r = w.r.data();
  double* inv = w.inverse_diagonal.data();
  for (std::size_t i = 0; i < n; ++i) x[i] = guess[L.cells[i]];
  // The first residual and the Jacobi corrections.
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
    double worst = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      inv[i] = 1.0 / a.diagonal[i];
      w.stop[i] = s.depth[L.cells[i]] <= deepest_tested ? inv[i] : 0.0;
      r[i] = L.rhs[i] - a.Row(x, i);
      worst = std::max(worst, std::abs(r[i] * w.stop[i]));
    }
    w.part_max[c] = worst;
  });
  const double worst = *std::max_element(w.part_max.begin(), w.part_max.end());
  const int iterations =
      ChooseIterations(s, worst, [&](int fixed) { return Iterate(s, L, multigrid, same_faces, fixed); });
  std::copy(x, x + n, L.t_new.begin());
  return iterations;
}

}  // namespace waam::twin::internal
