// Edits of a model's source text that keep every other byte as written: appending element
// statements to a model's body and replacing one element statement (`rheo diagnose` adds the
// elements it names to the user's own file this way, comments and layout intact).
//
// Offsets are byte offsets into the text the model was compiled from; the scanner skips `#`
// comments and "strings" when it matches brackets. TEXT must be the model's source: functions
// throw std::logic_error (a bug of the caller) when a location lies outside TEXT or the brackets
// do not match.
#pragma once

#include "lang/model.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rheo::lang {

struct TextSpan {
  std::size_t begin = 0;
  std::size_t end = 0;  // one past the last byte
};

// Byte offset of a 1-based line:column location.
std::size_t byte_offset(std::string_view text, const SourceLocation& where);

// Offset of the `}` that closes the body of MODEL (compiled from TEXT).
std::size_t model_body_close(std::string_view text, const CheckedModel& model);

// The statement of ELEMENT: from its kind word to the `)` closing its arguments (a leaf) or the
// `}` closing its body (a block), inclusive.
TextSpan element_statement(std::string_view text, const Element& element);

// TEXT with LINES added as the last lines of MODEL's body, each indented like the body's first
// element; lines may be comments (`# ...`) or element statements.
std::string append_to_model(std::string_view text, const CheckedModel& model, const std::vector<std::string>& lines);

// TEXT with SPAN replaced by REPLACEMENT.
std::string replace_span(std::string_view text, TextSpan span, std::string_view replacement);

// The leading blanks of the line holding OFFSET.
std::string line_indent(std::string_view text, std::size_t offset);

}  // namespace rheo::lang
