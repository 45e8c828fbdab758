#include "lang/source_edit.hpp"

#include "lang/frontend.hpp"

#include <doctest/doctest.h>

#include <stdexcept>

namespace source_edit_test {

using namespace rheo::lang;

namespace {

const char* kSource = R"(# Comments may hold brackets: { ( } ) and "quotes
model a {
    spring   s (k = 100 N/mm)   # ) } a comment closing nothing
    series arm {
      slider cap (fy = 20 N)
      maxwell m (k = 10 N/mm,
                 tau = 3 ms)
    }
}
model b { spring s (k = 1 N/mm) }
simulate a { harmonic frequency = 10 Hz, amplitude = 1 mm
  output "x}{.csv" }
)";

const Element& child(const CheckedModel& m, const std::string& name) {
  for (const auto& e : m.root.children)
    if (e.name == name) return e;
  FAIL("no element " << name);
  return m.root;
}

}  // namespace

TEST_CASE("source_edit: byte offsets of line:column locations") {
  const std::string text = "ab\ncd\n";
  CHECK(byte_offset(text, {"f", 1, 1}) == 0);
  CHECK(byte_offset(text, {"f", 2, 2}) == 4);
  CHECK_THROWS_AS(byte_offset(text, {"f", 5, 1}), std::logic_error);
}

TEST_CASE("source_edit: element statements span leaves over lines and whole blocks, past comments") {
  const Program p = compile_source("a.rheo", kSource);
  const CheckedModel& a = *p.find_model("a");
  const TextSpan spring = element_statement(kSource, child(a, "s"));
  CHECK(std::string_view(kSource).substr(spring.begin, spring.end - spring.begin) == "spring   s (k = 100 N/mm)");
  const TextSpan arm = element_statement(kSource, child(a, "arm"));
  const std::string arm_text(std::string_view(kSource).substr(arm.begin, arm.end - arm.begin));
  CHECK(arm_text.starts_with("series arm {"));
  CHECK(arm_text.ends_with("tau = 3 ms)\n    }"));
  const Element& maxwell = child(a, "arm").children.at(1);
  const TextSpan m = element_statement(kSource, maxwell);
  CHECK(std::string_view(kSource).substr(m.begin, m.end - m.begin) == "maxwell m (k = 10 N/mm,\n                 tau = 3 ms)");
}

TEST_CASE("source_edit: appended lines join the model body with its indent and compile") {
  const Program p = compile_source("a.rheo", kSource);
  const std::string edited = append_to_model(kSource, *p.find_model("a"), {"# added", "dashpot d (c = 1 N*s/mm)"});
  CHECK(edited.find("                 tau = 3 ms)\n    }\n    # added\n    dashpot d (c = 1 N*s/mm)\n}\nmodel b") != std::string::npos);
  const Program again = compile_source("a.rheo", edited);
  CHECK(again.find_model("a")->root.children.size() == 3);

  // A body on one line: the new lines get lines of their own before the brace.
  const std::string one_line = append_to_model(kSource, *p.find_model("b"), {"dashpot d (c = 1 N*s/mm)"});
  CHECK(one_line.find("model b { spring s (k = 1 N/mm) \n  dashpot d (c = 1 N*s/mm)\n}") != std::string::npos);
  CHECK(compile_source("a.rheo", one_line).find_model("b")->root.children.size() == 2);
}

TEST_CASE("source_edit: replacing a statement keeps every other byte") {
  const Program p = compile_source("a.rheo", kSource);
  const CheckedModel& a = *p.find_model("a");
  const std::string edited = replace_span(kSource, element_statement(kSource, child(a, "s")),
                                          "yeoh     s (D10 = 50 N/mm, D20 = 0 N/mm^3, D30 = 0 N/mm^5)");
  CHECK(edited.find("    yeoh     s (D10 = 50 N/mm, D20 = 0 N/mm^3, D30 = 0 N/mm^5)   # ) } a comment closing nothing\n") != std::string::npos);
  CHECK(compile_source("a.rheo", edited).find_model("a")->root.children.front().kind == ElementKind::yeoh);
  CHECK_THROWS_AS(replace_span("abc", {2, 5}, "x"), std::logic_error);
}

TEST_CASE("source_edit: text that is not the model's source is refused") {
  const Program p = compile_source("a.rheo", kSource);
  CHECK_THROWS_AS(model_body_close("model a { spring s (k = 1)", *p.find_model("a")), std::logic_error);
  CHECK(line_indent("x\n   y", 4) == "   ");
}

}  // namespace source_edit_test
