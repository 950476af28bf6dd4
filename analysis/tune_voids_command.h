// `waam tune-voids`: the junction void-filling shift tuned in the deposition twin instead of on sacrificial parts.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace waam::analysis {

struct TuneVoidsOptions {
  std::filesystem::path scenario;       // scenario YAML (a rib-web part; its path.void_filling is ignored)
  std::filesystem::path out_dir;        // output directory (created if missing)
  std::vector<std::string> overrides;   // "key.path=value" scenario overrides (--set)
  int layers = 5;                       // layers deposited per trial (Appendix A1 welded five), >= 2
  double threshold_mm3 = 1.0;           // void volume (mm^3) below which a junction counts as filled, > 0
  int max_trials = 10;                  // simulations per junction class after the plain one, >= 1
  double resolution_mm = 0.25;          // bracketing stops when the bracket is this narrow (mm), > 0
  double crop_mm = 0.0;                 // half-size of the square simulated around a junction (mm); 0 = 5 w
  std::filesystem::path training_csv;   // if set: Appendix A1-format table of the simulated junctions
  bool images = true;                   // PNG sections of each junction before and after
  bool quiet = false;
};

// One simulation of a junction with a given shift.
struct TuneTrial {
  double shift_mm = 0.0;                // PP_N* at the sharpest turning point
  double void_volume_mm3 = 0.0;         // empty voxels enclosed in horizontal cuts near the junction below the top
                                        // layer, mm^3
  double void_length_mm = 0.0;          // longest such region in one cut (L of Fig. 30), mm
  double peak_height_mm = 0.0;          // highest top near the junction minus the walls' crowns around it, mm
};

// The tuning of one junction class.
struct JunctionTuning {
  std::string junction_class;           // planner::Junction::ClassName()
  Eigen::Vector2d centre_mm = Eigen::Vector2d::Zero();  // the junction simulated (first of its class)
  int ribs = 0;
  int eta = 0;                          // turning points
  std::vector<double> angles_deg;       // descending
  double theta_min_deg = 0.0;
  TuneTrial plain;                      // shift 0: plain contours
  TuneTrial geometric;                  // lambda = 1 (eq. 4.3)
  TuneTrial tuned;                      // the smallest shift found below the threshold (or the last tried)
  double lambda = 0.0;                  // tuned shift over the eq. 4.3 shift
  bool converged = false;
  std::vector<TuneTrial> history;       // every simulation, in order
  std::vector<std::string> pictures;    // file names in out_dir
};

struct TuneVoidsResult {
  double spacing_mm = 0.0;              // l
  double bead_width_mm = 0.0;
  std::vector<JunctionTuning> junctions;
};

// Plans the scenario without void filling, finds its junction classes on the first layer, and per class simulates
// the first `layers` layers on a crop around one junction: plain, geometric (lambda = 1), then eq. 4.6 steps (the
// shift raised by the void length still measured) and bisection until the void volume is below the threshold.
// Writes tune.json (last), junction PNGs and the optional training CSV atomically. Throws InputError for bad options,
// scenarios, or a part without junctions of three or more ribs.
TuneVoidsResult RunTuneVoids(const TuneVoidsOptions& options);

// The tune.json document.
nlohmann::json TuneToJson(const TuneVoidsOptions& options, const TuneVoidsResult& result);

}  // namespace waam::analysis
