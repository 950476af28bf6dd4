// Additive-correction multigrid on the structured grid (Hutchinson & Raithby 1986): coarse levels from 2 x 2 x 2
// blocks, chunked symmetric Gauss-Seidel smoothing, symmetric Gauss-Seidel on the coarsest level.
#include "twin/thermal/thermal_multigrid.h"

#include <algorithm>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// Coarsening stops at this many cells (the coarsest level is smoothed by 8 symmetric Gauss-Seidel pairs) ...
constexpr std::size_t kCoarsestCells = 96;
// ... or when a level keeps more than this share of its finer level's cells (the blocks no longer merge cells).
constexpr double kPoorCoarsening = 0.75;

// One Gauss-Seidel sweep of A x = b over the chunks of ForChunks, forward or backward; inside a chunk the new values
// are used at once, values of other chunks are those from before the sweep. x holds 2 (n + 1) values: the iterate
// (n values and the zero slot) and, behind it, the copy from before the sweep, which `sweep` (SweepNeighbours) points
// a face at when its neighbour lies in another chunk; the loop reads without a branch. `inverse` holds 1 / A_ii.
// The y and z faces are summed first and the x faces (the neighbours next in the sweep's order, just updated) last,
// and the diagonal's inverse multiplies: the chain from one cell's new value to the next is a few operations long
// instead of seven additions and a division. With `copied`, the copy behind the iterate already holds it (both zero
// at the start of a cycle).
void Sweep(const PaddedStencil& a, const std::vector<std::array<int, 6>>& sweep, const std::vector<double>& inverse,
           const double* b, std::vector<double>& x, bool forward, bool copied = false) {
  const std::size_t n = a.size();
  const bool one_chunk = n <= kChunk;  // plain Gauss-Seidel: every face reads the iterate (the zero slot reads 0)
  const auto from = x.begin();
  if (!one_chunk && !copied) {
    std::copy(from, from + static_cast<std::ptrdiff_t>(n), from + static_cast<std::ptrdiff_t>(n + 1));
  }
  const std::vector<std::array<int, 6>>& faces = one_chunk ? a.neighbour : sweep;
  double* v = x.data();
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    auto relax = [&](std::size_t i) {
      const std::array<int, 6>& nb = faces[i];
      const std::array<double, 6>& g = a.conductance[i];
      const double far = (b[i] + g[2] * v[nb[2]] + g[3] * v[nb[3]]) + (g[4] * v[nb[4]] + g[5] * v[nb[5]]);
      v[i] = (far + (g[0] * v[nb[0]] + g[1] * v[nb[1]])) * inverse[i];
    };
    if (forward) {
      for (std::size_t i = begin; i < end; ++i) relax(i);
    } else {
      for (std::size_t i = end; i-- > begin;) relax(i);
    }
  });
}

// The faces Sweep reads over more than one chunk, into `sweep`: a neighbour in the cell's own chunk (or the zero slot
// n) as it is, one in another chunk moved by n + 1 to its value from before the sweep. Empty for a system of one chunk.
void SweepNeighbours(const PaddedStencil& a, std::vector<std::array<int, 6>>& sweep) {
  const std::size_t n = a.size();
  sweep.clear();
  if (n <= kChunk) return;
  sweep.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int f = 0; f < 6; ++f) {
      const std::size_t u = static_cast<std::size_t>(a.neighbour[i][f]);
      const bool here = u == n || u / kChunk == i / kChunk;
      sweep[i][f] = here ? static_cast<int>(u) : static_cast<int>(u + n + 1);
    }
  }
}

}  // namespace

void PaddedStencil::Assign(const StencilSystem& a) {
  const std::size_t n = a.size();
  const int pad = static_cast<int>(n);
  neighbour.resize(n);
  conductance.resize(n);
  diagonal = a.diagonal;
  for (std::size_t i = 0; i < n; ++i) {
    for (int f = 0; f < 6; ++f) {
      const bool present = a.neighbour[i][f] >= 0;
      neighbour[i][f] = present ? a.neighbour[i][f] : pad;
      conductance[i][f] = present ? a.conductance[i][f] : 0.0;
    }
  }
}

void AdditiveCorrectionMultigrid::Setup(const StencilSystem& fine, const std::vector<std::array<int, 3>>& ijk) {
  scratch_.Assign(fine);
  Setup(scratch_, ijk);
}

void AdditiveCorrectionMultigrid::Setup(const PaddedStencil& fine, const std::vector<std::array<int, 3>>& ijk) {
  const bool same = SameStructure(fine, ijk);
  fine_ = &fine;
  if (levels_.empty()) levels_.resize(1);
  if (!same) BuildStructure(ijk);
  SumCoefficients(true);
  InvertDiagonals();
}

void AdditiveCorrectionMultigrid::SetDiagonal(const PaddedStencil& fine) {
  fine_ = &fine;
  SumCoefficients(false);
  InvertDiagonals();
}

void AdditiveCorrectionMultigrid::InvertDiagonals() {
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const std::vector<double>& d = System(l).diagonal;
    std::vector<double>& inverse = levels_[l].inverse;
    inverse.resize(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) inverse[i] = 1.0 / d[i];
  }
}

bool AdditiveCorrectionMultigrid::SameStructure(const PaddedStencil& fine,
                                                const std::vector<std::array<int, 3>>& ijk) const {
  return !levels_.empty() && ijk_ == ijk && neighbour_ == fine.neighbour;
}

// The blocks of every level (Hutchinson & Raithby's coarse cells) and the coarse levels' faces; the coefficients
// are left to SumCoefficients. The levels' vectors of the last structure are filled again (the structure changes
// with nearly every step while metal is laid, and fresh vectors of that size cost a page fault per 4 kB).
void AdditiveCorrectionMultigrid::BuildStructure(const std::vector<std::array<int, 3>>& ijk) {
  ijk_ = ijk;
  neighbour_ = fine_->neighbour;
  levels_.reserve(32);
  std::vector<std::array<int, 3>>& coords = coords_;
  std::vector<std::array<int, 3>>& next = next_coords_;
  std::vector<int>& map = block_of_;
  coords = ijk;
  std::size_t used = 1;  // levels built
  while (true) {
    const std::size_t n = System(used - 1).size();
    if (n <= kCoarsestCells || used > 30) break;
    std::array<int, 3> lo = {coords[0][0] >> 1, coords[0][1] >> 1, coords[0][2] >> 1};
    std::array<int, 3> hi = lo;
    for (const auto& c : coords) {
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], c[d] >> 1);
        hi[d] = std::max(hi[d], c[d] >> 1);
      }
    }
    const std::size_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
    map.assign(nx * ny * nz, -1);
    std::vector<int>& parent = levels_[used - 1].parent;
    parent.resize(n);
    next.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<int, 3> c = {coords[i][0] >> 1, coords[i][1] >> 1, coords[i][2] >> 1};
      const std::size_t key = (c[0] - lo[0]) + nx * ((c[1] - lo[1]) + ny * static_cast<std::size_t>(c[2] - lo[2]));
      if (map[key] < 0) {
        map[key] = static_cast<int>(next.size());
        next.push_back(c);
      }
      parent[i] = map[key];
    }
    const std::size_t m = next.size();
    if (static_cast<double>(m) > kPoorCoarsening * static_cast<double>(n)) break;
    // A block's face f leads to the block holding the neighbour across face f of any of its cells (on the
    // structured grid that is one block).
    if (levels_.size() == used) levels_.emplace_back();  // reserved: references to the levels stay valid
    const PaddedStencil& a = System(used - 1);
    Level& coarse = levels_[used];
    PaddedStencil& c = coarse.system;
    const int pad = static_cast<int>(m);
    c.neighbour.assign(m, {pad, pad, pad, pad, pad, pad});
    c.conductance.assign(m, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
    c.diagonal.assign(m, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (int f = 0; f < 6; ++f) {
        const std::size_t j = static_cast<std::size_t>(a.neighbour[i][f]);
        if (j < n && parent[j] != parent[i]) c.neighbour[parent[i]][f] = parent[j];
      }
    }
    coarse.b.resize(m);
    coarse.residual.resize(m);
    coarse.x.assign(2 * (m + 1), 0.0);
    coords.swap(next);
    ++used;
  }
  levels_.resize(used);
  levels_.back().parent.clear();
  Level& fine = levels_[0];
  fine.residual.resize(fine_->size());
  fine.x.assign(2 * (fine_->size() + 1), 0.0);
  for (std::size_t l = 0; l < levels_.size(); ++l) SweepNeighbours(System(l), levels_[l].sweep);
}

// Hutchinson & Raithby eqs. 9-12: a block's equation is the sum of its cells' equations with one correction for
// all of them; faces inside the block cancel from the diagonal, faces between blocks add up. Without `faces` the
// coarse conductances are kept and only the diagonals are summed (in the same order, so to the same values).
void AdditiveCorrectionMultigrid::SumCoefficients(bool faces) {
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    const PaddedStencil& a = System(l);
    const std::vector<int>& parent = levels_[l].parent;
    PaddedStencil& c = levels_[l + 1].system;
    if (faces) {
      std::fill(c.conductance.begin(), c.conductance.end(), std::array<double, 6>{0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
    }
    std::fill(c.diagonal.begin(), c.diagonal.end(), 0.0);
    const std::size_t n = a.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int block = parent[i];
      c.diagonal[block] += a.diagonal[i];
      for (int f = 0; f < 6; ++f) {
        const std::size_t j = static_cast<std::size_t>(a.neighbour[i][f]);
        if (j >= n) continue;
        if (parent[j] == block) {
          c.diagonal[block] -= a.conductance[i][f];
        } else if (faces) {
          c.conductance[block][f] += a.conductance[i][f];
        }
      }
    }
  }
}

void AdditiveCorrectionMultigrid::Apply(const std::vector<double>& r, std::vector<double>& z) {
  Level& fine = levels_[0];
  const std::size_t n = fine_->size();
  Cycle(0, r.data());  // the fine level's right-hand side, read in place
  std::copy(fine.x.begin(), fine.x.begin() + static_cast<std::ptrdiff_t>(n), z.begin());
}

void AdditiveCorrectionMultigrid::Cycle(std::size_t level, const double* b) {
  Level& L = levels_[level];
  const PaddedStencil& a = System(level);
  const std::size_t n = a.size();
  // The iterate and the copy behind it (2 (n + 1) values) start at zero; a level of one chunk never reads the copy.
  std::fill(L.x.begin(), L.x.begin() + static_cast<std::ptrdiff_t>(n <= kChunk ? n + 1 : L.x.size()), 0.0);
  if (level + 1 == levels_.size()) {
    // The coarsest level: symmetric Gauss-Seidel pairs from zero (a symmetric operator).
    for (int pass = 0; pass < 8; ++pass) {
      Sweep(a, L.sweep, L.inverse, b, L.x, true, pass == 0);
      Sweep(a, L.sweep, L.inverse, b, L.x, false);
    }
    return;
  }
  Sweep(a, L.sweep, L.inverse, b, L.x, true, true);
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) L.residual[i] = b[i] - a.Row(L.x.data(), i);
  });
  Level& coarse = levels_[level + 1];
  std::fill(coarse.b.begin(), coarse.b.end(), 0.0);
  for (std::size_t i = 0; i < n; ++i) coarse.b[L.parent[i]] += L.residual[i];
  Cycle(level + 1, coarse.b.data());
  for (std::size_t i = 0; i < n; ++i) L.x[i] += coarse.x[L.parent[i]];
  Sweep(a, L.sweep, L.inverse, b, L.x, false);
}

}  // namespace waam::twin::internal
