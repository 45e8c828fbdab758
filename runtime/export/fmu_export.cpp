#include "runtime/export/fmu_export.hpp"

#include "runtime/core/errors.hpp"
#include "runtime/export/fmu_archive.hpp"
#include "runtime/export/fmu_binary.hpp"
#include "runtime/export/fmu_model_description.hpp"
#include "runtime/fmu/fmu_resources.hpp"
#include "runtime/fmu/fmu_variables.hpp"
#include "runtime/protocols/solver_choice.hpp"

#include <fmt/format.h>


namespace rheo::runtime::exporter {
namespace {

const lang::Element* find_element(const lang::Element& e, const std::string& path) {
  if (e.path == path) return &e;
  for (const auto& child : e.children)
    if (const lang::Element* found = find_element(child, path)) return found;
  return nullptr;
}

// The element the user wrote that subtree node INDEX stands for, or nullptr (a block).
const lang::Element* element_of(const Network& network, int index) {
  using Source = ElementProbe::Source;
  for (const auto& p : network.topology().probes)
    if (p.index == index && (p.source == Source::tree_node || p.source == Source::tree_maxwell_spring || p.source == Source::tree_maxwell_dashpot))
      return find_element(network.model().root, p.path);
  return nullptr;
}

// "FILE:LINE:COL: error: model 'M' cannot be exported as an FMU: KIND 'PATH'" for E (or the model).
std::string refusal(const Network& network, const lang::Element* e) {
  const lang::CheckedModel& m = network.model();
  return fmt::format("{}model '{}' cannot be exported as an FMU: {}", error_at(e ? e->where : m.where), m.name,
                     e ? fmt::format("{} '{}'", lang::kind_word(e->kind), e->path) : std::string("an element"));
}

// The deepest-nested leaf below NODE: {levels of blocks above it, its node index}.
std::pair<int, int> deepest_leaf(const Topology& t, int node) {
  const TreeNode& n = t.nodes[static_cast<std::size_t>(node)];
  std::pair<int, int> best{0, node};
  for (int i = 0; i < n.child_count; ++i) {
    const auto [levels, leaf] = deepest_leaf(t, t.children[static_cast<std::size_t>(n.first_child + i)]);
    if (levels + 1 > best.first) best = {levels + 1, leaf};
  }
  return best;
}

}  // namespace

void check_fmu_steppable(const Network& network) {
  const Topology& t = network.topology();
  for (std::size_t i = 0; i < t.nodes.size(); ++i)
    if (t.nodes[i].drive_prescribed)
      throw ModelError(
          fmt::format("{} sits in the model's body, driven directly by the input u: its force b d2u/dt2 is impulsive at every communication point "
                      "of a held or ramped input, and rheo simulates it with SUNDIALS IDA, which an FMU does not carry; put a compliant member in "
                      "series with it (as the hydrobushing's fluid column: spring k1 and inerter b in a series block of their own)",
                      refusal(network, element_of(network, static_cast<int>(i)))));
  for (int root : t.subtrees) {
    const auto [levels, leaf] = deepest_leaf(t, root);
    if (levels <= kFixedStepMaxBlockDepth) continue;
    throw ModelError(
        fmt::format("{} sits {} series and parallel blocks deep: the fixed-step kernels an FMU runs solve one Newton iteration per level (a "
                    "step's cost grows geometrically with the depth), so rheo simulates such networks with SUNDIALS IDA, which an FMU does not "
                    "carry; flatten the network to at most {} levels of alternating blocks",
                    refusal(network, element_of(network, leaf)), levels, kFixedStepMaxBlockDepth));
  }
}

std::string fmu_archive(const lang::CheckedModel& model, const FmuSource& source) {
  check_fmu_steppable(Network::compile(model));
  FmuDescription d;
  d.model_identifier = model.name;
  d.guid = fmu::fmu_guid(source.rheo_version, model.name, source.text);
  d.rheo_version = source.rheo_version;
  d.source_name = source.file_name;
  d.source = source.text;
  const std::string description = fmi2_model_description(model, d);
  const std::string model_name = model.name + "\n";
  static constexpr std::string_view kFmiHeadersNotice =
      "The binary in binaries/ is built with the FMI 2.0 header files fmi2Functions.h, fmi2FunctionTypes.h and\n"
      "fmi2TypesPlatform.h:\n\n"
      "Copyright (C) 2008-2011 MODELISAR consortium,\n"
      "              2012-2019 Modelica Association Project \"FMI\"\n"
      "              All rights reserved.\n\n"
      "Redistribution and use in source and binary forms, with or without modification, are permitted provided that the\n"
      "following conditions are met:\n\n"
      "- Redistributions of source code must retain the above copyright notice, this list of conditions and the following\n"
      "  disclaimer.\n\n"
      "- Redistributions in binary form must reproduce the above copyright notice, this list of conditions and the following\n"
      "  disclaimer in the documentation and/or other materials provided with the distribution.\n\n"
      "THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS \"AS IS\" AND ANY EXPRESS OR IMPLIED WARRANTIES,\n"
      "INCLUDING, BUT NOT LIMITED TO, THE IMPLIED WARRANTIES OF MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE\n"
      "DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL,\n"
      "SPECIAL, EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF SUBSTITUTE GOODS OR\n"
      "SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION) HOWEVER CAUSED AND ON ANY THEORY OF LIABILITY,\n"
      "WHETHER IN CONTRACT, STRICT LIABILITY, OR TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE\n"
      "OF THIS SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.\n";
  const std::string binary_name = fmt::format("binaries/{}/{}.so", kFmuPlatform, model.name);
  const std::string platform_folder = fmt::format("binaries/{}/", kFmuPlatform);
  return zip_archive({
      {"modelDescription.xml", description},
      {"binaries/", {}},
      {platform_folder, {}},
      {binary_name, fmu_binary()},
      {"resources/", {}},
      {std::string("resources/") + fmu::kSourceResource, source.text},
      {std::string("resources/") + fmu::kModelNameResource, model_name},
      {"documentation/", {}},
      {"documentation/licenses/", {}},
      {"documentation/licenses/fmi2-headers.txt", kFmiHeadersNotice},
  });
}

}  // namespace rheo::runtime::exporter
