// libFuzzer target: arbitrary text through the formula language (engine/formula.h), the safety
// boundary for a surface typed into the page or sent to the API. Properties (a violation aborts): no
// crash, no exception and no sanitizer report on any input; a refusal has a reason and a position
// within the text; an accepted formula is within the caps, evaluates without a fault at a point, and
// its jet's value is its double evaluation's.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/formula.h"
#include "fuzz/text_property.h"

using spinfold::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace spinfold;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const FormulaParameters parameters = {{"a", 1.5}, {"b", -0.25}, {"c", 2.0}};
  const FormulaParse parsed = parse_formula(text, parameters);
  if (!parsed.formula) {
    if (parsed.error.reason.empty()) violated("a refusal without a reason", text);
    if (parsed.error.position > text.size() && parsed.error.position != kMaxFormulaLength)
      violated("a refusal's position beyond the text", text);
    return 0;
  }
  if (text.size() > kMaxFormulaLength) violated("a formula over the length cap accepted", text);
  for (const FormulaWarning& w : parsed.formula->warnings())
    if (w.reason.empty() || w.position >= text.size())
      violated("a warning without a reason or a place", text);
  const Eigen::Vector3d X(0.3, -0.7, 1.1);
  const double value = parsed.formula->value(X);
  const FormulaJet jet = parsed.formula->jet(X);
  if (!(std::isnan(value) && std::isnan(jet.value)) && value != jet.value)
    violated("the jet's value differs from the double evaluation", text);
  if (parsed.formula->identity().empty()) violated("an accepted formula with no program", text);
  return 0;
}
