// Frame cost: build_scene, GL render and PNG encoding per frame size and layer set, against the
// bare OSMesa + libpng loop with the same geometry, measured in the same run.
#pragma once

namespace spinfold::bench {

int run_render_bench(int frames);

}  // namespace spinfold::bench
