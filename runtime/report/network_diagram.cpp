#include "runtime/report/network_diagram.hpp"

#include "runtime/report/element_symbols.hpp"
#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace rheo::runtime::report {
namespace {

using lang::Element;
using lang::ElementKind;

constexpr double kLeafHeight = 62, kLeafPort = 22, kLeafMinWidth = 96, kLeafMargin = 12;
constexpr double kBus = 14, kStackGap = 8, kFrame = 5, kFrameLabel = 14, kTerminal = 48;

bool is_block(const Element& e) { return e.kind == ElementKind::parallel || e.kind == ElementKind::series; }

// Size of an element's drawing; `port` is the height of its wire from the top.
struct Box {
  double width = 0, height = 0, port = 0;
  std::vector<Box> children;
};

Box measure(const Element& e, bool root) {
  Box box;
  if (!is_block(e)) {
    box.width = std::max(kLeafMinWidth, symbol_length(e.kind) + 2 * kLeafMargin);
    box.height = kLeafHeight;
    box.port = kLeafPort;
    return box;
  }
  for (const Element& child : e.children) box.children.push_back(measure(child, false));
  const double frame = root ? 0.0 : kFrame;
  const double label = root ? 0.0 : kFrameLabel;
  if (e.kind == ElementKind::series) {
    for (const Box& c : box.children) box.port = std::max(box.port, c.port), box.width += c.width;
    for (const Box& c : box.children) box.height = std::max(box.height, box.port - c.port + c.height);
  } else {
    for (const Box& c : box.children) box.width = std::max(box.width, c.width), box.height += c.height;
    box.width += 2 * kBus;
    box.height += kStackGap * static_cast<double>(std::max<std::size_t>(box.children.size(), 1) - 1);
    if (!box.children.empty()) {
      const double last_top = box.height - box.children.back().height;
      box.port = (box.children.front().port + last_top + box.children.back().port) / 2;
    }
  }
  box.width += 2 * frame;
  box.height += 2 * frame + label;
  box.port += frame + label;
  return box;
}

std::string wire(double x1, double x2, double y) {
  return x2 > x1 ? fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>", coordinate(x1), coordinate(y), coordinate(x2), coordinate(y)) : "";
}

std::string draw(const Element& e, const Box& box, double x, double y, bool root);

std::string draw_leaf(const Element& e, const Box& box, double x, double y) {
  const double length = symbol_length(e.kind);
  const double start = x + (box.width - length) / 2, cy = y + box.port;
  std::string out = fmt::format("<g class=\"element\" data-kind=\"{}\" data-path=\"{}\"><title>{}: {}</title>", lang::kind_word(e.kind),
                                escape(e.path), escape(e.path), lang::kind_word(e.kind));
  out += wire(x, start, cy) + symbol_svg(e.kind, start, cy) + wire(start + length, x + box.width, cy);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" stroke=\"none\" fill=\"#111\" font-weight=\"bold\">{}</text>",
                     coordinate(x + box.width / 2), coordinate(y + 44), escape(e.name));
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" stroke=\"none\" fill=\"#555\" font-size=\"11\">{}</text></g>\n",
                     coordinate(x + box.width / 2), coordinate(y + 57), lang::kind_word(e.kind));
  return out;
}

std::string draw_block(const Element& e, const Box& box, double x, double y, bool root) {
  std::string out;
  const double inset = root ? 0.0 : kFrame, label = root ? 0.0 : kFrameLabel;
  if (!root) {
    out += fmt::format("<g class=\"block\" data-kind=\"{}\" data-path=\"{}\"><title>{}: {}</title>", lang::kind_word(e.kind), escape(e.path),
                       escape(e.path), lang::kind_word(e.kind));
    out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"6\" fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 3\"/>",
                       coordinate(x + 1), coordinate(y + 1), coordinate(box.width - 2), coordinate(box.height - 2));
    out += fmt::format("<text x=\"{}\" y=\"{}\" stroke=\"none\" fill=\"#555\" font-size=\"11\">{} ({})</text>\n", coordinate(x + 8),
                       coordinate(y + 13), escape(e.name), lang::kind_word(e.kind));
  }
  const double inner_x = x + inset, inner_y = y + inset + label, inner_w = box.width - 2 * inset;
  const double cy = y + box.port;
  if (e.kind == ElementKind::series) {
    double cx = inner_x;
    for (std::size_t i = 0; i < e.children.size(); ++i) {
      const Box& c = box.children[i];
      out += draw(e.children[i], c, cx, cy - c.port, false);
      cx += c.width;
    }
    out += wire(x, inner_x, cy) + wire(cx, x + box.width, cy);
  } else {
    double cy_child = inner_y, first = cy, last = cy;
    const double left = inner_x + kBus, width = inner_w - 2 * kBus;
    for (std::size_t i = 0; i < e.children.size(); ++i) {
      const Box& c = box.children[i];
      const double port = cy_child + c.port;
      if (i == 0) first = port;
      last = port;
      out += draw(e.children[i], c, left + (width - c.width) / 2, cy_child, false);
      out += wire(inner_x, left + (width - c.width) / 2, port) + wire(left + (width + c.width) / 2, inner_x + inner_w, port);
      cy_child += c.height + kStackGap;
    }
    out += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke-width=\"2.5\"/>", coordinate(inner_x), coordinate(first),
                       coordinate(last));
    out += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke-width=\"2.5\"/>", coordinate(inner_x + inner_w), coordinate(first),
                       coordinate(last));
    out += wire(x, inner_x, cy) + wire(inner_x + inner_w, x + box.width, cy);
  }
  if (!root) out += "</g>\n";
  return out;
}

std::string draw(const Element& e, const Box& box, double x, double y, bool root) {
  return is_block(e) ? draw_block(e, box, x, y, root) : draw_leaf(e, box, x, y);
}

}  // namespace

std::string network_diagram_svg(const Element& root, const std::string& title, bool standalone) {
  const Box box = measure(root, true);
  const double margin = 10;
  const double width = box.width + 2 * kTerminal + 2 * margin, height = box.height + 2 * margin + 8;
  const double x = margin + kTerminal, y = margin + 8, cy = y + box.port;
  std::string out = svg_open(width, height, standalone, title);
  out += fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"#fff\"/>\n", coordinate(width), coordinate(height));
  out += "<g stroke=\"#111\" color=\"#111\" stroke-width=\"1.5\" fill=\"none\">\n";
  out += draw(root, box, x, y, true);
  // Ground: a wall with hatching on the left; drive: an arrow with u(t) on the right.
  out += wire(x - kTerminal + 14, x, cy);
  out += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke-width=\"2.5\"/>", coordinate(x - kTerminal + 14),
                     coordinate(cy - 14), coordinate(cy + 14));
  for (int i = 0; i < 5; ++i)
    out += fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>", coordinate(x - kTerminal + 14), coordinate(cy - 12 + 6 * i),
                       coordinate(x - kTerminal + 7), coordinate(cy - 6 + 6 * i));
  const double right = x + box.width;
  out += wire(right, right + kTerminal - 14, cy);
  out += fmt::format("<path d=\"M{} {}l-8 -4v8z\" fill=\"#111\"/>", coordinate(right + kTerminal - 10), coordinate(cy));
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" stroke=\"none\" fill=\"#111\">u(t)</text>\n", coordinate(right + kTerminal - 8),
                     coordinate(cy - 10));
  return out + "</g>\n</svg>\n";
}

}  // namespace rheo::runtime::report
