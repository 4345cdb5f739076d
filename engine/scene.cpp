#include "engine/scene.h"

namespace spinfold {

Scene companion_scene(const Scene& scene, std::size_t i) {
  const Companion& c = scene.companions.at(i);
  Scene out;
  out.name = scene.name;
  out.surface = scene.surface;
  out.body = c.body;
  out.potential = {scene.potential.radial, c.deformation, scene.potential.height};
  out.friction = scene.friction;
  out.initial = c.initial;
  out.integrator = c.integrator;
  out.on_degenerate = scene.on_degenerate;
  return out;
}

std::string main_body_label(const Scene& scene) {
  return scene.main_label.empty() ? "body 1" : scene.main_label;
}

std::string companion_label(const Scene& scene, std::size_t i) {
  const std::string& label = scene.companions.at(i).label;
  return label.empty() ? "body " + std::to_string(i + 2) : label;
}

}  // namespace spinfold
