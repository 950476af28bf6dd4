// HDF5 output of the planned path: one dataset of points per layer (HDF5 C API).
#include <hdf5.h>

#include <array>
#include <string>
#include <vector>

#include "analysis/h5_handle.h"
#include "analysis/plan_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

using internal::CheckH5Output;
using internal::H5Handle;

constexpr std::array<const char*, 11> kColumns = {
    "x_mm", "y_mm", "z_mm", "tool_x", "tool_y", "tool_z", "bead_width_mm", "bead_height_mm",
    "travel_speed_mm_min", "weld", "layer"};

void WriteStringAttribute(hid_t object, const char* name, const std::string& value,
                          const std::filesystem::path& path) {
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size() + 1);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  CheckH5Output(attribute.get() >= 0, path, "attribute create");
  CheckH5Output(H5Awrite(attribute.get(), type.get(), value.c_str()) >= 0, path, "attribute write");
}

}  // namespace

void WritePlanH5(const planner::Plan& plan, const std::filesystem::path& path) {
  AtomicOutput out(path);
  {
    H5Handle file = internal::CreateH5Output(out.temp_path(), path);
    std::string columns;
    for (const char* column : kColumns) columns += std::string(columns.empty() ? "" : ",") + column;
    WriteStringAttribute(file.get(), "columns", columns, path);
    WriteStringAttribute(file.get(), "scenario", plan.name, path);
    WriteStringAttribute(file.get(), "frame", "part frame P: z = 0 is the substrate top, mm", path);
    H5Handle group(H5Gcreate2(file.get(), "layers", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    CheckH5Output(group.get() >= 0, path, "group create");

    std::vector<double> table;
    for (const planner::LayerPath& layer : plan.layers) {
      table.clear();
      for (const planner::PathPoint& point : layer.points) {
        const double row[kColumns.size()] = {point.p_P.x(), point.p_P.y(), point.p_P.z(),
                                             point.tool_dir_P.x(), point.tool_dir_P.y(), point.tool_dir_P.z(),
                                             point.bead_width_mm, point.bead_height_mm, point.speed_mm_s * 60.0,
                                             point.weld ? 1.0 : 0.0, static_cast<double>(layer.index)};
        table.insert(table.end(), row, row + kColumns.size());
      }
      const hsize_t dims[2] = {layer.points.size(), kColumns.size()};
      H5Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
      char name[32];
      std::snprintf(name, sizeof(name), "layer_%04d", layer.index);
      H5Handle dataset(H5Dcreate2(group.get(), name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                  H5P_DEFAULT),
                       H5Dclose);
      CheckH5Output(dataset.get() >= 0, path, "dataset create");
      if (!table.empty()) {
        CheckH5Output(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, table.data()) >= 0, path,
              "dataset write");
      }
    }
    group.Close();
    internal::CloseH5Output(&file, path);
  }
  out.Commit();
}

}  // namespace waam::analysis
