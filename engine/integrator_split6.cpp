// Order-6 splitting: Yoshida's seven-stage symmetric composition of Strang steps ("solution A",
// H. Yoshida, Phys. Lett. A 150 (1990) 262).
#include "engine/splitting.h"

namespace spinfold {

const IntegratorInfo split6_info{
    "split6", 6,     true,
    false,    false, "exact orbit/internal flows + potential kicks, Yoshida order-6 composition",
    true};

std::unique_ptr<Integrator> make_split6() {
  const double w1 = -1.17767998417887, w2 = 0.235573213359357, w3 = 0.784513610477560;
  const double w0 = 1.0 - 2.0 * (w1 + w2 + w3);
  return std::make_unique<SplittingComposition>(split6_info, std::vector<double>{w3, w2, w1, w0, w1, w2, w3});
}

}  // namespace spinfold
