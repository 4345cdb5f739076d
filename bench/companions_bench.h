// What companions cost: a run with 8 companions against the same main body alone (engine, with and
// without the trail), for the closed form and a stepping integrator; and whether a scene without
// companions pays anything (its run against the same scene before the feature: the same code path,
// so the ratio of one body to itself measures the noise).
#pragma once

namespace spinfold::bench {

int run_companions_bench(int repeats, double until);

}  // namespace spinfold::bench
