// A run: a scene, its evolving state and the integrator that advances it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "engine/exact_solution.h"
#include "engine/integrator.h"
#include "engine/scene.h"
#include "engine/state.h"

namespace spinfold {

// det L crossed zero: the frame was squashed to a segment and came out mirrored (physics.md §2).
struct DegenerateEvent {
  double t = 0.0;  // time of the crossing [time], located to ~1e-12 of the step
};

struct Simulation {
  Scene scene;
  State state;
  const IntegratorInfo* info = nullptr;    // the integrator that runs (auto resolved)
  std::unique_ptr<Integrator> integrator;  // null when the exact solution runs
  std::optional<ExactSolution> exact;
  double h_next = 0.0;   // next trial step [time]
  Coords carry;          // compensated-summation remainder of the state (round-off not yet added)
  double t_carry = 0.0;  // the same for the time [time]
  double initial_energy = 0.0;  // [energy]
  double energy_scale = 0.0;    // kinetic + |potential| energy at the start [energy]: the yardstick
                                // of divergence
  double start_time = 0.0;  // [time] at which the scene's initial state holds
  std::vector<DegenerateEvent> events;
  std::uint64_t steps = 0;      // accepted steps
  std::uint64_t rejected = 0;   // rejected step attempts
  std::uint64_t recentres = 0;  // chart moves
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
bool advance_to(Simulation& run, double t_end, std::uint64_t max_attempts = kNoStepLimit);

// det L of the current state (frame-independent; λ₀² for the rigid model).
double det_L(const Scene& scene, const State& state);

}  // namespace spinfold
