// Marching tetrahedra: each cell of 2x2x2 voxel centres is cut into the six Kuhn tetrahedra sharing the diagonal
// 0-7; a tetrahedron with one or three corners inside gives one triangle, with two a quad, at the edge midpoints.
#include "twin/scanner/surface_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "twin/scanner/point_hash.h"

namespace waam::twin {
namespace {

// Corner c of a cell is at offset (c & 1, c >> 1 & 1, c >> 2 & 1).
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};

// The cell blocks to visit, sorted: every block with metal and its neighbours on the low side (cells reaching
// into it).
std::vector<Eigen::Vector3i> CellBlocks(const VoxelGrid& grid) {
  std::unordered_set<std::uint64_t> seen;
  std::vector<Eigen::Vector3i> cell_blocks;
  grid.ForEach([&](const VoxelIndex& idx, const VoxelData&) {
    const Eigen::Vector3i b(idx.x() >> 3, idx.y() >> 3, idx.z() >> 3);
    for (int d = 0; d < 8; ++d) {
      const Eigen::Vector3i c = b - Eigen::Vector3i(d & 1, d >> 1 & 1, d >> 2 & 1);
      if (seen.insert(CellKey(c)).second) cell_blocks.push_back(c);
    }
  });
  std::sort(cell_blocks.begin(), cell_blocks.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return cell_blocks;
}

// Marches the cells of the grid into `mesh`, block by block; vertices at edge midpoints are shared.
class TetMarcher {
 public:
  TetMarcher(const VoxelGrid& grid, planner::TriangleMesh* mesh) : grid_(grid), mesh_(mesh) {}

  // The cells of cell block `cb` (B^3 cells, the lowest at voxel cb * B).
  void Block(const Eigen::Vector3i& cb) {
    const Eigen::Vector3i origin = cb * B;
    for (int z = 0; z <= B; ++z)
      for (int y = 0; y <= B; ++y)
        for (int x = 0; x <= B; ++x)
          occ_[(z * (B + 1) + y) * (B + 1) + x] = grid_.Occupied(origin + Eigen::Vector3i(x, y, z)) ? 1 : 0;
    for (int z = 0; z < B; ++z) {
      for (int y = 0; y < B; ++y) {
        for (int x = 0; x < B; ++x) {
          std::array<std::uint8_t, 8> in;
          int count = 0;
          for (int c = 0; c < 8; ++c) {
            in[c] = occ_[((z + (c >> 2 & 1)) * (B + 1) + y + (c >> 1 & 1)) * (B + 1) + x + (c & 1)];
            count += in[c];
          }
          if (count == 0 || count == 8) continue;
          Cell(origin + Eigen::Vector3i(x, y, z), in);
        }
      }
    }
  }

  // Frees the vertex map (a voxel part's surface has ~10^7 facets).
  void Finish() { std::unordered_map<std::uint64_t, int>().swap(vertex_of_); }

 private:
  static constexpr int B = VoxelGrid::kBlock;

  // The six tetrahedra of the cell at `base` with corners `in` (1 = metal).
  void Cell(const Eigen::Vector3i& base, const std::array<std::uint8_t, 8>& in) {
    auto corner = [&](int c) -> Eigen::Vector3i { return base + Eigen::Vector3i(c & 1, c >> 1 & 1, c >> 2 & 1); };
    for (const auto& tet : kTets) {
      std::array<int, 4> inside{}, outside{};
      int ni = 0, no = 0;
      for (int t : tet) (in[t] ? inside[ni++] : outside[no++]) = t;
      if (ni == 0 || no == 0) continue;
      // Reference direction from the inside corners to the outside corners, for the facet orientation.
      Eigen::Vector3d ci = Eigen::Vector3d::Zero(), co = Eigen::Vector3d::Zero();
      for (int q = 0; q < ni; ++q) ci += corner(inside[q]).cast<double>() / ni;
      for (int q = 0; q < no; ++q) co += corner(outside[q]).cast<double>() / no;
      const Eigen::Vector3d out_dir = co - ci;
      if (ni == 1 || no == 1) {
        const int apex = ni == 1 ? inside[0] : outside[0];
        const std::array<int, 3> others = ni == 1 ? std::array<int, 3>{outside[0], outside[1], outside[2]}
                                                  : std::array<int, 3>{inside[0], inside[1], inside[2]};
        Emit(Vertex(corner(apex), corner(others[0])), Vertex(corner(apex), corner(others[1])),
             Vertex(corner(apex), corner(others[2])), out_dir);
      } else {
        // Two in, two out: the quad i0o0, i0o1, i1o1, i1o0.
        const int a = Vertex(corner(inside[0]), corner(outside[0]));
        const int b = Vertex(corner(inside[0]), corner(outside[1]));
        const int c = Vertex(corner(inside[1]), corner(outside[1]));
        const int d = Vertex(corner(inside[1]), corner(outside[0]));
        Emit(a, b, c, out_dir);
        Emit(a, c, d, out_dir);
      }
    }
  }

  // The vertex at the midpoint of the cell edge between voxel centres a and b.
  int Vertex(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    const Eigen::Vector3i key = a + b + Eigen::Vector3i::Ones();  // 2 x midpoint / v
    auto [it, inserted] = vertex_of_.emplace(CellKey(key), static_cast<int>(mesh_->vertices.size()));
    if (inserted) mesh_->vertices.push_back(key.cast<double>() * (0.5 * grid_.voxel_mm()));
    return it->second;
  }

  // The facet a, b, c, turned so that its normal points along `out_dir`.
  void Emit(int a, int b, int c, const Eigen::Vector3d& out_dir) {
    const auto& p = mesh_->vertices;
    const Eigen::Vector3d n = (p[b] - p[a]).cross(p[c] - p[a]);
    if (n.dot(out_dir) >= 0.0) {
      mesh_->facets.push_back({a, b, c});
    } else {
      mesh_->facets.push_back({a, c, b});
    }
  }

  const VoxelGrid& grid_;
  planner::TriangleMesh* mesh_;
  std::unordered_map<std::uint64_t, int> vertex_of_;  // edge midpoint in half-voxel units -> vertex
  std::array<std::uint8_t, (B + 1) * (B + 1) * (B + 1)> occ_{};
};

}  // namespace

planner::TriangleMesh ExtractSurface(const VoxelGrid& grid) {
  planner::TriangleMesh mesh;
  TetMarcher marcher(grid, &mesh);
  for (const Eigen::Vector3i& cb : CellBlocks(grid)) {
    CheckInterrupt();
    marcher.Block(cb);
  }
  // The vertex map first, then the slack of the arrays grown by push_back (a voxel part's surface has ~10^7 facets:
  // up to half their size again).
  marcher.Finish();
  mesh.vertices.shrink_to_fit();
  mesh.facets.shrink_to_fit();
  return mesh;
}

std::size_t ExposedFaces(const VoxelGrid& grid) {
  // Block by block on the occupancy words (word z: the slice at height z, bit x + 8 y): the neighbour of every voxel
  // in one direction is the block's word shifted, with the row or slice across the block's side taken from the
  // neighbouring block (the substrate below z = 0 is solid).
  using Bits = VoxelGrid::BlockBits;
  constexpr int B = VoxelGrid::kBlock;
  static_assert(B == 8, "a slice of a block is one 64-bit word");
  constexpr std::uint64_t kX0 = 0x0101010101010101ull;  // the bits of x = 0 in a slice
  constexpr std::uint64_t kX7 = kX0 << 7;
  static const Bits kEmpty{};
  Bits substrate;
  substrate.fill(~std::uint64_t{0});
  std::size_t faces = 0;
  grid.ForEachBlock([&](const VoxelIndex& origin, const Bits& w, const VoxelData*) {
    auto side = [&](int dx, int dy, int dz) -> const Bits& {
      if (origin.z() + dz * B < 0) return substrate;
      const Bits* bits = grid.BlockAt(origin + VoxelIndex(dx, dy, dz) * B);
      return bits != nullptr ? *bits : kEmpty;
    };
    const Bits &xp = side(1, 0, 0), &xm = side(-1, 0, 0), &yp = side(0, 1, 0), &ym = side(0, -1, 0);
    const Bits &zp = side(0, 0, 1), &zm = side(0, 0, -1);
    for (int z = 0; z < B; ++z) {
      const std::uint64_t s = w[static_cast<std::size_t>(z)];
      if (s == 0) continue;
      const auto k = static_cast<std::size_t>(z);
      const std::uint64_t solid[6] = {((s >> 1) & ~kX7) | ((xp[k] & kX0) << 7), ((s << 1) & ~kX0) | ((xm[k] & kX7) >> 7),
                                      (s >> 8) | (yp[k] << 56), (s << 8) | (ym[k] >> 56),
                                      z + 1 < B ? w[k + 1] : zp[0], z > 0 ? w[k - 1] : zm[B - 1]};
      for (const std::uint64_t n : solid) faces += static_cast<std::size_t>(std::popcount(s & ~n));
    }
  });
  return faces;
}

VoxelGrid Coarsen(const VoxelGrid& grid, int factor) {
  WAAM_THROW_UNLESS(factor >= 1, "coarsen: factor " << factor << " must be >= 1");
  VoxelGrid coarse(grid.voxel_mm() * factor, grid.max_voxels());
  if (factor == 1) {
    grid.ForEach([&](const VoxelIndex& v, const VoxelData& d) { coarse.Set(v, d); });
    return coarse;
  }
  auto floor_div = [factor](int a) { return a >= 0 ? a / factor : -((-a + factor - 1) / factor); };
  // Counted block by block in a small local array (the coarse cells one block touches), then added to the coarse
  // cells in the order first seen, each keeping the data of its first fine voxel in ForEach order (deterministic).
  // Where the factor divides the block size, a block holds its coarse cells whole and they are set at once.
  struct Cell {
    Eigen::Vector3i c;
    int count;
    VoxelData data;
  };
  std::vector<Cell> cells;
  std::unordered_map<std::uint64_t, std::size_t> slot;
  const int half = (factor * factor * factor + 1) / 2;
  const bool aligned = VoxelGrid::kBlock % factor == 0;  // every coarse cell inside one block
  const int span = (VoxelGrid::kBlock - 1) / factor + 2;  // coarse cells a block touches along an axis, at most
  std::vector<int> local_count(static_cast<std::size_t>(span * span * span), 0), local_first(local_count.size());
  std::vector<int> touched;
  grid.ForEachBlock([&](const VoxelIndex& origin, const VoxelGrid::BlockBits& bits, const VoxelData* data) {
    const Eigen::Vector3i c0(floor_div(origin.x()), floor_div(origin.y()), floor_div(origin.z()));
    touched.clear();
    for (int word = 0; word < static_cast<int>(bits.size()); ++word) {
      for (std::uint64_t w = bits[static_cast<std::size_t>(word)]; w != 0; w &= w - 1) {
        const int n = 64 * word + std::countr_zero(w);
        const VoxelIndex v = origin + VoxelIndex(n & 7, n >> 3 & 7, n >> 6);
        const Eigen::Vector3i c = Eigen::Vector3i(floor_div(v.x()), floor_div(v.y()), floor_div(v.z())) - c0;
        const auto l = static_cast<std::size_t>(c.x() + span * (c.y() + span * c.z()));
        if (local_count[l]++ == 0) {
          local_first[l] = n;
          touched.push_back(static_cast<int>(l));
        }
      }
    }
    for (const int l : touched) {
      const auto i = static_cast<std::size_t>(l);
      const Eigen::Vector3i c = c0 + Eigen::Vector3i(l % span, l / span % span, l / (span * span));
      if (aligned) {  // no other block reaches this coarse cell: it is complete
        if (local_count[i] >= half) coarse.Set(c, data[local_first[i]]);
        local_count[i] = 0;
        continue;
      }
      const auto [it, inserted] = slot.try_emplace(CellKey(c), cells.size());
      if (inserted) cells.push_back({c, 0, data[local_first[i]]});
      cells[it->second].count += local_count[i];
      local_count[i] = 0;
    }
  });
  for (const Cell& cell : cells) {
    if (cell.count >= half) coarse.Set(cell.c, cell.data);
  }
  return coarse;
}

std::size_t OpenEdges(const planner::TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& f : mesh.facets) {
    for (int k = 0; k < 3; ++k) ++uses[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
  }
  std::size_t open = 0;
  for (const auto& [edge, n] : uses) open += n != 2 ? 1 : 0;
  return open;
}

}  // namespace waam::twin
