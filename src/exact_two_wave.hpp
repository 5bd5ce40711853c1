// Exact plane-wave solution of an elastic-plastic impact in uniaxial strain
// (the `wilkins` flyer plate, docs/verification.md §8.2): each
// solid, a Mie-Gruneisen EOS with a hypo-elastic perfectly plastic deviator
// (von Mises), runs an elastic precursor up to the Hugoniot elastic limit and
// behind it a plastic shock, both Rankine-Hugoniot jumps in the stress
// P = -sigma_xx = p - S_xx:
//   mass      rho_a (U - u_a) = rho_b (U - u_b),
//   momentum  P_b - P_a = rho_a (U - u_a) (u_b - u_a),
//   energy    e_b - e_a = (P_a + P_b) (1/rho_a - 1/rho_b) / 2.
// In uniaxial strain the hypo-elastic deviator is S_xx = -(4/3) mu ln(rho/rho0)
// (the Jaumann rate integrated), S_yy = S_zz = -S_xx / 2, and von Mises yield
// is |S_xx| = 2Y/3: the elastic limit is at rho0 exp(Y / (2 mu)); behind it
// S_xx = -2Y/3. A weak impact stays elastic: one wave. The impact of a flyer
// at speed v on a target at rest matches the interface's stress: the target's
// waves at particle velocity u, the flyer's (in its own frame) at v - u.
//
// Plain host code, an independent reference for the problem's checks.
#pragma once

namespace lagremap {

// Mie-Gruneisen solid with a hypo-elastic perfectly plastic deviator, at rest
// in its initial state (rho0, e0).
struct ElasticPlasticSolid {
  double rho0, a0, Gamma0, s;  // Mie-Gruneisen (U_s = a0 + s u_p)
  double mu, yield_stress;     // shear modulus, von Mises yield stress Y
  double e0 = 0.0;             // initial specific internal energy
};

// A uniform state of a plane wave solution (velocity along the wave's
// direction of travel into the solid).
struct UniaxialState {
  double rho = 0.0, u = 0.0, e = 0.0;
  double p = 0.0;         // pressure (EOS)
  double sigma_xx = 0.0;  // -p + S_xx
};

// The waves a piston moving at u_piston (> 0, compressive) drives into the
// solid at rest: the initial state, the elastic precursor (at the elastic limit,
// or the final state of a purely elastic impact) and the plastic state behind
// the plastic shock (equal to the precursor's when the impact stays elastic).
// Speeds in the frame of the solid at rest, along the direction of travel.
struct TwoWaveSolution {
  UniaxialState initial, precursor, plastic;
  double precursor_speed = 0.0, plastic_speed = 0.0;
  bool plastic_wave = false;
};

// Throws std::invalid_argument for a non-positive material constant or speed,
// or a piston speed the EOS cannot take (beyond its limiting compression).
TwoWaveSolution solveTwoWave(const ElasticPlasticSolid& solid, double u_piston);

// Flyer at speed v (along +x) onto a target at rest: the target's waves move
// to +x with its material at u_interface behind them; the flyer's move to -x
// into it (flyer.* holds them in the flyer's own frame, velocities measured
// toward -x). Same materials: u_interface = v / 2 exactly.
struct ImpactSolution {
  TwoWaveSolution target, flyer;
  double u_interface = 0.0, sigma_interface = 0.0;
};
ImpactSolution solveImpact(const ElasticPlasticSolid& flyer, const ElasticPlasticSolid& target,
                           double v);

}  // namespace lagremap
