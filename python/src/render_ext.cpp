// voxr._render: voxr::render (include/voxr/render.h) for Python, behind voxr.render (python/voxr/render.py).
//   RenderSettings  the C++ struct, one attribute per `voxr render` flag (same names and defaults)
//   render(settings) -> (float32 ndarray (H, W, 4), report JSON text, warnings list)
// The image array owns the std::vector voxr::render returned (no copy: a capsule deletes it with the array);
// the GIL is released while rendering. A voxr::Error becomes voxr.Error (RuntimeError when the voxr package
// cannot be imported) with voxr's one-line message.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <utility>
#include <vector>

#include "voxr/render.h"

namespace nb = nanobind;

namespace {

using Image = nb::ndarray<nb::numpy, float, nb::shape<-1, -1, 4>, nb::c_contig>;

[[noreturn]] void raise_voxr_error(const char* message) {
  PyObject* type = PyExc_RuntimeError;
  nb::object error;
  try {
    error = nb::module_::import_("voxr").attr("Error");
    type = error.ptr();
  } catch (const nb::python_error&) {
    // voxr not importable (the module loaded on its own): a RuntimeError, as voxr.Error is one.
  }
  PyErr_SetString(type, message);
  throw nb::python_error();
}

nb::tuple render(const voxr::RenderSettings& settings) {
  voxr::RenderedImage image;
  try {
    nb::gil_scoped_release released;
    image = voxr::render(settings);
  } catch (const voxr::Error& e) {
    raise_voxr_error(e.what());
  }
  auto pixels = std::make_unique<std::vector<float>>(std::move(image.rgba));
  float* data = pixels->data();
  nb::capsule owner(pixels.get(), [](void* p) noexcept { delete static_cast<std::vector<float>*>(p); });
  pixels.release();  // the capsule owns it now
  Image array(data, {size_t(image.height), size_t(image.width), size_t(4)}, owner);
  return nb::make_tuple(array, image.report_json, image.warnings);
}

}  // namespace

NB_MODULE(_render, m) {
  m.doc() = "voxr's renderer (voxr::render); use voxr.render";
  nb::class_<voxr::RenderSettings>(m, "RenderSettings", "The flags of `voxr render` (docs/cli.md)")
      .def(nb::init<>())
      .def_rw("scene", &voxr::RenderSettings::scene)
      .def_rw("shadows", &voxr::RenderSettings::shadows)
      .def_rw("refraction", &voxr::RenderSettings::refraction)
      .def_rw("width", &voxr::RenderSettings::width)
      .def_rw("height", &voxr::RenderSettings::height)
      .def_rw("device", &voxr::RenderSettings::device)
      .def_rw("shadow_res", &voxr::RenderSettings::shadow_res)
      .def_rw("res", &voxr::RenderSettings::res)
      .def_rw("mode", &voxr::RenderSettings::mode)
      .def_rw("bias", &voxr::RenderSettings::bias)
      .def_rw("normal_offset", &voxr::RenderSettings::normal_offset)
      .def_rw("refraction_grid", &voxr::RenderSettings::refraction_grid)
      .def_rw("coarse_res", &voxr::RenderSettings::coarse_res)
      .def_rw("step", &voxr::RenderSettings::step)
      .def_rw("normals", &voxr::RenderSettings::normals)
      .def_rw("angle_threshold", &voxr::RenderSettings::angle_threshold)
      .def_rw("layers", &voxr::RenderSettings::layers)
      .def_rw("layer_res", &voxr::RenderSettings::layer_res)
      .def_rw("dm_depth", &voxr::RenderSettings::dm_depth)
      .def_rw("frames", &voxr::RenderSettings::frames)
      .def_rw("error_target", &voxr::RenderSettings::error_target)
      .def_rw("compare_reference", &voxr::RenderSettings::compare_reference);
  m.def("render", &render, nb::arg("settings"),
        "Renders as `voxr render` does: (float32 (H, W, 4) image, report JSON, warnings).");
}
