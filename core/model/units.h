// disco — the model's unit system (nondimensionalisation).
//
// The model is solved in units chosen from the scene, not in SI:
//   length L = mean robot radius,  mass M = mean robot mass,
//   force  F = mean F_max,         time T = sqrt(L M / F).
// In these units radii, masses and force bounds are all O(1), so Ipopt's
// tolerances and disco's certificate mean the same thing for a scene written
// in metres or millimetres, grams or tonnes: the certificate thresholds are
// relative to the scene's own scales. Every number leaving disco (solution
// files, logs) is converted back to SI.
#pragma once

#include "core/model/scene.h"

namespace disco {

struct Units {
  double length = 1.0;  // [m]
  double mass = 1.0;    // [kg]
  double time = 1.0;    // [s]
  double velocity() const { return length / time; }
  double force() const { return mass * length / (time * time); }
  double torque() const { return force() * length; }
};

Units choose_units(const Scene& scene);

// The same scene with every quantity divided by its unit (gravity, damping,
// inertia, positions, velocities, boxes, safe distances, the objective's horizon and energy
// weight; angles unchanged).
Scene to_model_units(const Scene& scene, const Units& u);

}  // namespace disco
