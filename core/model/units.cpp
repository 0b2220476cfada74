#include "core/model/units.h"

#include <cmath>

namespace disco {

Units choose_units(const Scene& scene) {
  double r = 0, m = 0, f = 0;
  int driven = 0;  // robots (objects have no force)
  for (const auto& rb : scene.robots) {
    r += rb.radius;
    m += rb.mass;
    f += rb.force_max;
    driven += rb.object ? 0 : 1;
  }
  const double n = static_cast<double>(scene.robots.size());
  Units u;
  u.length = r / n;
  u.mass = m / n;
  u.time = std::sqrt(u.length * u.mass / (f / driven));
  return u;
}

Scene to_model_units(const Scene& scene, const Units& u) {
  // Unit of each state component: x, y [L]; phi [1]; vx, vy [L/T]; omega [1/T].
  const State unit{u.length, u.length, 1.0, u.velocity(), u.velocity(), 1.0 / u.time};
  Scene s = scene;
  s.gravity = scene.gravity * u.time * u.time / u.length;
  for (auto& rb : s.robots) {
    rb.radius /= u.length;
    rb.mass /= u.mass;
    rb.inertia /= u.mass * u.length * u.length;
    rb.damping /= u.length * u.time;
    rb.force_max /= u.force();
    for (int c = 0; c < kStateSize; ++c) {
      rb.start[c] /= unit[c];
      rb.target.lower[c] /= unit[c];  // +-inf stays +-inf
      rb.target.upper[c] /= unit[c];
    }
  }
  for (auto& p : s.pairs) p.safe_distance /= u.length;
  // T_f + w E in model units is (T_f + w E) / T with E / (F^2 T): w scales by F^2.
  s.objective.horizon /= u.time;
  s.objective.energy_weight *= u.force() * u.force();
  for (auto& p : s.obstacle_pairs) p.safe_distance /= u.length;
  for (auto& ob : s.obstacles) {
    for (int a = 0; a < 2; ++a) {
      ob.from[a] /= u.length;
      ob.to[a] /= u.length;
      ob.velocity[a] /= u.velocity();
    }
    for (auto& w : ob.path) {  // a clamped spline is the same curve in scaled time and space
      w.t /= u.time;
      for (double& c : w.p) c /= u.length;
    }
    ob.radius /= u.length;
  }
  return s;
}

}  // namespace disco
