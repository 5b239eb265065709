// SPDX-License-Identifier: MIT
// The compiled module `libtangent._libtangent` (pybind11) of the package `libtangent`
// (python/libtangent re-exports it): the core on numpy arrays, and bake and check on files with
// the options and the reports of the `tangent` command. The GIL is released while
// C++ runs, so other Python threads (and Dask workers' threads) go on.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <bitset>
#include <filesystem>
#include <optional>
#include <string>

#include "tangent/batch.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/tangent.hpp"
#include "tangent/text.hpp"

namespace py = pybind11;

namespace {

// nlohmann JSON to Python objects, through Python's own json module (reports are small).
py::object toPython(const nlohmann::ordered_json& json) { return py::module_::import("json").attr("loads")(tangent::text::dumpJson(json)); }

[[noreturn]] void badArgument(const std::string& argument, const std::string& what) {
  throw py::value_error("libtangent: " + argument + ": " + what);
}

tangent::Method method(const std::string& name) {
  const std::optional<tangent::Method> m = tangent::parseMethod(name);
  if (!m) badArgument("method", "'" + name + "' is not mikktspace, lengyel, flat or meshopt");
  return *m;
}

tangent::Weighting weighting(const std::string& name) {
  const std::optional<tangent::Weighting> w = tangent::parseWeighting(name);
  if (!w) badArgument("weighting", "'" + name + "' is not angle, area or uniform");
  return *w;
}

unsigned threadCount(int threads) {
  if (threads < 0 || threads > 256) badArgument("threads", std::to_string(threads) + " is not 0 (all) to 256");
  return static_cast<unsigned>(threads);
}

// A float array of shape (n, width) or (n * width,), as float32 C-contiguous (converted only
// when it is not already).
py::array_t<float, py::array::c_style> floatRows(const py::handle& object, const char* argument, int width) {
  const py::array any = py::array::ensure(object);
  if (!any) badArgument(argument, "must be a numpy array (or convertible to one)");
  const char kind = any.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    badArgument(argument, "must hold real numbers, not dtype " + std::string(py::str(any.dtype())));
  const bool rows = any.ndim() == 2 && any.shape(1) == width;
  const bool flat = any.ndim() == 1 && any.shape(0) % width == 0;
  if (!rows && !flat)
    badArgument(argument, "must have shape (n, " + std::to_string(width) + ") or (n * " + std::to_string(width) + ",), not " +
                              std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(any.shape(), any.shape() + any.ndim()))))));
  return py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(any);
}

py::array_t<std::uint32_t, py::array::c_style> indexArray(const py::handle& object) {
  const py::array any = py::array::ensure(object);
  if (!any) badArgument("indices", "must be a numpy array (or convertible to one)");
  const char kind = any.dtype().kind();
  if (kind != 'i' && kind != 'u') badArgument("indices", "must hold integers, not dtype " + std::string(py::str(any.dtype())));
  const bool rows = any.ndim() == 2 && any.shape(1) == 3;
  const bool flat = any.ndim() == 1 && any.shape(0) % 3 == 0;
  if (!rows && !flat) badArgument("indices", "must have shape (t, 3) or (t * 3,)");
  if (any.size() > 0 && !(any.dtype().is(py::dtype::of<std::uint32_t>()))) {
    // Range-checked before narrowing: a negative or >= 2^32 index is an error, not a wrap.
    const py::object lo = any.attr("min")(), hi = any.attr("max")();
    if (lo.cast<long long>() < 0) badArgument("indices", "has a negative index " + std::string(py::str(lo)));
    if (hi.cast<unsigned long long>() > 0xFFFFFFFFull) badArgument("indices", "has an index beyond 2^32 - 1");
  }
  return py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(any);
}

// The options of `tangent bake`, from bake()'s and bake_tree()'s keyword arguments.
struct BakeKeywords {
  std::string method, weighting;
  int threads = 0;
  bool all = false, overwrite = false;
  std::optional<std::filesystem::path> assetRoot;
  std::string tangentFormat, normals;
  double creaseAngle = 60;
  bool keepExternal = false;
};

tangent::gltf::BakeOptions bakeOptions(const BakeKeywords& k) {
  tangent::gltf::BakeOptions options;
  options.tangents.method = method(k.method);
  options.tangents.weighting = weighting(k.weighting);
  options.tangents.threads = threadCount(k.threads);
  options.all = k.all;
  options.overwrite = k.overwrite;
  if (k.assetRoot) options.assetRoot = *k.assetRoot;
  const auto format = tangent::gltf::parseTangentFormat(k.tangentFormat);
  if (!format) badArgument("tangent_format", "'" + k.tangentFormat + "' is not float, short or byte");
  options.tangentFormat = *format;
  const auto normals = tangent::gltf::parseNormalsMode(k.normals);
  if (!normals) badArgument("normals", "'" + k.normals + "' is not flat, smooth or keep");
  options.normals = *normals;
  if (!(k.creaseAngle >= 0 && k.creaseAngle <= 180))
    badArgument("crease_angle", std::to_string(k.creaseAngle) + " is not degrees in [0, 180]");
  options.creaseAngleDegrees = k.creaseAngle;
  options.keepExternalImages = k.keepExternal;
  return options;
}

py::dict computeTangents(const py::handle& positionsIn, const py::handle& normalsIn, const py::handle& uvsIn,
                         const py::handle& indicesIn, const std::string& methodName, const std::string& weightingName,
                         int threads, const std::string& uvOrigin) {
  const auto positions = floatRows(positionsIn, "positions", 3);
  const auto normals = floatRows(normalsIn, "normals", 3);
  const auto uvs = floatRows(uvsIn, "uvs", 2);
  const auto indices = indexArray(indicesIn);
  const std::size_t vertices = static_cast<std::size_t>(positions.size() / 3);
  if (static_cast<std::size_t>(normals.size() / 3) != vertices)
    badArgument("normals", std::to_string(normals.size() / 3) + " normals for " + std::to_string(vertices) + " positions");
  if (static_cast<std::size_t>(uvs.size() / 2) != vertices)
    badArgument("uvs", std::to_string(uvs.size() / 2) + " UVs for " + std::to_string(vertices) + " positions");
  tangent::Options options;
  options.method = method(methodName);
  options.weighting = weighting(weightingName);
  options.threads = threadCount(threads);
  const std::optional<tangent::UvOrigin> origin = tangent::parseUvOrigin(uvOrigin);  // the core's names
  if (!origin) badArgument("uv_origin", "'" + uvOrigin + "' is not top-left (glTF) or bottom-left (OpenGL, OBJ)");
  options.uvOrigin = *origin;

  const std::size_t corners = static_cast<std::size_t>(indices.size());
  py::array_t<float> tangents({static_cast<py::ssize_t>(corners), py::ssize_t(4)});
  py::array_t<std::uint32_t> cornerVertex(static_cast<py::ssize_t>(corners));
  const tangent::MeshArrays arrays{{positions.data(), static_cast<std::size_t>(positions.size())},
                                   {normals.data(), static_cast<std::size_t>(normals.size())},
                                   {uvs.data(), static_cast<std::size_t>(uvs.size())},
                                   {indices.data(), corners}};
  const tangent::CornerOutputs outputs{{tangents.mutable_data(), corners * 4}, {}, {cornerVertex.mutable_data(), corners}};
  tangent::Report report;
  std::string error;
  {
    py::gil_scoped_release released;
    try {
      tangent::CachedWorkspace workspace;  // this thread's, kept between calls (release_cached_workspaces)
      report = tangent::computeCornerTangents(arrays, outputs, options, workspace.get());
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty()) throw py::value_error("libtangent: " + error);
  py::dict result;
  result["tangents"] = tangents;
  result["corner_vertex"] = cornerVertex;
  result["report"] = toPython(tangent::gltf::toJson(report));
  return result;
}

}  // namespace

PYBIND11_MODULE(_libtangent, m) {
  m.doc() =
      "libtangent: MikkTSpace-exact tangent frames for glTF and plain arrays.\n\n"
      "compute_tangents() works on numpy arrays; bake() and check() work on files, with the\n"
      "options and the JSON reports of the `tangent bake` and `tangent check` commands.";
  // The project's version (CMakeLists.txt `project(... VERSION ...)`), given by the build.
  m.attr("__version__") = TANGENT_VERSION;
  static py::exception<std::runtime_error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<tangent::gltf::InputError> inputError(m, "InputError", error.ptr());
  error.doc() = "Base class of libtangent's errors (I/O failures).";
  inputError.doc() = "A file libtangent refuses: the message names the file and the element, as the CLI's does.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tangent::gltf::InputError& e) {
      PyErr_SetString(inputError.ptr(), e.what());
    } catch (const py::builtin_exception&) {
      throw;  // ValueError and friends: pybind11's own translation
    } catch (const std::runtime_error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  m.def("compute_tangents", &computeTangents, py::arg("positions"), py::arg("normals"), py::arg("uvs"), py::arg("indices"),
        py::kw_only(), py::arg("method") = "mikktspace", py::arg("weighting") = "angle", py::arg("threads") = 0,
        py::arg("uv_origin") = "top-left",
        R"(Tangent frames per corner of an indexed triangle list.

positions, normals: float arrays of shape (n, 3) or (3n,); uvs: (n, 2) or (2n,);
indices: integer array of shape (t, 3) or (3t,), each below n. float32 and uint32 C-contiguous
arrays are used without copying; others are converted.

method: mikktspace (default; what normal-map bakers use) | lengyel | flat | meshopt
weighting: angle (default) | area | uniform   (lengyel only)
threads: worker threads, 0 = all hardware threads; the result never depends on it
uv_origin: top-left (glTF, default) | bottom-left (OpenGL, OBJ): decides the sign of w

Returns a dict: "tangents" float32 (3t, 4): x, y, z, w per corner, unit, w = +-1;
"corner_vertex" uint32 (3t,): the vertex each corner uses after splitting (input vertex v
keeps index v; report["splitVertices"] extra vertices follow); "report": what happened, as
the `tangents` object of `tangent bake --report`.
Raises ValueError naming the argument on a bad shape, dtype, option or index.
The GIL is released while the core runs.)");

  m.def(
      "bake",
      [](const std::filesystem::path& input, const std::filesystem::path& output, const std::string& methodName,
         const std::string& weightingName, int threads, bool all, bool overwrite, std::optional<std::filesystem::path> assetRoot,
         const std::string& tangentFormat, const std::string& normals, double creaseAngle, bool keepExternal) {
        const tangent::gltf::BakeOptions options = bakeOptions(
            {methodName, weightingName, threads, all, overwrite, assetRoot, tangentFormat, normals, creaseAngle, keepExternal});
        nlohmann::ordered_json entry = {{"input", input.string()}, {"output", output.string()}, {"status", "ok"}};
        {
          py::gil_scoped_release released;
          entry.update(tangent::gltf::toJson(tangent::gltf::bakeFile(input, output, options)));
        }
        return toPython(entry);
      },
      py::arg("input"), py::arg("output"), py::kw_only(), py::arg("method") = "mikktspace", py::arg("weighting") = "angle",
      py::arg("threads") = 0, py::arg("all") = false, py::arg("overwrite") = false, py::arg("asset_root") = py::none(),
      py::arg("tangent_format") = "float", py::arg("normals") = "flat", py::arg("crease_angle") = 60.0,
      py::arg("keep_external") = false,
      R"(Bake TANGENT into a glTF file, as `tangent bake INPUT -o OUTPUT` does.

Computes TANGENT for every triangle primitive whose material has a normalTexture, from the
UV set that texture uses, and writes OUTPUT (.glb, or .gltf + .bin). Inputs: .gltf, .glb,
.obj, .ply, .off. The input is never written to; the output is written atomically.

method: mikktspace (default) | lengyel | flat | meshopt
weighting: angle (default) | area | uniform   (lengyel only)
threads: worker threads (0 = all); the output never depends on it
all: bake every triangle primitive, normal texture or not (TEXCOORD_0)
overwrite: recompute valid existing TANGENT too
asset_root: folder buffer and image URIs may not leave (default: the input's folder)
tangent_format: float (default) | short | byte: TANGENT as float or normalized SHORT/BYTE
  (KHR_mesh_quantization)
normals: flat (default) | smooth | keep: for a primitive without NORMAL, write flat normals
  (what the specification requires of clients) or smooth ones, or keep it without (and skip it)
crease_angle: with normals="smooth": triangles meeting at more than this many degrees stay
  sharp (default 60, in [0, 180])
keep_external: a .glb output keeps the input's image files external (copied beside it) instead
  of embedding them (the default: one self-contained file)

Returns the dict `tangent bake --report` writes for this file.
Raises libtangent.InputError with the CLI's message on a file it refuses.)");

  m.def(
      "bake_tree",
      [](const std::filesystem::path& inputFolder, const std::filesystem::path& outputFolder, const std::string& methodName,
         const std::string& weightingName, int threads, bool all, bool overwrite, std::optional<std::filesystem::path> assetRoot,
         bool force, const std::string& tangentFormat, const std::string& normals, double creaseAngle, bool keepExternal) {
        tangent::gltf::BatchOptions options;
        options.bake = bakeOptions(
            {methodName, weightingName, threads, all, overwrite, assetRoot, tangentFormat, normals, creaseAngle, keepExternal});
        options.force = force;
        nlohmann::ordered_json entries = nlohmann::ordered_json::array();
        {
          py::gil_scoped_release released;
          for (const auto& entry : tangent::gltf::bakeTree(inputFolder, outputFolder, options)) entries.push_back(tangent::gltf::toJson(entry));
        }
        return toPython(entries);
      },
      py::arg("input_folder"), py::arg("output_folder"), py::kw_only(), py::arg("method") = "mikktspace",
      py::arg("weighting") = "angle", py::arg("threads") = 0, py::arg("all") = false, py::arg("overwrite") = false,
      py::arg("asset_root") = py::none(), py::arg("force") = false, py::arg("tangent_format") = "float",
      py::arg("normals") = "flat", py::arg("crease_angle") = 60.0, py::arg("keep_external") = false,
      R"(Bake a folder tree, as `tangent bake INPUT_FOLDER --recursive --out-dir OUTPUT_FOLDER` does.

Every .gltf, .glb, .obj, .ply and .off under INPUT_FOLDER is baked into the same relative
path under OUTPUT_FOLDER; one failure never stops the rest. OUTPUT_FOLDER/tangent-manifest.json
records each input's SHA-256 (with the buffers and images it names) and the options, so a
re-run skips what is unchanged (force=True bakes everything).

Options as for bake(). Returns the list `tangent bake --recursive --report` writes: per file
"input", "output", "status" ("ok" | "failed"), "unchanged", "digest", "error" when failed,
and the bake report when baked in this run.)");

  m.def("release_cached_workspaces", [] { tangent::releaseCachedWorkspaces(); },
        R"(Frees the scratch memory compute_tangents(), bake() and check() keep between calls.

Each thread keeps the workspace of its last call (up to 512 MiB; about 70 bytes a triangle), so
that the next call touches no fresh memory. Call this where a process computes one huge mesh and
then does other work.)");
  m.def("cached_workspace_bytes", [] { return tangent::cachedWorkspaceBytes(); },
        "Bytes of scratch memory kept between calls now, over all threads.");

  m.def("find_inputs", [](const std::filesystem::path& folder) {
        std::vector<std::string> names;
        for (const auto& path : tangent::gltf::findInputs(folder)) names.push_back(path.string());
        return names;
      }, py::arg("folder"), "The bakeable files under a folder, recursively and sorted, as bake_tree() finds them.");

  m.def("input_digest", [](const std::filesystem::path& input, std::optional<std::filesystem::path> assetRoot) {
        py::gil_scoped_release released;
        return tangent::gltf::inputDigest(input, assetRoot.value_or(std::filesystem::path()));
      }, py::arg("input"), py::kw_only(), py::arg("asset_root") = py::none(),
      "SHA-256 (hex) of a file and of every buffer and image it names: the manifest's digest.");

  m.def("manifest_digest", [](const std::filesystem::path& input, std::optional<std::filesystem::path> assetRoot,
                              const py::object& previous, bool verify) {
        const std::string previousText = py::module_::import("json").attr("dumps")(previous).cast<std::string>();
        const nlohmann::ordered_json previousJson = nlohmann::ordered_json::parse(previousText);
        tangent::gltf::InputDigest digest;
        {
          py::gil_scoped_release released;
          digest = tangent::gltf::digestForManifest(input, assetRoot.value_or(std::filesystem::path()), previousJson, verify);
        }
        return py::make_tuple(digest.digest, toPython(digest.stamps));
      }, py::arg("input"), py::kw_only(), py::arg("asset_root") = py::none(), py::arg("previous") = py::none(),
      py::arg("verify") = false,
      "(digest, stamps) as the manifest records them: where `previous` (the input's manifest record) has size and\n"
      "modification-time stamps that all still hold, its digest is returned without reading the files (unless verify).");

  m.def(
      "check",
      [](const std::filesystem::path& input, const std::string& methodName, double tolerance, bool all,
         std::optional<std::filesystem::path> assetRoot, std::optional<std::vector<std::string>> only,
         const std::vector<std::string>& ignore, bool allowMissing, std::optional<double> orthogonalTolerance,
         std::optional<double> referenceTolerance, std::optional<std::string> reference, double minCoverage) {
        tangent::gltf::CheckOptions options;
        options.method = method(methodName);
        if (options.method == tangent::Method::flat) badArgument("method", "check compares with mikktspace or lengyel");
        if (reference) {
          const std::optional<tangent::gltf::Generator> generator = tangent::gltf::parseGenerator(*reference);
          if (!generator) badArgument("reference", "'" + *reference + "' is not " + tangent::gltf::generatorNames());
          options.method = generator->method;
          options.weighting = generator->weighting;
        }
        auto degrees = [](const char* argument, double value) {
          if (!(value > 0 && value <= 180)) badArgument(argument, "must be degrees in (0, 180]");
          return value;
        };
        options.orthogonalToleranceDegrees = degrees("orthogonal_tolerance", orthogonalTolerance.value_or(degrees("tolerance", tolerance)));
        options.referenceToleranceDegrees = degrees("reference_tolerance", referenceTolerance.value_or(tolerance));
        auto checkSet = [](const char* argument, const std::vector<std::string>& names) {
          std::bitset<tangent::gltf::kCheckCount> set;
          for (const auto& name : names) {
            const auto id = tangent::gltf::parseCheck(name);
            if (!id) badArgument(argument, "'" + name + "' is not a check name");
            set.set(static_cast<std::size_t>(*id));
          }
          return set;
        };
        if (only) options.enabled = checkSet("only", *only);
        options.enabled &= ~checkSet("ignore", ignore);
        options.allowMissing = allowMissing;
        options.all = all;
        if (!(minCoverage >= 0 && minCoverage <= 1)) badArgument("min_coverage", "must be a fraction in [0, 1] (0: no coverage warning)");
        options.minCoverage = minCoverage;
        if (assetRoot) options.assetRoot = *assetRoot;
        tangent::gltf::FileCheck result;
        {
          py::gil_scoped_release released;
          result = tangent::gltf::checkFile(input, options);
        }
        return toPython(tangent::gltf::toJson(result));
      },
      py::arg("path"), py::kw_only(), py::arg("method") = "mikktspace", py::arg("tolerance") = 1.0, py::arg("all") = false,
      py::arg("asset_root") = py::none(), py::arg("only") = py::none(), py::arg("ignore") = std::vector<std::string>(),
      py::arg("allow_missing") = false, py::arg("orthogonal_tolerance") = py::none(), py::arg("reference_tolerance") = py::none(),
      py::arg("reference") = py::none(), py::arg("min_coverage") = tangent::gltf::kDefaultMinCoverage,
      R"(Check the TANGENTs stored in a glTF file, as `tangent check PATH --format json` does.

Per primitive that needs tangents: present, format, finite, unit, w, w-uniform, orthogonal,
handedness, reference (within `tolerance` degrees of freshly computed `method` tangents).

method: mikktspace (default) | lengyel
reference: the generator reference measures against, as `--reference` names it (mikktspace,
  lengyel/angle, lengyel/area, lengyel/uniform, flat, meshopt); overrides method
tolerance: degrees, for orthogonal and reference (default 1), on top of the rounding limits
orthogonal_tolerance, reference_tolerance: the same for one check (default: tolerance)
only: run only these checks (names as above); ignore: leave these out
allow_missing: a primitive without TANGENT is skipped, not a finding
min_coverage: warn where reference or handedness compared less than this share of a primitive's
  corners or triangles (default 0.5; 0: never), as `--min-coverage` does
all: every triangle primitive, not only normal-mapped ones
asset_root: folder buffer and image URIs may not leave (default: the file's folder)

Returns the file's entry of the JSON report (docs/check-json.md): "status" is "clean" or
"findings". Raises libtangent.InputError with the CLI's message on an unreadable file.)");
}
