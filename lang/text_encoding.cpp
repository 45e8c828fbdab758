#include "lang/text_encoding.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>

namespace rheo::lang {
namespace {
constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

bool continuation(unsigned char c) { return (c & 0xC0) == 0x80; }
bool control(unsigned char c) { return (c < 0x20 && c != '\t') || c == 0x7F; }

// Whether the 8 bytes at P are ASCII and none is NUL: the common case, checked a word at a time.
bool plain_ascii_word(const char* p) {
  std::uint64_t w = 0;
  std::memcpy(&w, p, sizeof w);
  constexpr std::uint64_t ones = 0x0101010101010101u, highs = 0x8080808080808080u;
  return ((w | ((w - ones) & ~w)) & highs) == 0;  // no high bit set, no zero byte
}
}  // namespace

std::size_t utf8_length(std::string_view text, std::size_t offset) {
  if (offset >= text.size()) return 0;
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[offset + i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF) length = 3, low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
  else if (lead >= 0xF0 && lead <= 0xF4) length = 4, low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (offset + length > text.size()) return 0;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t i = 2; i < length; ++i)
    if (!continuation(byte(i))) return 0;
  return length;
}

std::optional<EncodingProblem> find_encoding_problem(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    if (i + 8 <= text.size() && plain_ascii_word(text.data() + i)) {
      i += 8;
      continue;
    }
    if (text[i] == '\0') return EncodingProblem{i, "found a NUL byte; the file must be text: remove it"};
    const std::size_t n = utf8_length(text, i);
    if (n == 0)
      return EncodingProblem{i, fmt::format("found byte 0x{:02X}, which is not UTF-8; the file must be UTF-8 text: "
                                            "re-save it as UTF-8 or remove the byte",
                                            static_cast<unsigned char>(text[i]))};
    i += n;
  }
  return std::nullopt;
}

std::size_t append_printable_character(std::string& out, std::string_view text, std::size_t offset) {
  const std::size_t n = utf8_length(text, offset);
  if (n == 0 || control(static_cast<unsigned char>(text[offset]))) out += kReplacement;
  else out += text.substr(offset, n);
  return n == 0 ? 1 : n;
}

std::string printable(std::string_view text, std::size_t max_characters) {
  std::string out;
  std::size_t characters = 0;
  for (std::size_t i = 0; i < text.size(); ++characters) {
    if (characters == max_characters) return out + "...";
    i += append_printable_character(out, text, i);
  }
  return out;
}

TextPosition position_of(std::string_view text, std::size_t offset) {
  TextPosition p;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i)
    if (text[i] == '\n') ++p.line, line_start = i + 1;
  p.column = static_cast<int>(offset - line_start) + 1;
  return p;
}

}  // namespace rheo::lang
