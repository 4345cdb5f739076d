#pragma once

// A visitor made of lambdas, one per alternative: std::visit(Overloaded{[](A){..}, [](B){..}}, v).
namespace spinfold {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// clang 14 (the fuzz build) deduces no aggregate's template arguments without this guide.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace spinfold
