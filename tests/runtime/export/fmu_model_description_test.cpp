// modelDescription.xml's content: units in SI base units (closed forms of N, mm, s), every
// variable with its attributes, and the escaping that keeps the source text intact in an
// attribute, in FMI 2.0's form and FMI 3.0's. Validity against the FMI 2.0 and 3.0 schemas is
// checked by fmusim (tests/fmusim/).
#include "runtime/export/fmu_model_description.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

namespace fmu_model_description_test {

using namespace rheo;

namespace {

std::string description_of(const std::string& source, const std::string& model) {
  return runtime::exporter::fmi2_model_description(test::model_from(source, model), {model, "{guid}", "0.0.1", "x.rheo", source});
}

std::string fmi3_description_of(const std::string& source, const std::string& model) {
  return runtime::exporter::fmi3_model_description(test::model_from(source, model), {model, "{guid}", "0.0.1", "x.rheo", source});
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("fmu description: each unit is defined in SI base units: N = kg m/s^2, mm = 1e-3 m") {
  const std::string xml = description_of(
      "model m { yeoh y (D10 = 1 N/mm, D20 = 1 N/mm^3, D30 = 1 N/mm^5) maxwell m1 (k = 1 N/mm, tau = 1 ms) inerter i (b = 2 kg) spring s (k = 1) }",
      "m");
  CHECK(has(xml, "<Unit name=\"N\">\n      <BaseUnit kg=\"1\" m=\"1\" s=\"-2\"/>"));
  CHECK(has(xml, "<Unit name=\"mm\">\n      <BaseUnit m=\"1\" factor=\"0.001\"/>"));
  CHECK(has(xml, "<Unit name=\"N/mm\">\n      <BaseUnit kg=\"1\" s=\"-2\" factor=\"1000\"/>"));                         // 1 N/mm = 1000 kg/s^2
  CHECK(has(xml, "<Unit name=\"N/mm^5\">\n      <BaseUnit kg=\"1\" m=\"-4\" s=\"-2\" factor=\"1000000000000000\"/>"));  // 1 N/mm^5 = 1e15 kg/(m^4 s^2)
  CHECK(has(xml, "<Unit name=\"N*s/mm\">\n      <BaseUnit kg=\"1\" s=\"-1\" factor=\"1000\"/>"));
  CHECK(has(xml, "<Unit name=\"N*s^2/mm\">\n      <BaseUnit kg=\"1\" factor=\"1000\"/>"));  // inertance: 1 N s^2/mm = 1000 kg
  CHECK(has(xml, "<Unit name=\"s\">\n      <BaseUnit s=\"1\"/>"));
  CHECK(has(xml, "<Unit name=\"mm/s\">\n      <BaseUnit m=\"1\" s=\"-1\" factor=\"0.001\"/>"));
  // The inerter's 2 kg is 0.002 N*s^2/mm internally.
  CHECK(has(xml, "<Real unit=\"N*s^2/mm\" min=\"2.2250738585072014e-308\" start=\"0.002\"/>"));
}

TEST_CASE("fmu description: input, output, parameters and calculated parameters, with the model structure") {
  const std::string xml = description_of("model m { spring s (k = 20 N/mm in [1, 100]) maxwell m1 (k = 5 N/mm, tau = 2 ms) }", "m");
  CHECK(has(xml,
            "name=\"u\" valueReference=\"0\" description=\"terminal displacement (the other terminal is ground)\" causality=\"input\" "
            "variability=\"continuous\">\n      <Real unit=\"mm\" min=\"-1e+20\" max=\"1e+20\" start=\"0\"/>"));
  CHECK(has(xml,
            "name=\"F\" valueReference=\"1\" description=\"terminal force at the communication point\" causality=\"output\" "
            "variability=\"continuous\" initial=\"calculated\">\n      <Real unit=\"N\"/>"));
  CHECK(has(xml, "causality=\"parameter\" variability=\"fixed\" initial=\"exact\">\n      <Real unit=\"N/mm\" min=\"1\" max=\"100\" start=\"20\"/>"));
  CHECK(has(xml,
            "name=\"v\" valueReference=\"2\" description=\"terminal velocity over the next step, for hosts that provide it (0: u is held over "
            "the step)\" causality=\"input\" variability=\"continuous\">\n      <Real unit=\"mm/s\" start=\"0\" derivative=\"1\"/>"));
  // v is u's time derivative: u is ModelVariables' first (index 1); no other variable is one.
  CHECK(xml.find("derivative=") == xml.rfind("derivative="));
  CHECK(has(xml, "name=\"m1.c\" valueReference=\"6\""));
  CHECK(has(
      xml,
      "causality=\"calculatedParameter\" variability=\"fixed\" initial=\"calculated\">\n      <Real unit=\"N*s/mm\" min=\"2.2250738585072014e-308\"/>"));
  // Outputs: F (index 2) without direct feedthrough; initial unknowns: F and the calculated m1.c (index 7).
  CHECK(has(xml, "<Outputs>\n      <Unknown index=\"2\" dependencies=\"\"/>\n    </Outputs>"));
  CHECK(has(xml, "<InitialUnknowns>\n      <Unknown index=\"2\"/>\n      <Unknown index=\"7\"/>\n    </InitialUnknowns>"));
  CHECK(has(xml, "canGetAndSetFMUstate=\"true\""));
  CHECK(has(xml, "canSerializeFMUstate=\"true\""));
  CHECK(has(xml, "canInterpolateInputs=\"true\""));
}

TEST_CASE("fmu description: the source text and rheo's version stand in the description, escaped for an attribute") {
  const std::string source = "# \"a\" < b & c\nmodel m {\n\tspring s (k = 1)\n}\n";
  const std::string xml = description_of(source, "m");
  CHECK(has(xml, "exported by rheo 0.0.1. Source text:&#10;# &quot;a&quot; &lt; b &amp; c&#10;model m {&#10;&#9;spring s (k = 1)&#10;}&#10;\""));
  CHECK(runtime::exporter::xml_attribute("a\rb\x01<") == "a&#13;b&#xFFFD;&lt;");
}

TEST_CASE("fmu description: FMI 3.0 declares every variable as a Float64, time as the independent one, and the structure by value reference") {
  const std::string source = "model m { spring s (k = 20 N/mm in [1, 100]) maxwell m1 (k = 5 N/mm, tau = 2 ms) }";
  const std::string xml = fmi3_description_of(source, "m");
  CHECK(has(xml, "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"m\" instantiationToken=\"{guid}\""));
  CHECK_FALSE(has(xml, "guid="));
  CHECK(has(xml,
            "<Float64 name=\"u\" valueReference=\"0\" description=\"terminal displacement (the other terminal is ground)\" causality=\"input\" "
            "variability=\"continuous\" unit=\"mm\" min=\"-1e+20\" max=\"1e+20\" start=\"0\"/>"));
  CHECK(has(xml,
            "<Float64 name=\"F\" valueReference=\"1\" description=\"terminal force at the communication point\" causality=\"output\" "
            "variability=\"continuous\" initial=\"calculated\" unit=\"N\"/>"));
  CHECK(has(xml, "causality=\"parameter\" variability=\"fixed\" initial=\"exact\" unit=\"N/mm\" min=\"1\" max=\"100\" start=\"20\"/>"));
  CHECK(has(xml, "<Float64 name=\"m1.c\" valueReference=\"6\""));
  // v is u's time derivative, named by value reference; no other variable is one.
  CHECK(has(xml,
            "<Float64 name=\"v\" valueReference=\"2\" description=\"terminal velocity over the next step, for hosts that provide it (0: u is "
            "held over the step)\" causality=\"input\" variability=\"continuous\" unit=\"mm/s\" start=\"0\" derivative=\"0\"/>"));
  CHECK(xml.find("derivative=") == xml.rfind("derivative="));
  // The independent variable: continuous, in s, with no start (FMI 3.0 section 2.4.7.4).
  CHECK(has(xml,
            "<Float64 name=\"time\" valueReference=\"7\" description=\"time at the last communication point\" causality=\"independent\" "
            "variability=\"continuous\" unit=\"s\"/>"));
  // Outputs and initial unknowns by value reference (FMI 2.0 counts positions from 1).
  CHECK(has(xml,
            "<ModelStructure>\n    <Output valueReference=\"1\" dependencies=\"\"/>\n    <InitialUnknown valueReference=\"1\"/>\n"
            "    <InitialUnknown valueReference=\"6\"/>\n  </ModelStructure>"));
  for (const char* attribute : {"canGetAndSetFMUState=\"true\"", "canSerializeFMUState=\"true\"", "providesIntermediateUpdate=\"false\"",
                                "canHandleVariableCommunicationStepSize=\"true\"", "hasEventMode=\"false\"", "modelIdentifier=\"m\""})
    CHECK_MESSAGE(has(xml, attribute), attribute);
  // The units as FMI 2.0 writes them.
  CHECK(has(xml, "<Unit name=\"N/mm\">\n      <BaseUnit kg=\"1\" s=\"-2\" factor=\"1000\"/>"));
  CHECK(has(xml, "<Unit name=\"s\">\n      <BaseUnit s=\"1\"/>"));
  // FMI 2.0 leaves time implicit.
  const std::string fmi2 = description_of(source, "m");
  CHECK_FALSE(has(fmi2, "independent"));
  CHECK_FALSE(has(fmi2, "name=\"time\""));
}

}  // namespace fmu_model_description_test
