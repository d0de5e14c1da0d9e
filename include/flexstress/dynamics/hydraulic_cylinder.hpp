// A valve-controlled hydraulic cylinder (ModelBuilder::add_hydraulic_cylinder): lumped-fluid
// theory (Watton, Fluid Power Systems, 1989, ch. 4; Merritt, Hydraulic
// Control Systems, 1967, ch. 5). Two chambers, each one lump of oil with bulk modulus beta,
//
//   V1(x) / beta * p1' = Q1 - A1 x',      V1 = V01 + A1 x           (cap side)
//   V2(x) / beta * p2' = Q2 + A2 x',      V2 = V02 + A2 (s - x)     (rod side)
//
// fed by a critically centred, matched and symmetric 4/3 proportional valve with orifice flow
// (Merritt eq. 5-3): for a command u >= 0 supply -> chamber 1 and chamber 2 -> tank,
//   Q1 = K u sqrt(ps - p1),  Q2 = -K u sqrt(p2 - pt),
// for u < 0 the other way round. The square root is regularized below a transition pressure
// drop (laminar there, smooth, so Newton and the step see a finite flow gain). The piston
// position x is the distance between the two markers' origins minus `length_retracted`, the
// force on marker j is (p1 A1 - p2 A2) along the line from i to j (extending).
//
// Solved inside the implicit step: the chamber pressures are internal states of the element,
// kept in the Data (Data::force_states) as of the start of the step. At each evaluation of an
// iterate (x, x') the pressures at its time follow from a discrete balance of each chamber,
//
//   p - p_n = beta / V_mid * [ h (Q(p) + Q_n) / 2 - A (x - x_n) ]        (chamber 1; 2 alike)
//
// the flow by the trapezoidal rule and the compression by the piston displacement itself (not
// a rate times h), with the chamber volume at the midpoint: second order, like the mechanical
// integrator, and a closed valve leaves a pure oil spring of stiffness beta A^2 / V. Each chamber's
// equation is scalar and strictly monotone in p (the orifice flow falls as the chamber pressure
// rises), solved by a few Newton iterations. The pressures are eliminated this way (not added to
// the global unknowns): the oil column's stiffness beta A^2 / V is left out of the iteration
// matrix, which the modified Newton of the implicit integrator absorbs while it is small against M
// / (beta_N h^2). After an accepted step, hydraulics::commit stores the new pressures.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "flexstress/core/types.hpp"

namespace flexstress {

/// The cylinder and its valve (the command comes separately: a law of the model using it).
template <class Scalar>
struct HydraulicParams {
  Scalar bore_area = Scalar(0);              ///< A1 (m^2), cap side
  Scalar annulus_area = Scalar(0);           ///< A2 (m^2), rod side
  Scalar stroke = Scalar(0);                 ///< s (m), piston travel
  Scalar length_retracted = Scalar(0);       ///< marker distance at x = 0 (m)
  Scalar dead_volume_cap = Scalar(0);        ///< V01 (m^3): hoses and end clearance
  Scalar dead_volume_rod = Scalar(0);        ///< V02 (m^3)
  Scalar bulk_modulus = Scalar(1.4e9);       ///< beta (Pa), effective (oil, hoses, air)
  Scalar supply_pressure = Scalar(0);        ///< ps (Pa)
  Scalar tank_pressure = Scalar(0);          ///< pt (Pa)
  Scalar flow_gain = Scalar(0);              ///< K (m^3/s/Pa^0.5) at u = 1
  Scalar transition_pressure = Scalar(1e4);  ///< below this drop the orifice is laminar
};

/// Internal state: the chamber pressures and what the next step's balance needs of the last
/// accepted state.
template <class Scalar>
struct HydraulicState {
  Scalar p1 = Scalar(0), p2 = Scalar(0);  ///< chamber pressures (Pa)
  Scalar x = Scalar(0);                   ///< piston position (m)
  Scalar q1 = Scalar(0), q2 = Scalar(0);  ///< valve flows into the chambers (m^3/s)
  Scalar t = Scalar(0);
};

namespace hydraulics {

// p = b + k Q(p), with dQ/dp <= 0: g(p) = p - b - k Q(p) has g' >= 1, so the root lies
// within |g(v)| of any v. Newton, falling back to bisection of that bracket whenever a step
// would leave it: it cannot run away, whatever the orifice curve does near zero drop.
template <class Scalar, class Flow>
Scalar solve_chamber(Scalar b, Scalar k, const Flow& flow) {
  using std::abs;
  Scalar d = Scalar(0);
  Scalar v = b;
  Scalar g = v - b - k * flow(v, d);
  Scalar lo = v - abs(g), hi = v + abs(g);
  for (int it = 0; it < 60; ++it) {
    const Scalar tol = Scalar(64) * std::numeric_limits<Scalar>::epsilon() * (abs(v) + abs(b));
    if (!(abs(g) > tol)) break;
    if (g > Scalar(0))
      hi = std::min(hi, v);
    else
      lo = std::max(lo, v);
    Scalar next = v - g / (Scalar(1) - k * d);
    if (!(next > lo && next < hi)) next = Scalar(0.5) * (lo + hi);
    v = next;
    g = v - b - k * flow(v, d);
  }
  return v;
}

/// Checks the parameters (ModelBuilder::add_hydraulic_cylinder, so finalize() reports them): the
/// name of the first one out of its domain, or nullptr.
template <class Scalar>
const char* check(const HydraulicParams<Scalar>& p) {
  const auto positive = [](Scalar v) { return std::isfinite(double(v)) && v > Scalar(0); };
  if (!positive(p.bore_area)) return "bore_area must be positive";
  if (!positive(p.annulus_area)) return "annulus_area must be positive";
  if (!positive(p.stroke)) return "stroke must be positive";
  if (!positive(p.dead_volume_cap) || !positive(p.dead_volume_rod))
    return "dead volumes must be positive (a chamber never empties)";
  if (!positive(p.bulk_modulus)) return "bulk_modulus must be positive";
  if (!positive(p.transition_pressure)) return "transition_pressure must be positive";
  if (!std::isfinite(double(p.flow_gain)) || p.flow_gain < Scalar(0))
    return "flow_gain must be finite and not negative";
  if (!std::isfinite(double(p.tank_pressure)) || !std::isfinite(double(p.supply_pressure)) ||
      !(p.supply_pressure > p.tank_pressure))
    return "supply_pressure must be above tank_pressure";
  if (!std::isfinite(double(p.length_retracted))) return "length_retracted must be finite";
  return nullptr;
}

/// sign(dp) sqrt(|dp|), laminar below the transition drop: dp / (|dp| + c)^(1/2) has slope
/// c^(-1/2) at 0 and is within 0.5 % of the square root for |dp| > 100 c.
template <class Scalar>
Scalar orifice(Scalar dp, Scalar c, Scalar& slope) {
  using std::abs;
  using std::sqrt;
  const Scalar a = abs(dp) + c, r = sqrt(a);
  slope = (Scalar(0.5) * abs(dp) + c) / (a * r);
  return dp / r;
}
/// Valve flows into chamber 1 and chamber 2 at pressures p1, p2 and command u, with their
/// derivatives with respect to the chamber's own pressure.
template <class Scalar>
Scalar flow_cap(const HydraulicParams<Scalar>& p, Scalar u, Scalar p1, Scalar& d) {
  Scalar s = Scalar(0);
  const Scalar q = u >= Scalar(0)
                       ? p.flow_gain * u * orifice(p.supply_pressure - p1, p.transition_pressure, s)
                       : p.flow_gain * u * orifice(p1 - p.tank_pressure, p.transition_pressure, s);
  d = -p.flow_gain * std::abs(u) * s;
  return q;
}
template <class Scalar>
Scalar flow_rod(const HydraulicParams<Scalar>& p, Scalar u, Scalar p2, Scalar& d) {
  Scalar s = Scalar(0);
  const Scalar q =
      u >= Scalar(0) ? -p.flow_gain * u * orifice(p2 - p.tank_pressure, p.transition_pressure, s)
                     : -p.flow_gain * u * orifice(p.supply_pressure - p2, p.transition_pressure, s);
  d = -p.flow_gain * std::abs(u) * s;
  return q;
}

/// Piston position from the marker origins ri (cylinder) and rj (rod), and the unit vector from
/// i to j.
template <class Scalar>
Scalar piston(const HydraulicParams<Scalar>& p, const Vec3<Scalar>& ri, const Vec3<Scalar>& rj,
              Vec3<Scalar>& n) {
  const Vec3<Scalar> d = rj - ri;
  const Scalar length = d.norm();
  n = length > Scalar(0) ? Vec3<Scalar>(d / length) : Vec3<Scalar>::UnitZ();
  return length - p.length_retracted;
}

/// Chamber pressures at time t, piston position x and valve command u from the last accepted
/// state (the discrete balance above; Newton on each monotone scalar equation).
template <class Scalar>
void pressures(const HydraulicParams<Scalar>& p, const HydraulicState<Scalar>& s, Scalar t,
               Scalar x, Scalar u, Scalar& p1, Scalar& p2) {
  const Scalar h = t - s.t, dx = x - s.x;
  const Scalar x_mid = Scalar(0.5) * (x + s.x);
  const Scalar c1 = p.bulk_modulus / (p.dead_volume_cap + p.bore_area * x_mid);
  const Scalar c2 = p.bulk_modulus / (p.dead_volume_rod + p.annulus_area * (p.stroke - x_mid));
  const Scalar b1 = s.p1 + c1 * (Scalar(0.5) * h * s.q1 - p.bore_area * dx);
  const Scalar b2 = s.p2 + c2 * (Scalar(0.5) * h * s.q2 + p.annulus_area * dx);
  p1 = solve_chamber(b1, Scalar(0.5) * h * c1,
                     [&](Scalar v, Scalar& d) { return flow_cap(p, u, v, d); });
  p2 = solve_chamber(b2, Scalar(0.5) * h * c2,
                     [&](Scalar v, Scalar& d) { return flow_rod(p, u, v, d); });
}

/// Force on marker j's origin (global) at command u; marker i gets the opposite.
template <class Scalar>
Vec3<Scalar> force(const HydraulicParams<Scalar>& p, const HydraulicState<Scalar>& s, Scalar t,
                   Scalar u, const Vec3<Scalar>& ri, const Vec3<Scalar>& rj) {
  Vec3<Scalar> n;
  Scalar p1, p2;
  pressures(p, s, t, piston(p, ri, rj, n), u, p1, p2);
  return (p1 * p.bore_area - p2 * p.annulus_area) * n;
}

/// Starts a run at t from the pressures set in s (s.p1, s.p2): the piston position and flows
/// there.
template <class Scalar>
void start(const HydraulicParams<Scalar>& p, HydraulicState<Scalar>& s, Scalar t, Scalar u,
           const Vec3<Scalar>& ri, const Vec3<Scalar>& rj) {
  Vec3<Scalar> n;
  Scalar d;
  s = HydraulicState<Scalar>{
      s.p1, s.p2, piston(p, ri, rj, n), flow_cap(p, u, s.p1, d), flow_rod(p, u, s.p2, d), t};
}

/// Stores the state at t after an accepted step.
template <class Scalar>
void commit(const HydraulicParams<Scalar>& p, HydraulicState<Scalar>& s, Scalar t, Scalar u,
            const Vec3<Scalar>& ri, const Vec3<Scalar>& rj) {
  Vec3<Scalar> n;
  Scalar p1, p2, d;
  const Scalar x = piston(p, ri, rj, n);
  pressures(p, s, t, x, u, p1, p2);
  s = HydraulicState<Scalar>{p1, p2, x, flow_cap(p, u, p1, d), flow_rod(p, u, p2, d), t};
}

}  // namespace hydraulics

}  // namespace flexstress
