// The additive-correction multigrid preconditioner of the thermal solver: symmetric, positive and a fast smoother of
// the errors conjugate gradients leave slow.
#include "twin/thermal/thermal_multigrid.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace waam::twin::internal {
namespace {

// A backward-Euler-like system on an nx x ny x nz box with conductances varying 10x between faces and a small
// capacity term (alpha dt / dx^2 ~ 100, the whole-model steps' stiffness).
struct Box {
  StencilSystem system;
  std::vector<std::array<int, 3>> ijk;
};
Box MakeBox(int nx, int ny, int nz, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> g(0.1, 1.0);
  Box box;
  const int n = nx * ny * nz;
  auto index = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  box.system.neighbour.assign(n, {-1, -1, -1, -1, -1, -1});
  box.system.conductance.assign(n, {0, 0, 0, 0, 0, 0});
  box.system.diagonal.assign(n, 0.0);
  box.ijk.resize(n);
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int a = index(i, j, k);
        box.ijk[a] = {i, j, k};
        box.system.diagonal[a] += 0.01;  // capacity
        const int next[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (int d = 0; d < 3; ++d) {
          if (next[d][0] >= nx || next[d][1] >= ny || next[d][2] >= nz) continue;
          const int b = index(next[d][0], next[d][1], next[d][2]);
          const double conductance = g(random);
          box.system.neighbour[a][2 * d + 1] = b;
          box.system.neighbour[b][2 * d] = a;
          box.system.conductance[a][2 * d + 1] = box.system.conductance[b][2 * d] = conductance;
          box.system.diagonal[a] += conductance;
          box.system.diagonal[b] += conductance;
        }
      }
    }
  }
  return box;
}

double Dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
  return sum;
}

// B must be symmetric and positive definite for conjugate gradients: r1.B r2 = r2.B r1 and r.B r > 0.
// The box has 5,000 cells, so the Gauss-Seidel sweeps run in two chunks.
TEST(ThermalMultigrid, VCycleIsSymmetricAndPositive) {
  Box box = MakeBox(25, 20, 10, 7);
  AdditiveCorrectionMultigrid multigrid;
  multigrid.Setup(box.system, box.ijk);
  EXPECT_GE(multigrid.levels(), 4) << "5,000 cells coarsen to at most 96";
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  const std::size_t n = box.system.size();
  std::vector<double> r1(n), r2(n), z1(n), z2(n);
  for (int trial = 0; trial < 3; ++trial) {
    for (std::size_t i = 0; i < n; ++i) {
      r1[i] = normal(random);
      r2[i] = normal(random);
    }
    multigrid.Apply(r1, z1);
    multigrid.Apply(r2, z2);
    const double a = Dot(r2, z1), b = Dot(r1, z2);
    EXPECT_NEAR(a, b, 1e-10 * (std::abs(a) + std::abs(b))) << "r2.B r1 vs r1.B r2";
    EXPECT_GT(Dot(r1, z1), 0.0);
  }
}

// Used as a stationary iteration x += B (b - A x) on a stiff system, five V-cycles cut the residual several times
// and far more than five Jacobi sweeps do (piecewise-constant corrections undershoot smooth errors, so the cycle
// alone contracts slowly: it is meant as a preconditioner of conjugate gradients, where the solver takes ~7
// iterations on the whole-model steps). Measured: 11x for the V-cycles, none for Jacobi.
TEST(ThermalMultigrid, VCyclesReduceTheResidualOfAStiffSystemFarFasterThanJacobi) {
  Box box = MakeBox(24, 24, 8, 11);
  AdditiveCorrectionMultigrid multigrid;
  multigrid.Setup(box.system, box.ijk);
  const StencilSystem& a = box.system;
  const std::size_t n = a.size();
  std::vector<double> b(n, 1.0), r(n), z(n);
  auto residual = [&](const std::vector<double>& x) {
    double norm = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      double ax = a.diagonal[i] * x[i];
      for (int f = 0; f < 6; ++f) {
        if (a.neighbour[i][f] >= 0) ax -= a.conductance[i][f] * x[a.neighbour[i][f]];
      }
      r[i] = b[i] - ax;
      norm += r[i] * r[i];
    }
    return std::sqrt(norm);
  };
  std::vector<double> x(n, 0.0), y(n, 0.0);
  const double start = residual(x);
  for (int cycle = 0; cycle < 5; ++cycle) {
    residual(x);
    multigrid.Apply(r, z);
    for (std::size_t i = 0; i < n; ++i) x[i] += z[i];
  }
  const double multigrid_factor = start / residual(x);
  for (int sweep = 0; sweep < 5; ++sweep) {
    residual(y);
    for (std::size_t i = 0; i < n; ++i) y[i] += r[i] / a.diagonal[i];
  }
  const double jacobi_factor = start / residual(y);
  EXPECT_GT(multigrid_factor, 5.0) << "residual reduction by five V-cycles";
  EXPECT_GT(multigrid_factor, 3.0 * jacobi_factor) << "five Jacobi sweeps reduce it by " << jacobi_factor;
}

// A nonlinear round changes only the diagonal: SetDiagonal after a Setup must give the V-cycle of a Setup from
// scratch on the new system, to the last bit (the solver's results do not depend on which one ran).
TEST(ThermalMultigrid, SetDiagonalEqualsASetupOfTheNewSystem) {
  Box box = MakeBox(25, 20, 10, 11);
  AdditiveCorrectionMultigrid kept;
  kept.Setup(box.system, box.ijk);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> capacity(0.0, 0.5);
  for (double& d : box.system.diagonal) d += capacity(random);
  PaddedStencil changed;
  changed.Assign(box.system);
  kept.SetDiagonal(changed);
  AdditiveCorrectionMultigrid fresh;
  fresh.Setup(box.system, box.ijk);
  const std::size_t n = box.system.size();
  std::normal_distribution<double> normal;
  std::vector<double> r(n), z_kept(n), z_fresh(n);
  for (double& v : r) v = normal(random);
  kept.Apply(r, z_kept);
  fresh.Apply(r, z_fresh);
  EXPECT_EQ(z_kept, z_fresh);
  // ... and differs from the V-cycle of the old diagonal (the change reached every level).
  AdditiveCorrectionMultigrid old;
  Box before = MakeBox(25, 20, 10, 11);
  old.Setup(before.system, before.ijk);
  std::vector<double> z_old(n);
  old.Apply(r, z_old);
  EXPECT_NE(z_old, z_kept);
}

}  // namespace
}  // namespace waam::twin::internal
