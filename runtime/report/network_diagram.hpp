// The network of a model drawn as a diagram: series chains left to right, parallel blocks
// stacked between two bus bars, one symbol per leaf (element_symbols.hpp) labelled with its
// name and kind, nested blocks framed by a dashed box named after the block. The drive
// (u(t), right) and ground (left) are the terminals. Every leaf is
// <g class="element" data-kind="KIND" data-path="PATH">, every block below the root
// <g class="block" data-kind="series|parallel" data-path="PATH">, so that the drawing can be
// checked against the model.
#pragma once

#include "lang/model.hpp"

#include <string>

namespace rheo::runtime::report {

// `root`: a model's element tree (CheckedModel::root); `title` names the figure.
std::string network_diagram_svg(const lang::Element& root, const std::string& title, bool standalone);

}  // namespace rheo::runtime::report
