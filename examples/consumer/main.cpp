// voxr's C++ package from a program of its own (examples/consumer, docs/library.md): voxelize a box built in
// code, show a voxr::Error from a bad call, render the built-in default scene small. scripts/package-check.sh
// builds it against the installed package and checks what it prints.
#include <voxr/render.h>
#include <voxr/voxr.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

int main() {
  try {
    // An axis-aligned box [0, 2] x [0, 1] x [0, 1]: 8 corners, 12 triangles wound outwards.
    const std::vector<double> positions = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0,
                                           0, 0, 1, 2, 0, 1, 2, 1, 1, 0, 1, 1};
    const std::vector<uint32_t> triangles = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                             1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    voxr::MeshView box;
    box.positions = positions;
    box.triangles = triangles;
    box.name = "box";

    voxr::VoxelizeSettings settings;
    settings.resolution = 32;
    settings.solid = "flood";
    const voxr::VoxelVolume volume = voxr::voxelize(box, settings);
    const std::array<uint32_t, 3> dims = volume.dims();
    std::printf("voxr %s\n", voxr::version().c_str());
    std::printf("dims %u %u %u\n", dims[0], dims[1], dims[2]);
    std::printf("voxels set %llu, inside %llu\n", static_cast<unsigned long long>(volume.voxels_set()),
                static_cast<unsigned long long>(volume.inside_voxels()));

    // A bad call throws voxr::Error with voxr's one-line message.
    try {
      voxr::VoxelizeSettings bad;
      bad.method = "sideways";
      voxr::voxelize(box, bad);
      std::printf("no error\n");
    } catch (const voxr::Error& e) {
      std::printf("error: %s\n", e.what());
    }

    // The default scene, 64 x 48 pixels, as `voxr render --size 64x48` renders it.
    voxr::RenderSettings render_settings;
    render_settings.width = 64;
    render_settings.height = 48;
    const voxr::RenderedImage image = voxr::render(render_settings);
    double sum[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < image.rgba.size(); ++i) sum[i % 4] += image.rgba[i];
    const double pixels = double(image.width) * image.height;
    std::printf("image %ux%u, mean rgba %.4f %.4f %.4f %.4f\n", image.width, image.height, sum[0] / pixels,
                sum[1] / pixels, sum[2] / pixels, sum[3] / pixels);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxr_consumer: %s\n", e.what());
    return 1;
  }
}
