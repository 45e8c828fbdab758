#include "cli/fe_export.hpp"

#include "lang/text_encoding.hpp"
#include "lang/names.hpp"
#include "lang/units.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/export/abaqus_cards.hpp"
#include "runtime/export/ansys_cards.hpp"
#include "runtime/export/prony_cards.hpp"
#include "runtime/io/output.hpp"
#include "runtime/network/network.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <optional>

namespace rheo::cli {
namespace {

using runtime::UsageError;
namespace fe = runtime::fe;

// A quantity given on the command line, "314 mm^2" or "10mm", in internal units; its unit is
// required and of DIMENSION.
double quantity_option(const std::string& option, const std::string& text, const lang::Dimension& dimension, const char* example) {
  const std::string_view s = text;
  const std::size_t begin = s.find_first_not_of(' ');
  double number = 0.0;
  const char* first = s.data() + (begin == std::string_view::npos ? s.size() : begin);
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), number);
  std::string_view unit_text = std::string_view(end, static_cast<std::size_t>(s.data() + s.size() - end));
  while (!unit_text.empty() && unit_text.front() == ' ') unit_text.remove_prefix(1);
  while (!unit_text.empty() && unit_text.back() == ' ') unit_text.remove_suffix(1);
  const auto unit = lang::parse_unit(unit_text);
  const auto advice = [&] { return fmt::format("give {} with its unit, e.g. {} '{}'", lang::with_article(dimension), option, example); };
  if (ec != std::errc{}) throw UsageError(fmt::format("{} '{}': expected a number; {}", option, lang::printable(text), advice()));
  if (unit_text.empty()) throw UsageError(fmt::format("{} '{}' has no unit; {}", option, lang::printable(text), advice()));
  if (!unit) throw UsageError(fmt::format("{} '{}': unknown unit '{}'; {}", option, lang::printable(text), lang::printable(unit_text), advice()));
  if (!(unit->dimension == dimension))
    throw UsageError(fmt::format("{} '{}' is {}, not {}; {}", option, lang::printable(text), lang::with_article(unit->dimension),
                                 lang::with_article(dimension), advice()));
  const double value = number * unit->scale;
  if (!(value > 0.0 && std::isfinite(value))) throw UsageError(fmt::format("{} '{}' must be positive and finite", option, lang::printable(text)));
  return value;
}

// The specimen geometry: --area and --height, else the data lines of MODEL's fit blocks that
// give both (they must agree), else none.
std::optional<fe::Geometry> geometry(const lang::Program& program, const lang::CheckedModel& model, const FeExportOptions& o) {
  if (o.no_geometry) return std::nullopt;
  if (!o.area.empty())
    return fe::Geometry{quantity_option("--area", o.area, lang::dim::area, "314 mm^2"),
                        quantity_option("--height", o.height, lang::dim::length, "10 mm"), "--area and --height"};
  std::optional<fe::Geometry> found;
  for (const auto& fit : program.fits) {
    if (fit.model != model.name) continue;
    for (const auto& data : fit.data) {
      if (!data.area || !data.height) continue;
      const std::string where = fmt::format("{}:{}:{}", data.where.file, data.where.line, data.where.column);
      if (!found) {
        found = fe::Geometry{*data.area, *data.height, fmt::format("the data line at {}", where)};
      } else if (found->area != *data.area || found->height != *data.height) {
        throw UsageError(
            fmt::format("the data lines of model '{}' give two specimen geometries: area {:g} mm^2, height {:g} mm ({}) and "
                        "area {:g} mm^2, height {:g} mm ({}); choose one with --area and --height, or --no-geometry",
                        model.name, found->area, found->height, found->source, *data.area, *data.height, where));
      }
    }
  }
  return found;
}

fe::MaterialMapping mapping(const FeExportOptions& o) {
  return {o.modulus == "shear" ? fe::ModulusKind::shear : fe::ModulusKind::young, o.poisson};
}

}  // namespace

void add_fe_export_options(CLI::App& app, FeExportOptions& o) {
  app.add_option("--abaqus", o.abaqus, "Write an Abaqus material (*ELASTIC, *VISCOELASTIC, TIME=PRONY) to this .inp file ('-': standard output)");
  app.add_option("--ansys", o.ansys, "Write ANSYS APDL material commands (MP, TB,PRONY) to this .mac file ('-': standard output)");
  app.add_option("--area", o.area,
                 "The specimen's loaded area, e.g. '314 mm^2': cards in moduli (with --height); default: the fit block's data line");
  app.add_option("--height", o.height, "The specimen's height (gap, thickness), e.g. '10 mm' (with --area)");
  app.add_flag("--no-geometry", o.no_geometry,
               "Cards in the model's stiffness (N/mm read as MPa, a unit cube) even when a data line gives a geometry");
  app.add_option("--modulus", o.modulus, "young | shear: what the 1-D modulus is in the 3-D material (default young)")
      ->check(CLI::IsMember({"young", "shear"}));
  app.add_option("--poisson", o.poisson, "Poisson's ratio of the material, 0 to 0.5 (not in a 1-D model; default 0.49)")
      ->check(CLI::Range(0.0, 0.4999999));
  app.add_option("--leave-out", o.leave_out,
                 "Leave out this branch of the model's parallel block (an element with no FE counterpart, e.g. a friction element); "
                 "repeatable; the file's header lists it");
}

void check_fe_export_options(const FeExportOptions& o) {
  if (o.area.empty() != o.height.empty())
    throw UsageError(fmt::format("{} needs {} too: the specimen geometry is both, e.g. --area '314 mm^2' --height '10 mm'",
                                 o.area.empty() ? "--height" : "--area", o.area.empty() ? "--area" : "--height"));
  if (o.no_geometry && !o.area.empty()) throw UsageError("--no-geometry and --area/--height contradict each other; give one");
  if (!o.area.empty()) {
    quantity_option("--area", o.area, lang::dim::area, "314 mm^2");
    quantity_option("--height", o.height, lang::dim::length, "10 mm");
  }
  if (!o.abaqus.empty() && o.abaqus == o.ansys && o.abaqus != "-") throw UsageError("--abaqus and --ansys name the same file; give each its own");
  runtime::check_output_destination(o.abaqus);
  runtime::check_output_destination(o.ansys);
}

int run_fe_export(const std::string& file, const lang::Program& program, const lang::CheckedModel& model, const FeExportOptions& o) {
  const runtime::Network network = runtime::Network::compile(model);
  const fe::PronyCards cards = fe::prony_cards(network, geometry(program, model, o), o.leave_out);
  const fe::CardSource source{file, RHEO_VERSION};
  // Every text first: a model ANSYS cannot take leaves no Abaqus file behind either.
  const std::string abaqus = o.abaqus.empty() ? "" : fe::abaqus_material(cards, mapping(o), source);
  const std::string ansys = o.ansys.empty() ? "" : fe::ansys_material(cards, mapping(o), source);
  if (!o.abaqus.empty()) runtime::write_output(o.abaqus, abaqus);
  if (!o.ansys.empty()) runtime::write_output(o.ansys, ansys);
  const std::string units = cards.geometry ? "MPa" : "N/mm read as MPa";
  for (const auto& b : cards.left_out)
    std::cerr << fmt::format("rheo: left out {} '{}' ({}:{}:{}): the cards lack its force\n", lang::kind_word(b.kind), b.path, b.where.file,
                             b.where.line, b.where.column);
  for (const std::string& out : {o.abaqus, o.ansys})
    if (!out.empty() && out != "-")
      std::cerr << fmt::format("rheo: model {}: {} Prony term(s), M_0 = {:g} {}, M_inf = {:g} {}, written to {}\n", model.name, cards.terms.size(),
                               cards.instantaneous, units, cards.long_term, units, out);
  return runtime::exit_code::ok;
}

}  // namespace rheo::cli
