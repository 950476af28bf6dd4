// The `replay:` scenario section: the process log, its columns, frame, bead and thermocouples.
#include "analysis/replay_settings.h"

#include "models/core/error.h"
#include "models/core/yaml_map.h"

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

void ParseProbes(YamlMap& replay, ReplaySection* out) {
  WAAM_THROW_UNLESS(replay.Has("probes"), replay.Where("") << ": replay.probes is missing: name at least one "
                                                              "thermocouple as NAME: {column, at_mm: [x, y, z]}");
  YamlMap probes = replay.Map("probes");
  for (const std::string& name : probes.Names("probe")) {
    ReplayProbe probe;
    probe.name = name;
    YamlMap one = probes.Map(probe.name);
    probe.column = one.String("column");
    const std::vector<double> at = one.Numbers("at_mm", 3, -1e5, 1e5);
    probe.at_mm = {at[0], at[1], at[2]};
    probe.where = one.Where("at_mm");
    one.CheckNoUnknownKeys();
    out->probes.push_back(std::move(probe));
  }
  probes.CheckNoUnknownKeys();
  WAAM_THROW_UNLESS(!out->probes.empty(), probes.Where("") << ": name at least one thermocouple");
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
  if (replay.Has("ambient_column")) out->columns.ambient = replay.String("ambient_column");
  if (replay.Has("table_column")) out->columns.table = replay.String("table_column");
  ParseProbes(replay, out);
  replay.CheckNoUnknownKeys();
}

}  // namespace waam::analysis::internal
