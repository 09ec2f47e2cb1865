#pragma once
// The Python module's shared pieces: the settings registry under Python names, NumPy arrays
// from fresnel's images (without copying), and the binders of each part of the module.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/job/job.h"
#include "fresnel/job/settings.h"

namespace fresnel::python {

namespace py = pybind11;

// The settings Python accepts: those of the command line and of scene files. Each has two
// Python names: its key in snake case ("camera.yaw" -> camera_yaw, "render.shadowMapSize" ->
// render_shadow_map_size) and its flag's ("--yaw" -> yaw, "--shadow-map-size" ->
// shadow_map_size; negated flags such as --no-cache have none). The registry's keys and flags
// themselves are accepted too ("camera.yaw", "--yaw").
const std::map<std::string, const settings::Setting*>& python_names();
std::string python_name(const settings::Setting& setting);  // the snake-case key

// The setting `name` means; raises TypeError naming the close ones for an unknown name.
const settings::Setting& setting_for(const std::string& name);

// Sets `name` to a Python value through the registry (its syntax, range and message): bool,
// int, float, str, os.PathLike, None (an optional setting's "none"), and sequences for
// vectors (X,Y,Z) and sizes (W, H). Bad values raise fresnel.Error, wrong types TypeError.
void set_setting(Job& job, const std::string& name, py::handle value);
// A Python value as registry text: bool as true/false, str and os.PathLike as they are, numbers
// in their shortest form, sequences of numbers joined by `separator`; other types raise TypeError
// "<where>: expected <expected>, got <type>".
std::string python_text(py::handle value, const std::string& separator, const std::string& where,
                        const std::string& expected);
void set_settings(Job& job, const py::dict& values);
// A setting's value in `job` as a Python value (bool, int, float, tuple, str, None).
py::object get_setting(const Job& job, const settings::Setting& setting);

// Diagnostics as Python warnings (category fresnel.Warning... UserWarning).
void emit_warnings(const Diagnostics& diag);

// Arrays that own the image's memory (no copy): (H, W, 4) float32, (H, W, C) uint8.
py::array_t<float> to_array(ImageF&& image);
py::array_t<std::uint8_t> to_array(Image8&& image);
template <class T>
py::array_t<T> vector_array(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
    auto* held = new std::vector<T>(std::move(values));
    py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, held->data(), owner);
}

// An image given as a NumPy array (H, W, 3 or 4; uint8 as 0..255, floats as they are) or as
// a file name (read as `fresnel compare` reads it). `is_float`: the values are linear
// (an EXR/HDR file, or a float array the caller says is linear).
ImageF image_from(py::handle image, const std::string& what, bool* from_float_file = nullptr);

// A Python callable as a progress function called from worker threads: the GIL is taken for
// the call; an exception it raises (or Ctrl+C) sets `stop` and is raised when the work returns.
struct ProgressBridge {
    py::object callback;
    std::atomic<bool> stop{false};
    std::mutex mutex;
    std::optional<py::error_already_set> error;

    void operator()(double fraction) {
        if (stop) return;
        py::gil_scoped_acquire gil;
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!callback.is_none()) callback(fraction);
        } catch (py::error_already_set& e) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!error) error.emplace(std::move(e));
            stop = true;
        }
    }
    void rethrow() {
        if (error) {
            py::error_already_set e = std::move(*error);
            error.reset();
            throw e;
        }
    }
    ~ProgressBridge() {
        if (error) {
            py::gil_scoped_acquire gil;
            error.reset();
        }
    }
};

void bind_job(py::module_& m);
void bind_session(py::module_& m);
void bind_tools(py::module_& m);

}  // namespace fresnel::python
