// Exports of the simulated part: binary STL of its surface and the voxel grid in HDF5.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "analysis/h5_handle.h"
#include "analysis/simulate_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

using internal::H5Handle;

template <typename T>
void WriteDataset(hid_t parent, const char* name, hid_t file_type, hid_t memory_type, const std::vector<T>& data,
                  int rank, const hsize_t* dims, const std::filesystem::path& path) {
  H5Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  internal::CheckH5Output(space.get() >= 0, path, "dataspace");
  // Compressed (shuffle + deflate 4) in chunks of whole rows, about 256 KiB each: the readers take row ranges (the
  // voxels in deposition order, the height map's rows), so a chunk is never read for a few of its columns.
  H5Handle create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  internal::CheckH5Output(create.get() >= 0, path, "dataset properties");
  hsize_t row_values = 1;
  for (int r = 1; r < rank; ++r) row_values *= dims[r];
  if (dims[0] > 0 && row_values > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    std::vector<hsize_t> chunk(dims, dims + rank);
    const hsize_t kChunkBytes = 256 * 1024;
    chunk[0] = std::clamp<hsize_t>(kChunkBytes / (row_values * sizeof(T)), 1, dims[0]);
    internal::CheckH5Output(H5Pset_chunk(create.get(), rank, chunk.data()) >= 0 && H5Pset_shuffle(create.get()) >= 0 &&
                     H5Pset_deflate(create.get(), 4) >= 0,
                 path, "chunked, compressed layout");
  }
  H5Handle dataset(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, create.get(), H5P_DEFAULT), H5Dclose);
  internal::CheckH5Output(dataset.get() >= 0, path, name);
  if (!data.empty()) {
    internal::CheckH5Output(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0, path, name);
  }
}

void WriteDoubleAttribute(hid_t object, const char* name, const std::vector<double>& values,
                          const std::filesystem::path& path) {
  const hsize_t n = values.size();
  H5Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  H5Handle attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  internal::CheckH5Output(attribute.get() >= 0, path, name);
  internal::CheckH5Output(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) >= 0, path, name);
}

}  // namespace

void WriteSimulationH5(const twin::TwinResult& result, const std::filesystem::path& path) {
  const twin::VoxelGrid& grid = result.depositor.grid();
  std::vector<std::int32_t> ijk;
  std::vector<std::uint32_t> bead;
  std::vector<std::int32_t> layer;
  std::vector<float> time;
  ijk.reserve(grid.occupied() * 3);
  grid.ForEach([&](const twin::VoxelIndex& v, const twin::VoxelData& d) {
    ijk.insert(ijk.end(), {v.x(), v.y(), v.z()});
    bead.push_back(d.bead);
    layer.push_back(result.depositor.LayerOf(d));
    time.push_back(d.time_s);
  });
  AtomicOutput out(path);
  {
    H5Handle file = internal::CreateH5Output(out.temp_path(), path);
    WriteDoubleAttribute(file.get(), "voxel_mm", {grid.voxel_mm()}, path);
    WriteDoubleAttribute(file.get(), "origin_mm", {0.0, 0.0, 0.0}, path);
    H5Handle voxels(H5Gcreate2(file.get(), "voxels", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    internal::CheckH5Output(voxels.get() >= 0, path, "group voxels");
    const hsize_t n = bead.size();
    const hsize_t dims3[2] = {n, 3};
    WriteDataset(voxels.get(), "ijk", H5T_STD_I32LE, H5T_NATIVE_INT32, ijk, 2, dims3, path);
    WriteDataset(voxels.get(), "bead", H5T_STD_U32LE, H5T_NATIVE_UINT32, bead, 1, &n, path);
    WriteDataset(voxels.get(), "layer", H5T_STD_I32LE, H5T_NATIVE_INT32, layer, 1, &n, path);
    WriteDataset(voxels.get(), "time_s", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, time, 1, &n, path);
    // Top height map, rows along y.
    const twin::HeightMap& map = result.top;
    const hsize_t hdims[2] = {static_cast<hsize_t>(map.ny), static_cast<hsize_t>(map.nx)};
    WriteDataset(file.get(), "top_height_mm", H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, map.top_mm, 2, hdims, path);
    {
      H5Handle dataset(H5Dopen2(file.get(), "top_height_mm", H5P_DEFAULT), H5Dclose);
      WriteDoubleAttribute(dataset.get(), "first_column_ij",
                           {static_cast<double>(map.i0), static_cast<double>(map.j0)}, path);
    }
    // Bead table: layer, length mm, expected and deposited volume mm^3, start time s.
    std::vector<double> beads;
    for (const twin::BeadRecord& b : result.depositor.beads()) {
      beads.insert(beads.end(), {static_cast<double>(b.layer), b.length_mm, b.expected_volume_mm3,
                                 b.deposited_volume_mm3, b.start_time_s});
    }
    const hsize_t bdims[2] = {static_cast<hsize_t>(result.depositor.beads().size()), 5};
    WriteDataset(file.get(), "beads", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, beads, 2, bdims, path);
    voxels.Close();
    internal::CloseH5Output(&file, path);
  }
  out.Commit();
}

}  // namespace waam::analysis
