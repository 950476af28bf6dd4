// The `replay:` scenario section: the process log, its columns, frame, bead and thermocouples.
#include "analysis/replay_settings.h"

#include "models/core/error.h"
#include "models/core/yaml_map.h"

namespace waam::analysis {

void FinishReplayProbe(YamlMap& element, ReplayProbe* probe) {
  element.Require("column");
  element.Require("at_mm");
  probe->where = element.Where("at_mm");
}

}  // namespace waam::analysis

namespace waam::analysis::internal {

namespace {

void ParseColumns(YamlMap& replay, ReplaySection* out) {
  ReadFieldMap<ReplayColumns>(replay, "columns", kReplayColumnFields, &out->columns);
  const ReplayColumns& c = out->columns;
  const std::string where = replay.Where("columns");
  const bool volts_amps = !c.voltage_v.empty() || !c.current_a.empty();
  WAAM_THROW_UNLESS(!c.power_w.empty() || volts_amps,
                    where << ": name the arc power's column: power_w, or voltage_v and current_a");
  WAAM_THROW_UNLESS(c.power_w.empty() || !volts_amps, where << ": give power_w or voltage_v and current_a, not both");
  WAAM_THROW_UNLESS(!volts_amps || (!c.voltage_v.empty() && !c.current_a.empty()),
                    where << ": voltage_v needs current_a (and current_a voltage_v)");
  WAAM_THROW_UNLESS(!c.time.empty() && !c.x.empty() && !c.y.empty() && !c.z.empty(),
                    where << ": time, x, y and z must name columns");
}

}  // namespace

void ParseReplaySection(YamlMap& top, ReplaySection* out) {
  if (!top.Has("replay")) return;
  YamlMap replay = top.Map("replay");
  out->given = true;
  out->where = replay.Where("");
  WAAM_THROW_UNLESS(replay.Has("log"), out->where << ": replay.log is missing: name the process log (CSV)");
  out->log_where = replay.Where("log");
  ReadFields<ReplaySection>(replay, kReplayFields, out);
  ParseColumns(replay, out);
  ReadFieldMap<ReplaySection>(replay, "frame", kReplayFrameFields, out);
  ReadFieldMap<ReplaySection>(replay, "bead", kReplayBeadFields, out);
  WAAM_THROW_UNLESS(replay.Has("probes"), replay.Where("") << ": replay.probes is missing: name at least one "
                                                              "thermocouple as NAME: {column, at_mm: [x, y, z]}");
  WAAM_THROW_UNLESS(!out->probes.empty(), replay.Where("probes") << ": name at least one thermocouple");
  replay.CheckNoUnknownKeys();
}

}  // namespace waam::analysis::internal
