// Sparse blocked voxel grid of the deposited part: occupancy plus the bead and deposition time of every voxel.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace waam::twin {

// Integer voxel coordinates; voxel (i, j, k) covers [i, i+1) x [j, j+1) x [k, k+1) times voxel_mm in the part frame.
using VoxelIndex = Eigen::Vector3i;

// What is stored for one occupied voxel (8 bytes; the layer is found through the bead table of the deposit).
struct VoxelData {
  std::uint32_t bead = 0;   // index of the bead (weld pass) that deposited the voxel
  float time_s = 0.0f;      // deposition time from the start of the build, s
};

// A sparse grid of 8^3-voxel blocks in a hash map. Voxels below z = 0 are the substrate: solid, never stored.
// The const methods write nothing, so a const grid can be read from many threads at once. Holds at most
// `max_voxels` occupied voxels; Set() past that throws InputError naming the limit.
class VoxelGrid {
 public:
  static constexpr int kBlockBits = 3;
  static constexpr int kBlock = 1 << kBlockBits;            // 8 voxels per block edge
  static constexpr int kBlockVoxels = kBlock * kBlock * kBlock;

  // `voxel_mm` in (0, 10]; `max_voxels` >= 1. Throws InputError otherwise.
  VoxelGrid(double voxel_mm, std::size_t max_voxels);

  double voxel_mm() const { return voxel_mm_; }
  std::size_t max_voxels() const { return max_voxels_; }
  std::size_t occupied() const { return occupied_; }
  std::size_t blocks() const { return blocks_.size(); }
  // Volume of the occupied voxels, mm^3.
  double OccupiedVolume() const;
  // Approximate heap memory of the grid, bytes.
  std::size_t MemoryBytes() const;

  // Voxel containing the point `p_P` (mm).
  VoxelIndex IndexOf(const Eigen::Vector3d& p_P) const;
  // Centre of voxel `v` in the part frame, mm.
  Eigen::Vector3d Center(const VoxelIndex& v) const;

  // True if the voxel is occupied by deposited metal.
  bool Occupied(const VoxelIndex& v) const;
  // True if occupied or substrate (k < 0).
  bool Solid(const VoxelIndex& v) const { return v.z() < 0 || Occupied(v); }
  // Occupies voxel `v` (k >= 0) with `data`; returns false if it was already occupied (then nothing changes).
  bool Set(const VoxelIndex& v, const VoxelData& data);
  // Data of an occupied voxel, or nullptr.
  const VoxelData* Get(const VoxelIndex& v) const;

  // Inclusive bounds of the occupied voxels; false if the grid is empty.
  bool Bounds(VoxelIndex* lo, VoxelIndex* hi) const;

  // Calls f(index, data) for every occupied voxel, block by block (deterministic order of insertion).
  template <typename F>
  void ForEach(F&& f) const {
    for (const Block& block : blocks_) {
      for (int n = 0; n < kBlockVoxels; ++n) {
        if (!(block.occupancy[n >> 6] >> (n & 63) & 1u)) continue;
        const VoxelIndex v(block.origin.x() + (n & (kBlock - 1)), block.origin.y() + ((n >> kBlockBits) & (kBlock - 1)),
                           block.origin.z() + (n >> (2 * kBlockBits)));
        f(v, block.data[n]);
      }
    }
  }

  // The occupancy of one block: bit n of word n / 64 is voxel origin + (n & 7, n >> 3 & 7, n >> 6), so word z is the
  // 8 x 8 slice at height origin.z() + z, bit x + 8 y.
  using BlockBits = std::array<std::uint64_t, kBlockVoxels / 64>;

  // Calls f(origin, bits, data) for every block (origin: its first voxel, a multiple of kBlock on each axis; data:
  // kBlockVoxels entries, voxel n's valid where its bit is set), in the order of ForEach; for whole-block bit
  // operations (exposed faces, coarsening).
  template <typename F>
  void ForEachBlock(F&& f) const {
    for (const Block& block : blocks_) f(block.origin, block.occupancy, block.data.data());
  }
  // The occupancy of the block whose first voxel is `origin` (a multiple of kBlock on each axis), or nullptr when the
  // block holds no voxel.
  const BlockBits* BlockAt(const VoxelIndex& origin) const {
    const Block* block = FindBlock(origin);
    return block == nullptr ? nullptr : &block->occupancy;
  }

 private:
  struct Block {
    VoxelIndex origin;                                   // voxel index of the block's first voxel
    BlockBits occupancy{};
    std::array<VoxelData, kBlockVoxels> data{};
  };
  static std::uint64_t Key(const VoxelIndex& block_coord);
  // The block holding voxel `v`, or nullptr. Const and cache-free: a const grid is read from many threads at once.
  const Block* FindBlock(const VoxelIndex& v) const;
  // The same for Set(), through a one-entry cache of the last block (deposition writes runs of voxels per block).
  Block* FindBlockForWrite(const VoxelIndex& v);

  double voxel_mm_;
  std::size_t max_voxels_;
  std::size_t occupied_ = 0;
  std::vector<Block> blocks_;
  std::unordered_map<std::uint64_t, std::uint32_t> index_;
  // One-entry cache of the last block Set() looked up; written only by non-const methods.
  std::uint64_t cached_key_ = ~std::uint64_t{0};
  std::int64_t cached_block_ = -1;
};

}  // namespace waam::twin
