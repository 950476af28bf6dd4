// thermal.h5: probe histories, per-layer records, the timeline's spans and the temperature field at each layer's end.
#include <hdf5.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/h5_handle.h"
#include "analysis/thermal_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

using internal::H5Handle;

void ThermalH5Check(bool ok, const std::filesystem::path& path, const std::string& what) {
  WAAM_THROW_UNLESS(ok, "cannot write " << path.string() << ": HDF5 " << what << " failed");
}

// A dataset of `dims` (rank 1 or 3); 3D fields are chunked by z-slab and deflated when zlib is available.
template <typename T>
hid_t ThermalH5Dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                       const std::vector<T>& data, const std::vector<hsize_t>& dims,
                       const std::filesystem::path& path) {
  H5Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  ThermalH5Check(space.get() >= 0, path, "dataspace of " + name);
  H5Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (dims.size() == 3 && !data.empty() && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    const hsize_t chunk[3] = {1, dims[1], dims[2]};
    H5Pset_chunk(properties.get(), 3, chunk);
    H5Pset_deflate(properties.get(), 4);
  }
  const hid_t dataset =
      H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT);
  ThermalH5Check(dataset >= 0, path, name);
  if (!data.empty()) {
    ThermalH5Check(H5Dwrite(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0, path, name);
  }
  return dataset;
}

void ThermalH5Doubles(hid_t parent, const std::string& name, const std::vector<double>& data,
                      const std::filesystem::path& path) {
  H5Handle d(ThermalH5Dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, {data.size()}, path), H5Dclose);
}

void ThermalH5Attribute(hid_t object, const char* name, const std::vector<double>& values,
                        const std::filesystem::path& path) {
  const hsize_t n = values.size();
  H5Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  H5Handle attribute(H5Acreate2(object, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  ThermalH5Check(attribute.get() >= 0, path, name);
  ThermalH5Check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) >= 0, path, name);
}

hid_t ThermalH5Group(hid_t parent, const char* name, const std::filesystem::path& path) {
  const hid_t group = H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ThermalH5Check(group >= 0, path, std::string("group ") + name);
  return group;
}

void WriteLayersAndTimeline(hid_t file, const ThermalRunResult& result, const std::filesystem::path& path) {
  H5Handle layers(ThermalH5Group(file, "layers", path), H5Gclose);
  std::vector<double> index, start, end, interpass, peak, wait;
  for (const ThermalLayer& l : result.layers) {
    index.push_back(l.layer);
    start.push_back(l.start_s);
    end.push_back(l.end_s);
    interpass.push_back(l.interpass_c);
    peak.push_back(l.peak_c);
    wait.push_back(l.wait_s);
  }
  ThermalH5Doubles(layers.get(), "layer", index, path);
  ThermalH5Doubles(layers.get(), "start_s", start, path);
  ThermalH5Doubles(layers.get(), "end_s", end, path);
  ThermalH5Doubles(layers.get(), "interpass_c", interpass, path);
  ThermalH5Doubles(layers.get(), "peak_c", peak, path);
  ThermalH5Doubles(layers.get(), "wait_s", wait, path);
  H5Handle timeline(ThermalH5Group(file, "timeline", path), H5Gclose);
  std::vector<std::int32_t> kind, layer, point;
  std::vector<double> span_start, span_end;
  for (const planner::TimedSpan& s : result.timeline.spans) {
    kind.push_back(static_cast<std::int32_t>(s.kind));
    layer.push_back(s.layer);
    point.push_back(static_cast<std::int32_t>(s.point));
    span_start.push_back(s.start_s);
    span_end.push_back(s.end_s);
  }
  const hsize_t n = kind.size();
  H5Handle k(ThermalH5Dataset(timeline.get(), "kind", H5T_STD_I32LE, H5T_NATIVE_INT32, kind, {n}, path), H5Dclose);
  H5Handle l(ThermalH5Dataset(timeline.get(), "layer", H5T_STD_I32LE, H5T_NATIVE_INT32, layer, {n}, path), H5Dclose);
  H5Handle p(ThermalH5Dataset(timeline.get(), "point", H5T_STD_I32LE, H5T_NATIVE_INT32, point, {n}, path), H5Dclose);
  ThermalH5Doubles(timeline.get(), "start_s", span_start, path);
  ThermalH5Doubles(timeline.get(), "end_s", span_end, path);
}

}  // namespace

void WriteThermalH5(const ThermalRunResult& result, const std::filesystem::path& path) {
  AtomicOutput out(path);
  {
    H5Handle file(H5Fcreate(out.temp_path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    ThermalH5Check(file.get() >= 0, path, "file create");
    {
      H5Handle probes(ThermalH5Group(file.get(), "probes", path), H5Gclose);
      ThermalH5Doubles(probes.get(), "time_s", result.sample_time_s, path);
      for (const ThermalProbeHistory& probe : result.probes) {
        ThermalH5Doubles(probes.get(), probe.name, probe.temperature_c, path);
        H5Handle d(H5Dopen2(probes.get(), probe.name.c_str(), H5P_DEFAULT), H5Dclose);
        ThermalH5Attribute(d.get(), "position_mm", {probe.p_mm.x(), probe.p_mm.y(), probe.p_mm.z()}, path);
      }
    }
    WriteLayersAndTimeline(file.get(), result, path);
    H5Handle fields(ThermalH5Group(file.get(), "fields", path), H5Gclose);
    for (const ThermalLayerField& lf : result.fields) {
      const twin::TemperatureField& f = lf.field;
      char name[32];
      std::snprintf(name, sizeof(name), "layer_%04d", lf.layer);
      const std::vector<hsize_t> dims = {static_cast<hsize_t>(f.size.z()), static_cast<hsize_t>(f.size.y()),
                                         static_cast<hsize_t>(f.size.x())};
      H5Handle d(ThermalH5Dataset(fields.get(), name, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, f.temperature_c, dims, path),
                 H5Dclose);
      ThermalH5Attribute(d.get(), "origin_mm", {f.origin_mm.x(), f.origin_mm.y(), f.origin_mm.z()}, path);
      ThermalH5Attribute(d.get(), "cell_mm", {f.cell_mm}, path);
      ThermalH5Attribute(d.get(), "dims", {double(f.size.x()), double(f.size.y()), double(f.size.z())}, path);
      ThermalH5Attribute(d.get(), "time_s", {lf.time_s}, path);
      ThermalH5Attribute(d.get(), "layer", {double(lf.layer)}, path);
    }
  }
  out.Commit();
}

}  // namespace waam::analysis
