// Order-4 splitting: Yoshida's triple jump of Strang steps, w₁ = 1/(2 − 2^{1/3}), w₀ = 1 − 2w₁.
#include <cmath>

#include "engine/splitting.h"

namespace spinfold {

const IntegratorInfo split4_info{
    "split4", 4, true, false, false, "exact orbit/internal flows + potential kicks, triple-jump composition",
    true};

std::unique_ptr<Integrator> make_split4() {
  const double w1 = 1.0 / (2.0 - std::cbrt(2.0)), w0 = 1.0 - 2.0 * w1;
  return std::make_unique<SplittingComposition>(split4_info, std::vector<double>{w1, w0, w1});
}

}  // namespace spinfold
