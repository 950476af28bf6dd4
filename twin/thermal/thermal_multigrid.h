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

// One symmetric V-cycle of additive-correction multigrid, used as the preconditioner z = B r of conjugate gradients.
// The coarse cells are 2 x 2 x 2 blocks of the grid restricted to the system's cells; a coarse equation is the sum
// of its fine cells' equations with the correction constant over the block (Hutchinson & Raithby 1986, Numer. Heat
// Transfer 9, eqs. 9-12), so a coarse level is again a 7-point system on the half-resolution grid. Smoothing is one
// forward Gauss-Seidel sweep before the coarse correction and one backward sweep after it (the adjoint), so B is
// symmetric positive definite and the conjugate gradients stay valid. Gauss-Seidel runs in the fixed chunks of
// ForChunks and reads other chunks' values from before the sweep (block Gauss-Seidel): the result does not depend
// on the thread count.
class AdditiveCorrectionMultigrid {
 public:
  // Builds the coarse levels of `fine` (kept by reference: it must outlive every Apply), whose cell i lies at grid
  // coordinates ijk[i] (non-negative). Throws nothing.
  void Setup(const StencilSystem& fine, const std::vector<std::array<int, 3>>& ijk);
  // z = B r (sizes: fine.size()).
  void Apply(const std::vector<double>& r, std::vector<double>& z);
  int levels() const { return static_cast<int>(coarse_.size()) + 1; }

 private:
  struct Level {
    StencilSystem system;
    std::vector<int> parent;  // per cell of the finer level: its block's index in this level
    std::vector<double> b, x, residual, before;
  };
  void Cycle(std::size_t level, const std::vector<double>& b, std::vector<double>& x);

  const StencilSystem* fine_ = nullptr;
  std::vector<double> fine_residual_, fine_before_;
  std::vector<Level> coarse_;  // coarse_[0] is the first coarse level
};

}  // namespace waam::twin::internal
