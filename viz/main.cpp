// voxr-view: look at the volumes voxr writes. See view_options.cpp for the flags and viewer.cpp for the keys.
#include <cstdio>
#include <new>

#include "util/error.h"
#include "view_options.h"
#include "viewer.h"
#include "volume_loader.h"
#include "vtk_messages.h"

int main(int argc, char** argv) {
  using namespace voxr::view;
  install_vtk_message_collector();
  try {
    const std::optional<ViewOptions> options = parse_view_options(argc, argv);
    if (!options) return 0;
    Viewer viewer(load_volume(options->volume), *options);
    return viewer.run();
  } catch (const voxr::Error& e) {
    std::fprintf(stderr, "voxr-view: error: %s\n", e.what());
    return 1;
  } catch (const voxr::InternalError& e) {
    std::fprintf(stderr, "voxr-view: internal error (please report): %s\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "voxr-view: error: out of memory; the volume is too large to view\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxr-view: error: %s\n", e.what());
    return 1;
  }
}
