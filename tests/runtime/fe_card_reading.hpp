// Reading the Abaqus and ANSYS material cards of `rheo export` back, as those codes read them,
// and the complex modulus their Prony series defines: a second path to the model's storage and
// loss that shares no code with the writers (runtime/export/).
#pragma once

#include <complex>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rheo::test {

struct ReadPronyTerm {
  double shear, bulk, tau;  // g_i (alpha_i shear), k_i (alpha_i bulk) [-], tau_i [s]
};

struct ReadMaterial {
  double young = 0.0;                 // E_0 [MPa], the instantaneous Young's modulus
  double poisson = 0.0;               // nu [-]
  bool instantaneous_moduli = false;  // Abaqus: *ELASTIC, MODULI=INSTANTANEOUS
  std::vector<ReadPronyTerm> terms;
};

inline std::vector<std::string> card_fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string field; std::getline(s, field, ',');) out.push_back(field);
  return out;
}

// strtod, refusing anything but a whole number field (spaces around allowed).
inline double card_value(const std::string& field) {
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  while (*end == ' ') ++end;
  if (end == field.c_str() || *end != '\0') throw std::runtime_error("not a number: '" + field + "'");
  return v;
}

// *ELASTIC's data line, then every *VISCOELASTIC data line; "**" lines are comments.
inline ReadMaterial read_abaqus(const std::string& text) {
  ReadMaterial m;
  std::stringstream in(text);
  std::string keyword;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("**")) continue;
    if (line.starts_with("*")) {
      keyword = line;
      if (line.starts_with("*ELASTIC")) m.instantaneous_moduli = line.find("MODULI=INSTANTANEOUS") != std::string::npos;
      continue;
    }
    const auto f = card_fields(line);
    if (keyword.starts_with("*ELASTIC")) {
      m.young = card_value(f.at(0));
      m.poisson = card_value(f.at(1));
    } else if (keyword == "*VISCOELASTIC, TIME=PRONY") {
      m.terms.push_back({card_value(f.at(0)), card_value(f.at(1)), card_value(f.at(2))});
    }
  }
  return m;
}

// MP,EX and MP,PRXY; TB,PRONY,...,SHEAR and ...,BULK tables of TBDATA,STLOC,a,tau,...; "!" starts a comment.
inline ReadMaterial read_ansys(const std::string& text) {
  ReadMaterial m;
  std::vector<double> shear, bulk, *table = nullptr;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('!'));
    const auto f = card_fields(line);
    if (f.empty()) continue;
    if (f[0] == "MP" && f.at(1) == "EX") m.young = card_value(f.at(3));
    if (f[0] == "MP" && f.at(1) == "PRXY") m.poisson = card_value(f.at(3));
    if (f[0] == "TB") table = f.at(5) == "SHEAR" ? &shear : &bulk;
    if (f[0] == "TBDATA") {
      const auto start = static_cast<std::size_t>(card_value(f.at(1))) - 1;
      table->resize(start + f.size() - 2);
      for (std::size_t i = 2; i < f.size(); ++i) (*table)[start + i - 2] = card_value(f[i]);
    }
  }
  if (shear.size() != bulk.size()) throw std::runtime_error("the SHEAR and BULK tables differ in size");
  for (std::size_t i = 0; i + 1 < shear.size(); i += 2) {
    if (shear[i + 1] != bulk[i + 1]) throw std::runtime_error("the SHEAR and BULK relaxation times differ");
    m.terms.push_back({shear[i], bulk[i], shear[i + 1]});
  }
  m.instantaneous_moduli = true;  // ANSYS's MP moduli are the instantaneous ones
  return m;
}

// The uniaxial complex modulus at f [Hz]: E*(w) = E_0 (1 - sum g_i) + sum E_0 g_i i w tau_i / (1 + i w tau_i)
// (the shear ratios; the bulk ones equal them in what rheo writes).
inline std::complex<double> complex_young(const ReadMaterial& m, double frequency) {
  const double w = 2.0 * std::numbers::pi * frequency;
  double sum = 0.0;
  for (const auto& t : m.terms) sum += t.shear;
  std::complex<double> e = m.young * (1.0 - sum);
  for (const auto& t : m.terms) e += m.young * t.shear * std::complex<double>(0.0, w * t.tau) / std::complex<double>(1.0, w * t.tau);
  return e;
}

}  // namespace rheo::test
