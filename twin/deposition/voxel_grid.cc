// Sparse blocked voxel grid: block lookup through a hash map with a one-entry cache.
#include "twin/deposition/voxel_grid.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"

namespace waam::twin {
namespace {

int FloorDiv(int a, int bits) { return a >> bits; }  // arithmetic shift: floor division by 2^bits

}  // namespace

VoxelGrid::VoxelGrid(double voxel_mm, std::size_t max_voxels) : voxel_mm_(voxel_mm), max_voxels_(max_voxels) {
  WAAM_THROW_UNLESS(std::isfinite(voxel_mm) && voxel_mm > 0.0 && voxel_mm <= 10.0,
                    "voxel grid: voxel_mm = " << voxel_mm << ": must be in (0, 10] mm");
  WAAM_THROW_UNLESS(max_voxels >= 1, "voxel grid: max_voxels = 0: must be >= 1");
}

double VoxelGrid::OccupiedVolume() const {
  return static_cast<double>(occupied_) * voxel_mm_ * voxel_mm_ * voxel_mm_;
}

std::size_t VoxelGrid::MemoryBytes() const {
  return blocks_.capacity() * sizeof(Block) + index_.size() * (sizeof(std::uint64_t) + sizeof(std::uint32_t) + 16) +
         index_.bucket_count() * sizeof(void*);
}

VoxelIndex VoxelGrid::IndexOf(const Eigen::Vector3d& p_P) const {
  return VoxelIndex(static_cast<int>(std::floor(p_P.x() / voxel_mm_)), static_cast<int>(std::floor(p_P.y() / voxel_mm_)),
                    static_cast<int>(std::floor(p_P.z() / voxel_mm_)));
}

Eigen::Vector3d VoxelGrid::Center(const VoxelIndex& v) const {
  return (v.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_mm_;
}

std::uint64_t VoxelGrid::Key(const VoxelIndex& b) {
  // 21 bits per axis, offset so that negative block coordinates pack too.
  constexpr std::uint64_t kOffset = 1u << 20;
  return ((static_cast<std::uint64_t>(b.x() + kOffset) & 0x1FFFFF) << 42) |
         ((static_cast<std::uint64_t>(b.y() + kOffset) & 0x1FFFFF) << 21) |
         (static_cast<std::uint64_t>(b.z() + kOffset) & 0x1FFFFF);
}

const VoxelGrid::Block* VoxelGrid::FindBlock(const VoxelIndex& v) const {
  const VoxelIndex b(FloorDiv(v.x(), kBlockBits), FloorDiv(v.y(), kBlockBits), FloorDiv(v.z(), kBlockBits));
  const auto it = index_.find(Key(b));
  return it == index_.end() ? nullptr : &blocks_[it->second];
}

VoxelGrid::Block* VoxelGrid::FindBlockForWrite(const VoxelIndex& v) {
  const VoxelIndex b(FloorDiv(v.x(), kBlockBits), FloorDiv(v.y(), kBlockBits), FloorDiv(v.z(), kBlockBits));
  const std::uint64_t key = Key(b);
  if (key != cached_key_) {
    const auto it = index_.find(key);
    cached_key_ = key;
    cached_block_ = it == index_.end() ? -1 : static_cast<std::int64_t>(it->second);
  }
  return cached_block_ < 0 ? nullptr : &blocks_[static_cast<std::size_t>(cached_block_)];
}

namespace {
int LocalIndex(const VoxelIndex& v) {
  constexpr int m = VoxelGrid::kBlock - 1;
  return (v.x() & m) | ((v.y() & m) << VoxelGrid::kBlockBits) | ((v.z() & m) << (2 * VoxelGrid::kBlockBits));
}
}  // namespace

bool VoxelGrid::Occupied(const VoxelIndex& v) const {
  const Block* block = FindBlock(v);
  if (block == nullptr) return false;
  const int n = LocalIndex(v);
  return block->occupancy[n >> 6] >> (n & 63) & 1u;
}

const VoxelData* VoxelGrid::Get(const VoxelIndex& v) const {
  const Block* block = FindBlock(v);
  if (block == nullptr) return nullptr;
  const int n = LocalIndex(v);
  return (block->occupancy[n >> 6] >> (n & 63) & 1u) ? &block->data[n] : nullptr;
}

bool VoxelGrid::Set(const VoxelIndex& v, const VoxelData& data) {
  if (v.z() < 0) return false;  // substrate
  Block* block = FindBlockForWrite(v);
  if (block == nullptr) {
    const VoxelIndex b(FloorDiv(v.x(), kBlockBits), FloorDiv(v.y(), kBlockBits), FloorDiv(v.z(), kBlockBits));
    blocks_.emplace_back();
    blocks_.back().origin = b * kBlock;
    index_.emplace(Key(b), static_cast<std::uint32_t>(blocks_.size() - 1));
    cached_key_ = Key(b);
    cached_block_ = static_cast<std::int64_t>(blocks_.size() - 1);
    block = &blocks_.back();
  }
  const int n = LocalIndex(v);
  std::uint64_t& word = block->occupancy[n >> 6];
  const std::uint64_t bit = std::uint64_t{1} << (n & 63);
  if (word & bit) return false;
  WAAM_THROW_UNLESS(occupied_ < max_voxels_,
                    "voxel grid: more than simulation.max_voxels = " << max_voxels_ << " occupied voxels at "
                    << voxel_mm_ << " mm; use a coarser simulation.voxel_mm or raise max_voxels");
  word |= bit;
  block->data[n] = data;
  ++occupied_;
  return true;
}

bool VoxelGrid::Bounds(VoxelIndex* lo, VoxelIndex* hi) const {
  bool any = false;
  ForEach([&](const VoxelIndex& v, const VoxelData&) {
    if (!any) {
      *lo = v;
      *hi = v;
      any = true;
    } else {
      *lo = lo->cwiseMin(v);
      *hi = hi->cwiseMax(v);
    }
  });
  return any;
}

}  // namespace waam::twin
