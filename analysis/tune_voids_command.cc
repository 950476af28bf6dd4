// `waam tune-voids`: per junction class, simulate a few layers around one junction and update the void-filling shift
// until the twin shows no void (dissertation 003 sec. 4.4.1 eq. 4.3-4.6 and sec. 4.6.3.1, done in the twin instead
// of welding and milling one part per step).
#include "analysis/tune_voids_command.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "analysis/scenario.h"
#include "analysis/tune_voids_internal.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "planner/path/junctions.h"
#include "planner/plan_scenario.h"
#include "planner/scenario/scenario.h"

namespace waam::analysis {
namespace {

void Validate(const TuneVoidsOptions& o) {
  WAAM_THROW_UNLESS(o.layers >= 2 && o.layers <= 100, "tune-voids --layers = " << o.layers << ": must be in [2, 100]");
  WAAM_THROW_UNLESS(std::isfinite(o.threshold_mm3) && o.threshold_mm3 > 0.0,
                    "tune-voids --threshold-mm3 = " << o.threshold_mm3 << ": must be > 0");
  WAAM_THROW_UNLESS(o.max_trials >= 1 && o.max_trials <= 100,
                    "tune-voids --max-trials = " << o.max_trials << ": must be in [1, 100]");
  WAAM_THROW_UNLESS(std::isfinite(o.resolution_mm) && o.resolution_mm > 0.0,
                    "tune-voids --resolution-mm = " << o.resolution_mm << ": must be > 0");
  WAAM_THROW_UNLESS(std::isfinite(o.crop_mm) && o.crop_mm >= 0.0,
                    "tune-voids --crop-mm = " << o.crop_mm << ": must be >= 0 (0 = five bead widths)");
}

std::vector<planner::Move2D> Moves(const planner::LayerPath& layer) {
  std::vector<planner::Move2D> moves;
  for (const planner::PathPoint& p : layer.points) moves.push_back({p.p_P.head<2>(), p.weld});
  return moves;
}

nlohmann::json TrialJson(const TuneTrial& t) {
  return {{"shift_mm", t.shift_mm},
          {"void_volume_mm3", t.void_volume_mm3},
          {"void_length_mm", t.void_length_mm},
          {"peak_height_mm", t.peak_height_mm}};
}

std::string TrainingCsv(const TuneVoidsResult& result, const TuneVoidsOptions& options) {
  std::ostringstream out;
  out << "# Source: waam tune-voids on " << options.scenario.string() << ", " << options.layers
      << " simulated layers per junction, plain contours (no void filling).\n"
      << "# Columns as Appendix A1 of the Nguyen 2022 dissertation: eta = turning points, theta1..theta4 = angles\n"
      << "# between ribs in descending order (deg), theta4 = 0 for three ribs, void_length_mm = longest void in a\n"
      << "# horizontal cut near the junction (the caliper length L). Fit with: waam fit void-length <this file>\n"
      << "no,group,eta,theta1_deg,theta2_deg,theta3_deg,theta4_deg,void_length_mm\n";
  int no = 0;
  for (const JunctionTuning& j : result.junctions) {
    if (j.ribs < 3 || j.ribs > 4) continue;
    ++no;
    out << no << ",T" << no << "," << j.eta;
    for (int k = 0; k < 4; ++k) out << "," << (k < static_cast<int>(j.angles_deg.size()) ? j.angles_deg[k] : 0.0);
    out << "," << j.plain.void_length_mm << "\n";
  }
  return out.str();
}

// The junction classes of the first `layers` layers of `plan` (`all_classes`) and, per class, its first junction on
// layer 0 (`representative`), the one simulated.
void FindJunctionClasses(const planner::Plan& plan, int layers, double w, int min_ribs,
                         std::set<std::string>* all_classes, std::map<std::string, planner::Junction>* representative) {
  for (int k = 0; k < layers; ++k) {
    const planner::LayerPath& layer = plan.layers[k];
    for (const planner::Junction& j : planner::FindJunctions(layer.slice, Moves(layer), w, min_ribs)) {
      all_classes->insert(j.ClassName());
    }
  }
  const planner::LayerPath& first = plan.layers.front();
  for (const planner::Junction& j : planner::FindJunctions(first.slice, Moves(first), w, min_ribs)) {
    representative->emplace(j.ClassName(), j);
  }
}

// Searches the shift of one junction class after its plain and geometric (`unit_shift`, mm) trials in `tuning`:
// `run(shift)` deposits a trial. Fills the tuning's history, converged, tuned and lambda.
void SearchShift(double unit_shift, double half_mm, const TuneVoidsOptions& options,
                 const std::function<TuneTrial(double)>& run, JunctionTuning* tuning) {
  // Search: the smallest shift whose void volume is below the threshold. Above it: the shift is raised by the
  // void length still measured (eq. 4.6: the shift that fills a void is its length L); once a shift fills the
  // void, bisection between the last failing and the first filling shift.
  double lo = 0.0;
  double lo_length = tuning->plain.void_length_mm;
  double hi = -1.0;
  TuneTrial best = tuning->plain;
  if (tuning->plain.void_volume_mm3 <= options.threshold_mm3) {
    hi = 0.0;
  } else if (tuning->geometric.void_volume_mm3 <= options.threshold_mm3) {
    hi = unit_shift;
    best = tuning->geometric;
  } else {
    lo = unit_shift;
    lo_length = tuning->geometric.void_length_mm;
    best = tuning->geometric;
  }
  for (int trial = 0; trial < options.max_trials; ++trial) {
    double shift = 0.0;
    if (hi < 0.0) {
      shift = lo + std::max(lo_length, options.resolution_mm);
      if (shift > half_mm) break;  // the corner would leave the simulated square
    } else if (hi - lo > options.resolution_mm) {
      shift = 0.5 * (lo + hi);
    } else {
      break;
    }
    const TuneTrial t = run(shift);
    tuning->history.push_back(t);
    if (t.void_volume_mm3 <= options.threshold_mm3) {
      hi = shift;
      best = t;
    } else {
      lo = shift;
      lo_length = t.void_length_mm;
      if (hi < 0.0) best = t;
    }
  }
  tuning->converged = hi >= 0.0;
  tuning->tuned = best;
  tuning->lambda = unit_shift > 0.0 ? best.shift_mm / unit_shift : 0.0;
}

// The junction class `name` described from its representative `junction`, before any trial: centre, ribs, turning
// points, angles and the sharpest turn.
JunctionTuning DescribeJunction(const std::string& name, const planner::Junction& junction) {
  JunctionTuning tuning;
  tuning.junction_class = name;
  tuning.centre_mm = junction.centre;
  tuning.ribs = junction.ribs;
  tuning.eta = static_cast<int>(junction.turning_points.size());
  tuning.angles_deg = junction.angles_deg;
  tuning.theta_min_deg = junction.turning_points[junction.SharpestTurn()].theta_rad * 180.0 / kPi;
  return tuning;
}

// What every junction class is tuned with (the scenario planned without void filling, the classes, the bead width w
// and wall spacing l, mm) and the progress shared by the classes' trials.
class ClassTuner {
 public:
  ClassTuner(const Scenario& scenario, const planner::PlanResult& planned, const TuneVoidsOptions& options,
             std::set<std::string> all_classes, double l, std::size_t class_count)
      : scenario_(scenario),
        planned_(planned),
        options_(options),
        all_classes_(std::move(all_classes)),
        w_(planned.bead_width_mm),
        l_(l),
        progress_("tune-voids", class_count * static_cast<std::size_t>(options.max_trials + 3), "trials",
                  options.quiet) {}

  // Tunes class `name` (numbered `index` in the pictures' names) on its representative `junction`: the plain and
  // geometric trials side by side, then the search one trial at a time (each shift follows from the voids the
  // previous ones left), then the final shift again with its picture.
  JunctionTuning Tune(const std::string& name, const planner::Junction& junction, int index) {
    JunctionTuning tuning = DescribeJunction(name, junction);
    const double theta_min = junction.turning_points[junction.SharpestTurn()].theta_rad;
    const double unit_shift = l_ * (1.0 / std::sin(0.5 * theta_min) - 1.0);  // eq. 4.3 (lambda = 1)
    internal::JunctionCrop crop;
    crop.centre = junction.centre;
    crop.half_mm = options_.crop_mm > 0.0 ? options_.crop_mm : 5.0 * w_;
    // Voids of the junction lie within the gap corners (l / (2 sin(theta/2)) out) plus two bead widths (as the
    // X-junction reproduction in tests/twin/voids_test.cc measures them).
    crop.reach_mm = l_ / (2.0 * std::sin(0.5 * theta_min)) + 2.0 * w_;

    const std::string stem = "junction_" + std::to_string(index);
    TuneTrial first_two[2];
    ParallelFor(2, [&](std::size_t t) {
      first_two[t] = t == 0 ? Trial(name, crop, 0.0, options_.images ? stem + "_plain.png" : "")
                            : Trial(name, crop, unit_shift, "");
    });
    tuning.plain = first_two[0];
    tuning.geometric = first_two[1];
    tuning.history = {tuning.plain, tuning.geometric};
    SearchShift(unit_shift, crop.half_mm, options_, [&](double shift) { return Trial(name, crop, shift, ""); },
                &tuning);
    if (options_.images) {
      // Re-run the final shift with its picture (deterministic: the same numbers as the search found).
      const std::string picture = stem + "_tuned.png";
      Trial(name, crop, tuning.tuned.shift_mm, picture);
      tuning.pictures = {stem + "_plain.png", picture};
    }
    return tuning;
  }

  void Finish() { progress_.Finish(); }

 private:
  // Deposits the simulated layers with class `name` shifted by `shift` mm (every other class unshifted) and measures
  // the voids in `crop`; its picture into `picture` under the output folder when not empty.
  TuneTrial Trial(const std::string& name, const internal::JunctionCrop& crop, double shift,
                  const std::string& picture) {
    CheckInterrupt();
    planner::VoidFillingSettings settings = scenario_.path.void_filling;
    settings.mode = planner::VoidFillingMode::kTuned;
    settings.spacing_mm = l_;
    for (const std::string& c : all_classes_) settings.shift_by_class_mm[c] = 0.0;
    settings.shift_by_class_mm[name] = shift;
    const planner::VoidFiller filler(settings, w_, l_);
    const planner::Plan plan = internal::TrialPlan(planned_.plan, options_.layers, filler, crop);
    const double rapid_mm_s = scenario_.process.rapid_speed_mm_min / 60.0;
    TuneTrial trial = internal::SimulateTrial(plan, scenario_.simulation, rapid_mm_s, crop,
                                              picture.empty() ? std::filesystem::path() : options_.out_dir / picture);
    trial.shift_mm = shift;
    std::lock_guard<std::mutex> lock(progress_mutex_);
    progress_.Update(++done_);
    return trial;
  }

  const Scenario& scenario_;
  const planner::PlanResult& planned_;
  const TuneVoidsOptions& options_;
  const std::set<std::string> all_classes_;
  double w_, l_;
  Progress progress_;
  std::mutex progress_mutex_;
  std::size_t done_ = 0;
};

}  // namespace

TuneVoidsResult RunTuneVoids(const TuneVoidsOptions& options) {
  Validate(options);
  std::vector<std::string> overrides = options.overrides;
  overrides.push_back("path.void_filling.mode=none");
  const Scenario scenario = LoadScenario(options.scenario, overrides);
  const planner::PlanResult planned = planner::PlanScenario(scenario, nullptr);
  WAAM_THROW_UNLESS(static_cast<int>(planned.plan.layers.size()) >= options.layers,
                    "tune-voids --layers = " << options.layers << ": the part has only " << planned.plan.layers.size()
                                             << " layers");
  ClaimOutputDirectory(options.out_dir);

  TuneVoidsResult result;
  const double w = planned.bead_width_mm;
  result.bead_width_mm = w;
  result.spacing_mm = scenario.path.void_filling.spacing_mm > 0.0
                          ? scenario.path.void_filling.spacing_mm
                          : planner::OverlapSpacingFor(scenario.path.overlap_model, w).contour_to_contour_mm;
  const int min_ribs = scenario.path.void_filling.min_ribs;

  // Junction classes over the simulated layers; the first junction of each class (on layer 0) is the one simulated.
  std::set<std::string> all_classes;
  std::map<std::string, planner::Junction> representative;
  FindJunctionClasses(planned.plan, options.layers, w, min_ribs, &all_classes, &representative);
  WAAM_THROW_UNLESS(!representative.empty(), options.scenario.string()
                                                 << ": no junction of " << min_ribs
                                                 << " or more ribs on the first layer (is path.pattern eulerian or "
                                                    "contour on a rib-web part?)");

  // The junction classes are tuned in parallel, each into its own slot (a class's trials are its own deposits).
  const std::vector<std::pair<std::string, planner::Junction>> classes(representative.begin(), representative.end());
  ClassTuner tuner(scenario, planned, options, std::move(all_classes), result.spacing_mm, classes.size());
  std::vector<JunctionTuning> tunings(classes.size());
  ParallelFor(classes.size(), [&](std::size_t i) {
    tunings[i] = tuner.Tune(classes[i].first, classes[i].second, static_cast<int>(i) + 1);
  });
  result.junctions = std::move(tunings);
  tuner.Finish();

  if (!options.training_csv.empty()) WriteFileAtomic(options.training_csv, TrainingCsv(result, options));
  WriteFileAtomic(options.out_dir / "tune.json", JsonText(TuneToJson(options, result)) + "\n");
  return result;
}

nlohmann::json TuneToJson(const TuneVoidsOptions& options, const TuneVoidsResult& result) {
  nlohmann::json doc;
  doc["scenario"] = options.scenario.string();
  doc["layers"] = options.layers;
  doc["threshold_mm3"] = options.threshold_mm3;
  doc["resolution_mm"] = options.resolution_mm;
  doc["spacing_mm"] = result.spacing_mm;
  doc["bead_width_mm"] = result.bead_width_mm;
  doc["junctions"] = nlohmann::json::array();
  for (const JunctionTuning& j : result.junctions) {
    nlohmann::json history = nlohmann::json::array();
    for (const TuneTrial& t : j.history) history.push_back(TrialJson(t));
    doc["junctions"].push_back({{"class", j.junction_class},
                                {"centre_mm", {j.centre_mm.x(), j.centre_mm.y()}},
                                {"ribs", j.ribs},
                                {"eta", j.eta},
                                {"angles_deg", j.angles_deg},
                                {"theta_min_deg", j.theta_min_deg},
                                {"plain", TrialJson(j.plain)},
                                {"geometric", TrialJson(j.geometric)},
                                {"tuned", TrialJson(j.tuned)},
                                {"shift_mm", j.tuned.shift_mm},
                                {"lambda", j.lambda},
                                {"void_volume_mm3", j.tuned.void_volume_mm3},
                                {"peak_height_mm", j.tuned.peak_height_mm},
                                {"extra_peak_mm", j.tuned.peak_height_mm - j.plain.peak_height_mm},
                                {"converged", j.converged},
                                {"trials", j.history.size()},
                                {"history", history},
                                {"pictures", j.pictures}});
  }
  return doc;
}

}  // namespace waam::analysis
