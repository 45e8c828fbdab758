// The FMU as a whole: which networks are refused (element and line:col), and what the archive
// holds for FMI 2.0 and FMI 3.0, read back with minizip's reader.
#include "runtime/export/fmu_export.hpp"

#include "cli_support.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/export/fmu_binary.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <minizip/unzip.h>

#include <fstream>
#include <map>

namespace fmu_export_test {

using namespace rheo;

namespace {

// Every entry of the ZIP archive BYTES: name -> contents.
std::map<std::string, std::string> unzipped(const std::string& bytes) {
  const auto path = test::scratch_directory("fmu-export") / "x.fmu";
  std::ofstream(path, std::ios::binary) << bytes;
  std::map<std::string, std::string> out;
  unzFile zip = unzOpen64(path.c_str());
  REQUIRE(zip != nullptr);
  for (int status = unzGoToFirstFile(zip); status == UNZ_OK; status = unzGoToNextFile(zip)) {
    char name[512];
    unz_file_info64 info;
    REQUIRE(unzGetCurrentFileInfo64(zip, &info, name, sizeof name, nullptr, 0, nullptr, 0) == UNZ_OK);
    std::string content(info.uncompressed_size, '\0');
    REQUIRE(unzOpenCurrentFile(zip) == UNZ_OK);
    if (!content.empty()) CHECK(unzReadCurrentFile(zip, content.data(), static_cast<unsigned>(content.size())) == static_cast<int>(content.size()));
    CHECK(unzCloseCurrentFile(zip) == UNZ_OK);  // checks the CRC
    out[name] = content;
  }
  unzClose(zip);
  std::filesystem::remove_all(path.parent_path());
  return out;
}

}  // namespace

TEST_CASE("fmu export: the archive holds the description, the binary for linux64 and the source it compiles") {
  const std::string source = test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/bushing_d.rheo");
  const auto model = test::model_from(source, "bushing_d");
  const auto files = unzipped(runtime::exporter::fmu_archive(model, {"bushing_d.rheo", source, "1.2.3"}));
  for (const char* name : {"modelDescription.xml", "binaries/linux64/bushing_d.so", "resources/model.rheo", "resources/model_name.txt",
                           "documentation/licenses/fmi2-headers.txt", "documentation/licenses/fmi3-headers.txt"})
    CHECK_MESSAGE(files.count(name) == 1, name);
  CHECK(files.size() == 11);  // with the folders binaries/, binaries/linux64/, resources/, documentation/, documentation/licenses/
  CHECK(files.at("binaries/linux64/bushing_d.so") == runtime::exporter::fmu_binary());
  CHECK(files.at("resources/model.rheo") == source);
  CHECK(files.at("resources/model_name.txt") == "bushing_d\n");
  const std::string& xml = files.at("modelDescription.xml");
  CHECK(xml.find(fmt::format("guid=\"{}\"", runtime::fmu::fmu_guid("1.2.3", "bushing_d", source))) != std::string::npos);
  CHECK(xml.find("modelIdentifier=\"bushing_d\"") != std::string::npos);
  CHECK(xml.find("generationTool=\"rheo 1.2.3\"") != std::string::npos);
}

TEST_CASE("fmu export: an FMI 3.0 archive holds the FMI 3.0 description and the same binary, for x86_64-linux") {
  const std::string source = test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/bushing_d.rheo");
  const auto model = test::model_from(source, "bushing_d");
  const auto files = unzipped(runtime::exporter::fmu_archive(model, {"bushing_d.rheo", source, "1.2.3", runtime::fmu::FmiVersion::fmi3}));
  for (const char* name : {"modelDescription.xml", "binaries/x86_64-linux/bushing_d.so", "resources/model.rheo", "resources/model_name.txt",
                           "documentation/licenses/fmi2-headers.txt", "documentation/licenses/fmi3-headers.txt"})
    CHECK_MESSAGE(files.count(name) == 1, name);
  CHECK(files.count("binaries/linux64/bushing_d.so") == 0);
  CHECK(files.at("binaries/x86_64-linux/bushing_d.so") == runtime::exporter::fmu_binary());
  const std::string& xml = files.at("modelDescription.xml");
  CHECK(xml.find("fmiVersion=\"3.0\"") != std::string::npos);
  CHECK(xml.find(fmt::format("instantiationToken=\"{}\"", runtime::fmu::fmu_guid("1.2.3", "bushing_d", source))) != std::string::npos);
  CHECK(files.at("documentation/licenses/fmi3-headers.txt").find("FMI 3.0 header files fmi3Functions.h") != std::string::npos);
  CHECK(files.at("documentation/licenses/fmi3-headers.txt").find("2012-2023 Modelica Association Project") != std::string::npos);
}

TEST_CASE("fmu export: the embedded binary is the shared library this build made") {
  std::ifstream in(RHEO_FMU_BINARY_PATH, std::ios::binary);
  const std::string built((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(built.size() > 100000);
  CHECK(runtime::exporter::fmu_binary() == built);
  CHECK(built.compare(0, 4,
                      "\x7f"
                      "ELF") == 0);
}

TEST_CASE("fmu export: an inerter driven directly by the input is refused, naming it and its line:col") {
  const auto network = test::network_from("model m {\n  spring s (k = 10 N/mm)\n  inerter mass (b = 1 kg)\n}", "m");
  CHECK_THROWS_WITH_AS(runtime::exporter::check_fmu_steppable(network),
                       doctest::Contains("test.rheo:3:3: error: model 'm' cannot be exported as an FMU: inerter 'mass'"), ModelError);
}

TEST_CASE("fmu export: blocks nested deeper than the fixed-step kernels take are refused, naming the deepest element") {
  const auto network = test::network_from(
      "model m {\n  series a {\n    spring s1 (k = 10)\n    parallel b {\n      spring s2 (k = 10)\n      series c {\n        spring s3 (k = 10)\n"
      "        parallel d {\n          dashpot d1 (c = 1)\n          maxwell m1 (k = 5, tau = 1 ms)\n        }\n      }\n    }\n  }\n}",
      "m");
  CHECK_THROWS_WITH_AS(runtime::exporter::check_fmu_steppable(network), doctest::Contains("test.rheo:9:11: error: model 'm' cannot be exported"),
                       ModelError);
  CHECK_THROWS_WITH_AS(runtime::exporter::check_fmu_steppable(network), doctest::Contains("sits 4 series and parallel blocks deep"), ModelError);
  // Three levels (the hydrobushing's fluid branch has two) are stepped.
  CHECK_NOTHROW(runtime::exporter::check_fmu_steppable(
      test::network_from(test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo"), "hydrobushing")));
}

}  // namespace fmu_export_test
