// Reference solution of the large-deflection cantilever under a dead tip load (the
// elastica), for the cantilever_elastica validation case.
//
// A uniform inextensible Euler-Bernoulli beam of length L is clamped at s = 0 and carries a
// tip force P of fixed direction, perpendicular to the undeformed axis. With arc length s in
// units of L and theta(s) the angle of the tangent from the undeformed axis, moment balance
// E I theta' = P (x_tip - x(s)) gives
//   theta''(s) = -alpha cos(theta(s)),  theta(0) = 0,  theta'(1) = 0,  alpha = P L^2 / (E I),
// and the tip lies at x_tip = integral cos(theta) ds, y_tip = integral sin(theta) ds.
// SolveElastica shoots on the root curvature theta'(0) (bisection) and integrates with
// classical RK4; 100 steps already give 7 digits. Values this solver gives, for checking:
//   alpha = 1:  y_tip = 0.30172 L, L - x_tip = 0.05643 L, theta(1) = 0.46135 rad;
//   alpha = 3:  y_tip = 0.60325 L, L - x_tip = 0.25442 L, theta(1) = 0.98602 rad;
//   alpha = 10: y_tip = 0.81061 L, L - x_tip = 0.55500 L, theta(1) = 1.43029 rad.
// The alpha = 1 pair and y_tip(10) = 0.8106 L agree with the tabulated elastica of
// Bisshopp & Drucker, Q. Appl. Math. 3 (1945) 272, and Mattiasson, Int. J. Numer. Meth.
// Eng. 17 (1981) 145.
#pragma once

namespace fibrenet::validation {

struct ElasticaTip {
  double vertical = 0.0;        // tip deflection along the load, y_tip / L
  double horizontal = 0.0;      // tip displacement towards the clamp, 1 - x_tip / L
  double tip_angle = 0.0;       // theta(1) [rad]
  double root_curvature = 0.0;  // theta'(0) L = alpha x_tip / L
};

// Solves the elastica for the load parameter alpha = P L^2 / (E I) in [0, 100] on the
// stable (first) branch, with `steps` RK4 steps over the length (error ~ steps^-4).
// Throws fibrenet::InputError for alpha or steps out of range.
ElasticaTip SolveElastica(double alpha, int steps = 2000);

// The same beam made axially extensible, a diagnostic for the discrete fibre whose bonds
// stretch: lambda = P / (E A) [-]; the tangential force P sin(theta) stretches the beam by
// (1 + lambda sin theta) per unit rest length, so theta'' = -alpha (1 + lambda sin theta)
// cos theta. For the paper's fibre lambda = alpha R^2 / (4 L^2). lambda in [0, 0.1].
ElasticaTip SolveExtensibleElastica(double alpha, double lambda, int steps = 2000);

}  // namespace fibrenet::validation
