// libFuzzer target: a scene built field by field from the input, then validated, run for a short
// time with a bounded number of steps and checked. Properties (a violation aborts):
// - validation names a field and a reason for every error;
// - a scene that passes validation starts from a finite state with a finite energy;
// - after a run, with whatever status, the state is finite (the last good one), the time is the
//   requested one when the status is ok and the work was not cut, the paper coordinates that are
//   defined are finite, and the same scene gives the same bits;
// - the scene's JSON reads back to the same JSON;
// - on the scene with its immoderate numbers replaced by moderate ones, `exact` (where it accepts
//   the scene), `dop853` and `auto` at tolerance 1e-12 agree with the independent oracle (oracle/) at
//   a short horizon to 1e-6 (on one input in 16): the fuzzer looks for wrong answers, not only crashes.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>

#include "codec/scene_json.h"
#include "engine/invariants.h"
#include "engine/paper_coordinates.h"
#include "engine/simulation.h"
#include "engine/validation.h"
#include "oracle/differential.h"

namespace spinfold {
namespace {

[[noreturn]] void violated(const char* what, const Scene& scene) {
  std::fprintf(stderr, "property violated: %s\nscene: %s\n", what, scene_to_json(scene).dump().c_str());
  std::abort();
}

// Mostly values a person might type, sometimes the edges of double.
double pick(FuzzedDataProvider& in) {
  static constexpr double kNotable[] = {0.0,
                                        -0.0,
                                        1.0,
                                        -1.0,
                                        0.5,
                                        2.0,
                                        std::numbers::pi,
                                        std::numbers::pi / 2,
                                        2 * std::numbers::pi,
                                        1e-3,
                                        1e-8,
                                        1e-15,
                                        1e-300,
                                        1e3,
                                        1e8,
                                        1e15,
                                        1e300,
                                        -1e300,
                                        std::numeric_limits<double>::denorm_min(),
                                        std::numeric_limits<double>::max(),
                                        std::numeric_limits<double>::infinity(),
                                        std::numeric_limits<double>::quiet_NaN()};
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0: return in.PickValueInArray(kNotable);
    case 1: return in.ConsumeFloatingPoint<double>();
    default: return in.ConsumeFloatingPointInRange(-10.0, 10.0);
  }
}

Scene scene_from(FuzzedDataProvider& in) {
  Scene s;
  s.surface.kind = in.PickValueInArray({SurfaceKind::sphere, SurfaceKind::pseudosphere, SurfaceKind::plane});
  s.surface.radius = pick(in);
  if (in.ConsumeBool()) {  // the curvature dial's form
    s.surface.curvature_given = pick(in);
    resolve_curvature(s.surface);
  }
  s.body.model = in.ConsumeBool() ? BodyModel::rigid : BodyModel::affine;
  s.body.mass = pick(in);
  s.body.inertia = pick(in);
  if (in.ConsumeBool()) s.potential.radial = RadialPotential{pick(in)};
  switch (in.ConsumeIntegralInRange(0, 2)) {
    case 1: s.potential.deformation = AbcPotential{pick(in), pick(in), pick(in)}; break;
    case 2:
      s.potential.deformation =
          PolarPotential{pick(in), pick(in), in.ConsumeBool() ? PolarForm::cot2 : PolarForm::literal};
      break;
    default: break;
  }
  InitialState& q = s.initial;
  for (double* field : {&q.r, &q.phi, &q.alpha, &q.beta, &q.lambda, &q.mu, &q.r_dot, &q.phi_dot, &q.alpha_dot,
                        &q.beta_dot, &q.lambda_dot, &q.mu_dot})
    *field = pick(in);
  if (in.ConsumeBool()) q.mu = q.lambda;  // isotropic and rigid bodies
  if (s.body.model == BodyModel::rigid && in.ConsumeBool()) q.lambda_dot = q.mu_dot = 0.0;
  const auto catalog = integrator_catalog();
  const std::size_t k = in.ConsumeIntegralInRange<std::size_t>(0, catalog.size());
  s.integrator.name = k == catalog.size() ? std::string(kAutoIntegrator) : std::string(catalog[k].info.name);
  s.integrator.dt = pick(in);
  s.integrator.tolerance = in.ConsumeBool() ? 1e-10 : pick(in);
  s.on_degenerate = in.ConsumeBool() ? OnDegenerate::stop : OnDegenerate::report;
  return s;
}

bool finite(const std::optional<double>& v) {
  return !v || std::isfinite(*v);
}

void check_outputs(const Scene& scene, const State& state) {
  if (!state.y.allFinite()) violated("a non-finite state", scene);
  if (!std::isfinite(energy(scene, state))) violated("a non-finite energy", scene);
  const PaperCoordinates c = paper_coordinates(scene, state);
  for (double v : {c.r, c.lambda, c.mu, c.lambda_dot, c.mu_dot, c.p_phi, c.p_alpha, c.p_beta, c.p_lambda,
                   c.p_mu, c.det_L})
    if (!std::isfinite(v)) violated("a non-finite paper coordinate", scene);
  for (const auto& v :
       {c.phi, c.alpha, c.beta, c.theta, c.r_dot, c.phi_dot, c.alpha_dot, c.beta_dot, c.theta_dot, c.p_r})
    if (!finite(v)) violated("a non-finite defined paper coordinate", scene);
  if (!c.X.allFinite()) violated("a non-finite position", scene);
}

// The scene with numbers a person might type (each field outside a moderate range replaced by a
// fixed moderate value): the oracle's comparison is meaningful and quick for those, and most inputs
// give one.
std::optional<Scene> tamed(Scene s) {
  auto tame = [](double& v, double lo, double hi, double fallback) {
    if (!(v == 0.0 || (std::abs(v) >= lo && std::abs(v) <= hi))) v = fallback;
  };
  if (s.surface.kind == SurfaceKind::plane) s.surface.radius = 1.0;
  tame(s.surface.radius, 0.2, 10.0, 1.0);
  s.surface.radius = std::abs(s.surface.radius) > 0 ? std::abs(s.surface.radius) : 1.0;
  s.surface.curvature_given.reset();
  tame(s.body.mass, 0.1, 10.0, 1.0);
  tame(s.body.inertia, 0.05, 10.0, 0.2);
  s.body.mass = std::abs(s.body.mass) > 0 ? std::abs(s.body.mass) : 1.0;
  s.body.inertia = std::abs(s.body.inertia) > 0 ? std::abs(s.body.inertia) : 0.2;
  if (s.potential.radial) {
    tame(s.potential.radial->gamma, 1e-3, 1.0, 0.05);
    s.potential.radial->gamma = std::abs(s.potential.radial->gamma);  // g < 0 falls into the pole (§5)
  }
  if (auto* abc = std::get_if<AbcPotential>(&s.potential.deformation))
    for (double* v : {&abc->A, &abc->B, &abc->C}) tame(*v, 1e-3, 1.0, 0.1);
  if (auto* polar = std::get_if<PolarPotential>(&s.potential.deformation))
    for (double* v : {&polar->ghat, &polar->gtilde}) tame(*v, 1e-3, 1.0, 0.1);
  InitialState& q = s.initial;
  const double R = s.surface.radius;
  tame(q.r, 1e-2, s.surface.kind == SurfaceKind::pseudosphere ? 10.0 * R : 10.0, 1.0);
  q.r = std::abs(q.r);
  if (s.surface.kind == SurfaceKind::sphere && q.r > std::numbers::pi * R) q.r = 0.5 * R;
  for (double* v : {&q.phi, &q.alpha, &q.beta}) tame(*v, 1e-3, 10.0, 0.3);
  for (double* v : {&q.lambda, &q.mu}) tame(*v, 0.05, 10.0, 0.8);
  for (double* v : {&q.r_dot, &q.alpha_dot, &q.beta_dot, &q.lambda_dot, &q.mu_dot}) tame(*v, 1e-3, 10.0, 0.1);
  const double S = polar_S(s.surface, q.r);
  if (!(std::abs(q.phi_dot * S) <= 10.0)) q.phi_dot = 0.1;
  if (std::abs(q.lambda - q.mu) != 0.0 && std::abs(q.lambda - q.mu) < 1e-2) q.mu = q.lambda;
  if (!validate_scene(s).empty()) return std::nullopt;
  return s;
}

void compare_with_oracle(const Scene& found, double t_end) {
  const std::optional<Scene> scene = tamed(found);
  if (!scene || !(t_end > 0.0)) return;
  const double horizon = std::min(t_end, 0.25);
  nlohmann::json j = scene_to_json(*scene);
  j["on_degenerate"] = "report";
  const std::string text = j.dump();
  const oracle::OracleScene os = oracle::read_scene(text);
  const oracle::OracleRun reference = oracle::run_oracle(os, horizon, 1e-20, oracle::Precision::quad, 400);
  if (!reference.ok || !std::isfinite(reference.energy_scale)) return;  // too stiff for a quick reference
  for (const char* name : {"exact", "dop853", "auto"}) {
    const oracle::IntegratorCase c{name, 0.01, 1e-12, 1e-6};
    const oracle::Verdict v = oracle::check(text, c, horizon, os, reference, 20000);
    if (v.refused || v.incomplete || v.pass) continue;
    std::fprintf(stderr, "%s at t = %g: error %g (position %g, frame %g, energy %g) %s\n", name, horizon,
                 v.error, v.diff.position, v.diff.frame, v.diff.energy, v.message.c_str());
    violated("disagrees with the oracle", *parse_scene_text(v.scene_json).scene);
  }
}

}  // namespace
}  // namespace spinfold

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace spinfold;
  FuzzedDataProvider in(data, size);
  const Scene scene = scene_from(in);
  const double t_end = in.ConsumeFloatingPointInRange(0.0, 5.0);

  const std::vector<FieldError> errors = validate_scene(scene);
  for (const FieldError& e : errors)
    if (e.field.empty() || e.reason.empty()) violated("an error without a field or a reason", scene);
  if (!errors.empty()) return 0;

  const nlohmann::json written = scene_to_json(scene);
  const SceneParse reread = parse_scene(written);
  if (!reread.scene) violated("the scene's own JSON is rejected", scene);
  if (scene_to_json(*reread.scene) != written)
    violated("the scene's JSON does not read back to itself", scene);

  Simulation run = start_simulation(scene);
  check_outputs(scene, run.state);
  constexpr std::uint64_t kAttempts = 3000;
  const bool complete = advance_to(run, t_end, kAttempts);
  check_outputs(scene, run.state);
  if (complete && run.state.status == Status::ok && run.state.t != t_end)
    violated("an ok run that ended before the requested time", scene);

  Simulation again = start_simulation(scene);
  advance_to(again, t_end, kAttempts);
  if (again.state.y.size() != run.state.y.size() ||
      std::memcmp(again.state.y.data(), run.state.y.data(), sizeof(double) * run.state.y.size()) != 0 ||
      again.state.status != run.state.status)
    violated("the same scene gave different bits", scene);
  // one input in 16 (by its bytes, so a replay does the same): keeps the fuzz stage's time
  unsigned sum = 0;
  for (std::size_t i = 0; i < size; ++i) sum += data[i];
  if (sum % 16 == 0) compare_with_oracle(scene, t_end);
  return 0;
}
