// The physical alternatives to the paper's initial rates: spin, speed and heading (physics.md §3).
// A scene may give them instead of alpha_dot, r_dot and phi_dot (engine/scene.h InitialState);
// resolve_initial_rates fills those rates from them, and spin_of, speed_of and heading_of read
// them back off the rates. Plain functions of a scene, no JSON.
#pragma once

#include <vector>

#include "engine/scene.h"
#include "engine/validation.h"

namespace spinfold {

// Fills the rates from the physical fields of scene.initial that are set: first r_dot = v cos h and
// φ̇ = v sin h / S(r) from speed v and heading h, then α̇ = (s/J + 2λμβ̇)/(λ² + μ²) − C(r)φ̇ from spin s
// (with that φ̇). Returns the errors (paths relative to the scene, "initial.heading"): speed without
// heading or the other way round, a heading off E₁ at a pole (S = 0, where E₂ is undefined), a rate
// that is not a finite number. On errors the scene is left unchanged. Values the validator rejects
// anyway (non-finite, out of range) are left to validate_scene.
std::vector<FieldError> resolve_initial_rates(Scene& scene);

// s = p_α = J[(λ² + μ²)(α̇ + C(r)φ̇) − 2λμβ̇] [mass·length²/time] of the scene's initial rates
// (physics.md §3; rigid, λ = μ = λ₀: 2Jλ₀²(α̇ − β̇ + Cφ̇), §8.8).
double spin_of(const Scene& scene);
// v = √(ṙ² + S(r)²φ̇²) [length/time] of the scene's initial rates.
double speed_of(const Scene& scene);
// h = atan2(S(r)φ̇, ṙ) ∈ [−π, π] [rad]: the angle of the initial velocity from E₁ = ∂/∂r towards
// E₂ = (1/S)∂/∂φ (0 when the body is at rest).
double heading_of(const Scene& scene);

}  // namespace spinfold
