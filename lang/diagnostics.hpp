// Compiler diagnostics: `file:line:col: error: message`, then the source line and a caret
// under the column.
#pragma once

#include "lang/errors.hpp"
#include "lang/model.hpp"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

struct Diagnostic {
  SourceLocation where;
  std::string message;
};

// Source texts by file name, so diagnostics can quote the offending line.
class SourceSet {
 public:
  void add(const std::string& file, std::string text);
  // The line (1-based) of FILE without its newline; empty when unknown. Constant time.
  std::string_view line(const std::string& file, int line) const;

 private:
  struct Text {
    std::string text;
    std::vector<std::size_t> line_starts;  // byte offset of each line
  };
  std::map<std::string, Text> texts_;
};

// "file:line:col: error: message\n  <source line>\n  <caret>\n". The line is shown as
// printable text (text_encoding.hpp), cut to about 160 bytes around the column when longer
// (marked "..."), with the caret under the column's character.
std::string format(const Diagnostic& d, const SourceSet& sources);

// Every diagnostic of a failed compilation; what() is all of them formatted, each ending in a
// newline. A model error (exit 3).
class CompileError : public ModelError {
 public:
  CompileError(std::vector<Diagnostic> diagnostics, const SourceSet& sources);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace rheo::lang
