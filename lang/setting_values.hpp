// The value shapes a directive setting can take (simulate protocols, fit blocks) and their
// validation against one setting's spec. The schemas themselves live with their directives
// (protocol_schema.cpp, fit_schema.cpp).
#pragma once

#include "lang/ast.hpp"
#include "lang/diagnostics.hpp"

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

enum class Shape {
  list,        // several values: a value, [list] or FROM .. TO step STEP
  single,      // exactly one value with a dimension
  integer,     // one whole plain number
  number,      // one plain number
  identifier,  // one of `choices`
  string,      // "file.csv": a file name
  text,        // "text": any text in double quotes
  paths,       // parameter paths: `m1.k` or [m1.k, m1.tau]; kept as text, resolved by the caller
};

struct SettingSpec {
  std::string_view key;
  Shape shape;
  Dimension dimension;
  bool required = false;
  bool positive = false;                                     // list/single/number: every value > 0
  int minimum = 0;                                           // integer: value >= minimum
  int multiple_of = 0;                                       // integer: value % multiple_of == 0 when non-zero
  std::vector<std::string> choices = {};                     // identifier
  double lowest = -std::numeric_limits<double>::infinity();  // list/single/number: every value >= lowest
  double highest = std::numeric_limits<double>::infinity();  // ... and <= highest
  int maximum = std::numeric_limits<int>::max();             // integer: value <= maximum
};

// A parameter path written in a Shape::paths setting.
struct PathItem {
  std::string path;
  SourceLocation where;
};

// A file name written in a .rheo file (`output`, `data`, a history's `file`): not empty and
// without control characters, which no file name needs and a terminal would act on when the
// name is echoed. Reports at WHERE and returns false otherwise.
bool check_file_name(const std::string& name, const SourceLocation& where, std::vector<Diagnostic>& errors);

// Checks NODE's value against SPEC (shape, dimension, range) into OUT: numbers in internal
// units into OUT.values, identifiers and strings into OUT.text. Shape::paths leaves OUT alone
// and appends the paths to PATHS (when given). Reports to ERRORS and returns false when invalid.
bool check_setting_value(const ast::SettingNode& node, const SettingSpec& spec, Setting& out, std::vector<Diagnostic>& errors,
                         std::vector<PathItem>* paths = nullptr);

// The setting of SPECS that NODE names, checked; "unknown setting 'x' for WHAT; ... accepted:
// ..." when none does. nullopt when invalid.
std::optional<Setting> check_keyed_setting(const std::vector<SettingSpec>& specs, std::string_view what, const ast::SettingNode& node,
                                           std::vector<Diagnostic>& errors, std::vector<PathItem>* paths = nullptr);

}  // namespace rheo::lang
