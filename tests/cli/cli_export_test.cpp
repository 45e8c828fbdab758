// `rheo export --fmu` from the command line: what it writes, and the bad input of #27: a model
// that cannot be exported (element, line:col), an unwritable destination caught before any work,
// no partial .fmu after a failure, and the FMI version chosen with --fmi (docs/errors.md).
#include "cli_support.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace cli_export_test {

namespace fs = std::filesystem;

namespace {

// The names in DIR (its temporary files included), sorted.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("rheo export --fmu: writes the FMU of the file's model and says so") {
  const auto dir = rheo::test::scratch_directory("export-ok");
  const auto out = dir / "bushing_d.fmu";
  const auto r = rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo --fmu {}", RHEO_EXAMPLES_DIR, out.string()));
  CHECK(r.code == 0);
  CHECK(r.err.find("rheo: FMU of model bushing_d (FMI 2.0 co-simulation, 12 parameters) written to") != std::string::npos);
  std::ifstream in(out, std::ios::binary);
  std::string head(4, '\0');
  in.read(head.data(), 4);
  CHECK(head == std::string("PK\x03\x04", 4));  // a ZIP archive
  CHECK(fs::file_size(out) > 100000);
  CHECK(listing(dir) == std::vector<std::string>{"bushing_d.fmu"});
  fs::remove_all(dir);
}

TEST_CASE("rheo export --fmu --fmi 3: writes an FMI 3.0 FMU, its binary under binaries/x86_64-linux") {
  const auto dir = rheo::test::scratch_directory("export-fmi3");
  const auto out = dir / "bushing_d.fmu";
  const auto r = rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo --fmu {} --fmi 3", RHEO_EXAMPLES_DIR, out.string()));
  CHECK(r.code == 0);
  CHECK(r.err.find("rheo: FMU of model bushing_d (FMI 3.0 co-simulation, 12 parameters) written to") != std::string::npos);
  std::ifstream in(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(bytes.compare(0, 4, std::string("PK\x03\x04", 4)) == 0);
  // ZIP entry names are stored as they are: the FMI 3.0 platform folder, and no FMI 2.0 one.
  CHECK(bytes.find("binaries/x86_64-linux/bushing_d.so") != std::string::npos);
  CHECK(bytes.find("binaries/linux64/") == std::string::npos);
  CHECK(listing(dir) == std::vector<std::string>{"bushing_d.fmu"});
  fs::remove_all(dir);
}

TEST_CASE("rheo export --fmu: a model the fixed-step kernels cannot step is refused with its element and line:col, leaving nothing") {
  const auto dir = rheo::test::scratch_directory("export-refused");
  std::ofstream(dir / "mass.rheo") << "model m {\n  spring s (k = 10 N/mm)\n  inerter mass (b = 1 kg)\n}\n";
  const auto r = rheo::test::run_rheo(fmt::format("export {} --fmu {}", (dir / "mass.rheo").string(), (dir / "m.fmu").string()));
  CHECK(r.code == 3);
  CHECK(r.err.find("mass.rheo:3:3: error: model 'm' cannot be exported as an FMU: inerter 'mass' sits in the model's body") != std::string::npos);
  CHECK(listing(dir) == std::vector<std::string>{"mass.rheo"});  // no .fmu, no temporary file
  fs::remove_all(dir);
}

TEST_CASE("rheo export --fmu: an unwritable destination is caught before the model is read") {
  const auto dir = rheo::test::scratch_directory("export-destination");
  // The model file does not exist either: the destination is checked first.
  const auto r = rheo::test::run_rheo(fmt::format("export {} --fmu {}", (dir / "missing.rheo").string(), (dir / "no/such/dir/x.fmu").string()));
  CHECK(r.code == 4);
  CHECK(r.err.find("no/such/dir/x.fmu") != std::string::npos);
  CHECK(r.err.find("missing.rheo") == std::string::npos);
  const auto existing = rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo --fmu {}", RHEO_EXAMPLES_DIR, dir.string()));  // a directory
  CHECK(existing.code == 4);
  // A folder that exists but takes no new file (as root too: /proc creates none).
  const auto read_only = rheo::test::run_rheo(fmt::format("export {} --fmu /proc/x.fmu", (dir / "missing.rheo").string()));
  CHECK(read_only.code == 4);
  CHECK(read_only.err.find("/proc/x.fmu: error: cannot create a file in /proc") != std::string::npos);
  CHECK(listing(dir).empty());
  fs::remove_all(dir);
}

TEST_CASE("rheo export: usage errors: FMI versions other than 2 and 3, no output, several models") {
  const auto dir = rheo::test::scratch_directory("export-usage");
  const std::string d = RHEO_EXAMPLES_DIR;
  CHECK(rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo --fmu {}/x.fmu --fmi 1", d, dir.string())).code == 2);
  CHECK(rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo --fmu {}/x.fmu --fmi 4", d, dir.string())).code == 2);
  const auto none = rheo::test::run_rheo(fmt::format("export {}/bushing_d.rheo", d));
  CHECK(none.code == 2);
  CHECK(none.err.find("--fmu OUT.fmu") != std::string::npos);
  std::ofstream(dir / "two.rheo") << "model a { spring s (k = 1) }\nmodel b { spring s (k = 2) }\n";
  const auto two = rheo::test::run_rheo(fmt::format("export {}/two.rheo --fmu {}/x.fmu", dir.string(), dir.string()));
  CHECK(two.code == 2);
  CHECK(two.err.find("--model") != std::string::npos);
  CHECK(rheo::test::run_rheo(fmt::format("export {}/two.rheo --fmu {}/b.fmu --model b", dir.string(), dir.string())).code == 0);
  CHECK(listing(dir) == std::vector<std::string>{"b.fmu", "two.rheo"});
  fs::remove_all(dir);
}

}  // namespace cli_export_test
