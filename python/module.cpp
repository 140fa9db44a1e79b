// The compiled half of `import shadowlab` (python/shadowlab/__init__.py is the typed front):
// scenes, GBuffers, techniques, the reference, the metric, sweeps, tuning and the NSM features
// through the same library calls and flag rules as the programs (docs/python.md).
//
// Every call releases the GIL while it works. Bad input raises ValueError with the programs'
// "FLAG: reason" text (an InputError); notes the programs print after a successful run
// (core/notes.h) become Python warnings, and are dropped on an error, as the programs drop them.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "core/notes.h"
#include "core/parallel.h"
#include "lab/provenance.h"
#include "python/arrays.h"
#include "python/calls.h"

namespace py = pybind11;
using namespace shadowlab;
using namespace shadowlab::python;

namespace {

// Runs f without the GIL; the notes it held become warnings after it returns, and are dropped
// when it throws (the error is then the only message, as in run_main).
template <class F>
auto without_gil(F&& f) {
  try {
    auto r = [&] {
      py::gil_scoped_release release;
      return f();
    }();
    for (const std::string& line : take_notes())
      if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1) != 0) throw py::error_already_set();
    return r;
  } catch (...) {
    take_notes();
    throw;
  }
}

py::dict to_dict(const Fields& fields) {
  py::dict d;
  for (const Field& f : fields) {
    switch (f.kind) {
      case Field::Kind::none: d[f.name.c_str()] = py::none(); break;
      case Field::Kind::number: d[f.name.c_str()] = f.number; break;
      case Field::Kind::integer: d[f.name.c_str()] = f.integer; break;
      case Field::Kind::text: d[f.name.c_str()] = f.text; break;
    }
  }
  return d;
}

py::list to_records(const std::vector<Fields>& rows) {
  py::list l;
  for (const Fields& r : rows) l.append(to_dict(r));
  return l;
}

}  // namespace

PYBIND11_MODULE(_shadowlab, m) {
  m.doc() = "shadowlab's library calls; use the `shadowlab` package, which documents them.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  m.def("set_threads", [](int n) { set_thread_count(n); });
  m.def("threads", [] { return thread_count(); });
  m.def("version", [] { return std::string(shadowlab_version()); });
  m.def("commit", [] { return std::string(build_commit()); });

  py::class_<PyScene>(m, "Scene")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene.name; })
      .def_property_readonly("width", [](const PyScene& s) { return s.scene.camera.width; })
      .def_property_readonly("height", [](const PyScene& s) { return s.scene.camera.height; })
      .def_property_readonly("triangles", [](const PyScene& s) { return s.scene.triangle_count(); })
      .def_property_readonly("meshes", [](const PyScene& s) { return s.scene.meshes.size(); })
      .def_property_readonly("light_position", [](const PyScene& s) {
        const vec3 p = s.scene.light.position;
        return py::make_tuple(p.x, p.y, p.z);
      })
      .def_property_readonly("light_radius", [](const PyScene& s) { return s.scene.light.radius; })
      .def_property_readonly("eye", [](const PyScene& s) {
        const vec3 p = s.scene.camera.eye;
        return py::make_tuple(p.x, p.y, p.z);
      })
      .def_property_readonly("target", [](const PyScene& s) {
        const vec3 p = s.scene.camera.target;
        return py::make_tuple(p.x, p.y, p.z);
      })
      .def_property_readonly("flags", [](const PyScene& s) { return s.flags; });
  m.def("scene", [](const std::vector<std::string>& flags) {
    return without_gil([&] { return make_scene(flags); });
  });

  py::class_<PyGBuffer>(m, "GBuffer")
      .def_property_readonly("width", [](const PyGBuffer& g) { return g.g.width; })
      .def_property_readonly("height", [](const PyGBuffer& g) { return g.g.height; })
      .def_readonly("camera_ms", &PyGBuffer::camera_ms)
      .def_property_readonly("position", [](py::object self) { return vec3_view(self, self.cast<PyGBuffer&>().g.position, self.cast<PyGBuffer&>().g); })
      .def_property_readonly("geo_normal", [](py::object self) { return vec3_view(self, self.cast<PyGBuffer&>().g.geo_normal, self.cast<PyGBuffer&>().g); })
      .def_property_readonly("depth", [](py::object self) { auto& g = self.cast<PyGBuffer&>().g; return plane_view(self, g.depth.data(), g.width, g.height); })
      .def_property_readonly("mesh_id", [](py::object self) { auto& g = self.cast<PyGBuffer&>().g; return plane_view(self, g.mesh_id.data(), g.width, g.height); })
      .def_property_readonly("prim_id", [](py::object self) { auto& g = self.cast<PyGBuffer&>().g; return plane_view(self, g.prim_id.data(), g.width, g.height); })
      .def_property_readonly("covered", [](py::object self) { auto& g = self.cast<PyGBuffer&>().g; return plane_view(self, g.covered.data(), g.width, g.height); });
  m.def("gbuffer", [](const PyScene& s, int repeats) {
    return without_gil([&] { return make_gbuffer(s, repeats); });
  });

  py::class_<PyResult>(m, "Result")
      .def_readonly("spec", &PyResult::spec)
      .def_property_readonly("mask", [](py::object self) {
        const ImageF& mask = self.cast<PyResult&>().r.mask;
        return plane_view(self, mask.data.data(), mask.width, mask.height);
      })
      .def_property_readonly("texels", [](py::object self) -> py::object {
        const ImageU32& t = self.cast<PyResult&>().r.texels;
        if (t.empty()) return py::none();
        return plane_view(self, t.data.data(), t.width, t.height);
      })
      .def_property_readonly("times", [](const PyResult& r) { return to_dict(result_times(r)); })
      .def_property_readonly("work", [](const PyResult& r) { return to_dict(result_work(r)); })
      .def_property_readonly("faces", [](const PyResult& r) { return to_dict(result_faces(r)); })
      .def_property_readonly("notes", [](const PyResult& r) { return r.r.notes; })
      .def("shaded", [](const PyResult& r, const PyScene& s, const PyGBuffer& g, double ambient) {
        ImageF img = without_gil([&] { return shaded_image(r, s, g, ambient); });
        return rgb_copy(img);
      });
  m.def("render", [](const PyScene& s, const std::string& spec, const PyGBuffer& g, int repeats,
                     bool cache, bool texels) {
    return without_gil([&] { return render(s, spec, g, repeats, cache, texels); });
  });

  m.def("metric", [](py::array test, py::array ref, py::object texels, py::object shadow_ms,
                     double fps) {
    const ImageF t = mask_from_array(test, "metric: test");
    const ImageF r = mask_from_array(ref, "metric: reference");
    ImageU32 tex;
    const bool has_texels = !texels.is_none();
    if (has_texels) tex = texels_from_array(texels.cast<py::array>(), "metric: texels");
    const bool has_ms = !shadow_ms.is_none();
    const double ms = has_ms ? shadow_ms.cast<double>() : 0.0;
    return to_dict(without_gil([&] {
      return metric_fields(t, r, has_texels ? &tex : nullptr, has_ms ? &ms : nullptr, fps);
    }));
  });

  m.def("resolution_sweep", [](const std::vector<std::string>& flags) {
    return to_records(without_gil([&] { return resolution_sweep(flags); }));
  });
  m.def("tune", [](const std::vector<std::string>& flags) {
    return to_records(without_gil([&] { return tune(flags); }));
  });

  m.def("nsm_features", [](const PyScene& s, const PyGBuffer& g, const std::string& spec,
                           bool every_candidate) {
    auto f = std::make_shared<NsmFeatures>(
        without_gil([&] { return nsm_features(s, g, spec, every_candidate); }));
    py::dict d;
    // Each plane is a view of the shared feature set, which lives as long as any of them.
    py::object owner = py::cast(std::make_shared<FeatureOwner>(FeatureOwner{f}));
    for (size_t i = 0; i < f->names.size(); ++i)
      d[f->names[i].c_str()] = plane_view(owner, f->planes[i].data(), f->width, f->height);
    d["coverage"] = plane_view(owner, f->coverage.data(), f->width, f->height);
    return d;
  });
  py::class_<FeatureOwner, std::shared_ptr<FeatureOwner>>(m, "_Features");

  m.def("nsm_frame", [](const std::vector<std::string>& flags, int frame) {
    const std::string bytes = without_gil([&] { return nsm_frame(flags, frame); });
    return py::bytes(bytes);
  });
  m.def("nsm_frame_splits", [](const std::vector<std::string>& flags) {
    return without_gil([&] { return nsm_frame_splits(flags); });
  });
}
