// How predictable a run is: the maximal Lyapunov exponent and MEGNO, by Benettin's two-trajectory
// method. A reference run of the scene and a shadow started d₀ away are advanced with the scene's
// own integrator to t₀ + kΔ; at each of these times the separation's growth g_k = ln(d_k/d₀) is
// summed and the shadow restarted d₀ away along the separation (the tangent flow of the
// integrator's own map, to O(d₀)):
//   λ(t_n)  = Σ g_k / (t_n − t₀)                                    [1/time]
//   Y(t_n)  = (2/(t_n − t₀)) Σ g_k (t_{k−1} + t_k − 2t₀)/2            MEGNO [1]
//   ⟨Y⟩(t_n) = (1/n) Σ Y(t_k)                                         its running mean [1]
// ⟨Y⟩ → 2 on a quasi-periodic orbit and grows like λt/2 on a chaotic one (Cincotta & Simó 2000;
// REBOUND's indicator). The separation is the Euclidean norm of the difference of X, V, e_A, W_A
// after the isometry that takes the reference body to the pole (on S², H² and the plane; the
// embedding itself where the curvature varies): the same wherever the body is, so neither a chart
// move nor the e^{r/R} of H²'s coordinates counts as growth. The shadow is restarted along the
// separation in the reference's canonical coordinates. docs/numerics.md has the method and its checks.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "engine/simulation.h"

namespace spinfold {

struct ChaosIndicators {
  double t = 0.0;  // the last renormalisation time reached [time]
  std::uint64_t intervals = 0;
  double lyapunov = std::numeric_limits<double>::quiet_NaN();    // λ [1/time]
  double megno = std::numeric_limits<double>::quiet_NaN();       // Y [1]
  double megno_mean = std::numeric_limits<double>::quiet_NaN();  // ⟨Y⟩ [1]
  // 1/λ [time]: an error grows e-fold in this time (infinite where λ ≤ 0).
  double lyapunov_time = std::numeric_limits<double>::quiet_NaN();
  std::string stopped;  // why the indicators end before the time asked for ("" when they do not)
  // Where they ended on a budget of advance_to (the others are the runs' own stops).
  bool out_of_steps = false, out_of_time = false;
};

inline constexpr double kDefaultChaosInterval = 1.0;  // Δ [time]
inline constexpr double kChaosSeparation = 1e-8;      // d₀, relative to the state's size [1]
// Far out on H² a chart's isometry has entries of size e^{r/R}, and relating the shadow's chart to the
// reference's rounds to e^{2r/R}·1e-16 of the state: at 5.5 R that is 6e-12, 1/1000 of d₀. The
// indicators stop there rather than measure rounding.
inline constexpr double kChaosMaxHyperbolicDistance = 5.5;  // [R]

// Why Δ cannot be used for a run to t_end (not finite and > 0, or more than 10⁶ intervals: each
// restarts the shadow), or nullopt.
std::optional<std::string> chaos_interval_refusal(double interval, double t_end);

// The columns the indicators add to a row or a summary, and their values.
inline constexpr std::array<std::string_view, 5> kChaosColumns = {
    "chaos.lyapunov", "chaos.megno", "chaos.megno_mean", "chaos.lyapunov_time", "chaos.t"};
std::array<double, 5> chaos_values(const ChaosIndicators& c);

class ChaosMonitor {
 public:
  // For the scene's main body (its companions are not followed), from the scene's initial state at
  // start_time; `interval` Δ > 0 [time].
  ChaosMonitor(const Scene& scene, double interval = kDefaultChaosInterval, double start_time = 0.0);
  // Through every t₀ + kΔ ≤ t (stops where either run stops), within `max_attempts` step attempts of
  // the two runs together and before `deadline` (a front door's --max-steps and --max-seconds, a
  // server's job: the indicators stop where they ran out, saying which).
  void advance_to(double t, std::uint64_t max_attempts = kNoStepLimit,
                  std::optional<std::chrono::steady_clock::time_point> deadline = std::nullopt);
  // The same, asking `go_on` between slices of step attempts (false: stop, as at a deadline; a
  // front door's Ctrl-C may throw from it).
  void advance_to(double t, std::uint64_t max_attempts, const std::function<bool()>& go_on);
  ChaosIndicators indicators() const;

 private:
  void seed_shadow();
  double separation(const State& shadow, const State& reference, const Chart& chart) const;

  Scene scene_;
  double interval_, t0_;
  Simulation reference_, shadow_;
  State start_reference_, start_shadow_;  // the interval's start
  std::uint64_t k_ = 0;
  double sum_g_ = 0.0, sum_weighted_g_ = 0.0, sum_megno_ = 0.0, megno_ = 0.0;
  bool stopped_ = false, out_of_steps_ = false, out_of_time_ = false;
  std::string stopped_reason_;
};

}  // namespace spinfold
