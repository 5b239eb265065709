// SPDX-License-Identifier: MIT
// The compiled module `libtangent._libtangent` (pybind11) of the package `libtangent`
// (python/libtangent re-exports it): the core on numpy arrays, and bake and check on files with
// the options and the reports of the `tangent` command. The GIL is released while
// C++ runs, so other Python threads (and Dask workers' threads) go on.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "tangent/batch.hpp"
#include "tangent/check.hpp"
#include "tangent/gltf.hpp"
#include "tangent/option_table.hpp"
#include "tangent/output.hpp"
#include "tangent/tangent.hpp"
#include "tangent/text.hpp"

namespace py = pybind11;

namespace {

// nlohmann JSON to Python objects, through Python's own json module (reports are small).
py::object toPython(const nlohmann::ordered_json& json) { return py::module_::import("json").attr("loads")(tangent::text::dumpJson(json)); }

[[noreturn]] void badArgument(const std::string& argument, const std::string& what) {
  throw py::value_error("libtangent: " + argument + ": " + what);
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

namespace options = tangent::options;

// A keyword argument's value as the option table's text ("true", "60", "unit,w"), checked
// against the table; ValueError (TypeError for a wrong type) naming the argument otherwise.
std::string optionText(const options::Option& option, const py::handle& value) {
  using options::Kind;
  const std::string name = options::pythonName(option.name);
  const bool isBool = py::isinstance<py::bool_>(value);
  std::string text;
  switch (option.kind) {
    case Kind::flag:
      if (!isBool) throw py::type_error("libtangent: " + name + ": must be True or False");
      text = value.cast<bool>() ? "true" : "false";
      break;
    case Kind::choice:
    case Kind::text:
      if (!py::isinstance<py::str>(value)) throw py::type_error("libtangent: " + name + ": must be a str");
      text = value.cast<std::string>();
      break;
    case Kind::integer:
      if (isBool || !py::isinstance<py::int_>(value)) throw py::type_error("libtangent: " + name + ": must be an int");
      text = py::str(value).cast<std::string>();
      break;
    case Kind::number:
      if (isBool || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)))
        throw py::type_error("libtangent: " + name + ": must be a number");
      text = py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
      break;
    case Kind::path:
      text = py::str(py::module_::import("os").attr("fspath")(value)).cast<std::string>();
      break;
    case Kind::list:
      if (py::isinstance<py::str>(value)) throw py::type_error("libtangent: " + name + ": must be a list of names, not a str");
      for (const py::handle item : value) {
        if (!py::isinstance<py::str>(item)) throw py::type_error("libtangent: " + name + ": must be a list of str");
        text += (text.empty() ? "" : ",") + item.cast<std::string>();
      }
      break;
  }
  if (const auto why = options::checkValue(option, text)) badArgument(name, *why);
  return text;
}

// Applies the keyword arguments of `function` (the options of `command` in the table) to
// `options` through the table's `apply` for that struct, in the table's order (so that, as
// documented, reference overrides method and orthogonal_tolerance overrides tolerance); None is
// "not given". An argument the table does not give `function` is a TypeError, as Python's own.
template <typename Options>
void applyKeywords(const py::kwargs& kwargs, unsigned command, const char* function, Options& options,
                   bool (*apply)(Options&, const options::Option&, std::string_view)) {
  for (const auto& item : kwargs) {
    std::string name = py::str(item.first).cast<std::string>();
    for (char& c : name) c = c == '_' ? '-' : c;
    if (!options::find(name, command, options::kPython))
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + py::str(item.first).cast<std::string>() + "'");
  }
  for (const options::Option& option : options::table()) {
    if (!(option.commands & command) || !(option.frontEnds & options::kPython)) continue;
    const std::string name = options::pythonName(option.name);
    if (!kwargs.contains(name) || kwargs[name.c_str()].is_none()) continue;
    apply(options, option, optionText(option, kwargs[name.c_str()]));
  }
}

// The table as Python sees it (libtangent.option_table()): what __init__.py builds the
// signatures and docstrings from, and what tests compare the CLI, the stubs and npm with.
py::list optionTable() {
  using options::Kind;
  py::list rows;
  const std::pair<unsigned, const char*> commands[] = {
      {options::kArrays, "compute_tangents"}, {options::kBake, "bake"}, {options::kBakeTree, "bake_tree"}, {options::kCheck, "check"},
      {options::kBench, "bench"}};
  const std::pair<unsigned, const char*> frontEnds[] = {{options::kCommandLine, "cli"}, {options::kPython, "python"}, {options::kNpm, "npm"}};
  const char* kinds[] = {"flag", "choice", "integer", "number", "path", "text", "list"};
  for (const options::Option& option : options::table()) {
    py::dict row;
    row["name"] = std::string(option.name);
    row["python"] = options::pythonName(option.name);
    row["npm"] = options::npmName(option.name);
    row["short"] = option.shortName ? std::string(1, option.shortName) : std::string();
    row["kind"] = kinds[static_cast<int>(option.kind)];
    py::list choices;
    for (const std::string_view name : options::choiceNames(option.choices)) choices.append(std::string(name));
    row["choices"] = choices;
    const std::string text(option.defaultValue);
    py::object defaultValue = py::none();
    if (option.kind == Kind::flag) defaultValue = py::bool_(text == "true");
    else if (!text.empty() && option.kind == Kind::integer) defaultValue = py::int_(std::stoll(text));
    else if (!text.empty() && option.kind == Kind::number) defaultValue = py::float_(std::stod(text));
    else if (!text.empty()) defaultValue = py::str(text);
    row["default"] = defaultValue;
    row["min"] = option.min;
    row["max"] = option.max;
    row["min_open"] = option.minOpen;
    py::list in, at;
    for (const auto& [bit, name] : commands)
      if (option.commands & bit) in.append(name);
    for (const auto& [bit, name] : frontEnds)
      if (option.frontEnds & bit) at.append(name);
    row["commands"] = in;
    row["front_ends"] = at;
    row["value_name"] = std::string(option.valueName);
    row["help"] = std::string(option.help);
    rows.append(row);
  }
  return rows;
}

py::dict computeTangents(const py::handle& positionsIn, const py::handle& normalsIn, const py::handle& uvsIn,
                         const py::handle& indicesIn, const py::kwargs& kwargs) {
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
  applyKeywords(kwargs, options::kArrays, "compute_tangents", options, &options::applyOption);

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

// libtangent.Error and libtangent.InputError, and the translation of C++ exceptions into them.
void registerErrors(py::module_& m) {
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
}

// The core on numpy arrays.
void defineArrays(py::module_& m) {
  m.def("compute_tangents", &computeTangents, py::arg("positions"), py::arg("normals"), py::arg("uvs"), py::arg("indices"),
        R"(Tangent frames per corner of an indexed triangle list.

positions, normals: float arrays of shape (n, 3) or (3n,); uvs: (n, 2) or (2n,);
indices: integer array of shape (t, 3) or (3t,), each below n. float32 and uint32 C-contiguous
arrays are used without copying; others are converted.

Returns a dict: "tangents" float32 (3t, 4): x, y, z, w per corner, unit, w = +-1;
"corner_vertex" uint32 (3t,): the vertex each corner uses after splitting (input vertex v
keeps index v; report["splitVertices"] extra vertices follow); "report": what happened, as
the `tangents` object of `tangent bake --report`.
Raises ValueError naming the argument on a bad shape, dtype, option or index.
The GIL is released while the core runs.)");
}

// bake(), bake_tree() and check_tree(): the `tangent` command's file work.
void defineFileCommands(py::module_& m) {
  m.def(
      "bake",
      [](const std::filesystem::path& input, const std::filesystem::path& output, const py::kwargs& kwargs) {
        tangent::gltf::BakeOptions options;
        applyKeywords(kwargs, options::kBake, "bake", options, &tangent::gltf::applyBakeOption);
        nlohmann::ordered_json entry = {{"input", input.string()}, {"output", output.string()}, {"status", "ok"}};
        {
          py::gil_scoped_release released;
          entry.update(tangent::gltf::toJson(tangent::gltf::bakeFile(input, output, options)));
        }
        return toPython(entry);
      },
      py::arg("input"), py::arg("output"),
      R"(Bake TANGENT into a glTF file, as `tangent bake INPUT -o OUTPUT` does.

Computes TANGENT for every triangle primitive whose material reads the tangent frame (a
normalTexture, a clearcoat normal texture, anisotropy), from the UV set that texture uses,
and writes OUTPUT (.glb, or .gltf + .bin). Inputs: .gltf, .glb,
.obj, .ply, .off. The input is never written to; the output is written atomically.

Returns the dict `tangent bake --report` writes for this file.
Raises libtangent.InputError with the CLI's message on a file it refuses.)");

  m.def(
      "bake_tree",
      [](const std::filesystem::path& inputFolder, const std::filesystem::path& outputFolder, const py::kwargs& kwargs) {
        tangent::gltf::BatchOptions options;
        applyKeywords(kwargs, options::kBakeTree, "bake_tree", options, &tangent::gltf::applyBatchOption);
        nlohmann::ordered_json entries = nlohmann::ordered_json::array();
        {
          py::gil_scoped_release released;
          for (const auto& entry : tangent::gltf::bakeTree(inputFolder, outputFolder, options)) entries.push_back(tangent::gltf::toJson(entry));
        }
        return toPython(entries);
      },
      py::arg("input_folder"), py::arg("output_folder"),
      R"(Bake a folder tree, as `tangent bake INPUT_FOLDER --recursive --out-dir OUTPUT_FOLDER` does.

Every .gltf, .glb, .obj, .ply and .off under INPUT_FOLDER is baked into the same relative
path under OUTPUT_FOLDER; one failure never stops the rest. OUTPUT_FOLDER/tangent-manifest.json
records each input's SHA-256 (with the buffers and images it names) and the options, so a
re-run skips what is unchanged (force=True bakes everything).

Returns the list `tangent bake --recursive --report` writes: per file
"input", "output", "status" ("ok" | "failed"), "unchanged", "digest", "error" when failed,
and the bake report when baked in this run.)");

  m.def(
      "check_tree",
      [](const std::filesystem::path& folder, const py::kwargs& kwargs) {
        tangent::gltf::CheckOptions options;
        applyKeywords(kwargs, options::kCheck, "check_tree", options, &tangent::gltf::applyCheckOption);
        nlohmann::ordered_json files = nlohmann::ordered_json::array();
        {
          py::gil_scoped_release released;
          for (const std::filesystem::path& input : tangent::gltf::findInputs(folder)) {
            try {
              files.push_back(tangent::gltf::toJson(tangent::gltf::checkFile(input, options)));
            } catch (const tangent::gltf::InputError& e) {  // one unreadable file: named, the rest still checked
              tangent::gltf::FileCheck unreadable;
              unreadable.file = input.string();
              unreadable.error = e.what();
              files.push_back(tangent::gltf::toJson(unreadable));
            }
          }
        }
        return toPython(files);
      },
      py::arg("folder"),
      R"(Check every .gltf, .glb, .obj, .ply and .off under a folder, as `tangent check FOLDER --recursive
--format json` does (the files bake_tree() would bake, sorted).

Returns the report's "files" list: one entry per file as check() returns it; a file that
cannot be read is an entry with "status" "error" and its "error", and the others are checked.
Raises libtangent.InputError where the folder cannot be listed.)");
}

// The option table and the manifest's options record.
void defineOptions(py::module_& m) {
  m.def("option_table", &optionTable,
        R"(Every option of compute_tangents(), bake(), bake_tree() and check(), of the `tangent` command and
of the npm package, from the one table they are all made from (tangent/option_table.hpp): a list of
dicts with "name" (the command line's), "python", "npm", "kind", "choices", "default", "min", "max",
"commands", "front_ends", "value_name" and "help".)");

  m.def(
      "manifest_options",
      [](const py::kwargs& kwargs) {
        tangent::gltf::BatchOptions options;
        applyKeywords(kwargs, options::kBakeTree, "manifest_options", options, &tangent::gltf::applyBatchOption);
        return toPython(tangent::gltf::manifestOptions(options.bake));
      },
      R"(The "options" record bake_tree() keeps in tangent-manifest.json for these keyword arguments (those
of bake_tree()): what changes an output besides its input. A run whose record differs bakes
everything again; a tool that writes the manifest itself (examples/bake_dask.py) records this.)");
}

// What a scheduler of many calls needs: the workspace cache, inputs, digests.
void defineBatchSupport(py::module_& m) {
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

  m.def("write_file", [](const std::filesystem::path& path, const py::bytes& data) {
        const std::string bytes = data;
        py::gil_scoped_release released;
        tangent::output::writeFileAtomic(path, std::string_view(bytes));
      }, py::arg("path"), py::arg("data"),
      R"(Writes `data` (bytes) to `path` by the rule every libtangent writer follows (docs/security.md):
a temporary file beside it, written, synced, renamed into place (whole or not at all); only a regular
file or a new name is replaced; a symbolic link is followed only to a name of the same extension; a
character device or a FIFO with a reader is written in place. Raises libtangent.Error naming the path.)");

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
}

// check(): `tangent check PATH --format json` on one file.
void defineCheck(py::module_& m) {
  m.def(
      "check",
      [](const std::filesystem::path& input, const py::kwargs& kwargs) {
        tangent::gltf::CheckOptions options;
        applyKeywords(kwargs, options::kCheck, "check", options, &tangent::gltf::applyCheckOption);
        tangent::gltf::FileCheck result;
        {
          py::gil_scoped_release released;
          result = tangent::gltf::checkFile(input, options);
        }
        return toPython(tangent::gltf::toJson(result));
      },
      py::arg("path"),
      R"(Check the TANGENTs stored in a glTF file, as `tangent check PATH --format json` does.

Per primitive that needs tangents: present, format, finite, unit, w, w-uniform, orthogonal,
handedness, reference (within `tolerance` degrees of freshly computed `method` tangents).

Returns the file's entry of the JSON report (docs/check-json.md): "status" is "clean" or
"findings". Raises libtangent.InputError with the CLI's message on an unreadable file.)");
}

}  // namespace

PYBIND11_MODULE(_libtangent, m) {
  m.doc() =
      "libtangent: MikkTSpace-exact tangent frames for glTF and plain arrays.\n\n"
      "compute_tangents() works on numpy arrays; bake() and check() work on files, with the\n"
      "options and the JSON reports of the `tangent bake` and `tangent check` commands.";
  // The project's version (CMakeLists.txt `project(... VERSION ...)`), given by the build.
  m.attr("__version__") = TANGENT_VERSION;
  registerErrors(m);
  defineArrays(m);
  defineFileCommands(m);
  defineOptions(m);
  defineBatchSupport(m);
  defineCheck(m);
}
