// How the FMU binary finds its resources from a host's URI, and refuses resources that are not
// the ones its description was made for.
#include "runtime/fmu/fmu_resources.hpp"

#include "cli_support.hpp"
#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace fmu_resources_test {

using namespace rheo;
using runtime::fmu::resource_folder;

TEST_CASE("fmu resources: file URIs of every form name the local folder, percent-decoded") {
  CHECK(resource_folder("file:///tmp/x/resources/") == "/tmp/x/resources/");
  CHECK(resource_folder("file:/tmp/x/resources") == "/tmp/x/resources");
  CHECK(resource_folder("file://localhost/tmp/a%20b/resources/") == "/tmp/a b/resources/");
  CHECK(resource_folder("file:///tmp/%C3%A4") == "/tmp/\xC3\xA4");
  CHECK_THROWS_AS(resource_folder("http://example.org/resources/"), UsageError);
  CHECK_THROWS_AS(resource_folder("file://server/share/resources/"), UsageError);
  CHECK_THROWS_AS(resource_folder("file:///tmp/a%2"), UsageError);
  CHECK_THROWS_AS(resource_folder("file:///tmp/a%zz/"), UsageError);
  CHECK_THROWS_AS(resource_folder("file://"), UsageError);
}

TEST_CASE("fmu resources: the model loads when the GUID is the resources' own, and is refused otherwise") {
  const auto dir = test::scratch_directory("fmu-resources");
  const std::string source = "model a { spring s (k = 2 N/mm) }\nmodel b { spring s (k = 3 N/mm) }\n";
  std::ofstream(dir / runtime::fmu::kSourceResource) << source;
  std::ofstream(dir / runtime::fmu::kModelNameResource) << "b\n";
  const std::string guid = runtime::fmu::fmu_guid("9.9.9", "b", source);
  const auto c = runtime::fmu::load_cosimulation(dir.string(), guid, "9.9.9");
  CHECK(c->model().name == "b");
  CHECK(c->get_real(runtime::fmu::kFirstParameter) == 3.0);
  CHECK_THROWS_WITH_AS(runtime::fmu::load_cosimulation(dir.string(), guid, "9.9.8"), doctest::Contains("were changed or come from another FMU"),
                       UsageError);
  std::filesystem::remove(dir / runtime::fmu::kModelNameResource);
  CHECK_THROWS_WITH_AS(runtime::fmu::load_cosimulation(dir.string(), guid, "9.9.9"), doctest::Contains("model_name.txt"), DataError);
  std::filesystem::remove_all(dir);
}

}  // namespace fmu_resources_test
