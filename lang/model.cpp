#include "lang/model.hpp"

namespace rheo::lang {

const char* kind_word(ElementKind kind) {
  switch (kind) {
    case ElementKind::spring: return "spring";
    case ElementKind::yeoh: return "yeoh";
    case ElementKind::dashpot: return "dashpot";
    case ElementKind::maxwell: return "maxwell";
    case ElementKind::friction: return "friction";
    case ElementKind::slider: return "slider";
    case ElementKind::inerter: return "inerter";
    case ElementKind::quadratic_dashpot: return "quadratic_dashpot";
    case ElementKind::gap: return "gap";
    case ElementKind::bouc_wen: return "bouc_wen";
    case ElementKind::poly_spring: return "poly_spring";
    case ElementKind::springpot: return "springpot";
    case ElementKind::parallel: return "parallel";
    case ElementKind::series: return "series";
  }
  return "element";
}

double Expression::evaluate(const std::vector<double>& parameter_values) const {
  std::vector<double> stack;
  stack.reserve(code.size());
  auto pop = [&] {
    double v = stack.back();
    stack.pop_back();
    return v;
  };
  for (const auto& i : code) {
    switch (i.op) {
      case Op::constant: stack.push_back(i.constant); break;
      case Op::parameter: stack.push_back(parameter_values.at(static_cast<std::size_t>(i.parameter))); break;
      case Op::negate: stack.back() = -stack.back(); break;
      default: {
        double rhs = pop();
        double lhs = pop();
        if (i.op == Op::add) stack.push_back(lhs + rhs);
        else if (i.op == Op::subtract) stack.push_back(lhs - rhs);
        else if (i.op == Op::multiply) stack.push_back(lhs * rhs);
        else stack.push_back(lhs / rhs);  // IEEE: x/0 = +-inf
      }
    }
  }
  return stack.empty() ? 0.0 : stack.back();
}

bool Expression::is_constant() const {
  for (const auto& i : code)
    if (i.op == Op::parameter) return false;
  return true;
}

std::vector<int> default_free_parameters(const CheckedModel& model) {
  std::vector<int> out;
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    if (model.parameters[i].free) out.push_back(static_cast<int>(i));
  return out;
}

const CheckedModel* Program::find_model(const std::string& name) const {
  for (const auto& m : models)
    if (m.name == name) return &m;
  return nullptr;
}

}  // namespace rheo::lang
