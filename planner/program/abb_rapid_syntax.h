// ABB RAPID's syntax for the reader: aggregate values, instruction arguments and expressions, statements split at
// ';', data declarations and the module's procedures (abb_rapid_reader.cc runs them).
#pragma once

#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "planner/program/program_motion.h"
#include "planner/program/program_tokens.h"

namespace waam::planner::internal {

// A RAPID aggregate value: a number, a word (TRUE, a name), a string or a bracketed list.
struct RapidValue {
  enum class Kind { kNumber, kWord, kString, kList } kind = Kind::kWord;
  double number = 0.0;
  std::string text;
  std::vector<RapidValue> items;
};

// An argument: a literal, a data name, a function call (Offs, RelTool) or an expression the reader does not evaluate.
struct RapidExpr {
  enum class Kind { kValue, kName, kCall, kOther } kind = Kind::kOther;
  RapidValue value;
  std::string name;   // kName / kCall: upper case
  std::string text;   // as written, for messages
  std::vector<RapidExpr> args;
  std::map<std::string, std::optional<RapidExpr>> options;  // \Rx:=30, \InPos
};

struct RapidArgs {
  std::vector<RapidExpr> positional;
  std::map<std::string, std::optional<RapidExpr>> options;  // upper-case names: WOBJ, V, T, ON, WEAVE ...
};

struct RapidData {
  std::string type;  // upper case: ROBTARGET, TOOLDATA, NUM ...
  RapidValue value;
  int line = 0;
};

struct RapidStatement {
  std::string text;
  int line = 0;
};

// The module: its data (declared at module level and, as they run, inside procedures) and its procedures.
struct RapidModule {
  std::string name;
  std::map<std::string, RapidData> data;
  std::map<std::string, std::pair<std::size_t, std::size_t>> procs;  // statements [first, last) of each PROC body
  std::vector<RapidStatement> statements;
  std::string first_proc;
};

// The numbers of a list value of `n` numbers; InputError "file:line: <what> must be a list of n numbers".
std::vector<double> RapidNumbers(const RapidValue& v, std::size_t n, const std::string& file, int line,
                                 const char* what);

// [[x,y,z],[q1,q2,q3,q4]] -> pose (mm; q1 the scalar part); InputError for a quaternion not of unit length.
Eigen::Isometry3d RapidPose(const RapidValue& pos, const RapidValue& rot, const std::string& file, int line);

// Checks an aggregate of `items` items whose `poses` items are poses [[x,y,z],[q]]; InputError "file:line: <form>".
void CheckRapidShape(const RapidValue& v, std::size_t items, std::initializer_list<std::size_t> poses,
                     const std::string& file, int line, const char* form);

inline constexpr const char* kRobtargetForm = "robtarget must be [[x,y,z],[q1..q4],[cf1,cf4,cf6,cfx],[eax]]";
inline constexpr const char* kTooldataForm =
    "tooldata must be [robhold,[[x,y,z],[q1..q4]],[mass,[cog],[aom],ix,iy,iz]]";
inline constexpr const char* kWobjdataForm = "wobjdata must be [robhold,ufprog,ufmec,[[x,y,z],[q]],[[x,y,z],[q]]]";

// An instruction's arguments: "p1, v100, fine, tool0\WObj:=wobj1" or "\InPos, 1"; InputError on a syntax error.
RapidArgs ReadRapidArgs(TokenCursor& ts);

// True for the words that open or close a block (MODULE, PROC, IF, ENDIF, ...).
bool IsRapidBlockWord(const std::string& first);

// True when the statement at the cursor declares data ([LOCAL|TASK] CONST|PERS|VAR).
bool IsRapidDeclaration(TokenCursor& ts);

// "[LOCAL|TASK] CONST|PERS|VAR <type> <name> [:= <value>]": the data, checked where it is declared (robtarget,
// tooldata, wobjdata shapes and quaternions); false for an array or a declaration without a value.
bool ReadRapidDecl(TokenCursor& ts, const std::string& file, WarningList* warnings, std::string* name,
                   RapidData* data);

// The file's statements: ';'-terminated (over several lines), or a block line on its own; '!' comments, an S4 "%%%"
// header skipped. InputError for a statement without its ';'.
std::vector<RapidStatement> SplitRapidStatements(const std::vector<std::string_view>& lines, const std::string& file);

// MODULE name ... ENDMODULE: the module-level data and where each PROC's body lies; InputError without MODULE or
// ENDMODULE, for text after ENDMODULE or a second MODULE.
RapidModule ReadRapidModule(std::vector<RapidStatement> statements, const std::string& file, int last_line,
                            WarningList* warnings);

}  // namespace waam::planner::internal
