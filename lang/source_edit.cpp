#include "lang/source_edit.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace rheo::lang {
namespace {

// {offset of the first OPEN at or after FROM, offset of its matching CLOSE}, outside comments
// and strings.
TextSpan matching_brackets(std::string_view text, std::size_t from, char open, char close) {
  int depth = 0;
  std::size_t first = std::string_view::npos;
  for (std::size_t i = from; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '#') {
      i = text.find('\n', i);
      if (i == std::string_view::npos) break;
    } else if (c == '"') {
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (c == open) {
      if (depth++ == 0 && first == std::string_view::npos) first = i;
    } else if (c == close && depth > 0) {
      if (--depth == 0) return {first, i};
    }
  }
  throw std::logic_error(fmt::format("no matching '{}{}' after byte {}: the text is not the model's source", open, close, from));
}

// The first of '(' and '{' after the kind word and name of an element statement.
char statement_opener(std::string_view text, std::size_t from) {
  for (std::size_t i = from; i < text.size(); ++i) {
    if (text[i] == '#') {
      i = text.find('\n', i);
      if (i == std::string_view::npos) break;
    } else if (text[i] == '(' || text[i] == '{') {
      return text[i];
    }
  }
  throw std::logic_error(fmt::format("no element arguments or body after byte {}", from));
}

}  // namespace

std::size_t byte_offset(std::string_view text, const SourceLocation& where) {
  std::size_t offset = 0;
  for (int line = 1; line < where.line; ++line) {
    offset = text.find('\n', offset);
    if (offset == std::string_view::npos) throw std::logic_error(fmt::format("line {} lies beyond the text", where.line));
    ++offset;
  }
  offset += static_cast<std::size_t>(where.column > 0 ? where.column - 1 : 0);
  if (where.line < 1 || offset > text.size()) throw std::logic_error(fmt::format("{}:{} lies outside the text", where.line, where.column));
  return offset;
}

std::size_t model_body_close(std::string_view text, const CheckedModel& model) {
  return matching_brackets(text, byte_offset(text, model.where), '{', '}').end;
}

TextSpan element_statement(std::string_view text, const Element& element) {
  const std::size_t begin = byte_offset(text, element.where);
  const char open = statement_opener(text, begin);
  const TextSpan brackets = matching_brackets(text, begin, open, open == '(' ? ')' : '}');
  return {begin, brackets.end + 1};
}

std::string line_indent(std::string_view text, std::size_t offset) {
  const std::size_t newline = offset == 0 ? std::string_view::npos : text.rfind('\n', offset - 1);
  const std::size_t start = newline == std::string_view::npos ? 0 : newline + 1;
  std::size_t end = start;
  while (end < text.size() && (text[end] == ' ' || text[end] == '\t')) ++end;
  return std::string(text.substr(start, end - start));
}

std::string append_to_model(std::string_view text, const CheckedModel& model, const std::vector<std::string>& lines) {
  const std::size_t close = model_body_close(text, model);
  // The first element's indent, or two blanks more than the model's when it shares its line.
  const std::string model_indent = line_indent(text, byte_offset(text, model.where));
  std::string indent = model.root.children.empty() ? model_indent : line_indent(text, byte_offset(text, model.root.children.front().where));
  if (indent.size() <= model_indent.size()) indent = model_indent + "  ";
  std::string block;
  for (const auto& line : lines) block += indent + line + "\n";
  // The `}` on a line of its own: the new lines go before that line; else they get their own.
  const std::size_t line_start = close == 0 ? 0 : text.rfind('\n', close - 1);
  const bool own_line = line_start != std::string_view::npos &&
                        text.substr(line_start + 1, close - line_start - 1).find_first_not_of(" \t") == std::string_view::npos;
  if (own_line) return std::string(text.substr(0, line_start + 1)) + block + std::string(text.substr(line_start + 1));
  return std::string(text.substr(0, close)) + "\n" + block + std::string(text.substr(close));
}

std::string replace_span(std::string_view text, TextSpan span, std::string_view replacement) {
  if (span.begin > span.end || span.end > text.size()) throw std::logic_error("span lies outside the text");
  return std::string(text.substr(0, span.begin)) + std::string(replacement) + std::string(text.substr(span.end));
}

}  // namespace rheo::lang
