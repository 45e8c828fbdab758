#include "lang/text_encoding.hpp"

#include <doctest/doctest.h>

#include <string>

namespace text_encoding_test {

using namespace rheo::lang;
using namespace std::string_literals;

TEST_CASE("utf8_length: well-formed characters only (RFC 3629)") {
  CHECK(utf8_length("a", 0) == 1);
  CHECK(utf8_length("\xc2\xb5", 0) == 2);          // µ
  CHECK(utf8_length("\xe2\x80\x94", 0) == 3);      // em dash
  CHECK(utf8_length("\xf0\x9f\x98\x80", 0) == 4);  // U+1F600
  CHECK(utf8_length("\xff", 0) == 0);
  CHECK(utf8_length("\x80", 0) == 0);              // a continuation byte alone
  CHECK(utf8_length("\xc0\xaf", 0) == 0);          // overlong '/'
  CHECK(utf8_length("\xe0\x80\xaf", 0) == 0);      // overlong, 3 bytes
  CHECK(utf8_length("\xed\xa0\x80", 0) == 0);      // a surrogate
  CHECK(utf8_length("\xf4\x90\x80\x80", 0) == 0);  // past U+10FFFF
  CHECK(utf8_length("\xe2\x80", 0) == 0);          // cut short
  CHECK(utf8_length("", 0) == 0);
}

TEST_CASE("find_encoding_problem: the first byte that is not UTF-8 text, or the first NUL") {
  CHECK(!find_encoding_problem("plain ASCII\r\n# Prüfstand µ — 試験 😀\n"));
  const auto bad = find_encoding_problem("caf\xe9 \xff");
  REQUIRE(bad);
  CHECK(bad->offset == 3);
  CHECK(bad->description.find("found byte 0xE9, which is not UTF-8; the file must be UTF-8 text") == 0);
  const auto nul = find_encoding_problem("ab\0c"s);
  REQUIRE(nul);
  CHECK(nul->offset == 2);
  CHECK(nul->description.find("found a NUL byte") == 0);
}

TEST_CASE("printable: no byte that garbles a terminal, long text is cut") {
  CHECK(printable("µm") == "µm");
  CHECK(printable("a\xff"
                  "b") ==
        "a\xEF\xBF\xBD"
        "b");
  CHECK(printable("\x1b[31mred\tx"s) == "\xEF\xBF\xBD[31mred\tx");
  CHECK(printable("a\0b"s) ==
        "a\xEF\xBF\xBD"
        "b");
  CHECK(printable(std::string(100, 'x'), 10) == std::string(10, 'x') + "...");
  CHECK(printable("ééééé", 3) == "ééé...");  // cut at characters, not bytes
}

TEST_CASE("position_of: 1-based line and byte column") {
  CHECK(position_of("ab\ncd", 0).line == 1);
  CHECK(position_of("ab\ncd", 4).line == 2);
  CHECK(position_of("ab\ncd", 4).column == 2);
  CHECK(position_of("é\nx\xff", 4).column == 2);
}

}  // namespace text_encoding_test
