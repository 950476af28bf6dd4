// The bad-input catalogue: every kind of broken user file, fed to the built `waam` binary, must end in exit code 2,
// one line on stderr naming the file and the place, and no output file. docs/BAD_INPUTS.md lists the same cases.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/output_lock.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::FilesUnder;

using Facet = std::array<std::array<float, 3>, 3>;

// A closed tetrahedron (4 facets, outward normals) with a corner at the origin and edges `s` mm along the axes.
std::vector<Facet> Tetrahedron(float s = 10.0f) {
  const std::array<float, 3> a{0, 0, 0}, b{s, 0, 0}, c{0, s, 0}, d{0, 0, s};
  return {Facet{a, c, b}, Facet{a, b, d}, Facet{a, d, c}, Facet{b, c, d}};
}

// Binary STL bytes: an 80-byte header, `header_count` (the real count when negative), the facets.
std::string BinaryStl(const std::vector<Facet>& facets, long long header_count = -1) {
  std::string bytes(80, ' ');
  bytes.replace(0, 20, "waam bad input test ");
  const std::uint32_t count = static_cast<std::uint32_t>(header_count < 0 ? facets.size() : header_count);
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const Facet& f : facets) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    for (const auto& v : f) bytes.append(reinterpret_cast<const char*>(v.data()), 12);
    bytes.append(2, '\0');
  }
  return bytes;
}

// A scenario with the part from `mesh` (relative to the scenario) and every other value valid; `edit` replaces
// one line ("key: value" as written below) to break it. Lines: 3 part.mesh, 5 layer_height_mm, 7 pattern,
// 8 bead_width_mm, 10 travel_speed_mm_min.
std::string ScenarioText(const std::string& mesh = "part.stl", const std::string& from = "", const std::string& to = "") {
  std::string text =
      "name: bad_input\n"
      "part:\n"
      "  mesh: " + mesh + "\n"
      "slicing:\n"
      "  layer_height_mm: 1.5\n"
      "path:\n"
      "  pattern: contour\n"
      "  bead_width_mm: 6\n"
      "process:\n"
      "  travel_speed_mm_min: 400\n"
      "  wire_feed_mm_min: 3200\n";
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return text;
}

std::string CellScenario(const std::string& extra_cell_line) {
  return "name: bad_cell\n"
         "part:\n"
         "  generator: {type: box, size_mm: [100, 60, 15]}\n"
         "slicing:\n"
         "  layer_height_mm: 1.5\n"
         "path:\n"
         "  pattern: contour\n"
         "  bead_width_mm: 6\n"
         "process:\n"
         "  travel_speed_mm_min: 400\n"
         "  wire_feed_mm_min: 3200\n"
         "cell:\n" +
         extra_cell_line +
         "  robot: {base_mm: [0, 0, 0], yaw_deg: 0}\n"
         "  positioner: {base_mm: [1050, 0, 0], yaw_deg: 90, rotation_deg: 0}\n";
}

// A thermal scenario (waam thermal) with every value valid; `from` is replaced by `to` to break it. Lines: 12
// process.arc, 13 process.interpass, 15 thermal.material, 17 thermal.probes.
std::string ThermalScenario(const std::string& from, const std::string& to) {
  std::string text =
      "name: bad_thermal\n"
      "part:\n"
      "  generator: {type: box, size_mm: [60, 8, 4]}\n"
      "slicing:\n"
      "  layer_height_mm: 2\n"
      "path:\n"
      "  pattern: zigzag\n"
      "  bead_width_mm: 6\n"
      "process:\n"
      "  travel_speed_mm_min: 400\n"
      "  wire_feed_mm_min: 3200\n"
      "  arc: {power_w: 2000}\n"
      "  interpass: {max_c: 200}\n"
      "thermal:\n"
      "  material: mild_steel\n"
      "  substrate: {size_mm: [100, 40, 10]}\n"
      "  probes: {plate: [0, 10, -2]}\n";
  text.replace(text.find(from), from.size(), to);
  return text;
}

// ThermalScenario with one 20 x 10 mm clamp (line 18) at `centre` of conductance `g`.
std::string ClampScenario(const std::string& centre, const std::string& g) {
  return ThermalScenario("[0, 10, -2]}\n", "[0, 10, -2]}\n  clamps: [{centre_mm: " + centre +
                                               ", size_mm: [20, 10], conductance_w_m2k: " + g + "}]\n");
}

// A replay scenario (waam thermal replay, waam fit thermal) and its log, every value valid; `from` is replaced by
// `to` in the scenario. Lines: 20 replay.probes.tc; log rows on lines 2-6.
std::string ReplayScenario(const std::string& from = "", const std::string& to = "") {
  std::string text =
      "name: bad_replay\npart:\n  generator: {type: box, size_mm: [40, 6, 4]}\nslicing:\n  layer_height_mm: 2\n"
      "path:\n  pattern: zigzag\n  bead_width_mm: 6\nprocess:\n  travel_speed_mm_min: 400\n"
      "  wire_feed_mm_min: 3200\n  arc: {power_w: 2000}\nthermal:\n  material: mild_steel\n"
      "  substrate: {size_mm: [100, 40, 10]}\nreplay:\n  log: log.csv\n  columns: {power_w: power_w}\n"
      "  probes:\n    tc: {column: T1, at_mm: [0, 5, -2]}\n";
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return text;
}
std::string ReplayLogText(const std::string& from = "", const std::string& to = "") {
  std::string text = "time,power_w,arc_on,x,y,z,T1\n0,2000,1,-10,0,2,20\n1,2000,1,-2,0,2,25\n2,2000,1,6,0,2,30\n"
                     "3,0,0,6,0,2,40\n4,0,0,6,0,2,38\n";
  if (!from.empty()) text.replace(text.find(from), from.size(), to);
  return text;
}

// A six-joint arm in URDF (geometry irrelevant: every case fails before MuJoCo loads it); `mesh` is the filename of
// link_2's collision mesh, `velocity` the attribute text of every <limit>, `revolute` how many joints are revolute.
std::string MiniUrdf(const std::string& mesh, const std::string& velocity = "velocity=\"3\"", int revolute = 6) {
  std::string s = "<?xml version=\"1.0\"?>\n<robot name=\"mini\">\n  <link name=\"base_link\"/>\n";
  for (int i = 1; i <= 6; ++i) {
    s += "  <link name=\"link_" + std::to_string(i) + "\">";
    if (i == 2) s += "<collision><geometry><mesh filename=\"" + mesh + "\"/></geometry></collision>";
    s += "</link>\n";
  }
  s += "  <link name=\"tool0\"/>\n";
  for (int i = 1; i <= 6; ++i) {
    s += "  <joint name=\"joint_" + std::to_string(i) + "\" type=\"" + (i <= revolute ? "revolute" : "fixed") +
         "\">\n    <parent link=\"" + (i == 1 ? std::string("base_link") : "link_" + std::to_string(i - 1)) +
         "\"/><child link=\"link_" + std::to_string(i) + "\"/><origin xyz=\"0 0 0.3\"/><axis xyz=\"0 1 0\"/>\n"
         "    <limit lower=\"-3\" upper=\"3\" effort=\"0\" " + velocity + "/>\n  </joint>\n";
  }
  s += "  <joint name=\"flange\" type=\"fixed\"><parent link=\"link_6\"/><child link=\"tool0\"/></joint>\n";
  return s + "</robot>\n";
}

// `urdf` (a MiniUrdf) with joint_1 continuous and without its <limit>.
std::string ContinuousFirstJoint(std::string urdf) {
  const std::string revolute = "type=\"revolute\">";
  urdf.replace(urdf.find(revolute), revolute.size(), "type=\"continuous\">");
  const std::size_t limit = urdf.find("    <limit");
  urdf.erase(limit, urdf.find('\n', limit) + 1 - limit);
  return urdf;
}

// A scenario whose arm is `urdf`, packages looked up in pkgs/; `extra` more lines of cell.robot.
std::string UrdfScenario(const std::string& urdf, const std::string& extra = "") {
  return "name: bad_urdf\n"
         "part:\n"
         "  generator: {type: box, size_mm: [100, 60, 15]}\n"
         "slicing:\n"
         "  layer_height_mm: 1.5\n"
         "path:\n"
         "  pattern: contour\n"
         "  bead_width_mm: 6\n"
         "process:\n"
         "  travel_speed_mm_min: 400\n"
         "  wire_feed_mm_min: 3200\n"
         "cell:\n"
         "  robot:\n"
         "    urdf: " + urdf + "\n"
         "    package_paths: [pkgs]\n" + extra;
}

// One row of the catalogue (docs/BAD_INPUTS.md has the same rows, by id).
struct BadInput {
  std::string id;
  std::string command;                         // "plan", "check", "material", "thermal", "deviation", "fit <model>"...
  std::string input;                           // the file named on the command line, in the case's folder ('@': as is)
  std::map<std::string, std::string> files;    // name -> contents, written into the case's folder
  std::vector<std::string> expected;           // each must appear in the one stderr line
  std::vector<std::string> folders = {};       // folders created in the case's folder (before the files)
  std::string options = "";                    // options after the inputs, e.g. "--shard 3/3"
  std::vector<std::string> more_inputs = {};   // further files named after the input, in the case's folder
};

std::string ReplaceAll(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

std::vector<BadInput> Catalogue() {
  const std::string ok = ScenarioText();
  std::vector<Facet> tetra = Tetrahedron();
  std::vector<Facet> nan_facets = tetra;
  nan_facets[1][1][2] = std::numeric_limits<float>::quiet_NaN();
  // Two tetrahedra sharing the edge (0,0,0)-(10,0,0): that edge has four facets, every other edge two.
  std::vector<Facet> two = tetra;
  const std::array<float, 3> a{0, 0, 0}, b{10, 0, 0}, e{0, -10, 0}, f{0, 0, -10};
  for (const Facet& g : {Facet{a, b, e}, Facet{a, f, b}, Facet{a, e, f}, Facet{b, f, e}}) two.push_back(g);
  std::vector<Facet> open = tetra;
  open.pop_back();
  const std::string flat = BinaryStl({Facet{{{0, 0, 0}, {10, 0, 0}, {20, 0, 0}}}, Facet{{{1, 1, 1}, {1, 1, 1}, {5, 5, 5}}}});
  const std::string full = BinaryStl(tetra);
  const std::string csw_header = "travel_speed_mm_per_min,curvature_radius_mm,width_mm\n";
  // A valid thermal material file (docs/THERMAL.md, "Materials"): rows on lines 6 and 7.
  const std::string material_ok =
      "# solidus_c: 1400 | test\n# liquidus_c: 1450\n# latent_heat_j_kg: 250000\n# emissivity: 0.5\n"
      "temperature_c,conductivity_w_mk,density_kg_m3,specific_heat_j_kgk\n20,50,7800,450\n1000,30,7500,650\n";
  // A FANUC LS program with one position; P[2] is used and not defined.
  const std::string ls_head = "/PROG  T\n/ATTR\n/MN\n   1:L  P[1] 100mm/sec FINE    ;\n";
  const std::string ls_pos =
      "/POS\nP[1]{\n   GP1:\n\tUF : 0, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n"
      "\tX =  1000.000  mm,\tY =     0.000  mm,\tZ =   180.000  mm,\n";
  const std::string ls_tail = "\tW =   180.000 deg,\tP =     0.000 deg,\tR =     0.000 deg\n};\n/END\n";
  // A Yaskawa INFORM job whose ///NPOS says 3 C positions and gives 2.
  const std::string jbi_pos = "/JOB\n//NAME T\n//POS\n///NPOS 3,0,0,0,0,0\n///POSTYPE ROBOT\n///RECTAN\n"
                              "C00000=1000,0,180,180,0,0\nC00001=1000,0,150,180,0,0\n";
  const std::string jbi_inst = "//INST\n///GROUP1 RB1\nNOP\nMOVJ C00000 VJ=10.00\nMOVL C00001 V=10.0\n";
  return {
      {"program-ls-truncated-pos", "import", "prog.ls", {{"prog.ls", ls_head + ls_pos}},
       {"prog.ls:6: P[1] in /POS is not closed by '};' (truncated /POS)"}},
      {"program-ls-position-not-defined", "import", "prog.ls",
       {{"prog.ls", ls_head + "   2:L  P[2] 100mm/sec FINE    ;\n" + ls_pos + ls_tail}},
       {"prog.ls:5: P[2] is used but not defined in /POS"}},
      {"program-ls-uframe-not-defined", "import", "prog.ls",
       {{"prog.ls", ls_head + ReplaceAll(ls_pos, "UF : 0", "UF : 6") + ls_tail}},
       {"prog.ls:4: P[1] is taught in user frame UF 6, which the program does not define: give "
        "program.frames.uframe.6 = [x, y, z, w, p, r]"}},
      {"program-krl-base-not-defined", "import", "prog.src",
       {{"prog.src", "DEF prog( )\n$BASE=BASE_DATA[8]\n$VEL.CP=0.1\nLIN {X 10.0,Y 0.0,Z 5.0,A 0.0,B 0.0,C 180.0}\n"
                     "END\n"}},
       {"prog.src:4: $BASE is BASE_DATA[8], which the program does not define: give program.frames.uframe.8 = "
        "[x, y, z, a, b, c]"}},
      {"program-gcode-dwell-with-move", "import", "prog.nc", {{"prog.nc", "G1 X10 F400\nG4 G1 P500 X20\n"}},
       {"prog.nc:2: G4 shares its line with G1: a dwell stands alone"}},
      {"program-rapid-zero-quaternion", "import", "prog.mod",
       {{"prog.mod", "MODULE T\n  CONST robtarget p1:=[[1000,0,180],[0,0,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]];\n"
                     "  PROC main()\n    MoveL p1,v100,fine,tool0;\n  ENDPROC\nENDMODULE\n"}},
       {"prog.mod:2: quaternion [0,0,0,0] of length 0"}},
      {"program-gcode-nan", "import", "prog.nc", {{"prog.nc", "G21\nG1 X1 Y2 Z3 F400\nG1 XNaN Y2\n"}},
       {"prog.nc:3: X 'NaN' is not a finite number"}},
      {"program-jbi-wrong-count", "import", "prog.JBI", {{"prog.JBI", jbi_pos + jbi_inst}},
       {"prog.JBI:4: ///NPOS says 3 C positions, 2 are given"}},
      {"program-jbi-position-not-defined", "import", "prog.JBI",
       {{"prog.JBI", ReplaceAll(jbi_pos, "NPOS 3", "NPOS 2") + jbi_inst + "MOVL C00002 V=10.0\nEND\n"}},
       {"prog.JBI:14: C00002 is used but not defined in //POS"}},
      {"program-jbi-truncated-pos", "import", "prog.JBI", {{"prog.JBI", jbi_pos.substr(0, jbi_pos.rfind("C00001"))}},
       {"prog.JBI:7: the job ends inside //POS (no //INST): it is truncated"}},
      {"program-jbi-pulses-unknown", "import", "prog.JBI",
       {{"prog.JBI", ReplaceAll(ReplaceAll(jbi_pos, "NPOS 3", "NPOS 2"), "ROBOT\n///RECTAN", "PULSE\n///PULSE") +
                         jbi_inst + "END\n"}},
       {"prog.JBI:7: a pulse position and the robot's pulses per degree are unknown (axis S): give "
        "program.yaskawa.pulses_per_deg [S, L, U, R, B, T] or --pulses-per-deg"}},
      {"program-gcode-arc-without-centre", "import", "prog.nc", {{"prog.nc", "G0 X0 Y0 Z2\nG2 X10 Y0 F400\n"}},
       {"prog.nc:2: G2 needs its centre (I J) or a radius R in the plane of G17"}},
      {"program-gcode-arc-off-its-circle", "import", "prog.nc", {{"prog.nc", "G0 X0 Y0 Z2\nG3 X10 Y1 I5 J0 F400\n"}},
       {"prog.nc:2: G3: the end point is 0.0990195 mm off the circle about the centre (radius 5)"}},
      {"program-gcode-bad-arc-signal", "plan", "s.yaml",
       {{"s.yaml", "name: s\nprogram:\n  file: prog.nc\n  gcode: {arc_on: [X3]}\n"
                   "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n"},
        {"prog.nc", "G0 X0 Y0 Z2\nM3\nG1 X10 F400\nM5\n"}},
       {"s.yaml:4: program.gcode.arc_on 'X3': an arc signal is a G or M code and parameter words, as M3, G82 or M62 P1"}},
      {"program-rapid-wobj-not-declared", "import", "prog.mod",
       {{"prog.mod", "MODULE T\n  CONST robtarget p1:=[[1000,0,180],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,"
                     "9E+09]];\n  PROC main()\n    MoveL p1,v100,fine,tool0\\WObj:=wobjTable;\n  ENDPROC\nENDMODULE\n"}},
       {"prog.mod:4: wobjTable is used but not declared as a wobjdata"}},
      {"program-jbi-user-frame-not-defined", "import", "prog.JBI",
       {{"prog.JBI", ReplaceAll(ReplaceAll(jbi_pos, "NPOS 3", "NPOS 2"), "POSTYPE ROBOT", "USER 2\n///POSTYPE USER") +
                         jbi_inst + "END\n"}},
       {"prog.JBI:13: a position taught in user frame 2, which the job does not define: give program.frames.uframe.2 = "
        "[x, y, z, rx, ry, rz] (mm, deg, in the robot frame)"}},
      {"stl-truncated-mid-facet", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", full.substr(0, 84 + 50 + 20)}},
       {"part.stl: truncated binary STL: header says 4 facets", "it ends inside facet 2"}},
      {"stl-wrong-facet-count", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", BinaryStl(tetra, 3)}},
       {"part.stl: binary STL header facet count 3 disagrees with the file size 284 bytes"}},
      {"stl-2gb-header-claim", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", BinaryStl(tetra, 40'000'000)}},
       {"part.stl: binary STL header claims 40000000 facets, more than the limit of 20000000"}},
      {"stl-nan-coordinate", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", BinaryStl(nan_facets)}},
       {"part.stl: binary STL facet 2 of 4: vertex 2 has a non-finite coordinate"}},
      {"stl-inf-coordinate", "plan", "s.yaml",
       {{"s.yaml", ok},
        {"part.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex inf 0 0\nvertex 0 1 0\n"
                     "endloop\nendfacet\nendsolid t\n"}},
       {"part.stl: ASCII STL line 5: vertex x 'inf' is not finite"}},
      {"stl-zero-area-facets-only", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", flat}},
       {"part.stl: no usable facet: 2 facets read, 2 degenerate"}},
      {"stl-open-mesh", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", BinaryStl(open)}},
       {"part.stl: the mesh is open: 3 boundary edges"}},
      {"stl-non-manifold-edges", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", BinaryStl(two)}},
       {"part.stl: the mesh has 1 non-manifold edges (used by more than two facets)"}},
      {"scenario-wrong-type", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "travel_speed_mm_min: 400", "travel_speed_mm_min: fast")}, {"part.stl", full}},
       {"s.yaml:10: process.travel_speed_mm_min = 'fast': must be a number"}},
      {"scenario-negative-length", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "layer_height_mm: 1.5", "layer_height_mm: -1")}, {"part.stl", full}},
       {"s.yaml:5: slicing.layer_height_mm = -1: must be in [0.05, 20]"}},
      {"scenario-zero-length", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "bead_width_mm: 6", "bead_width_mm: 0")}, {"part.stl", full}},
       {"s.yaml:8: path.bead_width_mm = 0: must be in [0.5, 50]"}},
      {"scenario-unknown-pattern", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "pattern: contour", "pattern: wobble")}, {"part.stl", full}},
       {"s.yaml:7: path.pattern = 'wobble': unknown value, expected one of contour, zigzag, hybrid, continuous, "
        "eulerian, spiral"}},
      {"scenario-negative-arc-start", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "wire_feed_mm_min: 3200\n", "wire_feed_mm_min: 3200\n  arc_start_s: -1\n")},
        {"part.stl", full}},
       {"s.yaml:12: process.arc_start_s = -1: must be in [0, 60]"}},
      {"scenario-negative-min-layer-time", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "wire_feed_mm_min: 3200\n",
                                "wire_feed_mm_min: 3200\n  interpass:\n    min_layer_time_s: -5\n")},
        {"part.stl", full}},
       {"s.yaml:13: process.interpass.min_layer_time_s = -5: must be in [0, 86400]"}},
      {"scenario-unknown-island-order", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "pattern: contour", "pattern: contour\n  island_order: hottest")},
        {"part.stl", full}},
       {"s.yaml:8: path.island_order = 'hottest': unknown value, expected one of as_planned, round_robin, "
        "coolest_first"}},
      {"scenario-missing-mesh", "plan", "s.yaml", {{"s.yaml", ScenarioText("nothere.stl")}},
       {"s.yaml:3: part.mesh: mesh file ", "nothere.stl not found"}},
      {"scenario-mesh-is-a-directory", "plan", "s.yaml", {{"s.yaml", ScenarioText("adir")}},
       {"s.yaml:3: part.mesh: ", "adir is a directory, expected a file (mesh file)"}, {"adir"}},
      {"csv-missing-column", "fit csw", "bad.csv",
       {{"bad.csv", "travel_speed_mm_per_min,curvature_radius_mm\n300,30\n600,40\n900,50\n"}},
       {"bad.csv: no column 'width_mm'"}},
      {"csv-text-in-a-number", "fit csw", "bad.csv", {{"bad.csv", csw_header + "300,30,12.5\n600,abc,9.8\n"}},
       {"bad.csv:3: column 'curvature_radius_mm': 'abc' is not a number"}},
      {"csv-too-few-rows", "fit speed-height", "bad.csv",
       {{"bad.csv", "travel_speed_mm_per_min,height_mm\n300,1.5\n600,1.0\n"}},
       {"bad.csv: 2 rows: the power law has 2 parameters and needs at least 3"}},
      {"sweep-grid-value-not-a-list", "sweep", "sweep.yaml",
       {{"sweep.yaml", "base: s.yaml\ngrid:\n  path.bead_width_mm: 5\n"}},
       {"sweep.yaml:3: grid: path.bead_width_mm: must be a non-empty list of values"}},
      {"sweep-missing-base", "sweep", "sweep.yaml", {{"sweep.yaml", "base: nothere.yaml\ngrid: {path.pattern: [hybrid]}\n"}},
       {"sweep.yaml: base: scenario file ", "nothere.yaml not found"}},
      {"sweep-list-without-runs", "sweep", "sweep.yaml", {{"sweep.yaml", "base: s.yaml\nlist: []\n"}, {"s.yaml", ok}},
       {"sweep.yaml:2: list: must be a non-empty list of mappings"}},
      {"sweep-shard-out-of-range", "sweep", "sweep.yaml",
       {{"sweep.yaml", "base: s.yaml\ngrid: {path.pattern: [hybrid]}\n"}, {"s.yaml", ok}},
       {"--shard '3/3': expected K/N with 0 <= K < N, e.g. 0/4 for the first of 4 shards"}, {}, "--shard 3/3"},
      {"set-value-out-of-limits", "plan", "s.yaml", {{"s.yaml", ok}, {"part.stl", full}},
       {"cell.positioner.rotation_deg = 300: must be in [-240, 240]"}, {}, "--set cell.positioner.rotation_deg=300"},
      {"run-set-value-out-of-limits", "run", "s.yaml", {{"s.yaml", ok}, {"part.stl", full}},
       {"slicing.layer_height_mm = 50: must be in [0.05, 20]"}, {}, "--set slicing.layer_height_mm=50"},
      {"sweep-value-out-of-limits", "sweep", "sweep.yaml",
       {{"sweep.yaml", "base: s.yaml\ngrid: {slicing.layer_height_mm: [1.5, 50]}\n"}, {"s.yaml", ok},
        {"part.stl", full}},
       {"run 001-50: ", "slicing.layer_height_mm = 50: must be in [0.05, 20]"}},
      {"bench-set-value-out-of-limits", "bench", "s.yaml", {{"s.yaml", ok}, {"part.stl", full}},
       {"run s: ", "path.bead_width_mm = 100: must be in [0.5, 50]"}, {}, "--set path.bead_width_mm=100"},
      {"generator-parameter-out-of-range", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "  mesh: part.stl\n", "  generator: {type: box, size_mm: [100, 60, 0]}\n")}},
       {"s.yaml:3: part.generator.size_mm[2] = 0: must be in [0.1, 5000]"}},
      {"generator-unknown-parameter", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "  mesh: part.stl\n", "  generator: {type: box, radius_mm: 5}\n")}},
       {"s.yaml:3: part.generator.radius_mm: unknown key (known here: size_mm type)"}},
      // A key holding a newline (a YAML "\n" escape) is quoted back escaped, so the message stays one line.
      {"key-with-newline", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "  mesh: part.stl\n", "  mesh: part.stl\n  \"bad\\nkey\\r\": 1\n")},
        {"part.stl", full}},
       {"s.yaml:4: part.bad\\nkey\\r: unknown key (known here: generator mesh)"}},
      {"sub-volume-keep-not-fours", "plan", "s.yaml",
       {{"s.yaml", ScenarioText("part.stl", "  layer_height_mm: 1.5\n",
                                "  type: multi_directional\n  layer_height_mm: 1.5\n"
                                "  sub_volumes: [{name: a, direction: [0, 0, 1], keep: [0, 0, 1]}]\n")},
        {"part.stl", full}},
       {"s.yaml:7: slicing.sub_volumes[0].keep: 3 numbers: give 4 per entry"}},
      {"program-frame-given-twice", "plan", "s.yaml",
       {{"s.yaml", "name: s\nprogram:\n  file: prog.nc\n  frames: {uframe: {6: [0, 0, 0, 0, 0, 0], 06: [0, 0, 0, 0, 0, "
                   "0]}}\nprocess: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n"},
        {"prog.nc", "G0 X0 Y0 Z2\nM3\nG1 X10 F400\nM5\n"}},
       {"s.yaml:4: program.frames.uframe.06: a second frame 6 (also given as '6')"}},
      {"bench-merge-missing-shard", "bench --merge", "s0",
       {{"s0/bench.json", R"({"scenarios": [{"id": "a"}], "shard": {"index": 0, "count": 2, "runs_total": 2}})"}},
       {"shard 1/2 missing from --merge"}, {"s0"}},
      {"robot-model-does-not-parse", "check", "s.yaml",
       {{"s.yaml", CellScenario("  mjcf: broken.xml\n")}, {"broken.xml", "<mujoco><worldbody><body></mujoco>\n"}},
       {"broken.xml: MuJoCo cannot load the cell model: XML parse error", "Line number=1"}},
      {"robot-model-missing-asset", "check", "s.yaml",
       {{"s.yaml", CellScenario("  mjcf: cell.xml\n")},
        {"cell.xml", "<mujoco>\n  <asset>\n    <mesh name=\"m\" file=\"gone.stl\"/>\n  </asset>\n</mujoco>\n"}},
       {"cell.xml:3: <mesh file=\"gone.stl\">: file not found (looked for ", "gone.stl)"}},
      {"robot-model-two-assets-one-name", "check", "s.yaml",
       {{"s.yaml", CellScenario("  mjcf: cell.xml\n")},
        {"cell.xml", "<mujoco>\n  <asset>\n    <mesh name=\"a\" file=\"a/m.stl\"/>\n"
                     "    <mesh name=\"b\" file=\"b/M.STL\"/>\n  </asset>\n</mujoco>\n"},
        {"a/m.stl", "solid a\nendsolid a\n"},
        {"b/M.STL", "solid b\nendsolid b\n"}},
       {"cell.xml:4: <mesh file=\"b/M.STL\">: names ", "and another element names ",
        ": MuJoCo finds files by name, without their folders, in any case; rename one"},
       {"a", "b"}},
      {"urdf-not-six-revolute-joints", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf")}, {"arm.urdf", MiniUrdf("m.stl", "velocity=\"3\"", 5)}},
       {"arm.urdf:2: the chain from 'base_link' to 'tool0' has 5 revolute joints: the arm must be a serial chain of "
        "six"}},
      {"urdf-joint-not-in-urdf", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf", "    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_9]\n")},
        {"arm.urdf", MiniUrdf("m.stl")}},
       {"arm.urdf:2: cell.robot.joints names joint 'joint_9', which the URDF lacks"}},
      {"urdf-unknown-package", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf")}, {"arm.urdf", MiniUrdf("package://acme_support/meshes/l2.stl")}},
       {"arm.urdf:5: unknown package 'acme_support' of mesh 'package://acme_support/meshes/l2.stl': searched ",
        "/pkgs (cell.robot.package_paths, then ROS_PACKAGE_PATH)"},
       {"pkgs"}},
      {"urdf-missing-mesh", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf")}, {"arm.urdf", MiniUrdf("package://acme_support/meshes/l2.stl")}},
       {"arm.urdf:5: mesh ", "/pkgs/acme_support/meshes/l2.stl not found"},
       {"pkgs", "pkgs/acme_support"}},
      {"urdf-limit-without-velocity", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf")}, {"arm.urdf", MiniUrdf("m.stl", "")}},
       {"arm.urdf:", ": joint 'joint_1': <limit> without velocity (rad/s; waam checks joint speeds)"}},
      {"urdf-continuous-joint-without-limit", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf")}, {"arm.urdf", ContinuousFirstJoint(MiniUrdf("m.stl"))}},
       {"arm.urdf:11: joint 'joint_1' is continuous without <limit velocity>: no bound on its speed (rad/s; waam "
        "checks joint speeds and bounds the motion between samples by them)"}},
      {"cell-unknown-preset", "check", "s.yaml", {{"s.yaml", CellScenario("  preset: fanuc_m20ia\n")}},
       {"s.yaml:13: cell.preset = 'fanuc_m20ia': unknown value, expected one of fanuc_arcmate100ic, abb_irb1600, "
        "kuka_kr16, yaskawa_mh12, kuka_kr16_turntable, abb_irb1600_table"}},
      {"cell-unknown-positioner-type", "check", "s.yaml", {{"s.yaml", CellScenario("  positioner: {type: rotary}\n")}},
       {"s.yaml:13: cell.positioner.type = 'rotary': unknown value, expected one of none, turntable, tilt_rotate"}},
      {"cell-unknown-resolve", "check", "s.yaml", {{"s.yaml", CellScenario("  resolve: optimal\n")}},
       {"s.yaml:13: cell.resolve = 'optimal': unknown value, expected one of fixed, optimise"}},
      {"place-range-min-above-max", "place", "s.yaml",
       {{"s.yaml", CellScenario("  part: {yaw_deg: 0}\nplace:\n  part_x_mm: [50, -50, 10]\n")}},
       {"s.yaml:15: place.part_x_mm = [50, -50, 10]: min must not exceed max ([min, max, step])"}},
      {"place-range-outside-cell-limits", "place", "s.yaml",
       {{"s.yaml", CellScenario("  part: {yaw_deg: 0}\nplace:\n  table_rotation_deg: [0, 300, 30]\n")}},
       {"s.yaml:15: place.table_rotation_deg[1] = 300: must be in [-240, 240]"}},
      {"place-range-step-zero", "place", "s.yaml",
       {{"s.yaml", CellScenario("  part: {yaw_deg: 0}\nplace:\n  part_x_mm: [-10, 10, 0]\n")}},
       {"s.yaml:15: place.part_x_mm: step 0 with min < max; give a step, or one number for a single value"}},
      {"cell-robot-joints-not-six", "check", "s.yaml", {{"s.yaml", UrdfScenario("arm.urdf", "    joints: [a, b]\n")}},
       {"s.yaml:16: cell.robot.joints: must list 6 joints, got 2"}},
      {"program-format-unknown", "plan", "s.yaml",
       {{"s.yaml", "name: s\nprogram:\n  file: prog.nc\n  format: fanuc\n"
                   "process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}\n"},
        {"prog.nc", "G0 X0 Y0 Z2\nM3\nG1 X10 F400\nM5\n"}},
       {"s.yaml:4: program.format = 'fanuc': must be auto or one of csv, fanuc_ls"}},
      {"set-unknown-key", "plan", "s.yaml --set path.bead_widht_mm=5", {{"s.yaml", ok}, {"part.stl", full}},
       {"--set 'path.bead_widht_mm=5': unknown key 'path.bead_widht_mm' (keys of path: pattern bead_width_mm"}},
      {"cell-preset-and-urdf", "check", "s.yaml",
       {{"s.yaml", [] {
          std::string text = UrdfScenario("arm.urdf");
          text.replace(text.find("cell:\n"), 6, "cell:\n  preset: kuka_kr16\n");
          return text;
        }()}},
       {"s.yaml:13: cell.preset: give cell.preset or cell.robot.urdf, not both"}},
      {"material-unknown-name", "material", "@unobtainium", {},
       {"unknown material 'unobtainium': expected one of al5356, mild_steel, ss316l, ti6al4v"}},
      {"material-temperature-repeated", "material", "m.csv", {{"m.csv", material_ok + "1000,30,7500,650\n"}},
       {"m.csv:8: column 'temperature_c': 1000 does not exceed the previous row's 1000: temperatures must be "
        "strictly increasing"}},
      {"material-negative-value", "material", "m.csv", {{"m.csv", ReplaceAll(material_ok, "20,50,", "20,-50,")}},
       {"m.csv:6: column 'conductivity_w_mk': -50 must be > 0"}},
      {"material-text-in-a-number", "material", "m.csv", {{"m.csv", ReplaceAll(material_ok, "7800,", "heavy,")}},
       {"m.csv:6: column 'density_kg_m3': 'heavy' is not a number"}},
      {"material-missing-column", "material", "m.csv",
       {{"m.csv", ReplaceAll(ReplaceAll(ReplaceAll(material_ok, ",specific_heat_j_kgk", ""), ",450\n", "\n"),
                             ",650\n", "\n")}},
       {"m.csv: no column 'specific_heat_j_kgk'"}},
      {"material-solidus-above-liquidus", "material", "m.csv",
       {{"m.csv", ReplaceAll(material_ok, "solidus_c: 1400", "solidus_c: 1500")}},
       {"m.csv: solidus_c = 1500 is above liquidus_c = 1450: the solidus must not exceed the liquidus"}},
      {"thermal-unknown-material", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("material: mild_steel", "material: unobtainium")}},
       {"s.yaml:15: thermal.material: unknown material 'unobtainium': expected one of al5356, mild_steel, ss316l, "
        "ti6al4v"}},
      {"thermal-probe-outside-plate-and-part", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("{plate: [0, 10, -2]}", "{air: [0, 0, 50]}")}},
       {"s.yaml:17: thermal.probes.air = [0, 0, 50]: outside the plate [-50, -20, -10] .. [50, 20, 0] mm and the "
        "part ", "; a probe must lie in the metal"}},
      {"thermal-interpass-below-ambient", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("max_c: 200", "max_c: 10")}},
       {"s.yaml:13: process.interpass.max_c = 10: below the ambient temperature 20 degC (thermal.ambient_c)"}},
      {"thermal-clamp-off-plate", "thermal", "s.yaml", {{"s.yaml", ClampScenario("[45, 0]", "1000")}},
       {"s.yaml:18: thermal.clamps[0]: the patch (x 35 to 55, y -5 to 5 mm) reaches off the plate's top face"}},
      {"thermal-clamp-negative-conductance", "thermal", "s.yaml", {{"s.yaml", ClampScenario("[40, 0]", "-5")}},
       {"s.yaml:18: thermal.clamps[0].conductance_w_m2k = -5"}},
      {"thermal-table-body-without-contact", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("[0, 10, -2]}\n",
                                   "[0, 10, -2]}\n  table: {conductance_w_m2k: 0, thickness_mm: 25}\n")}},
       {"s.yaml:18: thermal.table.conductance_w_m2k = 0 with thickness_mm = 25: a table body needs a contact "
        "conductance > 0"}},
      {"thermal-arc-without-power", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("arc: {power_w: 2000}", "arc: {efficiency: 0.8}")}},
       {"s.yaml:12: process.arc: the arc has no power: give power_w (W), or voltage_v (V) and current_a (A)"}},
      {"replay-missing-column", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText("x,y,z", "x,y,height")}},
       {"log.csv:1: no column 'z' (replay.columns.z); the log's columns: time, power_w, arc_on, x, y, height, T1"}},
      {"replay-time-backwards", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText("3,0,0", "1.5,0,0")}},
       {"log.csv:5: time 1.5 s is before the previous row's 2 s (line 4): time must not go backwards"}},
      {"replay-time-out-of-range", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText("2,2000", "1e300,2000")}},
       {"log.csv:4: time 1e+300 s from the first row: must be within 1e9 s"}},
      {"replay-row-not-numbers", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText("1,2000", "1,2k")}},
       {"log.csv:3:2: column 'power_w': '2k' is not a number"}},
      {"replay-negative-power", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText("1,2000", "1,-2000")}},
       {"log.csv:3:2: column 'power_w': negative power -2000 W; arc power must be >= 0"}},
      {"replay-probe-outside-plate-and-part", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario("[0, 5, -2]", "[0, 5, 80]")}, {"log.csv", ReplayLogText()}},
       {"s.yaml:20: replay.probes.tc.at_mm = [0, 5, 80]: outside the plate", "a probe must lie in the metal"}},
      {"replay-window-outside-log", "thermal replay", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--windows '2:60': outside the log", "log.csv, which runs from 0 to 4 s"}, {}, "--windows 0:2,2:60"},
      {"fit-thermal-window-outside-log", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--window '0:60': outside the log", "log.csv, which runs from 0 to 4 s"}, {}, "--window 0:60"},
      {"fit-thermal-coarse-cell-not-coarser", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--coarse-cell 0.5 mm: must be 0 (no coarse stage) or larger than thermal.cell_mm"}, {},
       "--window 0:4 --free efficiency --coarse-cell 0.5"},
      {"fit-thermal-jacobian-cell-not-coarser", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--jacobian-cell 0.5 mm: must be auto, 0 (the scenario's grid) or larger than thermal.cell_mm"}, {},
       "--window 0:4 --free efficiency --jacobian-cell 0.5"},
      {"fit-thermal-jacobian-cell-not-a-number", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--jacobian-cell '3mm': must be auto, 0 (the scenario's grid) or a grid spacing in mm"}, {},
       "--window 0:4 --free efficiency --jacobian-cell 3mm"},
      {"fit-thermal-negative-prior", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"--prior = -1: must be a weight >= 0 degC (0: no prior)"}, {}, "--window 0:4 --free efficiency --prior -1"},
      {"fit-thermal-free-clamps-without-clamps", "fit thermal", "s.yaml",
       {{"s.yaml", ReplayScenario()}, {"log.csv", ReplayLogText()}},
       {"s.yaml: --free clamps: the scenario has no thermal.clamps[] (nothing to scale)"}, {},
       "--window 0:4 --free efficiency,clamps"},
      {"thermal-unknown-heat-source", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("material: mild_steel\n", "material: mild_steel\n  heat_source: gaussian\n")}},
       {"s.yaml:16: thermal.heat_source = 'gaussian': unknown value, expected one of double_ellipsoid, uniform_bead"}},
      {"thermal-shape-bead-model-missing", "thermal", "s.yaml",
       {{"s.yaml", ThermalScenario("probes: {plate: [0, 10, -2]}\n",
                                   "probes: {plate: [0, 10, -2]}\n  shape: {bead_model: beads.json}\n")}},
       {"s.yaml:18: thermal.shape.bead_model: ", "beads.json: file not found"}},
      {"fit-bead-temperature-one-temperature", "fit bead-temperature", "b.csv",
       {{"b.csv", "interpass_c,height_mm,width_mm\n100,1.2,5\n100,1.3,5\n100,1.2,5.1\n100,1.25,5\n"}},
       {"b.csv: every row has interpass temperature 100 degC: the slope needs at least 2 distinct temperatures"}},
      {"urdf-xacro", "check", "s.yaml",
       {{"s.yaml", UrdfScenario("arm.urdf.xacro")}, {"arm.urdf.xacro", MiniUrdf("m.stl")}},
       {"arm.urdf.xacro: a .xacro file is not read; run `xacro arm.urdf.xacro > arm.urdf` once and name the .urdf"}},
      {"deviation-scan-only-bottom-face", "deviation", "target.stl",
       {{"target.stl", full}, {"scan.stl", BinaryStl({tetra[0]})}},
       {"scan.stl: STL has no facets to sample above its bottom face"}, {}, "", {"scan.stl"}},
  };
}

struct CliRun {
  int exit_code = -1;
  std::string err;
};

CliRun Waam(const std::string& args, const fs::path& err_file) {
  const std::string command = std::string(WAAM_BINARY) + " " + args + " >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

// The flags after `-o` that keep a command to its outputs: no progress (-q) and no pictures (--no-images), where the
// command takes them.
std::string QuietFlags(const std::string& command) {
  if (command.rfind("fit", 0) == 0) return "";
  if (command == "sweep" || command.rfind("bench", 0) == 0 || command == "material") return " -q";
  if (command == "deviation") return " --no-images";
  return " -q --no-images";
}

fs::path CaseDir(const std::string& id) {
  const fs::path dir = fs::temp_directory_path() / ("waam_bad_input_" + std::to_string(::getpid())) / id;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(BadInputCatalogue, EveryCaseExitsTwoWithOneLineNamingFileAndPlaceAndNoOutput) {
  for (const BadInput& c : Catalogue()) {
    SCOPED_TRACE(c.id);
    const fs::path dir = CaseDir(c.id);
    for (const std::string& folder : c.folders) fs::create_directories(dir / folder);
    for (const auto& [name, contents] : c.files) std::ofstream(dir / name, std::ios::binary) << contents;
    const bool fit = c.command.rfind("fit", 0) == 0;
    const fs::path out = fit ? dir / "out" / "model.json" : dir / "out";
    // An input starting with '@' is passed as it is (a name, not a file of the case's folder).
    std::string inputs = c.input.rfind('@', 0) == 0 ? c.input.substr(1) : (dir / c.input).string();
    for (const std::string& more : c.more_inputs) inputs.append(" ").append((dir / more).string());
    const std::string args = c.command + " " + inputs + " " + c.options + " -o " + out.string() + QuietFlags(c.command);
    const CliRun run = Waam(args, dir / "stderr.txt");
    EXPECT_EQ(run.exit_code, 2) << "expected exit code 2 (bad input) for " << c.id << "; stderr: " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "expected one line on stderr: " << run.err;
    EXPECT_THAT(run.err, ::testing::StartsWith("waam: error: "));
    for (const std::string& expected : c.expected) EXPECT_THAT(run.err, HasSubstr(expected));
    EXPECT_THAT(FilesUnder(dir / "out"), ::testing::IsEmpty()) << "no output may be left behind on bad input";
  }
}

// docs/BAD_INPUTS.md must list every case of the catalogue with its message, so the document cannot drift.
TEST(BadInputCatalogue, DocumentListsEveryCaseAndItsMessage) {
  std::ifstream in(fs::path(WAAM_SOURCE_DIR) / "docs" / "BAD_INPUTS.md");
  ASSERT_TRUE(in) << "docs/BAD_INPUTS.md is missing";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  for (const BadInput& c : Catalogue()) {
    EXPECT_THAT(doc, HasSubstr("`" + c.id + "`")) << "docs/BAD_INPUTS.md has no row for " << c.id;
    for (const std::string& expected : c.expected) {
      EXPECT_THAT(doc, HasSubstr(expected)) << "docs/BAD_INPUTS.md row " << c.id << " lacks its message";
    }
  }
}

// The one catalogue entry that is not bad input: a path point no IK branch reaches is a check result (exit 3,
// check.json lists it with its layer and point), because the file is valid and the answer is "not weldable here".
TEST(BadInputCatalogue, UnreachablePathPointIsACheckViolationNamingThePoint) {
  const fs::path dir = CaseDir("unreachable");
  const CliRun run = Waam("check " + std::string(WAAM_SOURCE_DIR) +
                              "/scenarios/cell/cell_out_of_reach.yaml -q --no-images -o " + (dir / "out").string(),
                          dir / "stderr.txt");
  EXPECT_EQ(run.exit_code, 3) << run.err;
  std::ifstream in(dir / "out" / "check.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_THAT(ss.str(), HasSubstr("\"unreachable\"")) << "check.json must list the unreachable points";
}

// An output folder another process holds: the command refuses in one line naming the folder and the holder's pid
// (this test process holds it), exit 2, and writes nothing into it (docs/BAD_INPUTS.md, "Output folder in use").
TEST(BadInputCatalogue, OutputFolderInUseIsRefusedNamingFolderAndPid) {
  const fs::path dir = CaseDir("folder-in-use");
  ClaimOutputDirectory(dir / "out");
  const CliRun run = Waam("plan " + std::string(WAAM_SOURCE_DIR) + "/scenarios/box.yaml -q --no-images -o " +
                              (dir / "out").string(),
                          dir / "stderr.txt");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "expected one line on stderr: " << run.err;
  EXPECT_THAT(run.err, HasSubstr("output folder " + (dir / "out").string() + " is in use by pid " +
                                 std::to_string(::getpid())));
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json")) << "a refused command writes nothing";
}

}  // namespace
}  // namespace waam::analysis
