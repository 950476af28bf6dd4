// ABB RAPID module reader: statements split at ';' (block lines on their own), each tokenized; the module's data
// declarations, then PROC main run with its procedure calls, each instruction by a small function of its kind.
#include <cmath>
#include <map>
#include <optional>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/abb_rapid_syntax.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {

using internal::CheckRapidShape;
using internal::IsRapidBlockWord;
using internal::IsRapidDeclaration;
using internal::kRobtargetForm;
using internal::RapidArgs;
using internal::RapidData;
using internal::RapidExpr;
using internal::RapidModule;
using internal::RapidNumbers;
using internal::RapidPose;
using internal::RapidStatement;
using internal::RapidValue;
using internal::ReadRapidArgs;
using internal::ReadRapidDecl;
using internal::ReadRapidModule;
using internal::SplitRapidStatements;
using internal::TokenCursor;
using internal::Upper;

constexpr int kMaxRapidCalls = 16;  // nesting of procedure calls

// What runs while PROC main executes.
struct RapidRun {
  const std::string& file;
  RapidModule& module;
  ParsedProgram& program;
  internal::WarningList& warnings;
  bool arc_on = false;
  double velset_override = 1.0;  // VelSet Override (fraction)
  double velset_max = 0.0;       // VelSet Max (mm/s; 0: none)
};

const RapidData* FindRapidData(const RapidRun& run, const std::string& name, const char* type) {
  const auto found = run.module.data.find(name);
  return found != run.module.data.end() && found->second.type == type ? &found->second : nullptr;
}

// A number argument: a literal, a negated literal or a declared num; empty when computed.
std::optional<double> RapidNumber(const RapidRun& run, const RapidExpr& e) {
  if (e.kind == RapidExpr::Kind::kValue && e.value.kind == RapidValue::Kind::kNumber) return e.value.number;
  if (e.kind == RapidExpr::Kind::kName) {
    const RapidData* d = FindRapidData(run, e.name, "NUM");
    if (d == nullptr) d = FindRapidData(run, e.name, "DNUM");
    if (d != nullptr && d->value.kind == RapidValue::Kind::kNumber) return d->value.number;
  }
  return std::nullopt;
}

// A robtarget argument: a declared name, a literal, Offs(p, dx, dy, dz) (mm in the work object) or
// RelTool(p, dx, dy, dz [\Rx] [\Ry] [\Rz]) (mm and deg in the tool frame: about x, then y, then z); empty when
// computed otherwise. `value` receives the robtarget's aggregate (configuration and external axes).
std::optional<Eigen::Isometry3d> RapidTarget(const RapidRun& run, const RapidExpr& e, int line, RapidValue* value) {
  if (e.kind == RapidExpr::Kind::kValue || e.kind == RapidExpr::Kind::kName) {
    if (e.kind == RapidExpr::Kind::kName) {
      const RapidData* d = FindRapidData(run, e.name, "ROBTARGET");
      WAAM_THROW_UNLESS(d != nullptr, run.file << ":" << line << ": " << e.text
                                               << " is used but not declared as a ROBTARGET");
      *value = d->value;
    } else {
      *value = e.value;
    }
    CheckRapidShape(*value, 4, {}, run.file, line, kRobtargetForm);
    return RapidPose(value->items[0], value->items[1], run.file, line);
  }
  const bool offs = e.name == "OFFS", reltool = e.name == "RELTOOL";
  if (e.kind != RapidExpr::Kind::kCall || (!offs && !reltool) || e.args.size() != 4) return std::nullopt;
  std::optional<Eigen::Isometry3d> X = RapidTarget(run, e.args[0], line, value);
  Eigen::Vector3d d;
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> v = RapidNumber(run, e.args[static_cast<std::size_t>(k) + 1]);
    if (!v || !X) return std::nullopt;
    d[k] = *v;
  }
  if (offs) {
    X->translation() += d;
    return X;
  }
  X->translate(d);
  for (const char* axis : {"RX", "RY", "RZ"}) {
    const auto o = e.options.find(axis);
    if (o == e.options.end()) continue;
    const std::optional<double> deg = o->second ? RapidNumber(run, *o->second) : std::nullopt;
    if (!deg) return std::nullopt;
    const Eigen::Vector3d about = axis[1] == 'X' ? Eigen::Vector3d::UnitX()
                                                 : (axis[1] == 'Y' ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ());
    X->rotate(Eigen::AngleAxisd(*deg / kDeg, about));
  }
  return X;
}

// External axes eax_a, eax_b (deg; 9E+09: not in use) as the numbered positioner axes.
void SetRapidExternalAxes(const RapidValue& eax, const std::string& file, int line, ProgramMotion* m) {
  const std::vector<double> e = RapidNumbers(eax, 6, file, line, "extax");
  if (e[0] >= 8e9) return;
  m->has_positioner = true;
  m->positioner_numbered = true;
  m->tilt_rad = e[0] / kDeg;
  m->rotation_rad = e[1] < 8e9 ? e[1] / kDeg : 0.0;
}

// The work object of \WObj (wobj0 or none: the robot's base frame): uframe * oframe.
Eigen::Isometry3d RapidWorkObject(RapidRun& run, const RapidArgs& args, int line) {
  const auto w = args.options.find("WOBJ");
  if (w == args.options.end() || !w->second || w->second->name == "WOBJ0") return Eigen::Isometry3d::Identity();
  const RapidData* d = FindRapidData(run, w->second->name, "WOBJDATA");
  WAAM_THROW_UNLESS(d != nullptr, run.file << ":" << line << ": " << w->second->text
                                           << " is used but not declared as a wobjdata");
  const RapidValue& v = d->value;
  if (v.items[0].text == "TRUE") run.warnings.Add("robot-held work object (stationary tool) not modelled", line);
  if (v.items[1].text == "FALSE") {
    run.warnings.Add("work object moved by a mechanical unit (" + v.items[2].text.substr(0, 16) +
                         "): positions taken with the unit at zero",
                     line);
  }
  return RapidPose(v.items[3].items[0], v.items[3].items[1], run.file, d->line) *
         RapidPose(v.items[4].items[0], v.items[4].items[1], run.file, d->line);
}

// ABB's flange frame Fabb in the twin's flange frame F (X_F_Fabb): ABB's z along the flange normal, x down at the zero
// pose; the twin's x along the normal (x_abb = -z_F, y_abb = y_F, z_abb = x_F).
Eigen::Isometry3d AbbFlangeInTwinFlange() {
  Eigen::Isometry3d X_F_Fabb = Eigen::Isometry3d::Identity();
  X_F_Fabb.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  return X_F_Fabb;
}

// The tool argument: a tooldata the module declares (its tframe in ABB's flange frame), tool0 (the flange), or one
// kept on the controller (the cell's torch, warned).
void SetRapidTool(RapidRun& run, const RapidExpr& tool, int line, ProgramMotion* m) {
  if (tool.kind != RapidExpr::Kind::kName) {
    run.warnings.Add("tool from an expression: the cell's torch", line);
    return;
  }
  m->tool_name = tool.text;
  if (tool.name == "TOOL0") {
    m->has_tool = true;
    m->X_FT = AbbFlangeInTwinFlange();
    return;
  }
  const RapidData* d = FindRapidData(run, tool.name, "TOOLDATA");
  if (d == nullptr) {
    run.warnings.Add("tooldata " + tool.text + " not declared in the module: the cell's torch", line);
    return;
  }
  if (d->value.items[0].text == "FALSE") {
    run.warnings.Add("stationary tool " + tool.text + " (robhold FALSE) not modelled: the cell's torch", line);
    return;
  }
  m->has_tool = true;
  m->X_FT = AbbFlangeInTwinFlange() * RapidPose(d->value.items[1].items[0], d->value.items[1].items[1], run.file, d->line);
}

// The TCP speed of a move (mm/s; 0: the scenario's): welded Arc moves at their welddata's weld_speed, others at their
// speeddata (declared, a literal, or the predefined v5 ... v7000; vmax the scenario's), \V:= in its stead; VelSet's
// override and maximum applied.
double RapidSpeed(RapidRun& run, const RapidArgs& args, std::size_t speed_at, bool welded, int line) {
  double v = 0.0;
  const RapidExpr& speed = args.positional[speed_at];
  const RapidData* wd = welded ? FindRapidData(run, args.positional[speed_at + 2].name, "WELDDATA") : nullptr;
  const RapidData* sd = FindRapidData(run, speed.name, "SPEEDDATA");
  const RapidValue* value = sd != nullptr ? &sd->value : (speed.kind == RapidExpr::Kind::kValue ? &speed.value : nullptr);
  if (welded) {
    if (wd != nullptr && wd->value.kind == RapidValue::Kind::kList && !wd->value.items.empty() &&
        wd->value.items[0].kind == RapidValue::Kind::kNumber) {
      v = wd->value.items[0].number;
      WAAM_THROW_UNLESS(v > 0.0, run.file << ":" << wd->line << ": weld_speed must be > 0");
    } else {
      run.warnings.Add("welddata not declared in the module: the scenario's weld speed used", line);
    }
  } else if (value != nullptr) {
    v = RapidNumbers(*value, 4, run.file, sd != nullptr ? sd->line : line, "speeddata")[0];
    WAAM_THROW_UNLESS(v > 0.0, run.file << ":" << (sd != nullptr ? sd->line : line) << ": speeddata v_tcp must be > 0");
  } else if (speed.kind == RapidExpr::Kind::kName && speed.name.size() > 1 && speed.name[0] == 'V' &&
             speed.name.find_first_not_of("0123456789.", 1) == std::string::npos) {
    v = internal::ParseProgramNumber(speed.name.substr(1), run.file, line, "speed");
  } else if (speed.name != "VMAX") {
    run.warnings.Add("speeddata not declared in the module: the scenario's speed used", line);
  }
  const auto vv = args.options.find("V");
  if (!welded && vv != args.options.end() && vv->second) v = RapidNumber(run, *vv->second).value_or(v);
  if (args.options.count("T")) run.warnings.Add("\\T move time not followed: the move's speed used", line);
  if (v > 0.0) v *= run.velset_override;
  if (v > 0.0 && run.velset_max > 0.0) v = std::min(v, run.velset_max);
  return v;
}

// The motion instructions: kind, positions before the speed, whether the arc instructions' seam and weld follow.
struct RapidMotionForm {
  MotionKind kind;
  int positions;
  bool arc;
};

std::optional<RapidMotionForm> RapidMotionOf(const std::string& name) {
  static const std::map<std::string, RapidMotionForm> kForms = {
      {"MOVEJ", {MotionKind::kJoint, 1, false}},     {"MOVEL", {MotionKind::kLinear, 1, false}},
      {"MOVEC", {MotionKind::kCircular, 2, false}},  {"MOVEABSJ", {MotionKind::kJoint, 1, false}},
      {"TRIGGJ", {MotionKind::kJoint, 1, false}},    {"TRIGGL", {MotionKind::kLinear, 1, false}},
      {"TRIGGC", {MotionKind::kCircular, 2, false}}, {"ARCLSTART", {MotionKind::kLinear, 1, true}},
      {"ARCL", {MotionKind::kLinear, 1, true}},      {"ARCLEND", {MotionKind::kLinear, 1, true}},
      {"ARCCSTART", {MotionKind::kCircular, 2, true}}, {"ARCC", {MotionKind::kCircular, 2, true}},
      {"ARCCEND", {MotionKind::kCircular, 2, true}}};
  const auto found = kForms.find(name);
  return found == kForms.end() ? std::nullopt : std::optional<RapidMotionForm>(found->second);
}

// Warns the optional arguments a motion does not execute (\WObj, \V, \T, \On, \Off are taken; zones, IDs and the
// like change nothing on the path).
void WarnRapidMotionOptions(RapidRun& run, const std::string& name, const RapidArgs& args, int line) {
  static const char* const kQuiet[] = {"WOBJ", "V", "T", "ON", "OFF", "Z", "INPOS", "ID", "CONC", "TLOAD",
                                       "NOEOFFS", "SEAMNAME", "CORR", "T2", "T3", "T4"};
  for (const auto& [option, value] : args.options) {
    bool quiet = false;
    for (const char* q : kQuiet) quiet = quiet || option == q;
    if (!quiet) run.warnings.Add(name + " optional argument \\" + option + " not executed", line);
  }
}

// MoveJ / MoveL / MoveC / MoveAbsJ / TriggX / ArcX: targets, speed, tool and work object, the arc switching.
void ExecRapidMotion(RapidRun& run, const std::string& name, const RapidMotionForm& form, const RapidArgs& args,
                     int line) {
  const std::size_t speed_at = static_cast<std::size_t>(form.positions);
  const std::size_t needed = speed_at + (form.arc ? 5 : (name.compare(0, 5, "TRIGG") == 0 ? 4 : 3));
  WAAM_THROW_UNLESS(args.positional.size() >= needed, run.file << ":" << line << ": " << name << " needs " << needed
                                                              << " arguments, got " << args.positional.size());
  internal::CheckMotionCount(run.program.motions.size(), run.file, line);
  WarnRapidMotionOptions(run, name, args, line);
  ProgramMotion m;
  m.kind = form.kind;
  m.line = line;
  const RapidExpr& target = args.positional[speed_at - 1];
  if (name == "MOVEABSJ") {
    const RapidData* d = FindRapidData(run, target.name, "JOINTTARGET");
    const RapidValue* v = target.kind == RapidExpr::Kind::kValue ? &target.value : (d ? &d->value : nullptr);
    WAAM_THROW_UNLESS(v != nullptr, run.file << ":" << line << ": " << target.text
                                             << " is used but not declared as a JOINTTARGET");
    WAAM_THROW_UNLESS(v->kind == RapidValue::Kind::kList && v->items.size() == 2,
                      run.file << ":" << line << ": jointtarget must be [[j1..j6],[eax_a..eax_f]]");
    const std::vector<double> j = RapidNumbers(v->items[0], 6, run.file, line, "robax");
    m.has_joints = true;
    for (int k = 0; k < 6; ++k) m.q[k] = j[static_cast<std::size_t>(k)] / kDeg;
    SetRapidExternalAxes(v->items[1], run.file, line, &m);
  } else {
    RapidValue value, via_value;
    const std::optional<Eigen::Isometry3d> X = RapidTarget(run, target, line, &value);
    const std::optional<Eigen::Isometry3d> via =
        form.positions == 2 ? RapidTarget(run, args.positional[0], line, &via_value) : std::nullopt;
    if (!X || (form.positions == 2 && !via)) {
      const RapidExpr& e = !X ? target : args.positional[0];
      run.warnings.Add(name + " to a computed position (" + Upper(e.text.substr(0, e.text.find('('))).substr(0, 16) +
                           ") not executed",
                       line);
      return;
    }
    const Eigen::Isometry3d X_RU = RapidWorkObject(run, args, line);
    m.has_pose = true;
    m.frame = TargetFrame::kRobot;
    m.X_UT = X_RU * *X;
    if (via) m.has_via = true, m.via = X_RU * via->translation();
    const std::vector<double> cf = RapidNumbers(value.items[2], 4, run.file, line, "confdata");
    const int cfx = (cf[3] >= 0.0 && cf[3] <= 7.0) ? static_cast<int>(cf[3]) : -1;
    if (cfx >= 0) m.config = ((cfx & 4) ? 1 : 0) | ((cfx & 2) ? 2 : 0) | ((cfx & 1) ? 4 : 0);
    SetRapidExternalAxes(value.items[3], run.file, line, &m);
  }
  SetRapidTool(run, args.positional[needed - 1], line, &m);
  const bool start = name.find("START") != std::string::npos || args.options.count("ON");
  const bool end = name.find("END") != std::string::npos || args.options.count("OFF");
  m.speed_mm_s = RapidSpeed(run, args, speed_at, form.arc && !start, line);
  // ArcXStart moves to the seam and strikes the arc there; ArcX welds; ArcXEnd welds and ends the arc.
  m.weld = form.arc ? !start : run.arc_on;
  if (form.arc) run.arc_on = !end;
  run.program.motions.push_back(m);
}

void RunRapidProc(RapidRun& run, const std::string& name, int depth, int line);

// One statement of a procedure body.
void ExecRapidStatement(RapidRun& run, const RapidStatement& st, int depth) {
  TokenCursor ts(st.text, run.file, st.line);
  if (IsRapidDeclaration(ts)) {
    std::string name;
    RapidData data;
    if (ReadRapidDecl(ts, run.file, &run.warnings, &name, &data)) run.module.data[name] = std::move(data);
    return;
  }
  const std::string first = ts.ExpectWord("an instruction");
  if (IsRapidBlockWord(first)) {
    // IF / FOR / WHILE / TEST are not evaluated; their END lines close nothing the reader opened.
    if (first.compare(0, 3, "END") != 0) {
      run.warnings.Add("RAPID " + first + " not followed (its statements run in order)", st.line);
    }
    return;
  }
  if (ts.Is(":") && ts.Is("=", 1)) {
    run.warnings.Add("assignment to " + first.substr(0, 24) + " not executed", st.line);
    return;
  }
  const RapidArgs args = ReadRapidArgs(ts);
  if (const std::optional<RapidMotionForm> form = RapidMotionOf(first)) {
    ExecRapidMotion(run, first, *form, args, st.line);
  } else if (run.module.procs.count(first)) {
    RunRapidProc(run, first, depth + 1, st.line);
  } else if (first == "WAITTIME") {
    // WaitTime [\InPos,] t (s): the torch waits at its last target; a time the reader cannot evaluate is warned.
    const std::optional<double> t = args.positional.size() == 1 ? RapidNumber(run, args.positional[0]) : std::nullopt;
    if (!t) {
      run.warnings.Add("WaitTime of a variable not in the timeline", st.line);
      return;
    }
    WAAM_THROW_UNLESS(*t >= 0.0, run.file << ":" << st.line << ": WaitTime " << *t << " must be >= 0");
    internal::AddDwell(&run.program.motions, *t, st.line, &run.warnings);
  } else if ((first == "SETDO" || first == "SET" || first == "RESET") && !args.positional.empty() &&
             (args.positional[0].name.find("WELD") != std::string::npos ||
              args.positional[0].name.find("ARC") != std::string::npos)) {
    // A digital output named for the weld or the arc switches it: SetDO sig, 1 / Set sig / Reset sig.
    const std::optional<double> v = first == "SETDO" && args.positional.size() == 2
                                        ? RapidNumber(run, args.positional[1])
                                        : std::optional<double>(first == "SET" ? 1.0 : 0.0);
    if (!v) ts.Fail("SetDO " + args.positional[0].text + " needs its value 0 or 1");
    run.arc_on = *v != 0.0;
  } else if (first == "VELSET" && args.positional.size() == 2) {
    const std::optional<double> o = RapidNumber(run, args.positional[0]), mx = RapidNumber(run, args.positional[1]);
    if (!o || !mx || *o <= 0.0 || *mx <= 0.0) ts.Fail("VelSet needs an override (%) and a maximum (mm/s) > 0");
    run.velset_override = *o / 100.0, run.velset_max = *mx;
  } else if (first != "CONFL" && first != "CONFJ" && first != "SINGAREA" && first != "TPWRITE" && first != "TPERASE") {
    run.warnings.Add("instruction " + first.substr(0, 24) + " not executed", st.line);
  }
}

// Runs a PROC of the module (main, or one it calls).
void RunRapidProc(RapidRun& run, const std::string& name, int depth, int line) {
  WAAM_THROW_UNLESS(depth < kMaxRapidCalls, run.file << ":" << line << ": procedure calls nested deeper than "
                                                     << kMaxRapidCalls << " (" << name << " calls itself?)");
  const auto [first, last] = run.module.procs.at(name);
  for (std::size_t i = first; i < last; ++i) ExecRapidStatement(run, run.module.statements[i], depth);
}

}  // namespace

ParsedProgram ReadAbbRapid(std::string_view text, const std::string& file) {
  const std::vector<std::string_view> lines = internal::SplitProgramLines(text, file);
  ParsedProgram program;
  program.format = ProgramFormat::kAbbRapid;
  internal::WarningList warnings;
  RapidModule module =
      ReadRapidModule(SplitRapidStatements(lines, file), file, static_cast<int>(lines.size()), &warnings);
  program.name = module.name;
  RapidRun run{file, module, program, warnings, false, 1.0, 0.0};
  const std::string entry = module.procs.count("MAIN") ? "MAIN" : module.first_proc;
  if (entry.empty()) {
    warnings.Add("module without a procedure: nothing runs", 1);
  } else {
    if (entry != "MAIN") warnings.Add("no PROC main: " + entry + " run as the entry", 1);
    RunRapidProc(run, entry, 0, 1);
  }
  program.warnings = warnings.Take();
  return program;
}

}  // namespace waam::planner
