// Additive-correction multigrid (Hutchinson & Raithby 1986) on the thermal model's structured grid: the
// preconditioner of the conjugate gradients of every backward-Euler step big enough to need it (internal).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace waam::twin::internal {

// A symmetric system over cells of the structured grid: row i is diagonal[i] x_i - sum_f conductance[i][f]
// x_neighbour[i][f] over the faces whose neighbour index is >= 0 (the 7-point finite-volume stencil).
struct StencilSystem {
  std::vector<std::array<int, 6>> neighbour;       // index of each face's neighbour in the system, or < 0
  std::vector<std::array<double, 6>> conductance;  // W/K through each face (> 0 towards a neighbour in the system)
  std::vector<double> diagonal;                    // W/K
  std::size_t size() const { return diagonal.size(); }
};

// The same system in the form the hot loops read without branches: a face with no neighbour points at the zero
// slot n (vectors multiplied by it hold n + 1 values, the last 0) with conductance 0.
struct PaddedStencil {
  std::vector<std::array<int, 6>> neighbour;       // index in [0, n]
  std::vector<std::array<double, 6>> conductance;  // W/K, 0 towards the zero slot
  std::vector<double> diagonal;                    // W/K
  std::size_t size() const { return diagonal.size(); }
  // Copies `a` (faces with neighbour < 0 become the zero slot with conductance 0).
  void Assign(const StencilSystem& a);
  // (A v)_i for v of n + 1 values with v[n] = 0.
  double Row(const double* v, std::size_t i) const {
    const std::array<int, 6>& nb = neighbour[i];
    const std::array<double, 6>& g = conductance[i];
    double y = diagonal[i] * v[i];
    y -= g[0] * v[nb[0]];
    y -= g[1] * v[nb[1]];
    y -= g[2] * v[nb[2]];
    y -= g[3] * v[nb[3]];
    y -= g[4] * v[nb[4]];
    y -= g[5] * v[nb[5]];
    return y;
  }
};

// One symmetric V-cycle of additive-correction multigrid, used as the preconditioner z = B r of conjugate gradients.
// The coarse cells are 2 x 2 x 2 blocks of the grid restricted to the system's cells; a coarse equation is the sum
// of its fine cells' equations with the correction constant over the block (Hutchinson & Raithby 1986, Numer. Heat
// Transfer 9, eqs. 9-12), so a coarse level is again a 7-point system on the half-resolution grid. Smoothing is one
// forward Gauss-Seidel sweep before the coarse correction and one backward sweep after it (the adjoint), so B is
// symmetric positive definite and the conjugate gradients stay valid. Gauss-Seidel runs in the fixed chunks of
// ForChunks and reads other chunks' values from before the sweep (block Gauss-Seidel): the result does not depend
// on the thread count. The blocks are kept between Setups while the system's cells and faces stay the same (the
// usual case from one time step to the next): only the coefficients are summed again. The fine system is not copied:
// the multigrid reads the caller's PaddedStencil given to the last Setup or SetDiagonal, which must stay alive and
// unchanged until the Applies that follow are done.
class AdditiveCorrectionMultigrid {
 public:
  // Builds the coarse levels of `fine` (referenced, not copied), whose cell i lies at grid coordinates ijk[i]
  // (non-negative). Throws nothing.
  void Setup(const PaddedStencil& fine, const std::vector<std::array<int, 3>>& ijk);
  // The same on a copy of `fine` that the multigrid keeps.
  void Setup(const StencilSystem& fine, const std::vector<std::array<int, 3>>& ijk);
  // The same after a change of the fine system's diagonal alone (its cells, faces and conductances those of the last
  // Setup): only the diagonals are summed again, with the same results as a Setup. `fine` is referenced from then on.
  void SetDiagonal(const PaddedStencil& fine);
  // z = B r (sizes: at least the fine system's size; only its first values are read and written).
  void Apply(const std::vector<double>& r, std::vector<double>& z);
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    PaddedStencil system;  // empty on the fine level (its system is *fine_)
    std::vector<int> parent;  // per cell: its block's index in the next coarser level (empty on the coarsest)
    std::vector<double> inverse;  // 1 / the diagonal
    std::vector<double> b, residual;  // b: empty on the fine level (Apply's r is read in place)
    // 2 (n + 1) values: the iterate, its zero slot (0), and the iterate from before a sweep (Sweep).
    std::vector<double> x;
    std::vector<std::array<int, 6>> sweep;  // the faces a sweep over several chunks reads (SweepNeighbours)
  };
  bool SameStructure(const PaddedStencil& fine, const std::vector<std::array<int, 3>>& ijk) const;
  void BuildStructure(const std::vector<std::array<int, 3>>& ijk);
  void SumCoefficients(bool faces);
  void InvertDiagonals();
  void Cycle(std::size_t level, const double* b);  // b: the level's right-hand side
  const PaddedStencil& System(std::size_t level) const { return level == 0 ? *fine_ : levels_[level].system; }

  std::vector<Level> levels_;  // levels_[0] is the fine system
  std::vector<std::array<int, 3>> ijk_;  // the fine cells' grid coordinates of the last structure built
  std::vector<std::array<int, 6>> neighbour_;  // ... and the fine system's faces
  const PaddedStencil* fine_ = nullptr;  // the fine system of the last Setup or SetDiagonal (read until the next)
  PaddedStencil scratch_;
  // BuildStructure's scratch: a level's cells' and its blocks' grid coordinates, and the block at each coordinate.
  std::vector<std::array<int, 3>> coords_, next_coords_;
  std::vector<int> block_of_;
};

}  // namespace waam::twin::internal
