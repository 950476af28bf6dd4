// The linear solver of one multirate level's backward-Euler system: conjugate gradients preconditioned by the
// diagonal or, for large stiff systems, by one multigrid V-cycle (docs/THERMAL.md, "Discretisation").
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
  if (multigrid && !(same_faces && L.ijk.size() == n)) {
    L.ijk.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3i g = s.CellIndex(s.grid_of[L.cells[i]]);
      L.ijk[i] = {g.x(), g.y(), g.z()};
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
        most = std::max(most, std::abs(correction));
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

}  // namespace

// Solves the level's system by preconditioned conjugate gradients from `guess` (degC by active cell), until every
// Jacobi correction |r_i / A_ii| (the temperature correction a Jacobi sweep would make) is below the tolerance.
// Stiff systems of kMultigridCells cells or more are preconditioned by one additive-correction multigrid V-cycle
// (thermal_multigrid.h), the others by the diagonal. With `same_faces` the system differs from the one last solved
// only in its diagonal and right-hand side (a nonlinear round), so only the diagonal is copied. Returns the iterations.
int SolveLevel(ThermalState& s, LevelSystem& L, const std::vector<double>& guess, bool same_faces) {
  const std::size_t n = L.cells.size();
  if (n == 0) return 0;
  LevelScratch& w = L.scratch;
  const PaddedStencil& a = w.stencil;
  if (same_faces) {
    std::copy(L.diagonal.begin(), L.diagonal.end(), w.stencil.diagonal.begin());
  } else {
    w.stencil.Assign(L);
    w.multigrid_faces = false;
    L.ijk.clear();  // other cells: their grid coordinates are found again if the multigrid is taken
  }
  // x, z and p are multiplied by the matrix: n + 1 values, the last the zero slot.
  w.x.resize(n + 1);
  w.z.resize(n + 1);
  w.p.resize(n + 1);
  w.x[n] = w.z[n] = w.p[n] = 0.0;
  w.r.resize(n);
  w.ap.resize(n);
  w.inverse_diagonal.resize(n);
  const std::size_t chunks = Chunks(n);
  w.part_a.resize(chunks);
  w.part_b.resize(chunks);
  w.part_max.resize(chunks);
  double* x = w.x.data();
  double* r = w.r.data();
  double* inv = w.inverse_diagonal.data();
  for (std::size_t i = 0; i < n; ++i) x[i] = guess[L.cells[i]];
  // The first residual, the Jacobi corrections and the stiffness: conduction over storage and losses, summed.
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t c) {
    double worst = 0.0, conduction = 0.0, rest = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::array<double, 6>& g = a.conductance[i];
      const double faces = g[0] + g[1] + g[2] + g[3] + g[4] + g[5];
      conduction += faces;
      rest += a.diagonal[i] - faces;
      inv[i] = 1.0 / a.diagonal[i];
      r[i] = L.rhs[i] - a.Row(x, i);
      worst = std::max(worst, std::abs(r[i] * inv[i]));
    }
    w.part_max[c] = worst;
    w.part_a[c] = conduction;
    w.part_b[c] = rest;
  });
  // The preconditioner and the iteration count are choices (SolverChoices): a run following them takes the
  // recorded ones, so that its result is a continuous function of the system.
  int iterations = 0;
  const bool following = FollowingChoices(s);
  const bool multigrid = ChooseCount(s, n >= kMultigridCells && Sum(w.part_a) >= kMultigridStiffness *
                                                                                    Sum(w.part_b)) != 0;
  const int fixed = following ? ChooseCount(s, 0) : 0;
  if (fixed > 0 || (!following && *std::max_element(w.part_max.begin(), w.part_max.end()) >
                                       s.settings.solver_tolerance_c)) {
    iterations = Iterate(s, L, multigrid, same_faces, fixed);
  }
  if (!following) ChooseCount(s, iterations);
  std::copy(x, x + n, L.t_new.begin());
  return iterations;
}

}  // namespace waam::twin::internal
