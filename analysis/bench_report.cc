// report.html of `waam bench`: tables, the published figures, model-fit and void plots (inline SVG) and the
// scenarios' pictures (base64 PNG), in one file with no external resources.
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/bench_command.h"
#include "analysis/png_file.h"
#include "analysis/svg_plot.h"
#include "analysis/viewer.h"
#include "models/bead/csw_model.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/fit/model_file.h"
#include "models/voids/void_length_model.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::string Base64(const std::vector<unsigned char>& bytes) {
  return internal::Base64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// An <img> with the PNG at `path` scaled down to at most `max_width` px, or "" if the file is absent.
// Throws InputError naming `path` if it is not a readable PNG.
std::string EmbeddedPng(const fs::path& path, const std::string& caption, int max_width = 600) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "";
  cv::Mat image = internal::ReadPng(path, 3);
  if (image.cols > max_width) {
    cv::resize(image, image, cv::Size(max_width, image.rows * max_width / image.cols), 0, 0, cv::INTER_AREA);
  }
  const std::vector<unsigned char> png = internal::EncodePng(image);
  return "<figure><img alt=\"" + HtmlEscape(caption) + "\" src=\"data:image/png;base64," + Base64(png) +
         "\"><figcaption>" + HtmlEscape(caption) + "</figcaption></figure>\n";
}

std::string Cell(const nlohmann::json& v) {
  if (v.is_null()) return "&ndash;";
  if (v.is_number_float()) {
    char text[32];
    const double d = v.get<double>();
    std::snprintf(text, sizeof(text), std::abs(d) >= 1000 || d == std::floor(d) ? "%.0f" : "%.4g", d);
    return text;
  }
  if (v.is_string()) return HtmlEscape(v.get<std::string>());
  return HtmlEscape(JsonText(v, -1));
}

const nlohmann::json* Step(const nlohmann::json& entry, const std::string& name) {
  if (!entry.contains("steps")) return nullptr;
  for (const nlohmann::json& s : entry["steps"]) {
    if (s.value("name", "") == name) return &s;
  }
  return nullptr;
}

nlohmann::json Metric(const nlohmann::json& entry, const std::string& step, const std::string& key) {
  const nlohmann::json* s = Step(entry, step);
  return s && s->contains("metrics") && (*s)["metrics"].contains(key) ? (*s)["metrics"][key] : nlohmann::json();
}

// A simulate measure's cell: its value, or "n/a" with the reason (simulate.json not_applicable) as a tooltip.
std::string MeasureCell(const nlohmann::json& entry, const std::string& key) {
  const nlohmann::json value = Metric(entry, "simulate", key);
  const nlohmann::json reasons = Metric(entry, "simulate", "not_applicable");
  if (value.is_null() && reasons.is_object() && reasons.contains(key)) {
    return "<span class=\"na\" title=\"" + Cell(reasons[key]) + "\">n/a</span>";
  }
  return Cell(value);
}

// user + system CPU time of a scenario's child process, s (the wall time depends on the machine's load).
std::string CpuSeconds(const nlohmann::json& timing) {
  if (!timing.contains("user_s") || !timing.contains("sys_s")) return Cell(nullptr);
  return Cell(timing["user_s"].get<double>() + timing["sys_s"].get<double>());
}

std::string OverviewTable(const nlohmann::json& scenarios) {
  std::ostringstream html;
  html << "<table><tr><th>scenario</th><th>outcome</th><th>exit (expected)</th><th>wall s</th><th>CPU s</th>"
          "<th>peak MiB</th><th>layers</th><th>passes / layer</th><th>weld m</th><th>check violations</th><th>volume error %</th>"
          "<th>deviation rms mm</th><th>voids</th><th>Ra mm</th><th>boundary lag mm</th></tr>\n";
  for (const nlohmann::json& e : scenarios) {
    const std::string outcome = e.value("outcome", "fail");
    const nlohmann::json weld = Metric(e, "plan", "weld_length_mm");
    html << "<tr><td><a href=\"#" << HtmlEscape(e.value("id", "")) << "\">" << HtmlEscape(e.value("id", ""))
         << "</a></td><td class=\"" << outcome << "\">" << outcome << "</td><td>" << Cell(e["exit_code"]) << " ("
         << Cell(e["expected_exit_code"]) << ")</td><td>" << Cell(e["timing"].value("wall_s", nlohmann::json()))
         << "</td><td>" << CpuSeconds(e["timing"]) << "</td><td>"
         << Cell(e["timing"].value("peak_rss_mb", nlohmann::json())) << "</td><td>"
         << Cell(Metric(e, "plan", "layers")) << "</td><td>" << Cell(Metric(e, "plan", "max_passes_per_layer"))
         << "</td><td>" << (weld.is_number() ? Cell(weld.get<double>() / 1000.0) : Cell(weld)) << "</td><td>"
         << Cell(Metric(e, "check", "violation_count")) << "</td><td>"
         << Cell(Metric(e, "simulate", "volume_error_pct")) << "</td><td>"
         << Cell(Metric(e, "simulate", "deviation/rms_mm")) << "</td><td>" << Cell(Metric(e, "simulate", "voids/count"))
         << "</td><td>" << MeasureCell(e, "ra_mm") << "</td><td>" << MeasureCell(e, "boundary_lag_mm")
         << "</td></tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

std::string ReferenceTable(const nlohmann::json& reference) {
  std::ostringstream html;
  html << "<table><tr><th>source</th><th>quantity</th><th>published</th><th>ours</th><th>unit</th>"
          "<th>ours from</th></tr>\n";
  for (const nlohmann::json& r : reference) {
    html << "<tr><td>" << Cell(r["source"]) << "</td><td>" << Cell(r["quantity"]) << "</td><td>"
         << Cell(r["published"]) << "</td><td><b>" << Cell(r["ours"]) << "</b></td><td>" << Cell(r["unit"])
         << "</td><td>" << Cell(r["scenario"]) << "</td></tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

// The fitted default bead models drawn over the papers' tables they were fitted to.
std::string ModelPlots() {
  const fs::path data = models::DefaultModelPath("csw").parent_path();
  std::ostringstream html;
  const CsvTable t18 = CsvTable::Read(data / "nguyen2022_table18_bead_vs_speed.csv");
  const std::vector<double> speed = t18.Numbers("travel_speed_mm_per_min"), height = t18.Numbers("height_mm"),
                            width = t18.Numbers("width_mm");
  const models::SpeedHeightModel sh = models::SpeedHeightModel::Load(models::DefaultModelPath("speed_height"));
  const models::WidthHeightModel wh = models::WidthHeightModel::Load(models::DefaultModelPath("width_height"));
  SvgSeries sh_line{"fit v = a h^b (models/data/speed_height.json)", {}, {}, kColours[1], true};
  SvgSeries wh_line{"quartic fit (models/data/width_height.json)", {}, {}, kColours[1], true};
  for (double h = 0.9; h <= 2.8001; h += 0.02) {
    sh_line.x.push_back(h);
    sh_line.y.push_back(sh.Speed(h));
  }
  for (double h = wh.min_height_mm(); h <= wh.max_height_mm() + 1e-9; h += 0.02) {
    wh_line.x.push_back(h);
    wh_line.y.push_back(wh.Width(h));
  }
  html << SvgPlot("Speed vs bead height (Nguyen 2022 Table 18, eq. 6.6)", "bead height h [mm]",
                  "travel speed v [mm/min]", {{"Table 18 (measured)", height, speed, kColours[0], false}, sh_line});
  html << SvgPlot("Bead width vs height (Nguyen 2022 Table 18, eq. 6.7)", "bead height h [mm]", "bead width w [mm]",
                  {{"Table 18 (measured)", height, width, kColours[0], false}, wh_line});

  const CsvTable dai = CsvTable::Read(data / "dai2020_csw_table1.csv");
  const std::vector<double> radius = dai.Numbers("curvature_radius_mm", true),
                            v = dai.Numbers("travel_speed_mm_per_min"), w = dai.Numbers("width_mm");
  const models::CswModel csw = models::CswModel::Load(models::DefaultModelPath("csw"));
  std::map<double, SvgSeries> by_radius;
  for (std::size_t i = 0; i < radius.size(); ++i) {
    SvgSeries& s = by_radius[radius[i]];
    s.x.push_back(v[i]);
    s.y.push_back(w[i]);
  }
  std::vector<SvgSeries> series;
  int k = 0;
  for (auto& [r, s] : by_radius) {
    const std::string colour = kColours[k++ % 6];
    std::ostringstream label;
    label << "r = " << r << " mm";
    s.label = label.str() + " (Table 1)";
    s.colour = colour;
    SvgSeries line{label.str() + " CSW fit", {}, {}, colour, true};
    for (double speed_v = 250; speed_v <= 950; speed_v += 10) {
      line.x.push_back(speed_v);
      line.y.push_back(csw.Width(speed_v, r));
    }
    series.push_back(s);
    series.push_back(line);
  }
  html << SvgPlot("Curvature-speed-width model (Dai 2020 Table 1, sec. 4)", "travel speed v [mm/min]",
                  "bead width w [mm]", series, 520, 380);
  return html.str();
}

// Measured junction void lengths (Appendix A1) and the fitted model's prediction against the smallest angle.
std::string VoidPlot() {
  const fs::path data = models::DefaultModelPath("csw").parent_path();
  const CsvTable a1 = CsvTable::Read(data / "nguyen2022_appendixA1_junction_voids.csv");
  const std::vector<double> eta = a1.Numbers("eta"), t1 = a1.Numbers("theta1_deg"), t2 = a1.Numbers("theta2_deg"),
                            t3 = a1.Numbers("theta3_deg"), t4 = a1.Numbers("theta4_deg"),
                            length = a1.Numbers("void_length_mm");
  const auto model = models::LoadVoidLengthModel(models::DefaultModelPath("void_length"));
  SvgSeries measured{"measured (Appendix A1)", {}, {}, kColours[0], false};
  SvgSeries predicted{"model (models/data/void_length.json, " + model->kind() + ")", {}, {}, kColours[1], false};
  for (std::size_t i = 0; i < eta.size(); ++i) {
    models::Junction j;
    j.turning_points = static_cast<int>(eta[i]);
    j.angles_deg = {t1[i], t2[i], t3[i], t4[i]};
    measured.x.push_back(j.SmallestAngleDeg());
    measured.y.push_back(length[i]);
    predicted.x.push_back(j.SmallestAngleDeg());
    predicted.y.push_back(model->PredictMm(j));
  }
  return SvgPlot("Junction void length vs smallest junction angle (Nguyen 2022 sec. 4.4, eq. 4.6-4.7)",
                 "smallest angle theta_min [deg]", "void length L [mm]", {measured, predicted});
}

// Most scenarios whose pictures report.html embeds; past them it links the picture files (a 1,000-run sweep would
// otherwise make a report of hundreds of megabytes, and decoding every PNG dominates a merge).
constexpr std::size_t kMaxEmbeddedScenarios = 24;

// A link to the PNG at `dir`/`relative` (relative to report.html, as `id`/`relative`), or "" if it is absent.
std::string LinkedPng(const fs::path& dir, const std::string& id, const std::string& relative,
                      const std::string& caption) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / relative, ec)) return "";
  return "<figure><a href=\"" + HtmlEscape(id + "/" + relative) + "\">" + HtmlEscape(caption) + "</a></figure>\n";
}

std::string ScenarioSection(const nlohmann::json& e, const fs::path& out_dir, bool embed_pictures) {
  const std::string id = e.value("id", "");
  const fs::path dir = out_dir / id;
  std::ostringstream html;
  html << "<h3 id=\"" << HtmlEscape(id) << "\">" << HtmlEscape(id) << " <small>(scenario "
       << Cell(e.value("scenario", nlohmann::json())) << ", " << Cell(e.value("file", nlohmann::json())) << ", "
       << e.value("outcome", "fail") << ")</small></h3>\n";
  if (e.contains("error")) html << "<p class=\"fail\">" << Cell(e["error"]) << "</p>\n";
  std::error_code ec;
  if (fs::is_regular_file(dir / "check" / "viewer.html", ec)) {
    // The 3D viewer of the check step, relative to report.html (both stay in the bench folder).
    html << "<p><a href=\"" << HtmlEscape(id) << "/check/viewer.html\">3D viewer of the checked motion</a></p>\n";
  }
  html << "<table><tr><th>step</th><th>status</th><th>exit</th><th>wall s</th><th>peak MiB</th><th>metrics</th></tr>\n";
  const nlohmann::json timing = e.value("timing", nlohmann::json::object()).value("steps", nlohmann::json::object());
  for (const nlohmann::json& s : e.value("steps", nlohmann::json::array())) {
    const std::string name = s.value("name", "");
    const nlohmann::json t = timing.value(name, nlohmann::json::object());
    html << "<tr><td>" << HtmlEscape(name) << "</td><td>" << Cell(s.value("status", nlohmann::json())) << "</td><td>"
         << Cell(s.value("exit_code", nlohmann::json()))
         << "</td><td>" << Cell(t.value("wall_s", nlohmann::json())) << "</td><td>"
         << Cell(t.value("peak_rss_mb", nlohmann::json())) << "</td><td class=\"metrics\">";
    const nlohmann::json metrics = s.value("metrics", nlohmann::json::object());
    for (auto it = metrics.begin(); it != metrics.end(); ++it) {
      if (it.key() == "not_applicable" || it.key() == "notes") continue;  // listed below the table
      html << HtmlEscape(it.key()) << " = " << Cell(it.value()) << "; ";
    }
    html << "</td></tr>\n";
  }
  html << "</table>\n";
  // Measures that do not apply to this part and settings that explain its deviation (simulate.json).
  const nlohmann::json reasons = Metric(e, "simulate", "not_applicable");
  const nlohmann::json notes = Metric(e, "simulate", "notes");
  if ((reasons.is_object() && !reasons.empty()) || (notes.is_array() && !notes.empty())) {
    html << "<ul class=\"notes\">\n";
    if (reasons.is_object()) {
      for (auto it = reasons.begin(); it != reasons.end(); ++it) {
        html << "<li>" << HtmlEscape(it.key()) << " not applicable: " << Cell(it.value()) << "</li>\n";
      }
    }
    if (notes.is_array()) {
      for (const nlohmann::json& note : notes) html << "<li>note: " << Cell(note) << "</li>\n";
    }
    html << "</ul>\n";
  }
  html << "<div class=\"figs\">\n";
  // The middle layer of the plan, the joint trajectories, the worst cell pose, the part's height and deviation.
  std::vector<std::pair<std::string, std::string>> pictures;  // path under the run's folder, caption
  const nlohmann::json layers = Metric(e, "plan", "layers");
  if (layers.is_number_integer()) {
    char name[32];
    std::snprintf(name, sizeof(name), "layer_%04d.png", layers.get<int>() / 2);
    pictures.emplace_back(std::string("plan/layers/") + name, std::string("plan: ") + name);
  }
  pictures.emplace_back("check/joints.png", "check: joint trajectories");
  pictures.emplace_back("check/cell_worst.png", "check: cell at the worst sample");
  pictures.emplace_back("simulate/deviation_map.png", "simulate: deviation from the target");
  pictures.emplace_back("simulate/top_height.png", "simulate: top height");
  for (const auto& [relative, caption] : pictures) {
    html << (embed_pictures ? EmbeddedPng(dir / relative, caption) : LinkedPng(dir, id, relative, caption));
  }
  html << "</div>\n";
  return html.str();
}

std::string PerfTable(const nlohmann::json& perf) {
  if (perf.empty()) {
    return "<p>No inner-loop results in this bench folder: run <code>tools/perf_bench.sh &lt;out&gt;/perf</code> "
           "then <code>waam bench</code> again (scenario results are reused).</p>\n";
  }
  std::ostringstream html;
  html << "<table><tr><th>benchmark</th><th>real time</th><th>CPU time</th><th>unit</th><th>iterations</th>"
          "<th>counters</th></tr>\n";
  for (const nlohmann::json& b : perf) {
    html << "<tr><td>" << Cell(b["name"]) << "</td><td>" << Cell(b["real_time"]) << "</td><td>" << Cell(b["cpu_time"])
         << "</td><td>" << Cell(b["time_unit"]) << "</td><td>" << Cell(b["iterations"]) << "</td><td>";
    for (auto it = b["counters"].begin(); it != b["counters"].end(); ++it) {
      html << HtmlEscape(it.key()) << " = " << Cell(it.value()) << "; ";
    }
    html << "</td></tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

// The sweep's table: one row per run, its swept values, outcome and the chosen metrics ("step.metric").
std::string SweepTable(const nlohmann::json& sweep, const nlohmann::json& scenarios) {
  std::map<std::string, const nlohmann::json*> by_id;
  for (const nlohmann::json& e : scenarios) by_id[e.value("id", "")] = &e;
  std::ostringstream html;
  html << "<p>Sweep <b>" << Cell(sweep["name"]) << "</b> (" << Cell(sweep["file"]) << ") over base scenario "
       << Cell(sweep["base"]);
  if (!sweep["set"].empty()) {
    html << " with";
    for (const nlohmann::json& s : sweep["set"]) html << " <code>" << Cell(s) << "</code>";
  }
  html << ": " << sweep["runs"].size() << " runs.</p>\n<table><tr><th>run</th>";
  for (const nlohmann::json& key : sweep["keys"]) html << "<th>" << Cell(key) << "</th>";
  html << "<th>outcome</th>";
  for (const nlohmann::json& metric : sweep["metrics"]) html << "<th>" << Cell(metric) << "</th>";
  html << "</tr>\n";
  for (const nlohmann::json& run : sweep["runs"]) {
    const std::string id = run.value("id", "");
    const auto found = by_id.find(id);
    const nlohmann::json* entry = found == by_id.end() ? nullptr : found->second;
    html << "<tr><td><a href=\"#" << HtmlEscape(id) << "\">" << HtmlEscape(id) << "</a></td>";
    for (const nlohmann::json& key : sweep["keys"]) {
      html << "<td>" << Cell(run["values"].value(key.get<std::string>(), nlohmann::json())) << "</td>";
    }
    const std::string outcome = entry ? entry->value("outcome", "fail") : "not run";
    html << "<td class=\"" << outcome << "\">" << outcome << "</td>";
    for (const nlohmann::json& metric : sweep["metrics"]) {
      const std::string name = metric;
      const std::size_t dot = name.find('.');
      html << "<td>" << (entry ? Cell(Metric(*entry, name.substr(0, dot), name.substr(dot + 1))) : Cell(nullptr))
           << "</td>";
    }
    html << "</tr>\n";
  }
  html << "</table>\n";
  return html.str();
}

// Wall time and peak memory of each scenario's `waam run`, one bar per scenario.
std::string ScenarioPlots(const nlohmann::json& scenarios) {
  std::vector<SvgBar> wall, memory;
  for (const nlohmann::json& e : scenarios) {
    const std::string id = e.value("id", "");
    const nlohmann::json timing = e.value("timing", nlohmann::json::object());
    const nlohmann::json w = timing.value("wall_s", nlohmann::json()), m = timing.value("peak_rss_mb", nlohmann::json());
    const std::string colour = e.value("outcome", "fail") == "fail" ? "#d62728" : kColours[0];
    wall.push_back({id, w.is_number() ? w.get<double>() : std::nan(""), colour});
    memory.push_back({id, m.is_number() ? m.get<double>() : std::nan(""), kColours[2]});
  }
  if (wall.empty()) return "";
  return SvgBarChart("Wall time per scenario (red: failed)", "wall time [s]", wall, std::nan("")) +
         SvgBarChart("Peak memory per scenario", "peak resident memory [MiB]", memory, std::nan(""));
}

// The papers' figures against ours: ours / published per row with a numeric published value (1 = agreement).
std::string ReferencePlot(const nlohmann::json& reference) {
  std::vector<SvgBar> bars;
  for (const nlohmann::json& r : reference) {
    const nlohmann::json published = r.value("published_value", nlohmann::json());
    const nlohmann::json ours = r.value("ours", nlohmann::json());
    if (!published.is_number() || published.get<double>() == 0.0) continue;
    const double ratio = ours.is_number() ? ours.get<double>() / published.get<double>() : std::nan("");
    bars.push_back({r.value("source", "") + ": " + r.value("quantity", ""), ratio,
                    std::isfinite(ratio) && std::abs(ratio - 1.0) > 0.25 ? kColours[4] : kColours[0]});
  }
  if (bars.empty()) return "";
  return SvgBarChart("Ours / published (dashed: agreement; orange: more than 25 % off)", "ours / published", bars,
                     1.0, 760);
}

// One plot per sweep metric against each swept key with numeric values: the runs' metric over the key's values.
std::string SweepPlots(const nlohmann::json& sweep, const nlohmann::json& scenarios) {
  std::map<std::string, const nlohmann::json*> by_id;
  for (const nlohmann::json& e : scenarios) by_id[e.value("id", "")] = &e;
  std::ostringstream html;
  for (const nlohmann::json& metric : sweep.value("metrics", nlohmann::json::array())) {
    const std::string name = metric;
    const std::size_t dot = name.find('.');
    if (dot == std::string::npos) continue;
    for (const nlohmann::json& key_json : sweep.value("keys", nlohmann::json::array())) {
      const std::string key = key_json;
      SvgSeries points{name, {}, {}, kColours[0], false};
      for (const nlohmann::json& run : sweep.value("runs", nlohmann::json::array())) {
        const nlohmann::json x = run.value("values", nlohmann::json::object()).value(key, nlohmann::json());
        const auto found = by_id.find(run.value("id", ""));
        if (!x.is_number() || found == by_id.end()) continue;
        const nlohmann::json y = Metric(*found->second, name.substr(0, dot), name.substr(dot + 1));
        if (!y.is_number()) continue;
        points.x.push_back(x.get<double>());
        points.y.push_back(y.get<double>());
      }
      if (points.x.empty()) continue;
      html << SvgPlot(name + " against " + key, key, name, {points}, 420, 300);
    }
  }
  return html.str();
}

// A section whose data could not be read says why instead of failing the whole report.
template <typename F>
std::string Guarded(F&& make) {
  try {
    return make();
  } catch (const InputError& e) {
    return "<p class=\"fail\">" + HtmlEscape(e.what()) + "</p>\n";
  }
}

}  // namespace

void WriteBenchReport(const nlohmann::json& bench, const fs::path& out_dir) {
  const nlohmann::json& scenarios = bench["scenarios"];
  const nlohmann::json& counts = bench["counts"];
  const nlohmann::json& timing = bench["timing"];
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>waam bench report</title>\n"
          "<style>body{font-family:sans-serif;margin:1.5em;max-width:1500px}table{border-collapse:collapse;"
          "margin:.5em 0}td,th{border:1px solid #bbb;padding:2px 6px;font-size:13px;text-align:left}"
          "th{background:#eee}.pass{color:#070}.expected_fail{color:#a60}.fail{color:#c00;font-weight:bold}"
          "td.metrics{font-size:12px;max-width:800px}figure{display:inline-block;margin:4px;vertical-align:top}"
          "figcaption{font-size:12px}svg{margin:4px;vertical-align:top}</style></head><body>\n";
  const auto timing_of = [&timing](const char* key) { return Cell(timing.value(key, nlohmann::json())); };
  html << "<h1>waam bench report</h1>\n<p>" << Cell(counts["total"]) << " scenarios: " << Cell(counts["pass"])
       << " pass, " << Cell(counts["expected_fail"]) << " expected fail (planted faults found), "
       << Cell(counts["fail"]) << " fail. Scenario wall time " << timing_of("scenarios_wall_s") << " s ("
       << timing_of("reused_results") << " results reused from an earlier run), this invocation "
       << timing_of("total_s") << " s on " << timing_of("hardware_threads")
       << " hardware threads. Each scenario ran as <code>waam run</code> in its own process; peak memory is that "
          "process's maximum resident set.</p>\n";
  if (bench.contains("sweep")) {
    html << "<h2>Sweep</h2>\n" << SweepTable(bench["sweep"], scenarios) << "<div class=\"plots\">"
         << SweepPlots(bench["sweep"], scenarios) << "</div>\n";
  }
  html << "<h2>Scenarios</h2>\n" << OverviewTable(scenarios) << "<div class=\"plots\">" << ScenarioPlots(scenarios)
       << "</div>\n";
  html << "<h2>Published figures and ours</h2>\n" << ReferenceTable(bench["reference"]) << "<div class=\"plots\">"
       << ReferencePlot(bench["reference"]) << "</div>\n";
  html << "<h2>Bead models fitted to the papers' data</h2>\n" << Guarded([] { return ModelPlots(); });
  html << "<h2>Junction voids</h2>\n" << Guarded([] { return VoidPlot(); });
  html << "<h2>Inner-loop performance (Google Benchmark)</h2>\n" << PerfTable(timing.value("perf", nlohmann::json()));
  html << "<h2>Each scenario</h2>\n";
  if (scenarios.size() > kMaxEmbeddedScenarios) {
    html << "<p>The pictures of the first " << kMaxEmbeddedScenarios << " scenarios are shown; the others' are "
         << "linked (files in each scenario's folder).</p>\n";
  }
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    html << ScenarioSection(scenarios[i], out_dir, i < kMaxEmbeddedScenarios);
  }
  html << "</body></html>\n";
  WriteFileAtomic(out_dir / "report.html", html.str());
}

}  // namespace waam::analysis
