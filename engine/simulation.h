// A run: a scene, its evolving state and the integrator that advances it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "engine/embedded_run.h"
#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/invariants.h"
#include "engine/run_summary.h"
#include "engine/scene.h"
#include "engine/state.h"
#include "engine/surface_model.h"

namespace spinfold {

// det L crossed zero: the frame was squashed to a segment and came out mirrored (physics.md §2).
// The most det L = 0 crossings a run keeps (800 kB): past it the run stops as too_many_events. Only
// the closed form can meet it cheaply (it jumps over any number of periods in one advance); a
// stepping run takes steps for each.
inline constexpr std::size_t kMaxDegenerateEvents = 100'000;

struct DegenerateEvent {
  double t = 0.0;  // time of the crossing [time], located to ~1e-12 of the step
};

// A point of the run's own step sequence, with what the next step continues from.
struct StepPoint {
  State state;
  Coords carry;          // compensated-summation remainder of the state (round-off not yet added)
  double t_carry = 0.0;  // the same for the time [time]
  double h_next = 0.0;   // next trial step [time]
};

// What the closed form is checked against at every state it gives (an independent check: these
// come from the segment's start state, not from the closed form): the conserved quantities of
// physics.md §6 and, at τ = 0, the start itself.
struct ExactCheck {
  bool start_ok = true;                        // the closed form at τ = 0 reproduces the start
  double spin = 0.0;                           // s
  double orbital_energy = 0.0;                 // E_orb [energy]
  double p_phi = 0.0;                          // p_φ of the scene's chart
  bool p_phi_checked = false;                  // p_φ of the start kept 8 digits (not far out on H²)
  std::optional<SeparatedEnergies> separated;  // C_x, C_y (isotropic affine body)
  double momentum_scale = 0.0;                 // what momenta are measured against [angular momentum]
};

struct Simulation {
  Scene scene;  // the parameters in force now
  State state;  // the state at the time last asked for (advance_to's t_end)
  // The run's own step sequence: only whole steps that end before the time asked for are taken
  // here, so where advances, play ticks or frame requests stop never changes it. `state` is reached
  // from it by a cut step (or a few), which is recomputed, never kept: replay is bit-exact.
  StepPoint grid;
  StepPoint checked;  // the last grid point whose energy and range were checked and found good
  const IntegratorInfo* info = nullptr;  // the integrator that runs (auto resolved)
  // The scene's surface resolved (engine/surface_model.h): what it offers, its F, charts and drawn piece.
  std::shared_ptr<const SurfaceModel> surface;
  // Where the curvature varies (engine/embedded_run.h): the chart-free scene and field that the
  // integrator steps; null on the sphere, pseudosphere and plane (their chart equations).
  std::shared_ptr<const EmbeddedScene> embedded;
  std::shared_ptr<const VectorField> field;
  std::unique_ptr<Integrator> integrator;  // null when the exact solution runs
  std::optional<ExactSolution> exact;      // from the state at segment_start
  ExactCheck exact_check;                  // what the closed form is checked against (exact only)
  bool exact_evaluated = false;            // the closed form of this segment was used (counted once in steps)
  double initial_energy = 0.0;             // H right after the last change (energy_reference_t) [energy]
  double energy_scale = 0.0;               // kinetic + |potential| energy then [energy]: the yardstick of
                                           // divergence
  double start_time = 0.0;                 // [time] at which the scene's initial state holds
  double segment_start = 0.0;              // [time] of the last change of parameters (start_time at first):
                                           // energy errors are measured from here (energy_reference_t)
  std::vector<DegenerateEvent> events;     // crossings on the step sequence
  std::vector<DegenerateEvent> view_events;  // crossings between the sequence and `state`
  std::uint64_t steps = 0;                   // accepted steps of the sequence
  std::uint64_t rejected = 0;                // rejected step attempts of the sequence
  std::uint64_t recentres = 0;               // chart moves of the sequence
  // What the run did (engine/run_summary.h): fed each step of the sequence when watch() started it;
  // `monitor_checked` is its copy at `checked`, so a stop on trouble rewinds it too.
  std::optional<RunMonitor> monitor, monitor_checked;
  // The companions' runs (scene.companions[i], companion_scene), advanced with this one to the same
  // times. A companion that stops keeps its last good state and status; the others go on.
  std::vector<Simulation> companions;
};

// The catalog name that runs for this scene: the scene's own, or for "auto" the exact solution
// when the scene has one and otherwise the integrator that is cheapest at the scene's tolerance.
std::string_view resolve_integrator(const Scene& scene);

// A run whose initial state (the scene's) is at time start_time [time]. The scene must have passed
// validate_scene.
Simulation start_simulation(const Scene& scene, double start_time = 0.0);

inline constexpr std::uint64_t kNoStepLimit = std::numeric_limits<std::uint64_t>::max();

// Advances the run to exactly t_end [time] unless its status stops it earlier. On numerical
// trouble the state stays at the last good step and the status says why. At most max_attempts
// step attempts (accepted or rejected; the exact solution makes one) are made: when they run out
// first, the function returns false with the state at the last accepted step and the status ok,
// and a later call continues from there. A stiff scene can need arbitrarily many steps; callers
// that serve others (the server, the fuzzers) bound the work of one call this way.
//
// Steppers take whole steps of their own sequence (run.grid) up to t_end and reach t_end by a cut
// step from there that is not kept, so the result at any t is the same however the run got
// there (one advance or many). The exact solution jumps from the last change.
bool advance_to(Simulation& run, double t_end, std::uint64_t max_attempts = kNoStepLimit);
// The same, spending `attempts` (what is left stays there): for callers that split one budget
// over several advances (trail samples). Companions are advanced after the main body, from the
// same budget; a companion's trouble stops only that companion.
bool advance_within(Simulation& run, double t_end, std::uint64_t& attempts);

// Changes the parameters at the current time and state: the body keeps its
// position, velocity, frame and frame rates; the new mass, inertia, potentials, radius and
// integrator act from here on; energy errors are measured from here. `next` must have passed
// validate_scene and have the same surface kind (a different surface is a different run) and as
// many companions: each companion is retuned to its new scene the same way.
//
// A curvature dial (the new scene gives surface.curvature, and the surface changed: `dialled`) may change the
// surface's kind: the body keeps its geodesic polar place (r, φ) about O, its velocity and frame in
// (E₁, E₂), so the motion continues through K = 0 (physics.md §16).
void retune(Simulation& run, const Scene& next);

// True when `after` gives its curvature and differs from `before` (retune continues through it).
bool dialled(const Surface& before, const Surface& after);
// Where a point of the scene's embedding on `before` goes on `after` as retune carries the body:
// the same (r, φ) after a dial, the same place in units of R after a radius change [length].
Vec3 carried_position(const Surface& before, const Surface& after, const Vec3& X);

// The det L = 0 crossings up to the current state that come after time `after` [time], oldest
// first: those of the step sequence and those between it and the state (each once).
std::vector<DegenerateEvent> events_after(const Simulation& run, double after);

// Starts summaries and events of the run from its current state (before it is advanced); refuses a
// spec check_monitor refuses (std::invalid_argument).
void watch(Simulation& run, MonitorSpec spec);
// The summaries' and events' values of the run so far, up to its current state (monitor_columns
// order): the sequence's steps and the cut step from the last of them to the state.
std::vector<double> monitor_values(const Simulation& run);

// The state `tau` after `from` [time], a point of the run's step sequence: one sub-step of the
// run's integrator from it (as the det L events are located), or the closed form at from.t + tau.
State state_after(const Simulation& run, const State& from, double tau);

// det L of the current state (frame-independent; λ₀² for the rigid model).
double det_L(const Scene& scene, const State& state);

}  // namespace spinfold
