// `spinfold integrators`: the integrator catalog.
#include <cstdio>
#include <string>

#include "cli/commands/command.h"
#include "engine/integrator.h"

namespace spinfold::cli {

namespace {

int list_integrators() {
  std::printf("%-18s %5s %10s %8s %5s  %s\n", "name", "order", "symplectic", "adaptive", "exact", "summary");
  for (const CatalogEntry& e : integrator_catalog()) {
    const IntegratorInfo& i = e.info;
    std::printf("%-18s %5d %10s %8s %5s  %s\n", std::string(i.name).c_str(), i.order,
                i.symplectic ? "yes" : "no", i.adaptive ? "yes" : "no", i.exact ? "yes" : "no",
                std::string(i.summary).c_str());
  }
  return 0;
}

}  // namespace

Command register_integrators(CLI::App& app) {
  return {app.add_subcommand("integrators", "Print the integrator catalog"),
          [](int, char**) { return list_integrators(); }};
}

}  // namespace spinfold::cli
