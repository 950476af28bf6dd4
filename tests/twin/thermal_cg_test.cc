// The thermal solver's conjugate gradients on systems too mild for the multigrid: preconditioned by symmetric
// Gauss-Seidel in wavefront order (Eisenstat's implementation), they stop at the tolerance on the true residual,
// whatever the order of the system's cells.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// A state whose active cells are the cells of an nx x ny x nz grid, and a level whose system covers them in the
// order `cells` (active ids): faces with conductances from 0.1 to 1 W/K, each cell storing `capacity` W/K, the
// right-hand side random. Stiffness (faces over capacity) about 3 / capacity.
struct Problem {
  ThermalState state;
  LevelSystem level;
};

void Build(Problem& p, int nx, int ny, int nz, const std::vector<int>& cells, double capacity, std::uint32_t seed) {
  ThermalState& s = p.state;
  s.size = {nx, ny, nz};
  s.settings.solver_tolerance_c = 1e-9;
  const int n = nx * ny * nz;
  s.grid_of.resize(n);
  s.cell_ijk.resize(n);
  s.depth.assign(n, 0);  // every cell the level's own (none in a finer region)
  for (int c = 0; c < n; ++c) {
    s.grid_of[c] = c;  // active id c is grid cell c
    const Eigen::Vector3i g = s.CellIndex(c);
    s.cell_ijk[c] = {g.x(), g.y(), g.z()};
  }
  // Per active cell: conductances to +x, +y, +z, and the right-hand side (the same for any order).
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0.1, 1.0);
  std::vector<std::array<double, 3>> up(n);
  std::vector<double> rhs(n);
  for (int c = 0; c < n; ++c) {
    for (double& g : up[c]) g = uniform(random);
    rhs[c] = 100.0 * uniform(random);
  }
  LevelSystem& L = p.level;
  L.cells = cells;
  std::vector<int> local(n);
  for (int i = 0; i < n; ++i) local[cells[i]] = i;
  L.neighbour.assign(n, {-1, -1, -1, -1, -1, -1});
  L.conductance.assign(n, {0, 0, 0, 0, 0, 0});
  L.diagonal.assign(n, capacity);
  L.rhs.resize(n);
  L.t_new.resize(n);
  for (int c = 0; c < n; ++c) {
    const int i = local[c];
    L.rhs[i] = rhs[c];
    const Eigen::Vector3i g = s.CellIndex(c);
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3i next = g;
      next[d] += 1;
      if (next[d] >= s.size[d]) continue;
      const int j = local[s.GridIndex(next.x(), next.y(), next.z())];
      L.neighbour[i][2 * d + 1] = j;
      L.neighbour[j][2 * d] = i;
      L.conductance[i][2 * d + 1] = L.conductance[j][2 * d] = up[c][d];
      L.diagonal[i] += up[c][d];
      L.diagonal[j] += up[c][d];
    }
  }
}

// The largest Jacobi correction |(b - A x)_i / A_ii| of the level's solution, over the cells of depth <= `deepest`.
double LargestCorrection(const LevelSystem& L, const ThermalState& s, int deepest = 0) {
  double worst = 0.0;
  for (std::size_t i = 0; i < L.cells.size(); ++i) {
    if (s.depth[static_cast<std::size_t>(L.cells[i])] > deepest) continue;
    double r = L.rhs[i] - L.diagonal[i] * L.t_new[i];
    for (int f = 0; f < 6; ++f) {
      if (L.neighbour[i][f] >= 0) r += L.conductance[i][f] * L.t_new[static_cast<std::size_t>(L.neighbour[i][f])];
    }
    worst = std::max(worst, std::abs(r / L.diagonal[i]));
  }
  return worst;
}

TEST(ThermalConjugateGradients, SymmetricGaussSeidelStopsAtTheTolerance) {
  // 3,000 cells, stiffness about 6 (under the multigrid's 10), in a shuffled order.
  const int nx = 20, ny = 15, nz = 10, n = nx * ny * nz;
  std::vector<int> shuffled(n);
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
  Problem p;
  Build(p, nx, ny, nz, shuffled, 0.5, 11);
  const std::vector<double> guess(n, 20.0);
  const int iterations = SolveLevel(p.state, p.level, guess, false);
  EXPECT_GT(iterations, 3);
  EXPECT_LE(LargestCorrection(p.level, p.state), 1e-9);
  // A nonlinear round: only the diagonal changes (more capacity), the faces are kept.
  for (double& d : p.level.diagonal) d += 0.25;
  std::vector<double> previous(n);
  for (int i = 0; i < n; ++i) previous[static_cast<std::size_t>(shuffled[i])] = p.level.t_new[i];
  const int again = SolveLevel(p.state, p.level, previous, true);
  EXPECT_GT(again, 0);
  EXPECT_LE(LargestCorrection(p.level, p.state), 1e-9);
}

TEST(ThermalConjugateGradients, APredictorLeavesItsFinerRegionOutOfTheStoppingTest) {
  // The cells x < 5 are a finer level's region (depth 1), cut off from the level's own cells (no faces between them:
  // the preconditioner then keeps the two blocks apart too). From a first guess that solves the own cells and is
  // 500 K off in the region, the solve that tests only the own cells has nothing to do; the one that tests all
  // iterates until the region converges. Both preconditioners: Gauss-Seidel (capacity 0.5) and the multigrid (0.02).
  for (const double capacity : {0.5, 0.02}) {
    const int nx = 20, ny = 15, nz = 10, n = nx * ny * nz;
    std::vector<int> shuffled(n);
    std::iota(shuffled.begin(), shuffled.end(), 0);
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));
    Problem exact, all, own;
    for (Problem* p : {&exact, &all, &own}) {
      Build(*p, nx, ny, nz, shuffled, capacity, 11);
      LevelSystem& L = p->level;
      for (std::size_t i = 0; i < L.cells.size(); ++i) {
        const int x = p->state.CellIndex(L.cells[i]).x();
        if (x < 5) p->state.depth[static_cast<std::size_t>(L.cells[i])] = 1;
        const int f = x == 4 ? 1 : x == 5 ? 0 : -1;  // the face across the cut
        if (f < 0) continue;
        L.diagonal[i] -= L.conductance[i][f];
        L.neighbour[i][f] = -1;
        L.conductance[i][f] = 0.0;
      }
    }
    SolveLevel(exact.state, exact.level, std::vector<double>(n, 20.0), false);
    std::vector<double> guess(n);
    for (std::size_t i = 0; i < exact.level.cells.size(); ++i) {
      const std::size_t c = static_cast<std::size_t>(exact.level.cells[i]);
      guess[c] = exact.level.t_new[i] + (exact.state.depth[c] > 0 ? 500.0 : 0.0);
    }
    EXPECT_EQ(SolveLevel(own.state, own.level, guess, false, 0), 0) << "capacity " << capacity;
    EXPECT_LE(LargestCorrection(own.level, own.state, 0), 1e-9);
    EXPECT_GT(LargestCorrection(own.level, own.state, 1), 1.0);
    EXPECT_GT(SolveLevel(all.state, all.level, guess, false), 3) << "capacity " << capacity;
    EXPECT_LE(LargestCorrection(all.level, all.state, 1), 1e-9);
  }
}

TEST(ThermalConjugateGradients, TheOrderOfTheCellsChangesOnlyRounding) {
  // The same system over cells listed in grid order and shuffled: the wavefront order puts lower neighbours before
  // upper ones either way, so the preconditioner is the same and the solutions agree to rounding.
  const int nx = 12, ny = 9, nz = 7, n = nx * ny * nz;
  std::vector<int> sorted(n);
  std::iota(sorted.begin(), sorted.end(), 0);
  std::vector<int> shuffled = sorted;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
  Problem a, b;
  Build(a, nx, ny, nz, sorted, 0.4, 3);
  Build(b, nx, ny, nz, shuffled, 0.4, 3);
  const std::vector<double> guess(n, 20.0);
  const int iterations_a = SolveLevel(a.state, a.level, guess, false);
  const int iterations_b = SolveLevel(b.state, b.level, guess, false);
  EXPECT_EQ(iterations_a, iterations_b);
  for (int i = 0; i < n; ++i) {
    const double x = b.level.t_new[static_cast<std::size_t>(i)];
    const double y = a.level.t_new[static_cast<std::size_t>(shuffled[static_cast<std::size_t>(i)])];
    EXPECT_NEAR(x, y, 1e-10 * std::abs(y)) << "cell " << shuffled[static_cast<std::size_t>(i)];
  }
}

}  // namespace
}  // namespace waam::twin::internal
