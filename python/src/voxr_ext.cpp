// voxr._core: nanobind bindings of the public C++ API (include/voxr/voxr.h). The Python-facing layer
// (argument checks, mesh adapters, VoxelGrid) is python/voxr/*.py; this file is thin on purpose:
//  - every voxr::Error becomes voxr.Error (a RuntimeError) with voxr's one-line message;
//  - device work (Context creation, voxelize, save) and the bit expansion of occupancy/inside run with the
//  GIL
//    released; a Context runs one call at a time (its mutex), as voxr::Context requires;
//  - the attribute channels are zero-copy read-only NumPy views whose owner is the Volume object (which holds
//    the C++ VoxelVolume), so a view outlives the VoxelGrid that handed it out;
//  - occupancy and inside are one byte per voxel expanded from the device's bits (the one unavoidable copy),
//    made once per volume and cached, shaped (nx, ny, nz) with Fortran strides over the x-fastest buffer.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/unique_ptr.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <utility>

#include "voxr/voxr.h"

namespace nb = nanobind;

namespace {

// A voxr::Context with the lock that keeps it to one run at a time across Python threads (the GIL is
// released while it runs).
struct ContextHandle {
  explicit ContextHandle(const std::string& device) : context(device) {}
  voxr::Context context;
  std::mutex run;
};

// A voxelization result and its lazily expanded dense masks.
struct VolumeHandle {
  explicit VolumeHandle(voxr::VoxelVolume v) : volume(std::move(v)) {}
  voxr::VoxelVolume volume;
  std::mutex expand;                           // one expansion at a time (the GIL is released during it)
  std::unique_ptr<uint8_t[]> occupancy_bytes;  // nx*ny*nz bytes, 0/1, x fastest; null until first asked
  std::unique_ptr<uint8_t[]> inside_bytes;

  uint64_t voxel_count() const {
    const auto d = volume.dims();
    return uint64_t(d[0]) * d[1] * d[2];
  }
};

nb::dict device_dict(const voxr::DeviceDescription& d) {
  nb::dict out;
  out["id"] = d.id;
  out["name"] = d.name;
  out["platform"] = d.platform;
  out["type"] = d.type;
  out["driver_version"] = d.driver_version;
  out["compute_units"] = d.compute_units;
  out["global_memory"] = d.global_memory;
  out["max_allocation"] = d.max_allocation;
  return out;
}

using Positions = nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using Triangles = nb::ndarray<const uint32_t, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;
using Materials = nb::ndarray<const uint32_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

voxr::MeshView mesh_view(const Positions& positions, const Triangles& triangles,
                         const std::optional<Materials>& materials, const std::string& name) {
  voxr::MeshView mesh;
  mesh.positions = {positions.data(), positions.shape(0) * 3};
  mesh.triangles = {triangles.data(), triangles.shape(0) * 3};
  if (materials) mesh.materials = {materials->data(), materials->shape(0)};
  mesh.name = name;
  return mesh;
}

// The dense 0/1 bytes of occupancy (inside == false) or the interior, expanded once and kept; returned as a
// read-only bool (nx, ny, nz) view indexed [x, y, z] whose owner is `self`.
nb::ndarray<nb::numpy, const bool, nb::ndim<3>> dense_mask(VolumeHandle& self, bool inside) {
  const auto d = self.volume.dims();
  const uint64_t n = self.voxel_count();
  const uint8_t* data = nullptr;
  {
    nb::gil_scoped_release release;
    std::lock_guard lock(self.expand);
    auto& bytes = inside ? self.inside_bytes : self.occupancy_bytes;
    if (!bytes) {
      std::unique_ptr<uint8_t[]> fresh;
      try {
        fresh = std::make_unique_for_overwrite<uint8_t[]>(n);
      } catch (const std::bad_alloc&) {
        throw voxr::Error("a dense " + std::string(inside ? "inside" : "occupancy") + " array of the " +
                          std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) +
                          " grid needs " + std::to_string(n) +
                          " bytes, more than this process can allocate; use occupied_indices()");
      }
      if (inside)
        self.volume.inside({fresh.get(), n});
      else
        self.volume.occupancy({fresh.get(), n});
      bytes = std::move(fresh);
    }
    data = bytes.get();
  }
  const size_t shape[3] = {d[0], d[1], d[2]};
  const int64_t strides[3] = {1, int64_t(d[0]), int64_t(d[0]) * int64_t(d[1])};  // in elements
  // NumPy's bool is one byte holding 0 or 1: the bytes are used as they are.
  return nb::ndarray<nb::numpy, const bool, nb::ndim<3>>(reinterpret_cast<const bool*>(data), 3, shape,
                                                         nb::find(&self), strides);
}

// A read-only view of `count` entries of `width` values (width 1: a vector) owned by `self`.
template <class T>
nb::ndarray<nb::numpy, const T> channel_view(VolumeHandle& self, std::span<const T> values, size_t width) {
  const size_t rows = width ? values.size() / width : 0;
  const size_t shape[2] = {rows, width};
  return nb::ndarray<nb::numpy, const T>(values.data(), width == 1 ? 1 : 2, shape, nb::find(&self));
}

}  // namespace

NB_MODULE(_core, m) {
  m.doc() = "voxr's compiled core (nanobind). Use the `voxr` package, not this module.";

  nb::exception<voxr::Error>(m, "Error", PyExc_RuntimeError);

  m.def("version", &voxr::version, "The C++ library's version, 'major.minor.patch'.");
  m.def(
      "devices",
      [] {
        std::vector<voxr::DeviceDescription> list;
        {
          nb::gil_scoped_release release;
          list = voxr::devices();
        }
        nb::list out;
        for (const auto& d : list) out.append(device_dict(d));
        return out;
      },
      "Every OpenCL device as a dict (id, name, platform, type, driver_version, compute_units, "
      "global_memory, "
      "max_allocation).");

  nb::class_<voxr::VoxelizeSettings>(m, "Settings", "voxr::VoxelizeSettings: the flags of `voxr voxelize`.")
      .def(nb::init<>())
      .def_rw("resolution", &voxr::VoxelizeSettings::resolution)
      .def_rw("dims", &voxr::VoxelizeSettings::dims)
      .def_rw("bounds", &voxr::VoxelizeSettings::bounds)
      .def_rw("method", &voxr::VoxelizeSettings::method)
      .def_rw("mode", &voxr::VoxelizeSettings::mode)
      .def_rw("slicing", &voxr::VoxelizeSettings::slicing)
      .def_rw("channels", &voxr::VoxelizeSettings::channels)
      .def_rw("solid", &voxr::VoxelizeSettings::solid)
      .def_rw("layout", &voxr::VoxelizeSettings::layout)
      .def_rw("memory_budget", &voxr::VoxelizeSettings::memory_budget)
      .def_rw("device", &voxr::VoxelizeSettings::device);

  nb::class_<VolumeHandle>(m, "Volume", "voxr::VoxelVolume; wrapped by voxr.VoxelGrid.")
      .def_prop_ro("dims", [](const VolumeHandle& v) { return v.volume.dims(); })
      .def_prop_ro("voxel_size", [](const VolumeHandle& v) { return v.volume.voxel_size(); })
      .def_prop_ro("index_to_world", [](const VolumeHandle& v) { return v.volume.index_to_world(); })
      .def_prop_ro("channels", [](const VolumeHandle& v) { return v.volume.channels(); })
      .def_prop_ro("sparse", [](const VolumeHandle& v) { return v.volume.sparse(); })
      .def_prop_ro("voxels_set", [](const VolumeHandle& v) { return v.volume.voxels_set(); })
      .def_prop_ro("inside_voxels", [](const VolumeHandle& v) { return v.volume.inside_voxels(); })
      .def_prop_ro("report_json", [](const VolumeHandle& v) { return v.volume.report().json; })
      .def_prop_ro("warnings", [](const VolumeHandle& v) { return v.volume.report().warnings; })
      .def("occupancy", [](VolumeHandle& v) { return dense_mask(v, false); })
      .def("inside", [](VolumeHandle& v) { return dense_mask(v, true); })
      .def("occupied_indices",
           [](VolumeHandle& v) {
             const uint64_t n = v.volume.voxels_set();
             auto buffer = std::make_unique_for_overwrite<uint32_t[]>(n * 3);
             {
               nb::gil_scoped_release release;
               v.volume.occupied_indices({buffer.get(), n * 3});
             }
             uint32_t* data = buffer.get();
             nb::capsule owner(
                 data, [](void* p) noexcept { std::unique_ptr<uint32_t[]>(static_cast<uint32_t*>(p)); });
             buffer.release();
             const size_t shape[2] = {size_t(n), 3};
             return nb::ndarray<nb::numpy, uint32_t, nb::ndim<2>>(data, 2, shape, owner);
           })
      .def("count", [](VolumeHandle& v) { return channel_view(v, v.volume.count(), 1); })
      .def("normal", [](VolumeHandle& v) { return channel_view(v, v.volume.normal(), 3); })
      .def("material", [](VolumeHandle& v) { return channel_view(v, v.volume.material(), 1); })
      .def("color", [](VolumeHandle& v) { return channel_view(v, v.volume.color(), 4); })
      .def(
          "save", [](const VolumeHandle& v, const std::string& path) { return v.volume.save(path); },
          nb::arg("path"), nb::call_guard<nb::gil_scoped_release>());

  nb::class_<ContextHandle>(m, "Context", "voxr::Context: one OpenCL device with its programs built.")
      .def(nb::init<const std::string&>(), nb::arg("device") = "", nb::call_guard<nb::gil_scoped_release>())
      .def_prop_ro("device", [](const ContextHandle& c) { return device_dict(c.context.device()); })
      .def(
          "voxelize",
          [](ContextHandle& c, const Positions& positions, const Triangles& triangles,
             const std::optional<Materials>& materials, const voxr::VoxelizeSettings& settings,
             const std::string& name) {
            const voxr::MeshView mesh = mesh_view(positions, triangles, materials, name);
            std::optional<voxr::VoxelVolume> volume;
            {
              nb::gil_scoped_release release;
              std::lock_guard lock(c.run);
              volume.emplace(c.context.voxelize(mesh, settings));
            }
            return std::make_unique<VolumeHandle>(std::move(*volume));
          },
          nb::arg("positions").noconvert(), nb::arg("triangles").noconvert(),
          nb::arg("materials").noconvert().none(), nb::arg("settings"), nb::arg("name") = "mesh")
      .def(
          "voxelize_file",
          [](ContextHandle& c, const std::string& path, const voxr::VoxelizeSettings& settings) {
            std::optional<voxr::VoxelVolume> volume;
            {
              nb::gil_scoped_release release;
              std::lock_guard lock(c.run);
              volume.emplace(c.context.voxelize_file(path, settings));
            }
            return std::make_unique<VolumeHandle>(std::move(*volume));
          },
          nb::arg("path"), nb::arg("settings"));
}
