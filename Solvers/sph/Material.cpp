#include "sph/Material.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace craterkit {

namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos)
    return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}
} // namespace

double Material::switchToLateStage(double c, double poissonRatio) {
  if (!eos.hasLateStage())
    return 1.0; // gases keep their law
  const double Kold = lawBulkModulus();
  const double K = eos.switchToLateStage(c);
  double scale = 1.0;
  if (shearModulus > 0.0) {
    const double G = shearModulus;
    const double nu =
        poissonRatio >= 0.0 ? poissonRatio : (3.0 * Kold - 2.0 * G) / (2.0 * (3.0 * Kold + G));
    const double Gnew = 3.0 * K * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu));
    scale = Gnew / G;
    shearModulus = Gnew;
  }
  bulkModulus = K;
  return scale;
}

std::string materialDirectory(const std::string& chosen, const std::string& builtIn) {
  if (!chosen.empty())
    return chosen;
  if (const char* env = std::getenv("CRATERKIT_MATERIALS"))
    return env;
  return builtIn;
}

Material fluidMaterial(const EquationOfState& eos, const std::string& name) {
  Material m;
  m.name = name;
  m.eos = eos;
  return m;
}

Material readMaterial(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot open the material file");
  Material m;
  TillotsonParams& t = m.eos.tillotson;
  std::map<std::string, std::function<void(double)>> numbers = {
      {"rho0", [&](double v) { t.rho0 = m.eos.murnaghanRho0 = m.eos.stiffRho0 = v; }},
      {"c0", [&](double v) { m.eos.stiffC0 = v; }},
      {"gruneisen", [&](double v) { m.eos.stiffGamma = v; }},
      {"A", [&](double v) { t.A = v; }},
      {"B", [&](double v) { t.B = v; }},
      {"E0", [&](double v) { t.E0 = v; }},
      {"Eiv", [&](double v) { t.Eiv = v; }},
      {"Ecv", [&](double v) { t.Ecv = v; }},
      {"a", [&](double v) { t.a = v; }},
      {"b", [&](double v) { t.b = v; }},
      {"alpha", [&](double v) { t.alpha = v; }},
      {"beta", [&](double v) { t.beta = v; }},
      {"rho_limit", [&](double v) { t.rhoLimit = v; }},
      {"K0", [&](double v) { m.eos.murnaghanK0 = v; }},
      {"n", [&](double v) { m.eos.murnaghanN = v; }},
      {"gamma", [&](double v) { m.eos.gamma = v; }},
      {"shear_modulus", [&](double v) { m.shearModulus = v; }},
      {"bulk_modulus", [&](double v) { m.bulkModulus = v; }},
      {"yield_stress", [&](double v) { m.yieldStress = v; }},
      {"friction_angle", [&](double v) { m.frictionAngle = v; }},
      {"cohesion", [&](double v) { m.cohesion = v; }},
      {"distention", [&](double v) { m.distention = v; }},
      {"crush_pe", [&](double v) { m.crushPe = v; }},
      {"crush_ps", [&](double v) { m.crushPs = v; }},
      {"weibull_k", [&](double v) { m.weibullK = v; }},
      {"weibull_m", [&](double v) { m.weibullM = v; }},
  };
  std::string line;
  int lineNo = 0;
  bool haveEos = false;
  while (std::getline(in, line)) {
    ++lineNo;
    const auto hash = line.find('#');
    if (hash != std::string::npos)
      line.resize(hash);
    line = trim(line);
    if (line.empty())
      continue;
    const auto eq = line.find('=');
    auto fail = [&](const std::string& what) {
      throw InputError(path + ":" + std::to_string(lineNo) + ": " + what);
    };
    if (eq == std::string::npos)
      fail("expected 'key = value', got '" + line + "'");
    const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    if (key == "name") {
      m.name = value;
    } else if (key == "source") {
      m.source = value;
    } else if (key == "eos") {
      try {
        m.eos.model = EquationOfState::modelFromName(value);
      } catch (const InputError& e) {
        fail(e.what());
      }
      haveEos = true;
    } else if (key == "strength") {
      if (value == "None")
        m.strength = Material::Strength::None;
      else if (value == "VonMises")
        m.strength = Material::Strength::VonMises;
      else if (value == "DruckerPrager")
        m.strength = Material::Strength::DruckerPrager;
      else
        fail("unknown strength model '" + value + "' (None, VonMises, DruckerPrager)");
    } else {
      const auto it = numbers.find(key);
      if (it == numbers.end())
        fail("unknown key '" + key + "'");
      std::istringstream s(value);
      double v;
      std::string rest;
      if (!(s >> v) || (s >> rest) || !std::isfinite(v))
        fail("'" + key + "' needs one finite number, got '" + value + "'");
      it->second(v);
    }
  }
  if (m.name.empty())
    throw InputError(path + ": the material has no name");
  if (!haveEos)
    throw InputError(path + ": the material names no equation of state ('eos = ...')");
  if (!(m.distention >= 1.0))
    throw InputError(path + ": distention must be at least 1");
  if (m.shearModulus < 0.0 || m.bulkModulus < 0.0 || m.yieldStress < 0.0 || m.cohesion < 0.0)
    throw InputError(path + ": moduli, yield stress and cohesion must not be negative");
  if (!(m.crushPe >= 0.0 && m.crushPs > m.crushPe))
    throw InputError(path + ": the crush curve needs 0 <= crush_pe < crush_ps");
  if (!(m.weibullK >= 0.0) || !(m.weibullM > 0.0))
    throw InputError(path + ": weibull_k must not be negative and weibull_m must be positive");
  if (m.weibullK > 0.0 && !(m.bulkModulus > 0.0 && m.shearModulus > 0.0))
    throw InputError(path + ": fracture (weibull_k) needs bulk_modulus and shear_modulus");
  if (m.strength != Material::Strength::None && !(m.shearModulus > 0.0))
    throw InputError(path + ": a material with strength needs a positive shear_modulus");
  if (!(m.frictionAngle >= 0.0 && m.frictionAngle < 90.0))
    throw InputError(path + ": friction_angle must be in [0, 90) degrees");
  try {
    m.eos.validate();
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  return m;
}

std::vector<Material> readMaterialLibrary(const std::string& directory) {
  std::vector<Material> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec))
    if (entry.path().extension() == ".cfg")
      out.push_back(readMaterial(entry.path().string()));
  if (ec)
    throw InputError(directory + ": cannot list the material directory");
  std::sort(out.begin(), out.end(),
            [](const Material& a, const Material& b) { return a.name < b.name; });
  return out;
}

Material findMaterial(const std::string& directory, const std::string& name) {
  const std::vector<Material> all = readMaterialLibrary(directory);
  std::string names;
  for (const Material& m : all) {
    if (m.name == name)
      return m;
    names += (names.empty() ? "" : ", ") + m.name;
  }
  throw InputError("unknown material '" + name + "' (known: " + names + ")");
}

} // namespace craterkit
