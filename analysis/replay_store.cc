// replay.h5 and probes_replay.png: measured and simulated thermocouple histories side by side.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "analysis/h5_handle.h"
#include "analysis/replay_command.h"
#include "analysis/png_file.h"
#include "analysis/thermal_plot.h"
#include "models/core/files.h"

namespace waam::analysis {

namespace {

using internal::H5Handle;

void ReplayDataset(hid_t parent, const std::string& name, const std::vector<double>& data, const std::vector<hsize_t>& dims,
             const std::filesystem::path& path) {
  H5Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  internal::CheckH5Output(space.get() >= 0, path, "dataspace");
  H5Handle d(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose);
  internal::CheckH5Output(d.get() >= 0, path, "dataset create");
  if (!data.empty()) {
    internal::CheckH5Output(H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0,
                            path, "dataset write");
  }
}

H5Handle ReplayGroup(hid_t parent, const char* name, const std::filesystem::path& path) {
  H5Handle g(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  internal::CheckH5Output(g.get() >= 0, path, "group create");
  return g;
}

}  // namespace

void WriteReplayH5(const ReplayModel& model, const ReplaySimulation& simulation, const std::filesystem::path& path) {
  const ReplayLog& log = model.log;
  const hsize_t rows = log.time_s.size();
  AtomicOutput out(path);
  {
    H5Handle file = internal::CreateH5Output(out.temp_path(), path);
    ReplayDataset(file.get(), "time_s", log.time_s, {rows}, path);
    ReplayDataset(file.get(), "power_w", log.power_w, {rows}, path);
    ReplayDataset(file.get(), "arc_on", std::vector<double>(log.arc_on.begin(), log.arc_on.end()), {rows}, path);
    std::vector<double> head;
    for (const Eigen::Vector3d& p : log.head_mm) head.insert(head.end(), {p.x(), p.y(), p.z()});
    ReplayDataset(file.get(), "head_mm", head, {rows, 3}, path);
    {
      H5Handle measured = ReplayGroup(file.get(), "measured", path);
      H5Handle simulated = ReplayGroup(file.get(), "simulated", path);
      for (std::size_t p = 0; p < model.probes.size(); ++p) {
        ReplayDataset(measured.get(), model.probes[p].name, log.probe_c[p], {rows}, path);
        ReplayDataset(simulated.get(), model.probes[p].name, simulation.probe_c[p], {rows}, path);
      }
    }
    internal::CloseH5Output(&file, path);
  }
  out.Commit();
}

namespace {

std::pair<double, double> ReplayRange(const std::vector<double>& a, const std::vector<double>& b) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const std::vector<double>* v : {&a, &b}) {
    for (double x : *v) {
      if (!std::isfinite(x)) continue;
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  if (!std::isfinite(lo)) lo = 0.0, hi = 100.0;
  const double pad = std::max(1.0, 0.05 * (hi - lo));
  return {lo - pad, hi + pad};
}

void ReplaySeries(cv::Mat& image, const internal::PlotFrame& frame, const std::vector<double>& t,
            const std::vector<double>& v, const cv::Scalar& colour, int width) {
  std::vector<cv::Point> line;
  auto flush = [&] {
    if (line.size() > 1) cv::polylines(image, line, false, colour, width, cv::LINE_AA);
    line.clear();
  };
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(v[i])) {
      flush();
      continue;
    }
    line.push_back(frame.Px(t[i], v[i]));
  }
  flush();
}

}  // namespace

void WriteReplayPng(const ReplayModel& model, const ReplaySimulation& simulation,
                    const std::vector<std::pair<double, double>>& windows, const std::filesystem::path& path) {
  const std::size_t n = model.probes.size();
  const int panel_h = 300, top = 50, width = 1100;
  cv::Mat image(top + static_cast<int>(n) * panel_h + 20, width, CV_8UC3, cv::Scalar(255, 255, 255));
  internal::PutLabel(image, "Thermocouples: measured (black) and simulated (blue); shaded: --windows", {90, 30}, 0.7);
  const std::vector<double>& t = model.log.time_s;
  const double t_end = std::max(1.0, t.back());
  for (std::size_t p = 0; p < n; ++p) {
    const auto [lo, hi] = ReplayRange(model.log.probe_c[p], simulation.probe_c[p]);
    const int y0 = top + static_cast<int>(p) * panel_h;
    const internal::PlotFrame frame{cv::Rect(90, y0 + 30, 820, panel_h - 100), 0.0, t_end, lo, hi};
    for (const auto& [a, b] : windows) {
      cv::rectangle(image, frame.Px(a, hi), frame.Px(b, lo), cv::Scalar(235, 235, 235), cv::FILLED);
    }
    frame.DrawAxes(image, "time from the log's first row [s]", "temperature [degC]");
    ReplaySeries(image, frame, t, model.log.probe_c[p], cv::Scalar(0, 0, 0), 1);
    ReplaySeries(image, frame, t, simulation.probe_c[p], cv::Scalar(180, 119, 31), 2);
    const ReplayErrors e = CompareProbe(t, model.log.probe_c[p], simulation.probe_c[p], 0.0, t_end);
    char text[160];
    std::snprintf(text, sizeof(text), "%s (column %s) at (%.0f, %.0f, %.0f) mm", model.probes[p].name.c_str(),
                  model.probes[p].column.c_str(), model.probes[p].at_mm.x(), model.probes[p].at_mm.y(),
                  model.probes[p].at_mm.z());
    internal::PutLabel(image, text, {330, y0 + 22}, 0.5);
    const int lx = 925, ly = y0 + 50;
    cv::line(image, {lx, ly - 5}, {lx + 30, ly - 5}, cv::Scalar(0, 0, 0), 2);
    internal::PutLabel(image, "measured", {lx + 36, ly});
    cv::line(image, {lx, ly + 20}, {lx + 30, ly + 20}, cv::Scalar(180, 119, 31), 2);
    internal::PutLabel(image, "simulated", {lx + 36, ly + 25});
    std::snprintf(text, sizeof(text), "rmse %.1f degC", e.rmse_c);
    internal::PutLabel(image, text, {lx, ly + 55}, 0.45);
    std::snprintf(text, sizeof(text), "max |err| %.1f degC", e.max_error_c);
    internal::PutLabel(image, text, {lx, ly + 75}, 0.45);
  }
  internal::WritePngAtomic(image, path);
}

}  // namespace waam::analysis
