#include "oracle/differential.h"

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>

#include "codec/scene_json.h"
#include "engine/chart.h"
#include "engine/embedded_run.h"
#include "engine/integrator.h"
#include "engine/simulation.h"

namespace spinfold::oracle {

using nlohmann::json;

std::vector<IntegratorCase> integrator_cases() {
  std::vector<IntegratorCase> cases;
  for (const CatalogEntry& entry : integrator_catalog()) {
    IntegratorCase c;
    c.name = std::string(entry.info.name);
    // fixed steps small enough for 1e-8 over the test's horizon at the generator's rates (≤ ~5/time)
    if (c.name == "rk4" || c.name == "gauss4")
      c.dt = 1e-4;
    else if (c.name == "split4")
      c.dt = 5e-5;
    else if (c.name == "gauss6")
      c.dt = 5e-4;
    else if (c.name == "split6")
      c.dt = 2.5e-4;
    else if (c.name == "implicit_midpoint")
      c.dt = 2e-5, c.bound = 1e-5;
    cases.push_back(c);
  }
  cases.push_back({std::string(kAutoIntegrator), 0.01, 1e-12, 1e-8});
  return cases;
}

std::string with_integrator(std::string_view scene_json, const IntegratorCase& c) {
  json j = json::parse(scene_json);
  j["integrator"] = {{"name", c.name}, {"dt", c.dt}, {"tolerance", c.tolerance}};
  return j.dump(2);
}

namespace {

using B3 = std::array<Big, 3>;

B3 big3(const Vec3& v) {
  return {Big(v[0]), Big(v[1]), Big(v[2])};
}

// M v + b in 50 digits (the chart matrix's entries are exact doubles).
B3 chart_apply(const Mat3& M, const B3& v) {
  B3 out;
  for (int i = 0; i < 3; ++i) out[i] = Big(M(i, 0)) * v[0] + Big(M(i, 1)) * v[1] + Big(M(i, 2)) * v[2];
  return out;
}

}  // namespace

EngineBody engine_body(const Scene& sc, const State& state, const OracleScene& scene) {
  if (chart_free(sc.surface)) {  // the chart-free state, in the scene's frame
    const EmbeddedBody b = embedded_body(*make_embedded_scene(sc), state.y);
    EngineBody out;
    Body3& body = out.in_start_frame;
    body.X = big3(b.X), body.V = big3(b.V), body.e1 = big3(b.e[0]), body.e2 = big3(b.e[1]);
    body.W1 = big3(b.W[0]), body.W2 = big3(b.W[1]);
    out.in_chart = body;
    return out;
  }
  // the engine's body in its chart's coordinates, then globally, then in the oracle's start frame
  const BodyKinematics k = chart_kinematics(sc, state.y);
  const Vec3 F2 = rotate_quarter(sc.surface, k.X, k.F1);
  const Vec3 e1 = k.F1 * k.L(0, 0) + F2 * k.L(1, 0), e2 = k.F1 * k.L(0, 1) + F2 * k.L(1, 1);
  const Vec3 W1 = k.F1 * k.M(0, 0) + F2 * k.M(1, 0), W2 = k.F1 * k.M(0, 1) + F2 * k.M(1, 1);
  const Mat3& A = state.chart.A;
  const Isometry iso = start_isometry(scene);
  B3 X = chart_apply(A, big3(k.X));
  for (int i = 0; i < 3; ++i) X[i] += Big(state.chart.b[i]);
  EngineBody out;
  Body3& body = out.in_start_frame;
  body.X = to_start_point(scene, iso, X);
  body.V = to_start_vector(scene, iso, chart_apply(A, big3(k.V)));
  body.e1 = to_start_vector(scene, iso, chart_apply(A, big3(e1)));
  body.e2 = to_start_vector(scene, iso, chart_apply(A, big3(e2)));
  body.W1 = to_start_vector(scene, iso, chart_apply(A, big3(W1)));
  body.W2 = to_start_vector(scene, iso, chart_apply(A, big3(W2)));
  Body3& local = out.in_chart;
  local.X = big3(k.X), local.V = big3(k.V), local.e1 = big3(e1), local.e2 = big3(e2);
  local.W1 = big3(W1), local.W2 = big3(W2);
  return out;
}

Verdict check(std::string_view scene_json, const IntegratorCase& c, double t_end, const OracleScene& scene,
              const OracleRun& reference, std::uint64_t max_attempts) {
  Verdict v;
  v.integrator = c.name;
  v.scene_json = with_integrator(scene_json, c);
  SceneParse parsed = parse_scene_text(v.scene_json);
  if (!parsed.scene) {
    v.refused = true;
    v.message = describe_errors(parsed.errors);
    v.pass = c.name != kAutoIntegrator;  // `auto` must run every valid scene
    return v;
  }
  const Scene& sc = *parsed.scene;
  Simulation run = start_simulation(sc);
  if (!advance_to(run, t_end, max_attempts)) {
    v.incomplete = true;
    v.message = "work budget spent at t = " + std::to_string(run.state.t);
    return v;
  }
  if (run.state.status != Status::ok || run.state.t != t_end) {
    v.stopped = true;
    v.message = std::string(status_name(run.state.status)) + " at t = " + std::to_string(run.state.t);
    v.error = INFINITY;
    return v;
  }
  const EngineBody body = engine_body(sc, run.state, scene);
  const Difference& d = v.diff = compare(scene, reference, body.in_start_frame, body.in_chart);
  // each measure against the bound, those that go through double coordinates of size R cosh(r/R)
  // against the bound plus what such coordinates can resolve
  v.error = std::max({d.radius, d.invariants, d.energy, d.position - d.position_floor,
                      d.velocity - d.vector_floor, d.frame - d.vector_floor});
  v.pass = v.error <= c.bound;
  return v;
}

// ---- the scene generator --------------------------------------------------------------------
const std::vector<std::string>& regimes() {
  static const std::vector<std::string> names = {
      "generic", "undeformed", "pole", "band_edge",   "far_h2",        "degenerate", "torus",  "spheroid",
      "bump",    "catenoid",   "axis", "zero_circle", "inner_equator", "friction",   "formula"};
  return names;
}

bool varying_regime(const std::string& regime) {
  return regime == "torus" || regime == "spheroid" || regime == "bump" || regime == "catenoid" ||
         regime == "axis" || regime == "zero_circle" || regime == "inner_equator" || regime == "friction" ||
         regime == "formula";
}

namespace {

// body.inertia: with probability `anisotropic` a symmetric positive-definite matrix J^{AB}, else a
// number (the generators' one draw of it, in this order).
template <class Uni, class Coin>
json random_inertia(Uni& uni, Coin& coin, double anisotropic) {
  if (coin(anisotropic)) {
    const double a = uni(0.1, 0.5), d = uni(0.1, 0.5), o = uni(-0.4, 0.4) * std::sqrt(a * d);
    return json::array({json::array({a, o}), json::array({o, d})});
  }
  return uni(0.1, 0.5);
}

// A scene on a surface whose curvature varies (physics-surfaces.md §1): the torus, spheroid, bump
// and catenoid (a regime each, placed anywhere on it), an affine or rigid body (anisotropic J sometimes), no,
// a gravity or a spring height potential, no, abc or polar internal potential, friction in the `friction`
// regime; placed generically, on or near an axis point heading over it (`axis`: the spheroid's poles, the
// bump's top), along and across the torus's K = 0 circles (`zero_circle`), on a thin torus's inner equator
// where K is most negative (`inner_equator`).
// A scene on a formula surface (physics-anysurface.md): a triaxial ellipsoid, a monkey saddle, an egg
// crate, two bumps (graphs) or a genus-2 surface, with random parameters, a random guess near it
// (Newton takes it onto F = 0), an affine or rigid body, any potentials and sometimes friction.
std::string random_formula_scene(std::mt19937_64& rng, unsigned long long seed) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto coin = [&](double p) { return uni(0, 1) < p; };
  auto pick = [&](int n) { return static_cast<int>(std::uniform_int_distribution<int>(0, n - 1)(rng)); };
  const double pi = std::numbers::pi;
  json j;
  j["name"] = "oracle_formula_" + std::to_string(seed);
  std::array<double, 3> X{};
  switch (pick(5)) {
    case 0: {
      const double a = uni(1.0, 2.0), b = uni(0.7, 1.5), c = uni(0.5, 1.2);
      j["surface"] = {{"kind", "implicit"},
                      {"F", "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1"},
                      {"parameters", {{"a", a}, {"b", b}, {"c", c}}}};
      const double t = uni(-pi, pi), p = uni(-1.2, 1.2);
      X = {a * std::cos(p) * std::cos(t) * 1.05, b * std::cos(p) * std::sin(t), c * std::sin(p) * 0.95};
      break;
    }
    case 1:
      j["surface"] = {{"kind", "graph"}, {"z", "k*(x^3 - 3*x*y^2)"}, {"parameters", {{"k", uni(0.1, 0.5)}}}};
      X = {uni(-0.8, 0.8), uni(-0.8, 0.8), 0.0};
      break;
    case 2:
      j["surface"] = {{"kind", "graph"},
                      {"z", "h*sin(k*x)*sin(k*y)"},
                      {"parameters", {{"h", uni(0.1, 0.4)}, {"k", uni(0.8, 2.0)}}}};
      X = {uni(-2.0, 2.0), uni(-2.0, 2.0), 0.0};
      break;
    case 3:
      j["surface"] = {
          {"kind", "graph"},
          {"z", "h*exp(-((x - d)^2 + y^2)/(2*w^2)) + h*exp(-((x + d)^2 + y^2)/(2*w^2))"},
          {"parameters",
           {{"h", uni(0.3, 1.0) * (coin(0.5) ? 1 : -1)}, {"d", uni(0.8, 1.5)}, {"w", uni(0.5, 1.0)}}}};
      X = {uni(-2.0, 2.0), uni(-1.5, 1.5), 0.0};
      break;
    default: {  // the genus-2 surface of physics-anysurface.md §7 (regular for 0 < r < a⁴)
      j["surface"] = {{"kind", "implicit"},
                      {"F", "((x^2 + y^2)^2 - 2*a^2*(x^2 - y^2))^2 + (z/c)^2 - r^2"},
                      {"parameters", {{"a", 1.0}, {"c", uni(0.4, 0.7)}, {"r", uni(0.5, 0.8)}}}};
      const double t = uni(-0.6, 0.6);
      X = {(coin(0.5) ? 1.0 : -1.0) * (1.2 + uni(-0.1, 0.1)) * std::cos(t), 1.2 * std::sin(t),
           uni(-0.2, 0.2)};
      break;
    }
  }
  const bool rigid = coin(0.35);
  j["body"] = {{"mass", uni(0.5, 2.0)}, {"model", rigid ? "rigid" : "affine"}};
  j["body"]["inertia"] = random_inertia(uni, coin, 0.35);
  double lambda = uni(0.6, 1.4), mu = uni(0.3, 1.2);
  if (std::abs(lambda - mu) < 0.1) mu = lambda - 0.2;
  double lambda_dot = uni(-0.3, 0.3), mu_dot = uni(-0.3, 0.3), beta_dot = uni(-0.5, 0.5);
  if (rigid) mu = lambda, lambda_dot = mu_dot = beta_dot = 0;
  json potential = json::object();
  const int height = pick(3);
  if (height == 1) potential["height"] = {{"kind", "gravity"}, {"g", uni(-0.5, 0.5)}};
  if (height == 2) potential["height"] = {{"kind", "spring"}, {"k", uni(0.1, 1.0)}};
  if (!rigid && coin(0.5))
    potential["deformation"] = {{"kind", "abc"},
                                {"A", coin(0.5) ? uni(0.005, 0.05) : 0.0},
                                {"B", coin(0.7) ? uni(0.05, 0.4) : 0.0},
                                {"C", uni(0.05, 0.3)}};
  j["potential"] = potential;
  if (coin(0.25)) j["friction"] = {{"translational", uni(0.0, 0.3)}, {"internal", uni(0.0, 0.2)}};
  json q = {{"X", X},
            {"alpha", uni(-pi, pi)},
            {"beta", uni(-pi, pi)},
            {"lambda", lambda},
            {"mu", mu},
            {"lambda_dot", lambda_dot},
            {"mu_dot", mu_dot},
            {"beta_dot", beta_dot},
            {"speed", uni(0.0, 1.0)},
            {"heading", uni(-pi, pi)}};
  if (coin(0.5))
    q["spin"] = uni(-1.0, 1.0);
  else
    q["alpha_dot"] = uni(-1.0, 1.0);
  j["initial"] = q;
  j["integrator"] = {{"name", "auto"}};
  return j.dump(2);
}

std::string random_varying_scene(const std::string& regime, std::mt19937_64& rng, unsigned long long seed) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto coin = [&](double p) { return uni(0, 1) < p; };
  auto pick = [&](int n) { return static_cast<int>(std::uniform_int_distribution<int>(0, n - 1)(rng)); };
  const double pi = std::numbers::pi;
  json j;
  j["name"] = "oracle_" + regime + "_" + std::to_string(seed);

  // surface: 0 torus, 1 spheroid, 2 bump, 3 catenoid (one per regime of that name, any in `friction`)
  int kind = pick(4);
  if (regime == "torus" || regime == "zero_circle" || regime == "inner_equator") kind = 0;
  if (regime == "spheroid") kind = 1;
  if (regime == "bump") kind = 2;
  if (regime == "catenoid") kind = 3;
  if (regime == "axis") kind = coin(0.5) ? 1 : 2;
  double u = 0;  // the start on the profile
  bool on_axis = false;
  switch (kind) {
    case 0: {
      const double a = uni(0.5, 1.2), gap = regime == "inner_equator" ? uni(0.3, 0.6) : uni(0.5, 2.0);
      j["surface"] = {{"kind", "torus"}, {"tube_radius", a}, {"center_radius", a + gap}};
      if (regime == "zero_circle")
        u = (coin(0.5) ? 0.5 : -0.5) * pi + (coin(0.3) ? 0.0 : uni(-0.05, 0.05));
      else if (regime == "inner_equator")
        u = pi + uni(-0.1, 0.1);
      else
        u = uni(-pi, pi);
      break;
    }
    case 1: {
      const double a = uni(0.7, 2.0), b = coin(0.2) ? a : uni(0.5, 2.0);
      j["surface"] = {{"kind", "spheroid"}, {"equatorial_radius", a}, {"polar_radius", b}};
      if (regime == "axis") {
        const double d[] = {0.0, 1e-9, 1e-4, 0.01, 0.05};
        u = d[pick(5)];
        on_axis = u == 0.0;
        if (coin(0.4)) u = pi - u;  // the south pole
      } else {
        u = uni(0.1, pi - 0.1);
      }
      break;
    }
    case 2: {
      const double h = uni(0.3, 1.5) * (coin(0.5) ? 1 : -1), w = uni(0.5, 1.5);
      j["surface"] = {{"kind", "bump"}, {"height", h}, {"width", w}};
      if (regime == "axis") {
        const double d[] = {0.0, 1e-9, 1e-4, 0.01, 0.05};
        u = d[pick(5)] * w;
        on_axis = u == 0.0;
      } else {
        u = uni(0.1, 3.0) * w;
      }
      break;
    }
    default: {
      const double c = uni(0.5, 1.5);
      j["surface"] = {{"kind", "catenoid"}, {"neck_radius", c}};
      u = uni(-1.5, 1.5) * c;
      break;
    }
  }

  // body: affine or rigid (the incompressible body runs only under the chart's splitting methods)
  const bool rigid = coin(0.35);
  json body = {{"mass", uni(0.5, 2.0)}, {"model", rigid ? "rigid" : "affine"}};
  body["inertia"] = random_inertia(uni, coin, 0.35);
  j["body"] = body;

  double lambda = uni(0.6, 1.4), mu = uni(0.3, 1.2);
  if (std::abs(lambda - mu) < 0.1) mu = lambda - 0.2;
  double lambda_dot = uni(-0.3, 0.3), mu_dot = uni(-0.3, 0.3), beta_dot = uni(-0.5, 0.5);
  if (rigid) mu = lambda, lambda_dot = mu_dot = beta_dot = 0;

  json potential = json::object();
  const int height = pick(3);  // none, gravity, spring
  if (height == 1) potential["height"] = {{"kind", "gravity"}, {"g", uni(-0.5, 0.5)}};
  if (height == 2) potential["height"] = {{"kind", "spring"}, {"k", uni(0.1, 1.0)}};
  if (!rigid) {
    const int def = pick(3);  // none, abc, polar
    if (def == 1)
      potential["deformation"] = {{"kind", "abc"},
                                  {"A", coin(0.5) ? uni(0.005, 0.05) : 0.0},
                                  {"B", coin(0.7) ? uni(0.05, 0.4) : 0.0},
                                  {"C", uni(0.05, 0.3)}};
    else if (def == 2)  // the cot2 form only: the literal one's a²b denominator makes the internal
                        // motion stiff near λ = μ, which is the flat motion (§4's decoupling) and is
                        // tested on the constant-curvature surfaces; here the surface is under test
      potential["deformation"] = {
          {"kind", "polar"}, {"gtilde", -uni(0.1, 0.5)}, {"ghat", uni(0.05, 0.2)}, {"form", "cot2"}};
  }
  j["potential"] = potential;
  if (regime == "friction") {
    json friction = json::object();
    if (coin(0.8)) friction["translational"] = uni(0.0, 0.3);
    if (coin(0.8) || friction.empty()) friction["internal"] = uni(0.0, 0.2);
    j["friction"] = friction;
  }

  json q = {{"u", u},
            {"phi", uni(-pi, pi)},
            {"alpha", uni(-pi, pi)},
            {"beta", uni(-pi, pi)},
            {"lambda", lambda},
            {"mu", mu},
            {"lambda_dot", lambda_dot},
            {"mu_dot", mu_dot},
            {"beta_dot", beta_dot}};
  const double speed = uni(0.0, 1.0);
  if (on_axis) {  // E₂ is undefined there: along E₁ (over the axis for heading π at the bump's top)
    q["speed"] = speed;
    q["heading"] = coin(0.5) ? 0.0 : pi;
  } else if (regime == "axis") {  // near it, heading (nearly) over it
    q["speed"] = speed;
    q["heading"] = (u < 1.0 ? pi : 0.0) + uni(-1e-3, 1e-3);
  } else if (regime == "zero_circle") {  // along the circle or across it
    q["speed"] = uni(0.2, 1.0);
    q["heading"] = coin(0.5) ? pi / 2 + uni(-0.3, 0.3) : uni(-pi, pi);
  } else if (coin(0.5)) {
    q["speed"] = speed;
    q["heading"] = uni(-pi, pi);
  } else {
    q["u_dot"] = uni(-0.7, 0.7);
    q["phi_dot"] = uni(-0.5, 0.5);
  }
  // a spin (needed on the axis, where φ̇ is undefined), or α̇
  if (on_axis || regime == "axis" || regime == "zero_circle" || coin(0.5))
    q["spin"] = uni(-1.0, 1.0) * (regime == "zero_circle" ? 3.0 : 1.0);
  else
    q["alpha_dot"] = uni(-1.0, 1.0);
  j["initial"] = q;
  j["integrator"] = {{"name", "auto"}};
  return j.dump(2);
}

}  // namespace

std::string random_scene(const std::string& regime, unsigned long long seed) {
  std::mt19937_64 rng(seed * 7919 + std::hash<std::string>{}(regime));
  if (regime == "formula") return random_formula_scene(rng, seed);
  if (varying_regime(regime)) return random_varying_scene(regime, rng, seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto coin = [&](double p) { return uni(0, 1) < p; };
  auto pick = [&](int n) { return static_cast<int>(std::uniform_int_distribution<int>(0, n - 1)(rng)); };
  const double pi = std::numbers::pi;

  json j;
  j["name"] = "oracle_" + regime + "_" + std::to_string(seed);
  // surface
  int kind = pick(3);  // 0 sphere, 1 pseudosphere, 2 plane
  if (regime == "far_h2") kind = 1;
  if (regime == "pole" && kind == 2) kind = pick(2);
  const double R = uni(0.7, 2.0);
  const bool curvature_form = kind != 2 && coin(0.25);
  if (curvature_form)
    j["surface"] = {{"curvature", (kind == 0 ? 1.0 : -1.0) / (R * R)}};
  else if (kind == 2)
    j["surface"] = {{"kind", "plane"}};
  else
    j["surface"] = {{"kind", kind == 0 ? "sphere" : "pseudosphere"}, {"radius", R}};
  const double Rs = kind == 2 ? 1.0 : R;  // the scene's length scale (the plane's radius defaults to 1)

  // body
  const int model =
      regime == "degenerate" ? 0 : (coin(0.6) ? 0 : (coin(0.5) ? 1 : 2));  // affine, rigid, incompressible
  const char* model_name[] = {"affine", "rigid", "incompressible"};
  json body = {{"mass", uni(0.5, 2.0)}, {"model", model_name[model]}};
  body["inertia"] = random_inertia(uni, coin, 0.3);
  j["body"] = body;

  // the internal start
  const bool undeformed = model == 1 || regime == "undeformed";
  double lambda = uni(0.6, 1.4), mu = uni(0.3, 1.2);
  if (std::abs(lambda - mu) < 0.1) mu = lambda - 0.2;
  if (undeformed) mu = lambda;
  double lambda_dot = 0, mu_dot = 0, beta_dot = 0;
  if (!undeformed) {
    lambda_dot = uni(-0.3, 0.3), mu_dot = uni(-0.3, 0.3), beta_dot = uni(-0.5, 0.5);
    if (model == 2) mu_dot = -lambda_dot * mu / lambda;  // d(det L)/dt = 0
  }
  if (regime == "degenerate") {  // det L crosses 0 about when μ does
    lambda = uni(0.8, 1.2), mu = uni(0.01, 0.1), mu_dot = -uni(0.1, 0.5), lambda_dot = uni(-0.1, 0.1);
  }

  // potentials
  json potential = json::object();
  const bool radial =
      kind != 2 || coin(0.5) ? coin(regime == "band_edge" || regime == "pole" ? 0.75 : 0.5) : false;
  if (radial) potential["radial"] = {{"gamma", uni(0.01, 0.1) * (kind == 2 ? 1.0 : 1.0)}};
  if (model != 1) {
    const int def = regime == "degenerate" ? pick(2) * 1 : pick(3);  // none, abc, polar
    if (def == 1) {
      const bool A_ok = !undeformed && regime != "degenerate";
      potential["deformation"] = {{"kind", "abc"},
                                  {"A", A_ok && coin(0.5) ? uni(0.005, 0.05) : 0.0},
                                  {"B", regime != "degenerate" && coin(0.7) ? uni(0.05, 0.4) : 0.0},
                                  {"C", uni(0.05, 0.3)}};
    } else if (def == 2 && !undeformed) {
      potential["deformation"] = {{"kind", "polar"},
                                  // ĝ > 0 keeps ς off 0 (no Kepler collision: a stiffness, not a regime)
                                  {"gtilde", -uni(0.1, 0.5)},
                                  {"ghat", uni(0.05, 0.2)},
                                  {"form", coin(0.5) ? "cot2" : "literal"}};
    }
  }
  j["potential"] = potential;

  // the place
  double r = 1.0;
  if (regime == "pole") {
    const double d[] = {0.0, 1e-9, 1e-4, 0.01, 0.05, 0.2};
    r = d[pick(6)] * Rs;
    // g > 0 is a barrier at the pole: with it, "near" is where the barrier is still gentle
    if (radial) r = uni(0.15, 0.3) * Rs;
    if (kind == 0 && coin(0.3)) r = pi * R - r;  // the south pole
  } else if (regime == "band_edge") {
    // the edges of the chart bands (engine/chart.cpp: |S|/ℓ ∈ {0.3, 0.5}, r/ℓ ∈ {3, 4}) ± a little
    const double off = coin(0.3) ? 0.0 : uni(-0.02, 0.02);
    if (kind == 0) {
      const double s = coin(0.5) ? 0.3 : 0.5;
      r = R * std::asin(s) * (1 + off);
      if (coin(0.3)) r = pi * R - r;
    } else {
      const double e[] = {0.3, 0.5, 3.0, 4.0};
      r = e[pick(4)] * Rs * (1 + off);
    }
  } else if (regime == "far_h2") {
    r = uni(8.0, 30.0) * R;
  } else {
    r = kind == 0 ? uni(0.05, pi - 0.05) * R : uni(0.1, 5.0) * Rs;
  }
  const double phi = uni(-pi, pi);
  json q = {{"r", r},
            {"phi", phi},
            {"alpha", uni(-pi, pi)},
            {"beta", uni(-pi, pi)},
            {"lambda", lambda},
            {"mu", mu},
            {"lambda_dot", lambda_dot},
            {"mu_dot", mu_dot},
            {"beta_dot", model == 1 ? 0.0 : beta_dot}};
  const bool at_pole = r == 0.0 || (kind == 0 && r == pi * R);
  const double speed = uni(0.0, 1.0);
  const double S0 = kind == 0 ? R * std::sin(r / R) : kind == 1 ? R * std::sinh(r / R) : r;
  // far out the rates would be e^{r/R}-sized: the physical fields then
  if (regime == "far_h2" || coin(0.5)) {
    q["speed"] = speed;
    q["heading"] = at_pole ? (coin(0.5) ? 0.0 : pi) : uni(-pi, pi);
  } else {
    q["r_dot"] = uni(-0.7, 0.7);
    q["phi_dot"] = S0 > 0.05 * Rs ? uni(-0.7, 0.7) / S0 : 0.0;
  }
  // near a pole with a given speed φ̇ = v sin h/S is huge, and so would α̇ + Cφ̇ be: a spin then
  if (regime == "far_h2" || S0 < 0.05 * Rs || coin(0.5))
    q["spin"] = uni(-1.0, 1.0);
  else
    q["alpha_dot"] = uni(-1.0, 1.0);
  j["initial"] = q;
  j["integrator"] = {{"name", "auto"}};
  return j.dump(2);
}

}  // namespace spinfold::oracle
