// The MuJoCo side of the cell model (internal to twin/cell: mujoco_cell.cc and mujoco_geometry.cc), the only header
// that includes MuJoCo's: the model's Impl, one mjData, and CellState's data.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "twin/cell/mujoco_cell.h"

namespace waam::twin {

// The MuJoCo side of a CellModel: immutable once the constructor has returned.
struct CellModel::Impl {
  const mjModel* m = nullptr;  // read-only: edited only by BuildModel, through the pointer LoadModel returns
  std::filesystem::path file;
  CellModel::RobotInfo robot;
  int qadr[8] = {};
  int jnt[8] = {};
  int robot_base = -1, positioner_base = -1, flange = -1;
  int tcp = -1, part_origin = -1, nozzle = -1, speeds = -1;
  planner::CellKinematics kinematics;
  planner::PositionerType positioner_type = planner::PositionerType::kTiltRotate;  // from the joints it has
  bool closed_form = true;
  std::string not_opw_reason;  // why the closed form does not apply (empty when it does)
  Eigen::Vector3d nozzle_a_T = Eigen::Vector3d::Zero(), nozzle_b_T = Eigen::Vector3d::Zero();
  double nozzle_radius_mm = 0.0;
  ~Impl() {
    if (m) mj_deleteModel(const_cast<mjModel*>(m));  // MuJoCo's delete takes a non-const pointer
  }
};

// One mjData over a model (deleted with it).
class ScratchData {
 public:
  explicit ScratchData(const mjModel* m) : d_(mj_makeData(m)) {}
  ~ScratchData() { mj_deleteData(d_); }
  ScratchData(const ScratchData&) = delete;
  ScratchData& operator=(const ScratchData&) = delete;
  mjData* get() const { return d_; }

 private:
  mjData* d_;
};

struct CellState::Data {
  explicit Data(const mjModel* m) : d(m) {}
  ScratchData d;
  std::vector<mjtNum> collide_xpos;  // geom poses at the last Collide()
  std::vector<mjtNum> collide_xmat;
};

}  // namespace waam::twin
