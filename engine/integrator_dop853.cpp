// Dormand–Prince 8(5,3): explicit Runge–Kutta of order 8, 12 evaluations per step, with the
// combined 5th- and 3rd-order error estimate and step control of Hairer, Nørsett & Wanner,
// "Solving Ordinary Differential Equations I", 2nd ed., §II.10 (coefficients from that source).
#include <algorithm>
#include <cmath>

#include "engine/integrator.h"

namespace spinfold {

const IntegratorInfo dop853_info{
    "dop853", 8, false, true, false, "adaptive Dormand-Prince 8(5,3), error controlled per step"};

namespace {

constexpr int kStages = 12;

// Butcher tableau, row i holds a_{i+1, j+1} (zeros where the method has none).
constexpr double a[kStages][kStages] = {
    {},
    {5.26001519587677318785587544488e-2},
    {1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2},
    {2.95875854768068491816892993775e-2, 0, 8.87627564304205475450678981324e-2},
    {2.41365134159266685502369798665e-1, 0, -8.84549479328286085344864962717e-1,
     9.24834003261792003115737966543e-1},
    {3.7037037037037037037037037037e-2, 0, 0, 1.70828608729473871279604482173e-1,
     1.25467687566822425016691814123e-1},
    {3.7109375e-2, 0, 0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2,
     -1.7578125e-2},
    {3.70920001185047927108779319836e-2, 0, 0, 1.70383925712239993810214054705e-1,
     1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2,
     8.27378916381402288758473766002e-3},
    {6.24110958716075717114429577812e-1, 0, 0, -3.36089262944694129406857109825e0,
     -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1,
     2.01540675504778934086186788979e1, -4.34898841810699588477366255144e1},
    {4.77662536438264365890433908527e-1, 0, 0, -2.48811461997166764192642586468e0,
     -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1,
     1.52792336328824235832596922938e1, -3.32882109689848629194453265587e1,
     -2.03312017085086261358222928593e-2},
    {-9.3714243008598732571704021658e-1, 0, 0, 5.18637242884406370830023853209e0,
     1.09143734899672957818500254654e0, -8.14978701074692612513997267357e0,
     -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1, 2.49360555267965238987089396762e0,
     -3.0467644718982195003823669022e0},
    {2.27331014751653820792359768449e0, 0, 0, -1.05344954667372501984066689879e1,
     -2.00087205822486249909675718444e0, -1.79589318631187989172765950534e1,
     2.79488845294199600508499808837e1, -2.85899827713502369474065508674e0,
     -8.87285693353062954433549289258e0, 1.23605671757943030647266201528e1,
     6.43392746015763530355970484046e-1},
};

// 8th-order weights.
constexpr double b[kStages] = {5.42937341165687622380535766363e-2,
                               0,
                               0,
                               0,
                               0,
                               4.45031289275240888144113950566e0,
                               1.89151789931450038304281599044e0,
                               -5.8012039600105847814672114227e0,
                               3.1116436695781989440891606237e-1,
                               -1.52160949662516078556178806805e-1,
                               2.01365400804030348374776537501e-1,
                               4.47106157277725905176885569043e-2};
// 3rd-order error estimate: b − bhh, with bhh on stages 1, 9 and 12.
constexpr double bhh1 = 0.244094488188976377952755905512e+00;
constexpr double bhh9 = 0.733846688281611857341361741547e+00;
constexpr double bhh12 = 0.220588235294117647058823529412e-01;
// 5th-order error estimate.
constexpr double er[kStages] = {0.1312004499419488073250102996e-01,
                                0,
                                0,
                                0,
                                0,
                                -0.1225156446376204440720569753e+01,
                                -0.4957589496572501915214079952e+00,
                                0.1664377182454986536961530415e+01,
                                -0.3503288487499736816886487290e+00,
                                0.3341791187130174790297318841e+00,
                                0.8192320648511571246570742613e-01,
                                -0.2235530786388629525884427845e-01};

constexpr double kSafety = 0.9;
constexpr double kMaxShrink = 1.0 / 0.333;  // h may shrink by at most 3x after a rejection
constexpr double kMaxGrow = 6.0;

class Dop853 final : public Integrator {
 public:
  const IntegratorInfo& info() const override { return dop853_info; }

  StepResult try_step(const StepProblem& f, const Coords& y, double h, double tolerance,
                      Coords& increment) override {
    const Eigen::Index n = y.size();
    for (int i = 0; i < kStages; ++i) {
      stage_ = y;
      for (int j = 0; j < i; ++j)
        if (a[i][j] != 0.0) stage_ += (h * a[i][j]) * k_[j];
      f(stage_, k_[i]);
    }
    Coords slope = Coords::Zero(n), err5 = Coords::Zero(n);
    for (int i = 0; i < kStages; ++i) {
      if (b[i] != 0.0) slope += b[i] * k_[i];
      if (er[i] != 0.0) err5 += er[i] * k_[i];
    }
    increment = h * slope;
    const Coords y_next = y + increment;
    const Coords err3 = slope - bhh1 * k_[0] - bhh9 * k_[8] - bhh12 * k_[11];

    double sum5 = 0.0, sum3 = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double sk = tolerance * (1.0 + std::max(std::abs(y[i]), std::abs(y_next[i])));
      sum5 += (err5[i] / sk) * (err5[i] / sk);
      sum3 += (err3[i] / sk) * (err3[i] / sk);
    }
    double denominator = sum5 + 0.01 * sum3;
    if (denominator <= 0.0) denominator = 1.0;
    const double err = std::abs(h) * sum5 * std::sqrt(1.0 / (static_cast<double>(n) * denominator));
    if (!std::isfinite(err)) return {false, h / kMaxShrink};

    const double fac = std::pow(err, 1.0 / 8.0) / kSafety;
    if (err <= 1.0) return {true, h / std::clamp(fac, 1.0 / kMaxGrow, kMaxShrink)};
    return {false, h / std::min(kMaxShrink, fac)};
  }

 private:
  Coords k_[kStages];
  Coords stage_;
};

}  // namespace

std::unique_ptr<Integrator> make_dop853() {
  return std::make_unique<Dop853>();
}

}  // namespace spinfold
