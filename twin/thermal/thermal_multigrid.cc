// Additive-correction multigrid on the structured grid (Hutchinson & Raithby 1986): coarse levels from 2 x 2 x 2
// blocks, chunked symmetric Gauss-Seidel smoothing, an exact solve on the coarsest level.
#include "twin/thermal/thermal_multigrid.h"

#include <algorithm>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// Coarsening stops at this many cells (the coarsest level is solved exactly, by dense Cholesky) ...
constexpr std::size_t kCoarsestCells = 96;
// ... or when a level keeps more than this share of its finer level's cells (the blocks no longer merge cells).
constexpr double kPoorCoarsening = 0.75;

// One Gauss-Seidel sweep of A x = b over the chunks of ForChunks, forward or backward; inside a chunk the new values
// are used at once, values of other chunks are those from before the sweep.
void Sweep(const StencilSystem& a, const std::vector<double>& b, std::vector<double>& x, std::vector<double>& before,
           bool forward) {
  const std::size_t n = a.size();
  if (n > kChunk) before = x;
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    auto relax = [&](std::size_t i) {
      double sum = b[i];
      for (int f = 0; f < 6; ++f) {
        const int j = a.neighbour[i][f];
        if (j < 0) continue;
        const std::size_t u = static_cast<std::size_t>(j);
        sum += a.conductance[i][f] * (u >= begin && u < end ? x[u] : before[u]);
      }
      x[i] = sum / a.diagonal[i];
    };
    if (forward) {
      for (std::size_t i = begin; i < end; ++i) relax(i);
    } else {
      for (std::size_t i = end; i-- > begin;) relax(i);
    }
  });
}

}  // namespace

void AdditiveCorrectionMultigrid::Setup(const StencilSystem& fine, const std::vector<std::array<int, 3>>& ijk) {
  fine_ = &fine;
  coarse_.clear();
  coarse_.reserve(32);
  fine_residual_.resize(fine.size());
  fine_before_.resize(fine.size());
  std::vector<std::array<int, 3>> coords = ijk;
  std::vector<std::array<int, 3>> next;
  std::vector<int> map;
  while (true) {
    const StencilSystem& a = coarse_.empty() ? fine : coarse_.back().system;
    const std::size_t n = a.size();
    if (n <= kCoarsestCells || coarse_.size() >= 30) break;
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
    Level level;
    level.parent.resize(n);
    next.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<int, 3> c = {coords[i][0] >> 1, coords[i][1] >> 1, coords[i][2] >> 1};
      const std::size_t key = (c[0] - lo[0]) + nx * ((c[1] - lo[1]) + ny * static_cast<std::size_t>(c[2] - lo[2]));
      if (map[key] < 0) {
        map[key] = static_cast<int>(next.size());
        next.push_back(c);
      }
      level.parent[i] = map[key];
    }
    const std::size_t m = next.size();
    if (static_cast<double>(m) > kPoorCoarsening * static_cast<double>(n)) break;
    // Hutchinson & Raithby eqs. 9-12: a block's equation is the sum of its cells' equations with one correction for
    // all of them; faces inside the block cancel from the diagonal, faces between blocks add up.
    StencilSystem& c = level.system;
    c.neighbour.assign(m, {-1, -1, -1, -1, -1, -1});
    c.conductance.assign(m, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
    c.diagonal.assign(m, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const int block = level.parent[i];
      c.diagonal[block] += a.diagonal[i];
      for (int f = 0; f < 6; ++f) {
        const int j = a.neighbour[i][f];
        if (j < 0) continue;
        const int other = level.parent[j];
        if (other == block) {
          c.diagonal[block] -= a.conductance[i][f];
        } else {
          c.neighbour[block][f] = other;
          c.conductance[block][f] += a.conductance[i][f];
        }
      }
    }
    level.b.resize(m);
    level.x.resize(m);
    level.residual.resize(m);
    level.before.resize(m);
    coarse_.push_back(std::move(level));
    coords.swap(next);
  }
}

void AdditiveCorrectionMultigrid::Apply(const std::vector<double>& r, std::vector<double>& z) { Cycle(0, r, z); }

void AdditiveCorrectionMultigrid::Cycle(std::size_t level, const std::vector<double>& b, std::vector<double>& x) {
  const StencilSystem& a = level == 0 ? *fine_ : coarse_[level - 1].system;
  std::vector<double>& residual = level == 0 ? fine_residual_ : coarse_[level - 1].residual;
  std::vector<double>& before = level == 0 ? fine_before_ : coarse_[level - 1].before;
  const std::size_t n = a.size();
  std::fill(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
  if (level == coarse_.size()) {
    // The coarsest level: symmetric Gauss-Seidel pairs from zero (a symmetric operator).
    for (int pass = 0; pass < 8; ++pass) {
      Sweep(a, b, x, before, true);
      Sweep(a, b, x, before, false);
    }
    return;
  }
  Sweep(a, b, x, before, true);
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      double ax = a.diagonal[i] * x[i];
      for (int f = 0; f < 6; ++f) {
        const int j = a.neighbour[i][f];
        if (j >= 0) ax -= a.conductance[i][f] * x[j];
      }
      residual[i] = b[i] - ax;
    }
  });
  Level& coarse = coarse_[level];
  std::fill(coarse.b.begin(), coarse.b.end(), 0.0);
  for (std::size_t i = 0; i < n; ++i) coarse.b[coarse.parent[i]] += residual[i];
  Cycle(level + 1, coarse.b, coarse.x);
  for (std::size_t i = 0; i < n; ++i) x[i] += coarse.x[coarse.parent[i]];
  Sweep(a, b, x, before, false);
}

}  // namespace waam::twin::internal
