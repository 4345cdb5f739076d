// The integrator interface and the catalog (one entry per integrator_<name>.cpp).
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string_view>

#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// A vector field dy/dt = f(y) given as a function.
using VectorField = std::function<void(const Coords& y, Coords& dydt)>;

// What a step integrates: Hamilton's equations of `scene` in `chart` (dynamics.h), callable as the
// autonomous vector field dy/dt = f(y); or, when `field` is set, that field (the chart-free
// equations of a surface whose curvature varies, engine/embedded_dynamics.h), which every method
// that asks only for f steps alike. Splitting methods also use the scene's structure, so they take
// only the first kind.
struct StepProblem {
  const Scene& scene;
  const Chart& chart;
  const VectorField* field = nullptr;
  void operator()(const Coords& y, Coords& dydt) const;
};

struct IntegratorInfo {
  std::string_view name;
  int order = 0;            // global order of accuracy
  bool symplectic = false;  // preserves the canonical symplectic form of the (L, P) chart
  bool adaptive = false;    // chooses its own step from the tolerance
  bool exact = false;       // closed-form solution, no stepping error
  std::string_view summary;
  // Composes the constant-curvature chart's exact flows (a splitting method): it steps only the
  // scene's chart equations, not a field given as a function (StepProblem::field).
  bool chart_flows_only = false;
};

struct StepResult {
  bool accepted = false;  // false: the increment is meaningless and the caller retries with h_next
  double h_next = 0.0;    // proposed next step [time]
};

// Contract: try_step never modifies y; on acceptance y + increment is the state after time h.
// The increment is returned rather than the new state so that the caller can add it with
// compensated summation (round-off then grows like √t, Brouwer's law). A non-finite increment
// must be rejected by the caller (the integrator may not notice it).
class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual const IntegratorInfo& info() const = 0;
  // One attempt at a step of size h [time] with the per-step error tolerance (adaptive methods).
  virtual StepResult try_step(const StepProblem& f, const Coords& y, double h, double tolerance,
                              Coords& increment) = 0;
};

struct CatalogEntry {
  IntegratorInfo info;
  std::unique_ptr<Integrator> (*make)();  // nullptr for the exact solver, which does not step
};

// The name that asks the engine to choose (see resolve_integrator in simulation.h).
inline constexpr std::string_view kAutoIntegrator = "auto";

std::span<const CatalogEntry> integrator_catalog();
// nullptr if the name is not in the catalog.
const CatalogEntry* find_integrator(std::string_view name);

// Factories, one per integrator file.
std::unique_ptr<Integrator> make_rk4();
std::unique_ptr<Integrator> make_dop853();
std::unique_ptr<Integrator> make_implicit_midpoint();
std::unique_ptr<Integrator> make_gauss4();
std::unique_ptr<Integrator> make_gauss6();
std::unique_ptr<Integrator> make_split4();
std::unique_ptr<Integrator> make_split6();
// Not in the catalog: `auto`'s adaptive split6 for the incompressible body (resolve_integrator).
std::unique_ptr<Integrator> make_split6_adaptive();
extern const IntegratorInfo rk4_info;
extern const IntegratorInfo dop853_info;
extern const IntegratorInfo implicit_midpoint_info;
extern const IntegratorInfo gauss4_info;
extern const IntegratorInfo gauss6_info;
extern const IntegratorInfo exact_info;
extern const IntegratorInfo split4_info;
extern const IntegratorInfo split6_info;
extern const IntegratorInfo split6_adaptive_info;

}  // namespace spinfold
