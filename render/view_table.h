// The view table: one row per view, pairing what the API, the CLI and the UI know of it (ViewInfo:
// name, surfaces, title, description) with its implementation, one file in render/views/ behind
// the ViewModel interface (render/views/view_model.h). Adding a view is one new file there and one
// row here (docs/architecture.md, "Adding a view").
#pragma once

#include <span>

#include "render/view.h"

namespace spinfold::render {

class ViewModel;

struct ViewRow {
  ViewInfo info;
  const ViewModel& (*model)();  // the view's one instance (render/views/<name>.cpp)
};

// Every view, in the order menus and help texts list them (views() is this table's infos).
std::span<const ViewRow> view_table();
// The implementation of a view (the table's first row's for a kind not in it, as view_info).
const ViewModel& view_model(ViewKind view);

}  // namespace spinfold::render
