// The Python module `swell` (docs/python.md): open caches and read frames as NumPy arrays, run
// the replay to NumPy height fields (swell::runtime::Playback on a headless GL context), and
// bake scenes with overrides. Errors are the programs' messages as Python exceptions:
// swell.CacheError, swell.SceneError, swell.DivergenceError, swell.GLError (RuntimeError
// subclasses), ValueError for bad parameters, KeyboardInterrupt for a bake stopped by Ctrl-C.

#include "swell/bake/bake_driver.h"
#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/cache/error.h"
#include "swell/cache/json_depth.h"
#include "swell/cache/reader.h"
#include "swell/runtime/error.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/playback.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using nlohmann::json;

namespace {

using namespace swell;

/// json -> Python objects, through the json module (values are small: metadata, summaries).
py::object toPython(const json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

/// Python dict / list / number -> json, through the json module.
/// A value nested deeper than cache::kMaxJsonDepth is a ValueError naming its depth.
json fromPython(const py::handle& o) {
    std::string text;
    try {
        text = py::module_::import("json").attr("dumps")(o).cast<std::string>();
    } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_RecursionError))
            throw;
        throw std::invalid_argument(fmt::format(
            "a value nests deeper than Python's json module writes; at most {} levels are allowed",
            cache::kMaxJsonDepth));
    }
    if (const std::string deep = cache::jsonDepthProblem(text); !deep.empty())
        throw std::invalid_argument("a value " + deep);
    return json::parse(text);
}

py::array_t<float> floats(const std::vector<float>& v, std::size_t columns) {
    py::array_t<float> a(
        {static_cast<py::ssize_t>(v.size() / columns), static_cast<py::ssize_t>(columns)});
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

/// An open cache (validated header and index).
struct Cache {
    explicit Cache(const std::string& path) : reader(path) {}
    cache::Reader reader;
};

/// Frame i of the cache (negative: from the end, as Python indexes) as a dict of arrays.
py::dict frameAt(const Cache& c, long i) {
    const long n = static_cast<long>(c.reader.frameCount());
    if (i < -n || i >= n)
        throw py::index_error(fmt::format("frame {} of a {}-frame cache", i, n));
    const cache::Frame f = c.reader.readFrame(static_cast<std::size_t>(i < 0 ? i + n : i));
    py::dict d;
    d["surface"] = floats(f.surface, 2);
    d["splash"] = floats(f.splash, 4);
    return d;
}

/// One replay with its own headless context (PlaybackSession).
class Replay {
public:
    Replay(const Cache& c, const std::string& mode, std::optional<std::pair<int, int>> cells,
           std::uint64_t seed, std::optional<int> slices, std::optional<double> fluctuation,
           const py::dict& params, const py::dict& ripple, const py::dict& whirlpool,
           const py::dict& splash, std::optional<double> memoryBudgetGiB)
        : m_session(c.reader,
                    configOf(mode, cells, seed, slices, fluctuation, params, ripple, whirlpool,
                             splash, memoryBudgetGiB),
                    runtime::PlaybackSession::Context::Own) {}

    runtime::Playback& playback() { return m_session.playback(); }

    py::array_t<float> heights() {
        const runtime::HeightField& h = playback().heights();
        py::array_t<float> a({h.cellsZ, h.cellsX}); // a[m, n]: z rows, x columns
        std::copy(h.heights.begin(), h.heights.end(), a.mutable_data());
        return a;
    }

    py::array_t<float> run(const std::vector<double>& seconds) {
        runtime::Playback& p = playback();
        const runtime::Grid& g = p.grid();
        py::array_t<float> a({static_cast<py::ssize_t>(seconds.size()),
                              static_cast<py::ssize_t>(g.cellsZ),
                              static_cast<py::ssize_t>(g.cellsX)});
        float* out = a.mutable_data();
        for (double t : seconds) {
            p.advance(t);
            for (double v : p.heights().heights)
                *out++ = static_cast<float>(v);
        }
        return a;
    }

    py::array_t<double> sample(py::array_t<double, py::array::c_style | py::array::forcecast> x,
                               py::array_t<double, py::array::c_style | py::array::forcecast> z) {
        if (x.ndim() != 1 || z.ndim() != 1 || x.size() != z.size())
            throw std::invalid_argument(fmt::format(
                "sample: x and z must be 1-D arrays of one length, got {} and {} values", x.size(),
                z.size()));
        py::array_t<double> out(x.size());
        const auto n = static_cast<std::size_t>(x.size());
        playback().sample({x.data(), n}, {z.data(), n}, {out.mutable_data(), n});
        return out;
    }

    py::array_t<float> splashes() {
        std::vector<float> v;
        for (const runtime::SplashSprite& s : playback().splashes())
            v.insert(v.end(), {s.x, s.y, s.z, s.alpha});
        return floats(v, 4);
    }

    py::dict grid() {
        const runtime::Grid& g = playback().grid();
        py::dict d;
        d["cells_x"] = g.cellsX;
        d["cells_z"] = g.cellsZ;
        d["slices"] = g.slices;
        d["x0"] = g.x0;
        d["dx"] = g.dx;
        d["dz"] = g.dz;
        d["extent_z"] = g.extentZ;
        return d;
    }

    py::object params() {
        const runtime::Playback& p = m_session.playback();
        const runtime::PlaybackConfig& c = p.config();
        json j = {{"params", runtime::toJson(c.params)},
                  {"mode", runtime::toJson(c.mode)},
                  {"timeline", runtime::toJson(p.plan())},
                  {"renderer", m_session.context()->renderer()}};
        return toPython(j);
    }

private:
    /// playbackConfig of the keyword arguments (None: the default; cells given must be > 0).
    static runtime::PlaybackConfig
    configOf(const std::string& mode, std::optional<std::pair<int, int>> cells, std::uint64_t seed,
             std::optional<int> slices, std::optional<double> fluctuation, const py::dict& params,
             const py::dict& ripple, const py::dict& whirlpool, const py::dict& splash,
             std::optional<double> memoryBudgetGiB) {
        runtime::PlaybackChoice choice;
        choice.mode = runtime::replayModeFromString(mode);
        if (memoryBudgetGiB)
            choice.named["memory_budget_gib"] = *memoryBudgetGiB;
        for (const auto& [key, dict] :
             {std::pair{"params", &params}, std::pair{"ripple", &ripple},
              std::pair{"whirlpool", &whirlpool}, std::pair{"splash", &splash}}) {
            if (!dict->empty())
                choice.named[key] = fromPython(*dict);
        }
        if (cells && (cells->first <= 0 || cells->second <= 0))
            throw std::invalid_argument(fmt::format(
                "cells must be (N, M) with N, M > 0, got ({}, {})", cells->first, cells->second));
        if (cells) {
            choice.cellsX = cells->first;
            choice.cellsZ = cells->second;
        }
        choice.slices = slices;
        choice.fluctuation = fluctuation;
        choice.seed = seed;
        return runtime::playbackConfig(choice, "the Replay keyword arguments");
    }

    runtime::PlaybackSession m_session;
};

py::object bakeScene(const std::string& scene, const std::string& output,
                     const std::vector<std::string>& overrides, int threads,
                     std::optional<std::string> probes, bool resume, long checkpointEvery) {
    const bake::Scene s = bake::loadScene(scene, overrides);
    (void)bake::frameIntervalSteps(s); // the bake's own scene errors first
    (void)bake::totalSteps(s);
    bake::BakeOptions opt;
    opt.output = output;
    if (probes)
        opt.probes = *probes;
    opt.sceneFile = scene;
    opt.overrides = overrides;
    if (threads > 0)
        omp_set_num_threads(threads);
    opt.threads = threads > 0 ? threads : omp_get_max_threads();
    opt.programVersion = SWELL_VERSION;
    opt.resume = resume;
    opt.checkpointEvery = checkpointEvery;
    // Ctrl-C in Python stops the bake cleanly (no cache is left); checked every 64 steps.
    long polls = 0;
    opt.cancelled = [&polls] {
        if (++polls % 64 != 0)
            return false;
        py::gil_scoped_acquire gil;
        return PyErr_CheckSignals() != 0;
    };
    bake::BakeSummary summary;
    {
        py::gil_scoped_release release;
        summary = bake::runBake(s, opt);
    }
    return toPython(bake::toJson(summary));
}

} // namespace

PYBIND11_MODULE(swell, m) {
    m.doc() = "swell: bake 2D MPS water into caches and replay them as 3D height fields "
              "(docs/python.md)";
    m.attr("__version__") = SWELL_VERSION;

    static py::exception<cache::CacheError> cacheError(m, "CacheError", PyExc_RuntimeError);
    static py::exception<bake::SceneError> sceneError(m, "SceneError", PyExc_ValueError);
    static py::exception<bake::DivergenceError> divergenceError(m, "DivergenceError",
                                                                PyExc_RuntimeError);
    static py::exception<runtime::RuntimeError> glError(m, "GLError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const cache::CacheError& e) {
            cacheError(e.what());
        } catch (const bake::SceneError& e) {
            sceneError(e.what());
        } catch (const bake::DivergenceError& e) {
            divergenceError(e.what());
        } catch (const runtime::RuntimeError& e) {
            glError(e.what());
        } catch (const bake::BakeCancelled& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        } catch (const json::exception& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });

    py::class_<Cache>(m, "Cache", "An open .swell cache (header and frame index validated).")
        .def(py::init<const std::string&>(), py::arg("path"))
        .def("__len__", [](const Cache& c) { return c.reader.frameCount(); })
        .def_property_readonly("path", [](const Cache& c) { return c.reader.path().string(); })
        .def_property_readonly("frame_count", [](const Cache& c) { return c.reader.frameCount(); })
        .def_property_readonly(
            "frame_seconds",
            [](const Cache& c) { return c.reader.header().dt * c.reader.header().frameInterval; })
        .def_property_readonly("domain",
                               [](const Cache& c) {
                                   const cache::Domain& d = c.reader.header().domain;
                                   return py::make_tuple(d.xMin, d.yMin, d.xMax, d.yMax);
                               })
        .def_property_readonly(
            "metadata",
            [](const Cache& c) { return toPython(json::parse(c.reader.header().metadataJson)); })
        .def("frame", &frameAt, py::arg("index"),
             "Frame `index` (negative: from the end) as {'surface': (N, 2) float32 x, y; "
             "'splash': (S, 4) float32 x, y, vx, vy}.")
        .def("__getitem__", &frameAt);

    py::class_<Replay>(m, "Replay",
                       "The replay of a cache on a headless GL context: advance(seconds), then "
                       "heights(), sample(x, z), splashes().")
        .def(py::init<const Cache&, const std::string&, std::optional<std::pair<int, int>>,
                      std::uint64_t, std::optional<int>, std::optional<double>, const py::dict&,
                      const py::dict&, const py::dict&, const py::dict&, std::optional<double>>(),
             py::arg("cache"), py::kw_only(), py::arg("mode") = "surging",
             py::arg("cells") = py::none(), py::arg("seed") = 1, py::arg("slices") = py::none(),
             py::arg("fluctuation") = py::none(), py::arg("params") = py::dict(),
             py::arg("ripple") = py::dict(), py::arg("whirlpool") = py::dict(),
             py::arg("splash") = py::dict(), py::arg("memory_budget_gib") = py::none(),
             py::keep_alive<1, 2>())
        .def(
            "advance", [](Replay& r, double t) { r.playback().advance(t); }, py::arg("seconds"))
        .def("heights", &Replay::heights,
             "Height field (metres) at the current time, float32 array [z, x] (cells_z, cells_x).")
        .def("run", &Replay::run, py::arg("seconds"),
             "Height fields at every time of `seconds`: float32 array (T, cells_z, cells_x).")
        .def("sample", &Replay::sample, py::arg("x"), py::arg("z"),
             "Heights at points (bilinear between cell centres, NaN outside the mesh).")
        .def("splashes", &Replay::splashes,
             "Splash sprites at the current time: float32 array (S, 4) x, y, z, alpha.")
        .def_property_readonly("grid", &Replay::grid)
        .def_property_readonly("params", &Replay::params)
        .def_property_readonly("seconds", [](Replay& r) { return r.playback().seconds(); });

    m.def("bake", &bakeScene, py::arg("scene"), py::arg("output"), py::kw_only(),
          py::arg("overrides") = std::vector<std::string>{}, py::arg("threads") = 0,
          py::arg("probes") = py::none(), py::arg("resume") = false,
          py::arg("checkpoint_every") = 0,
          "Bakes `scene` (JSON file) into the cache `output` with 'section.key=value' "
          "overrides, as swell-bake does; returns swell-bake's --json summary as a dict.");
}
