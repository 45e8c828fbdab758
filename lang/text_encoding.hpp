// Source files and CSV data are UTF-8 text. These helpers find where a file stops being text
// and show text from a file safely: no byte that would garble a terminal is written back.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace rheo::lang {

struct EncodingProblem {
  std::size_t offset = 0;   // of the offending byte
  std::string description;  // "found byte 0xFF, which is not UTF-8; ..." / "found a NUL byte; ..."
};

// The first byte of TEXT that is not part of well-formed UTF-8 (RFC 3629: no overlong forms,
// surrogates or code points past U+10FFFF), or the first NUL byte; nullopt when TEXT is text.
std::optional<EncodingProblem> find_encoding_problem(std::string_view text);

// Length in bytes of the well-formed UTF-8 character at TEXT[offset], or 0 when the bytes
// there are not one.
std::size_t utf8_length(std::string_view text, std::size_t offset);

// TEXT for a message: malformed UTF-8 and control characters but tab replaced by U+FFFD, and
// more than MAX_CHARACTERS characters cut to that many and "...".
std::string printable(std::string_view text, std::size_t max_characters = 60);
// Appends the character at TEXT[offset] to OUT as printable() shows it; returns its length in
// bytes (1 for a malformed byte).
std::size_t append_printable_character(std::string& out, std::string_view text, std::size_t offset);

// 1-based line and byte column of OFFSET in TEXT.
struct TextPosition {
  int line = 1;
  int column = 1;
};
TextPosition position_of(std::string_view text, std::size_t offset);

}  // namespace rheo::lang
