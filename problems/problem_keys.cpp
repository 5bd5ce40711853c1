// The keys problems share: mesh, boundaries, solids and their hardening,
// the ambient gas, tractions; declared with their defaults and read back.
#include <string>

#include "../src/boundary_keys.hpp"
#include "../src/materials.hpp"
#include "../src/problem.hpp"

namespace lagremap {

void declareMeshKeys(Config& config, int nx, int ny, int nz) {
  config.addInteger("mesh.nx", nx, "cells along x", true);
  config.addInteger("mesh.ny", ny, "cells along y", true);
  config.addInteger("mesh.nz", nz, "cells along z", true);
}

void declareBoundaryKeys(Config& config, const std::array<const char*, kNumSides>& defaults) {
  for (int side = 0; side < kNumSides; ++side) {
    config.addChoice(std::string("bc.") + sideName(side), defaults[side],
                     {"free", "wall", "symmetry", "fixed", "traction"},
                     std::string("boundary condition on the ") + sideName(side) + " side");
  }
}

void declareHypoSolidKeys(Config& config, const std::string& prefix, const std::string& preset) {
  const MaterialParams m = materialPreset(preset);
  config.addReal(prefix + ".rho0", m.rho0, "kg/m^3", "reference density (Mie-Gruneisen)");
  config.addReal(prefix + ".a0", m.a0, "m/s", "bulk sound speed a0 (Mie-Gruneisen)");
  config.addReal(prefix + ".Gamma0", m.Gamma0, "-", "Gruneisen coefficient Gamma0");
  config.addReal(prefix + ".s", m.s, "-", "Hugoniot slope s (Us = a0 + s up)");
  config.addReal(prefix + ".mu", m.mu, "Pa", "shear modulus (hypo-elastic)");
  config.addReal(prefix + ".yield_stress", m.yield_stress, "Pa",
                 "von Mises yield stress Y0 (Johnson-Cook's A)");
  declareHardeningKeys(config, prefix, m);
}

void declareHardeningKeys(Config& config, const std::string& prefix, const MaterialParams& m) {
  config.addChoice(prefix + ".hardening", hardeningName(m.hardening),
                   {"perfect", "linear", "johnson_cook"},
                   "yield stress: perfect (Y0), linear (Y0 + H eps_p), johnson_cook");
  config.addReal(prefix + ".hardening_modulus", m.hardening_modulus, "Pa",
                 "H of linear hardening, Y = Y0 + H eps_p");
  config.addReal(prefix + ".jc_B", m.jc_B, "Pa", "Johnson-Cook B (strain term B eps_p^n)");
  config.addReal(prefix + ".jc_n", m.jc_n, "-", "Johnson-Cook strain exponent n");
  config.addReal(prefix + ".jc_C", m.jc_C, "-", "Johnson-Cook rate coefficient C");
  config.addReal(prefix + ".jc_rate0", m.jc_rate0, "1/s", "Johnson-Cook reference strain rate");
  config.addReal(prefix + ".jc_m", m.jc_m, "-", "Johnson-Cook thermal exponent m");
  config.addReal(prefix + ".room_temperature", m.room_temperature, "K",
                 "temperature at e = 0 (Johnson-Cook T_room)");
  config.addReal(prefix + ".melt_temperature", m.melt_temperature, "K",
                 "Johnson-Cook melting temperature T_melt");
  config.addReal(prefix + ".specific_heat", m.specific_heat, "J/(kg K)",
                 "c_v of T = T_room + e / c_v (0: no thermal softening)");
}

void readHardening(const Config& config, const std::string& prefix, MaterialParams& m) {
  const std::string kind = config.text(prefix + ".hardening");
  m.hardening = kind == "linear"         ? HardeningKind::Linear
                : kind == "johnson_cook" ? HardeningKind::JohnsonCook
                                         : HardeningKind::Perfect;
  m.hardening_modulus = config.real(prefix + ".hardening_modulus");
  m.jc_B = config.real(prefix + ".jc_B");
  m.jc_n = config.real(prefix + ".jc_n");
  m.jc_C = config.real(prefix + ".jc_C");
  m.jc_rate0 = config.real(prefix + ".jc_rate0");
  m.jc_m = config.real(prefix + ".jc_m");
  m.room_temperature = config.real(prefix + ".room_temperature");
  m.melt_temperature = config.real(prefix + ".melt_temperature");
  m.specific_heat = config.real(prefix + ".specific_heat");
  if (!(m.hardening_modulus >= 0)) throw ConfigError(prefix + ".hardening_modulus must be >= 0");
  if (!(m.jc_B >= 0 && m.jc_n > 0 && m.jc_C >= 0 && m.jc_rate0 > 0 && m.jc_m > 0)) {
    throw ConfigError(prefix + ": need jc_B >= 0, jc_n > 0, jc_C >= 0, jc_rate0 > 0, jc_m > 0");
  }
  if (!(m.specific_heat >= 0 && m.room_temperature >= 0 && m.melt_temperature >= 0)) {
    throw ConfigError(prefix + ": specific_heat, room_temperature, melt_temperature must be >= 0");
  }
  if (m.hardening == HardeningKind::JohnsonCook && m.specific_heat > 0 &&
      !(m.melt_temperature > m.room_temperature)) {
    throw ConfigError(prefix + ".melt_temperature must exceed room_temperature" +
                      " (or specific_heat = 0: no thermal softening)");
  }
}

const char* hardeningName(HardeningKind kind) {
  switch (kind) {
    case HardeningKind::Linear:
      return "linear";
    case HardeningKind::JohnsonCook:
      return "johnson_cook";
    case HardeningKind::Perfect:
      break;
  }
  return "perfect";
}

MaterialParams readHypoSolid(const Config& config, const std::string& prefix,
                             const std::string& preset) {
  MaterialParams m = materialPreset(preset);
  m.rho0 = config.real(prefix + ".rho0");
  m.a0 = config.real(prefix + ".a0");
  m.Gamma0 = config.real(prefix + ".Gamma0");
  m.s = config.real(prefix + ".s");
  m.mu = config.real(prefix + ".mu");
  m.yield_stress = config.real(prefix + ".yield_stress");
  readHardening(config, prefix, m);
  // (Gamma0 > 0, not >= 0: the problems set a solid's initial energy from its
  // pressure at rho0, e0 = p0 / (rho0 Gamma0))
  if (!(m.rho0 > 0 && m.a0 > 0 && m.Gamma0 > 0 && m.s >= 0 && m.mu >= 0 && m.yield_stress >= 0)) {
    throw ConfigError(prefix + ": rho0, a0 and Gamma0 must be > 0; s, mu and yield_stress >= 0");
  }
  return m;
}

void declareNeoHookeanKeys(Config& config, const std::string& prefix, const std::string& preset) {
  const MaterialParams m = materialPreset(preset);
  config.addReal(prefix + ".rho0", m.rho0, "kg/m^3", "reference density");
  config.addReal(prefix + ".young", m.young, "Pa", "Young's modulus E (Neo-Hookean)");
  config.addReal(prefix + ".poisson", m.poisson, "-", "Poisson's ratio nu (Neo-Hookean)");
}

MaterialParams readNeoHookean(const Config& config, const std::string& prefix,
                              const std::string& preset) {
  MaterialParams m = materialPreset(preset);
  m.rho0 = config.real(prefix + ".rho0");
  m.young = config.real(prefix + ".young");
  m.poisson = config.real(prefix + ".poisson");
  if (!(m.rho0 > 0 && m.young > 0 && m.poisson >= 0 && m.poisson < 0.5)) {
    throw ConfigError(prefix + ": need rho0 > 0, young > 0 and 0 <= poisson < 0.5");
  }
  return m;
}

AmbientGas readAmbientGas(const Config& config, const std::string& problem) {
  AmbientGas gas;
  gas.material.gamma = config.real("gas.gamma");
  gas.rho = config.real("gas.rho");
  const double p = config.real("gas.p");
  if (!(gas.rho > 0 && p > 0 && gas.material.gamma > 1)) {
    throw ConfigError(problem + ": gas.rho, gas.p must be > 0 and gas.gamma > 1");
  }
  gas.e = p / ((gas.material.gamma - 1.0) * gas.rho);
  return gas;
}

void declareTractionKeys(Config& config, int side, const SymMat3& stress) {
  const std::string prefix = std::string("bc.") + sideName(side) + ".sigma_";
  const double values[6] = {stress.xx, stress.yy, stress.zz, stress.xy, stress.yz, stress.xz};
  const char* names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
  for (int k = 0; k < 6; ++k) {
    config.addReal(prefix + names[k], values[k], "Pa",
                   std::string("imposed Cauchy stress (tension > 0) on ") + sideName(side));
  }
}

SideBoundaries readBoundaries(const Config& config) {
  SideBoundaries boundaries;
  for (int side = 0; side < kNumSides; ++side) {
    const std::string key = std::string("bc.") + sideName(side);
    boundaries[side].kind = parseBoundaryKind(key, config.text(key));
    if (boundaries[side].kind == BoundaryKind::Traction) {
      const std::string prefix = key + ".sigma_";
      if (!config.has(prefix + "xx")) {
        throw ConfigError("side " + std::string(sideName(side)) +
                          " has a traction condition but this problem declares no " + prefix +
                          "* keys");
      }
      SymMat3& s = boundaries[side].traction_stress;
      s = {config.real(prefix + "xx"), config.real(prefix + "yy"), config.real(prefix + "zz"),
           config.real(prefix + "xy"), config.real(prefix + "yz"), config.real(prefix + "xz")};
    }
  }
  return boundaries;
}

void refuseLagrangeMode(Config& config, const std::string& problem, const std::string& why) {
  if (config.remapSetup()) return;
  if (config.aleMode()) {  // ALE starts from the remap set-up
    config.useRemapSetup();
    return;
  }
  throw ConfigError(problem + ": lagrange mode is not available (" + why + "); use --mode remap");
}

}  // namespace lagremap
