// The physics across CPUs: glibc's libm picks FMA variants of sin, cos, exp, log at run time, so the
// last bits of a run depend on the CPU. Runs every catalog integrator on a few presets here and in
// a copy of this program with GLIBC_TUNABLES hiding FMA/AVX2 from glibc (a CPU without them), and
// reports the largest differences (docs/performance.md, "Across CPUs").
#pragma once

#include <string>
#include <vector>

namespace spinfold::bench {

struct CrossCpuOptions {
  double until = 100.0;  // [time]
  std::vector<std::string> scenes = {"spinning_rigid_sphere",       "breathing_ellipse_sphere",
                                     "spin_vs_geodesic_sphere",     "spinning_rigid_pseudosphere",
                                     "deforming_spin_pseudosphere", "spin_vs_geodesic_pseudosphere"};
  // The glibc tunable for the other CPU; glibc 2.36 takes the bare feature names (the older
  // "_Usable" names are silently ignored: the run would be this CPU's again).
  std::string tunable = "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX";
  bool dump = false;  // print this process's results (hex floats) instead of comparing
};

int run_cross_cpu(const CrossCpuOptions& options);

}  // namespace spinfold::bench
