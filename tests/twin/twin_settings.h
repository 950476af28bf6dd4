// The twin's settings for tests: the scenario defaults with the default CSW model loaded, as the scenario loader does.
#pragma once

#include <memory>

#include "models/bead/csw_model.h"
#include "models/fit/model_file.h"
#include "twin/simulation_settings.h"

namespace waam::twin {

// The default `simulation:` section with its CSW model (models/data/csw.json) loaded.
inline SimulationSettings TestSimulationSettings() {
  SimulationSettings s;
  s.csw = std::make_shared<const models::CswModel>(models::CswModel::Load(models::DefaultModelPath("csw")));
  return s;
}

}  // namespace waam::twin
