// `import fresnel`: the library from Python (docs/python.md). This file: the module, its
// exception type, the settings registry under Python names, and the Job.
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "common.h"
#include "fresnel/core/spelling.h"
#include "fresnel/core/version.h"
#include "fresnel/job/lights.h"

namespace fresnel::python {

namespace {

std::string snake_case(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '.' || c == '-') out += '_';
        else if (std::isupper(static_cast<unsigned char>(c))) {
            out += '_';
            out += char(std::tolower(static_cast<unsigned char>(c)));
        } else out += c;
    }
    return out;
}

constexpr unsigned kPythonFrontEnds = settings::kCli | settings::kSceneFile;

}  // namespace

std::string python_name(const settings::Setting& setting) { return snake_case(setting.key); }

const std::map<std::string, const settings::Setting*>& python_names() {
    static const std::map<std::string, const settings::Setting*> names = [] {
        std::map<std::string, const settings::Setting*> n;
        auto add = [&](const std::string& name, const settings::Setting* s) {
            auto [it, added] = n.emplace(name, s);
            if (!added && it->second != s)
                throw std::logic_error("fresnel: the Python name '" + name + "' means both " + it->second->key + " and " + s->key);
        };
        for (const settings::Setting& s : settings::all()) {
            if (!s.offered(kPythonFrontEnds)) continue;
            add(python_name(s), &s);
            if (!s.flag.empty() && !s.negated_flag) add(snake_case(s.flag.substr(2)), &s);
        }
        return n;
    }();
    return names;
}

const settings::Setting& setting_for(const std::string& name) {
    const auto& names = python_names();
    if (auto it = names.find(name); it != names.end()) return *it->second;
    if (const settings::Setting* s = settings::find(name); s && s->offered(kPythonFrontEnds)) return *s;
    std::vector<std::string> candidates;
    for (const auto& [n, s] : names) candidates.push_back(n);
    throw py::type_error("unknown setting '" + name + "'" + did_you_mean(name, candidates) +
                         "; fresnel.settings() lists them");
}

namespace {

std::string number_text(py::handle v) {
    if (py::isinstance<py::int_>(v) || (py::hasattr(v, "__index__") && !py::isinstance<py::float_>(v)))
        return py::str(py::int_(py::reinterpret_borrow<py::object>(v)));
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(v)));
}

bool is_number(py::handle v) {
    return !py::isinstance<py::str>(v) && !py::isinstance<py::bool_>(v) && PyNumber_Check(v.ptr()) &&
           !PySequence_Check(v.ptr());
}

}  // namespace

std::string python_text(py::handle v, const std::string& separator, const std::string& where, const std::string& expected) {
    auto wrong = [&](const char* got) { return py::type_error(where + ": expected " + expected + ", got " + got); };
    if (py::isinstance<py::bool_>(v) || py::isinstance(v, py::module_::import("numpy").attr("bool_")))
        return v.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    if (py::hasattr(v, "__fspath__")) return py::str(py::module_::import("os").attr("fspath")(v)).cast<std::string>();
    if (is_number(v)) return number_text(v);
    if (PySequence_Check(v.ptr())) {
        py::sequence seq = py::reinterpret_borrow<py::sequence>(v);
        std::string text;
        for (std::size_t i = 0; i < seq.size(); ++i) {
            py::object e = seq[i];
            if (!is_number(e)) throw wrong("a sequence with a non-number in it");
            if (i) text += separator;
            text += number_text(e);
        }
        return text;
    }
    throw wrong(Py_TYPE(v.ptr())->tp_name);
}

namespace {

// A Python value as the registry's text: python_text, with the setting's own rules for None and
// for booleans (a bool only for a Bool setting, a number never for one).
std::string value_text(const settings::Setting& s, py::handle v, const std::string& where) {
    using settings::Type;
    auto wrong = [&](const char* got) { return py::type_error(where + ": expected " + s.expected() + ", got " + got); };
    if (v.is_none()) {
        if (s.none.empty()) throw wrong("None");
        return s.none;
    }
    const bool is_bool = py::isinstance<py::bool_>(v) || py::isinstance(v, py::module_::import("numpy").attr("bool_"));
    if (is_bool && s.type != Type::Bool) throw wrong("a bool");
    if (is_number(v) && s.type == Type::Bool) throw wrong("a number");
    return python_text(v, s.type == Type::Size ? "x" : ",", where, s.expected());
}

}  // namespace

void set_setting(Job& job, const std::string& name, py::handle value) {
    const settings::Setting& s = setting_for(name);
    const std::string where = name;
    settings::set(job, s, value_text(s, value, where), where);
}

void set_settings(Job& job, const py::dict& values) {
    for (auto [k, v] : values) set_setting(job, py::str(k).cast<std::string>(), v);
}

py::object get_setting(const Job& job, const settings::Setting& s) {
    using settings::Type;
    settings::Value v = settings::parse(s, settings::get(job, s), s.key);
    if (v.unset) return py::none();
    switch (s.type) {
    case Type::Bool: return py::bool_(v.flag);
    case Type::Int: return py::int_(static_cast<long long>(v.number));
    case Type::Number: return py::float_(v.number);
    case Type::Vec3: return py::make_tuple(v.vec.x, v.vec.y, v.vec.z);
    case Type::Size: return py::make_tuple(v.width, v.height);
    case Type::Choice:
    case Type::Text: break;
    }
    return py::str(v.text);
}

void emit_warnings(const Diagnostics& diag) {
    for (const std::string& line : diag.lines())
        if (PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 2) != 0) throw py::error_already_set();
}

py::array_t<float> to_array(ImageF&& image) {
    const py::ssize_t h = image.height, w = image.width;
    return vector_array(std::move(image.pixels), {h, w, 4});
}

py::array_t<std::uint8_t> to_array(Image8&& image) {
    const py::ssize_t h = image.height, w = image.width, c = image.channels;
    return vector_array(std::move(image.pixels), {h, w, c});
}

ImageF image_from(py::handle image, const std::string& what, bool* from_float_file) {
    if (from_float_file) *from_float_file = false;
    if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__")) {
        std::string path = py::str(py::module_::import("os").attr("fspath")(image)).cast<std::string>();
        const ImageLimits limits;
        std::vector<std::uint8_t> bytes;
        {
            py::gil_scoped_release release;
            bytes = read_file_bytes(path, limits.max_decoded_bytes);
        }
        if (from_float_file) *from_float_file = is_linear_image(bytes);
        py::gil_scoped_release release;
        return decode_image_float(bytes, path, limits);
    }
    py::array a = py::array::ensure(image);
    if (!a || a.ndim() < 2 || a.ndim() > 3)
        throw py::type_error(what + ": expected an image array of shape (H, W), (H, W, 3) or (H, W, 4), or a file name");
    const py::ssize_t h = a.shape(0), w = a.shape(1), c = a.ndim() == 3 ? a.shape(2) : 1;
    if (c < 1 || c > 4 || h < 1 || w < 1)
        throw py::type_error(what + ": expected an image array of shape (H, W), (H, W, 3) or (H, W, 4)");
    const bool bytes = a.dtype().is(py::dtype::of<std::uint8_t>());
    auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    ImageF out{int(w), int(h)};
    const float* src = f.data();
    const float scale = bytes ? 1.0f / 255.0f : 1.0f;
    for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i) {
        const float* p = src + i * std::size_t(c);
        float* q = &out.pixels[i * 4];
        if (c <= 2) q[0] = q[1] = q[2] = p[0] * scale;
        else for (int k = 0; k < 3; ++k) q[k] = p[k] * scale;
        q[3] = c == 4 ? p[3] * scale : c == 2 ? p[1] * scale : 1.0f;
    }
    return out;
}

namespace {

std::string job_repr(const Job& job) {
    std::string text = "fresnel.Job(";
    bool first = true;
    for (const settings::Setting* s : settings::offered_by(kPythonFrontEnds)) {
        if (settings::is_default(job, *s)) continue;
        text += (first ? "" : ", ") + python_name(*s) + "=" + py::repr(get_setting(job, *s)).cast<std::string>();
        first = false;
    }
    if (!job.lights.extra.empty())
        text += std::string(first ? "" : ", ") + "lights=" + std::to_string(job.lights.extra.size());
    return text + ")";
}

}  // namespace

void bind_job(py::module_& m) {
    py::class_<Job>(m, "Job",
                    "What to render: the settings of the settings registry (fresnel.settings()), by their Python\n"
                    "names (camera_yaw or yaw, render_size or size, ...), checked as the command line checks them.\n"
                    "The scene comes separately (fresnel.load); a Job is a plain value, copied freely.")
        .def(py::init([](const py::object& values, const py::kwargs& kwargs) {
                 Job job;
                 if (!values.is_none()) set_settings(job, py::dict(values));
                 set_settings(job, kwargs);
                 return job;
             }),
             py::arg("settings") = py::none(),
             "Job(settings=None, **kwargs): the default job with `settings` (a dict of name -> value) and the keyword\n"
             "arguments applied, e.g. Job(size=(512, 512), yaw=30, env='studio').")
        .def(
            "set",
            [](Job& job, const std::string& name, py::handle value) -> Job& {
                set_setting(job, name, value);
                return job;
            },
            py::arg("name"), py::arg("value"), py::return_value_policy::reference_internal,
            "Sets one setting (a Python name, a registry key or a flag) and returns the job.")
        .def(
            "update",
            [](Job& job, const py::kwargs& kwargs) -> Job& {
                set_settings(job, kwargs);
                return job;
            },
            py::return_value_policy::reference_internal, "Sets settings from keyword arguments and returns the job.")
        .def(
            "copy",
            [](const Job& job, const py::kwargs& kwargs) {
                Job out = job;
                set_settings(out, kwargs);
                return out;
            },
            "A copy of the job with the keyword arguments applied.")
        .def(
            "get", [](const Job& job, const std::string& name) { return get_setting(job, setting_for(name)); },
            py::arg("name"), "A setting's value: bool, int, float, tuple, str, or None for an optional setting left unset.")
        .def("__getitem__", [](const Job& job, const std::string& name) { return get_setting(job, setting_for(name)); })
        .def("__setitem__", [](Job& job, const std::string& name, py::handle value) { set_setting(job, name, value); })
        .def(
            "settings",
            [](const Job& job, bool all) {
                py::dict d;
                for (const settings::Setting* s : settings::offered_by(kPythonFrontEnds))
                    if (all || !settings::is_default(job, *s)) d[py::str(python_name(*s))] = get_setting(job, *s);
                return d;
            },
            py::arg("all") = false,
            "The settings as a dict of Python name -> value: those that differ from the default job, or all.")
        .def(
            "add_light",
            [](Job& job, const std::string& spec) -> Job& {
                job.lights.extra.push_back(parse_light(spec));
                return job;
            },
            py::arg("spec"), py::return_value_policy::reference_internal,
            "Adds a light, as --light spells it: 'dir:AZ,EL,LUX[,R,G,B]', 'point:X,Y,Z,CANDELA[,R,G,B]' or\n"
            "'spot:X,Y,Z,AZ,EL,CANDELA,INNER,OUTER[,R,G,B]'. Returns the job.")
        .def(
            "clear_lights",
            [](Job& job) -> Job& {
                job.lights.extra.clear();
                return job;
            },
            py::return_value_policy::reference_internal, "Removes the lights add_light added.")
        .def_property_readonly("light_count", [](const Job& job) { return job.lights.extra.size(); },
                               "How many lights add_light added.")
        .def("__eq__", [](const Job& a, const Job& b) { return a == b; })
        .def("__repr__", &job_repr)
        .def("__copy__", [](const Job& job) { return job; })
        .def("__deepcopy__", [](const Job& job, py::dict) { return job; });
}

}  // namespace fresnel::python

namespace {

namespace py = pybind11;
using namespace fresnel::python;

py::list settings_list() {
    py::list out;
    py::object json = py::module_::import("json");
    py::list all = json.attr("loads")(fresnel::settings::describe_json());
    for (py::handle item : all) {
        py::dict d = py::reinterpret_borrow<py::dict>(item);
        const fresnel::settings::Setting* s = fresnel::settings::find(d["key"].cast<std::string>());
        if (!s || !s->offered(fresnel::settings::kCli | fresnel::settings::kSceneFile)) continue;
        d["python"] = python_name(*s);
        py::list aliases;
        for (const auto& [name, setting] : python_names())
            if (setting == s && name != python_name(*s)) aliases.append(name);
        d["aliases"] = aliases;
        out.append(d);
    }
    return out;
}

}  // namespace

PYBIND11_MODULE(_fresnel, m) {
    m.doc() = "fresnel's C++ library (the package `fresnel` wraps it; see docs/python.md)";
    m.attr("__version__") = FRESNEL_VERSION_STRING;
    static py::exception<fresnel::Error> error(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const fresnel::Error& e) {
            py::object instance = py::reinterpret_borrow<py::object>(error.ptr())(e.what());
            instance.attr("file") = e.file();
            instance.attr("where") = e.where();
            instance.attr("reason") = e.reason();
            PyErr_SetObject(error.ptr(), instance.ptr());
        }
    });
    python_names();  // a clash of two settings' Python names fails the import, not a call
    m.def("settings", &settings_list,
          "Every setting a Job takes: a list of dicts (key, python, aliases, flag, type, unit, min, max, choices,\n"
          "none, default, example, doc), from the settings registry that the CLI and scene files read.");
    bind_job(m);
    bind_session(m);
    bind_tools(m);
}
